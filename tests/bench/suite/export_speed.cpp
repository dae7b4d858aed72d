// The export part (issue 47 item 8): how the trajectory writers' time grows with the bodies.
// A run of N falling, spinning bodies (boxes and spheres of a few sizes, so a few shared
// meshes) over 31 frames is simulated in a child process, which then times one writer
// writing those frames (a fresh process meets the allocator as a user's run does: a
// writer that copies its buffer again and again pays the page faults there); the fastest
// of three children is kept. A writer linear in bodies x frames doubles its time when
// the bodies double; the table gives that growth and each format's time against the CSV's.
#include "bench.h"

#include <tumble/io/trajectory_writer.h>
#include <tumble/world.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace tumble::bench {

namespace {

SceneDesc fallingBodies(int n) {
    SceneDesc s;
    s.settings.dt = 1.0 / 120;
    s.settings.duration = 0.5;  // 31 frames at 60 a second
    s.settings.frameRate = 60;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.shape.normal = Vec3(0, 1, 0);
    s.bodies.push_back(ground);
    const int side = static_cast<int>(std::ceil(std::sqrt(n)));
    for (int i = 0; i < n; ++i) {
        BodyDesc b;
        b.name = "body" + std::to_string(i);
        b.mass = 1.0;
        const double size = 0.2 + 0.05 * (i % 3);
        if (i % 2) {
            b.shape.type = ShapeType::Sphere;
            b.shape.radius = size;
        } else {
            b.shape.type = ShapeType::Box;
            b.shape.halfExtents = Vec3::Constant(size);
        }
        b.position = Vec3(1.5 * (i % side), 3.0 + 0.1 * (i % 7), 1.5 * (i / side));
        b.angularVelocity = Vec3(0.5, 1.0 + 0.01 * i, 0.2);
        s.bodies.push_back(b);
    }
    return s;
}

}  // namespace

int exportChildMain(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: tumble-bench --child export BODIES FILE\n");
        return 2;
    }
    const SceneDesc scene = fallingBodies(std::atoi(argv[3]));
    const std::filesystem::path file = argv[4];
    World world(scene);
    std::vector<State> frames;
    simulate(world, [&](int, const State& st) { frames.push_back(st); });
    const Model& model = world.model();
    try {
        const double t0 = wallNow();
        auto writer = io::makeTrajectoryWriter(file);
        writer->begin(model, scene, static_cast<int>(frames.size()), model.settings.frameRate);
        for (size_t k = 0; k < frames.size(); ++k) writer->frame(static_cast<int>(k), frames[k]);
        writer->finish();
        const double seconds = wallNow() - t0;
        std::uintmax_t bytes = std::filesystem::file_size(file);
        if (file.extension() == ".gltf")
            bytes += std::filesystem::file_size(std::filesystem::path(file).replace_extension(".bin"));
        std::printf("RESULT %.6g %ju %zu\n", seconds, bytes, frames.size());
        return 0;
    } catch (const std::exception& e) {
        std::printf("FAILED %s\n", e.what());
        return 1;
    }
}

bool runExport(const Options& opt, std::vector<ExportRow>& rows) {
    const std::filesystem::path dir = opt.out / "export-tmp";
    std::filesystem::create_directories(dir);
    bool ok = true;
    std::printf("%-7s %-5s %10s %12s\n", "bodies", "file", "seconds", "bytes");
    const std::vector<int> sizes =
        opt.quick ? std::vector<int>{250, 500} : std::vector<int>{250, 500, 1000, 2000};
    for (int n : sizes) {
        for (const char* ext : {"csv", "json", "gltf", "glb"}) {
            ExportRow row;
            row.bodies = n;
            row.format = ext;
            const std::string file = (dir / (std::string("run.") + ext)).string();
            for (int run = 0; run < 3 && row.note.empty(); ++run) {
                std::string cmd = "'";  // appended piece by piece: GCC 12 warns falsely on one sum
                cmd += selfPath();
                cmd += "' --child export " + std::to_string(n) + " '";
                cmd += file;
                cmd += "' 2>&1";
                FILE* pipe = popen(cmd.c_str(), "r");
                std::string out;
                char buf[1024];
                while (pipe && std::fgets(buf, sizeof buf, pipe)) out += buf;
                const int status = pipe ? pclose(pipe) : -1;
                double seconds = 0;
                unsigned long long bytes = 0;
                if (status != 0 ||
                    std::sscanf(out.c_str(), "RESULT %lf %llu %d", &seconds, &bytes, &row.frames) != 3) {
                    row.note = "failed: " + out.substr(0, 200);
                    while (!row.note.empty() && row.note.back() == '\n') row.note.pop_back();
                    ok = false;
                    break;
                }
                row.seconds = run == 0 ? seconds : std::min(row.seconds, seconds);
                row.bytes = bytes;
            }
            std::printf("%-7d %-5s %10.4f %12llu %s\n", n, ext, row.seconds, row.bytes, row.note.c_str());
            std::fflush(stdout);
            rows.push_back(row);
        }
    }
    std::filesystem::remove_all(dir);
    return ok;
}

void writeExport(const Options& opt, const std::vector<ExportRow>& rows) {
    std::filesystem::create_directories(opt.out);
    std::ofstream csv(opt.out / "export.csv");
    csv << "bodies,format,frames,seconds,bytes\n";
    for (const ExportRow& r : rows)
        csv << r.bodies << ',' << r.format << ',' << r.frames << ',' << r.seconds << ',' << r.bytes << '\n';

    // Against the CSV of the same run, and against the same format with half the bodies.
    auto find = [&](int bodies, const std::string& format) -> const ExportRow* {
        for (const ExportRow& r : rows)
            if (r.bodies == bodies && r.format == format && r.note.empty()) return &r;
        return nullptr;
    };
    std::ofstream md(opt.out / "summary.md", std::ios::app);
    md << "\n## Trajectory export\n\n"
       << "Each writer alone on the frames of one run (31 frames), the fastest of three.\n\n"
       << "| bodies | format | seconds | MB | x CSV | x half the bodies |\n|---|---|---|---|---|---|\n";
    char line[256];
    for (const ExportRow& r : rows) {
        const ExportRow* csvRow = find(r.bodies, "csv");
        const ExportRow* half = find(r.bodies / 2, r.format);
        std::snprintf(
            line, sizeof line, "| %d | %s | %.4f | %.2f | %s | %s |\n", r.bodies, r.format.c_str(), r.seconds,
            r.bytes / 1048576.0,
            csvRow && csvRow->seconds > 0 ? std::to_string(r.seconds / csvRow->seconds).substr(0, 4).c_str()
                                          : "",
            half && half->seconds > 0 ? std::to_string(r.seconds / half->seconds).substr(0, 4).c_str() : "");
        md << line;
    }
}

}  // namespace tumble::bench
