// Welding uses a uniform grid with cells at least as large as the tolerance, so every
// vertex within the tolerance of a point lies in the point's cell or one of its 26
// neighbours. Grid keys are taken relative to the bounding box's corner, so a mesh far
// from the origin does not overflow them.
#include "mesh/mesh_clean.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace tumble::mesh {

namespace {

struct CellHash {
    size_t operator()(const std::array<std::int64_t, 3>& k) const {
        std::uint64_t h = 1469598103934665603ull;
        for (std::int64_t c : k) h = (h ^ static_cast<std::uint64_t>(c)) * 1099511628211ull;
        return static_cast<size_t>(h);
    }
};

void checkInput(const TriangleMesh& mesh) {
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (!mesh.vertices[v].allFinite()) {
            throw std::invalid_argument("vertex " + std::to_string(v) + " is not finite");
        }
    }
    const int n = static_cast<int>(mesh.vertices.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int v : mesh.triangles[t]) {
            if (v < 0 || v >= n) {
                throw std::invalid_argument("triangle " + std::to_string(t) + " uses vertex " +
                                            std::to_string(v) + ", but there are " + std::to_string(n));
            }
        }
    }
}

// For each vertex, the index of the vertex it is welded to (itself when it is kept).
std::vector<int> weld(const std::vector<Vec3>& vertices, double tolerance) {
    std::vector<int> target(vertices.size());
    if (vertices.empty()) return target;
    Vec3 lo = vertices[0], hi = vertices[0];
    for (const Vec3& p : vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double diagonal = (hi - lo).norm();
    // Cells never smaller than 1e-12 of the mesh, which keeps the keys far from overflow.
    const double cell = std::max(tolerance, 1e-12 * diagonal);
    auto key = [&](const Vec3& p) {
        std::array<std::int64_t, 3> k{};
        for (int a = 0; a < 3; ++a) {
            k[a] = cell > 0.0 ? static_cast<std::int64_t>(std::floor((p[a] - lo[a]) / cell)) : 0;
        }
        return k;
    };
    std::unordered_map<std::array<std::int64_t, 3>, std::vector<int>, CellHash> grid;
    for (size_t i = 0; i < vertices.size(); ++i) {
        const Vec3& p = vertices[i];
        const auto k = key(p);
        int found = -1;
        for (int dx = -1; dx <= 1 && found < 0; ++dx) {
            for (int dy = -1; dy <= 1 && found < 0; ++dy) {
                for (int dz = -1; dz <= 1 && found < 0; ++dz) {
                    auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == grid.end()) continue;
                    for (int j : it->second) {
                        // The earliest kept vertex wins, whatever cell it is in.
                        if ((vertices[j] - p).norm() <= tolerance && (found < 0 || j < found)) found = j;
                    }
                }
            }
        }
        if (found >= 0) {
            target[i] = found;
        } else {
            target[i] = static_cast<int>(i);
            grid[k].push_back(static_cast<int>(i));
        }
    }
    return target;
}

bool degenerate(const Vec3& a, const Vec3& b, const Vec3& c, double tolerance) {
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double twiceArea = (b - a).cross(c - a).norm();
    // The height over the longest edge is 2 area / longest; no area at all is degenerate
    // even with a zero tolerance.
    return !(twiceArea > tolerance * longest);
}

}  // namespace

double weldTolerance(const std::vector<Vec3>& vertices) {
    if (vertices.empty()) return 0.0;
    Vec3 lo = vertices[0], hi = vertices[0];
    for (const Vec3& p : vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    return kWeldRelative * (hi - lo).norm();
}

TriangleMesh cleanMesh(const TriangleMesh& mesh, double tolerance, CleanStats* statsOut) {
    checkInput(mesh);
    CleanStats stats;
    const std::vector<int> target = weld(mesh.vertices, tolerance);
    for (size_t i = 0; i < target.size(); ++i) stats.weldedVertices += target[i] != static_cast<int>(i);

    std::vector<std::array<int, 3>> kept;
    std::set<std::array<int, 3>> seen;  // each kept triangle, rotated to start at its least index
    for (const auto& t : mesh.triangles) {
        const std::array<int, 3> w = {target[t[0]], target[t[1]], target[t[2]]};
        if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0] ||
            degenerate(mesh.vertices[w[0]], mesh.vertices[w[1]], mesh.vertices[w[2]], tolerance)) {
            ++stats.degenerateTriangles;
            continue;
        }
        const int first = static_cast<int>(std::min_element(w.begin(), w.end()) - w.begin());
        const std::array<int, 3> canonical = {w[first], w[(first + 1) % 3], w[(first + 2) % 3]};
        if (!seen.insert(canonical).second) {
            ++stats.duplicateTriangles;
            continue;
        }
        kept.push_back(w);
    }

    TriangleMesh out;
    std::vector<int> newIndex(mesh.vertices.size(), -1);
    for (const auto& t : kept) {
        for (int v : t) newIndex[v] = 0;  // mark used
    }
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (newIndex[v] < 0) continue;
        newIndex[v] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(mesh.vertices[v]);
    }
    stats.unusedVertices =
        static_cast<int>(mesh.vertices.size()) - stats.weldedVertices - static_cast<int>(out.vertices.size());
    out.triangles.reserve(kept.size());
    for (const auto& t : kept) out.triangles.push_back({newIndex[t[0]], newIndex[t[1]], newIndex[t[2]]});
    if (statsOut) *statsOut = stats;
    return out;
}

TriangleMesh cleanMesh(const TriangleMesh& mesh, CleanStats* stats) {
    return cleanMesh(mesh, weldTolerance(mesh.vertices), stats);
}

}  // namespace tumble::mesh
