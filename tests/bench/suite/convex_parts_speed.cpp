// The convex-parts part (issue 49 item 3): the split of a concave mesh into convex parts,
// timed, with the figures that judge it, on the meshes the issue names: a mug, a U-bracket,
// a 10 000-triangle torus (the time target: 2 s on this machine), the mug sample's mesh and
// the assimp test models' spider (its STL, when assimp-testmodels is installed), each upright
// and turned (a split must not depend on the pose much). Run with `--scene convex-parts`;
// not in --quick (the torus alone takes seconds).
#include "bench.h"

#include "../../engine/test_meshes.h"

#include <tumble/convex_parts.h>
#include <tumble/io/mesh_import.h>
#include <tumble/scene.h>

#include <chrono>
#include <cstdio>
#include <fstream>

namespace tumble::bench {

namespace {

struct Model {
    std::string name;
    TriangleMesh mesh;
    int maxParts = 16;  // the default; the spider again with more (18 pieces, eight bent legs)
};

std::vector<Model> models() {
    std::vector<Model> out;
    out.push_back({"mug (test)", test::mug(0.4, 1.0, 0.3, 0.8, 48)});
    out.push_back({"u-bracket", test::uBracket(1.0, 0.2, 0.6, 0.4)});
    out.push_back({"torus 10k", test::torus(1.0, 0.3, 100, 50)});
    try {
        out.push_back(
            {"mug.obj", io::importMesh(std::string(TUMBLE_BENCH_SCENES_DIR) + "/../meshes/mug.obj")});
    } catch (const std::exception& e) {
        std::printf("mug.obj: %s\n", e.what());
    }
    const char* spider = "/usr/share/assimp/models/STL/Spider_binary.stl";
    if (std::filesystem::exists(spider)) {
        try {
            const TriangleMesh m = io::importMesh(spider);
            out.push_back({"spider (assimp)", m});
            out.push_back({"spider, 48 parts", m, 48});
        } catch (const std::exception& e) {
            std::printf("spider: %s\n", e.what());
        }
    } else {
        std::printf("spider: %s not there (Debian package assimp-testmodels)\n", spider);
    }
    return out;
}

TriangleMesh turned(TriangleMesh m) {
    const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()));
    for (Vec3& v : m.vertices) v = q * v + Vec3(0.3, -0.2, 0.1);
    return m;
}

}  // namespace

bool runConvexParts(const Options& opt, std::vector<ConvexPartsRow>& rows) {
    (void)opt;
    bool ok = true;
    std::printf("%-18s %-7s %9s %6s %10s %12s %10s %8s\n", "mesh", "pose", "triangles", "parts", "volume +%",
                "reach out mm", "tol mm", "seconds");
    for (const Model& m : models()) {
        for (const bool turn : {false, true}) {
            ShapeDesc shape;
            shape.type = ShapeType::Mesh;
            shape.file = m.name;
            shape.collision = MeshCollision::ConvexParts;
            shape.maxParts = m.maxParts;
            shape.meshData = std::make_shared<const TriangleMesh>(turn ? turned(m.mesh) : m.mesh);
            ConvexPartsRow row;
            row.mesh = m.name;
            row.turned = turn;
            row.triangles = static_cast<int>(m.mesh.triangles.size());
            try {
                const mesh::ConvexParts p = mesh::convexPartsOfShape(shape);
                row.parts = static_cast<int>(p.parts.size());
                row.volumeOver = 100.0 * (p.partsVolume / p.meshVolume - 1.0);
                row.reachOut = p.largestPokeOut;
                row.tolerance = p.tolerance;
                row.seconds = p.seconds;
            } catch (const std::exception& e) {
                row.note = e.what();
            }
            std::printf("%-18s %-7s %9d %6d %10.2f %12.2f %10.2f %8.2f %s\n", row.mesh.c_str(),
                        turn ? "turned" : "upright", row.triangles, row.parts, row.volumeOver,
                        1000 * row.reachOut, 1000 * row.tolerance, row.seconds, row.note.c_str());
            std::fflush(stdout);
            rows.push_back(row);
        }
    }
    return ok;
}

void writeConvexParts(const Options& opt, const std::vector<ConvexPartsRow>& rows) {
    std::filesystem::create_directories(opt.out);
    std::ofstream csv(opt.out / "convex_parts.csv");
    csv << "mesh,pose,triangles,parts,volume_over_percent,reach_out_m,tolerance_m,seconds,note\n";
    for (const ConvexPartsRow& r : rows)
        csv << '"' << r.mesh << "\"," << (r.turned ? "turned" : "upright") << ',' << r.triangles << ','
            << r.parts << ',' << r.volumeOver << ',' << r.reachOut << ',' << r.tolerance << ',' << r.seconds
            << ",\"" << r.note << "\"\n";
    std::ofstream md(opt.out / "summary.md", std::ios::app);
    md << "\n## Convex parts\n\nThe default options (16 parts at most, tolerance 1 % of the mesh's "
          "diagonal; the spider also with 48 parts).\n\n"
       << "| mesh | pose | triangles | parts | volume over the mesh's | reach out (mm) | tolerance (mm) | s "
          "|\n"
       << "|---|---|---|---|---|---|---|---|\n";
    char line[256];
    for (const ConvexPartsRow& r : rows) {
        std::snprintf(line, sizeof line, "| %s | %s | %d | %d | %+.1f %% | %.2f | %.2f | %.2f |%s\n",
                      r.mesh.c_str(), r.turned ? "turned" : "upright", r.triangles, r.parts, r.volumeOver,
                      1000 * r.reachOut, 1000 * r.tolerance, r.seconds,
                      r.note.empty() ? "" : (" " + r.note).c_str());
        md << line;
    }
}

}  // namespace tumble::bench
