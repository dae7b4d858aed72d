// convexParts: a closed mesh of one piece is split as one solid (convex_parts.cpp); a mesh
// of several pieces (a spider's body, head and leg segments, each closed on its own and
// overlapping where they meet) is split piece by piece, each given a share of the parts by
// its volume, and the parts then merged back down to the number asked for, the pair whose
// joint hull adds least volume first. Pieces are split apart because a ray's crossings tell
// inside from outside only within one closed surface: where two pieces overlap, the
// crossings of both are counted and the overlap would look like a hole.
#include <tumble/convex_hull.h>
#include <tumble/convex_parts.h>

#include "mesh/convex_split.h"
#include "mesh/mesh_holes.h"
#include "mesh/solid_frame.h"
#include "mesh/triangle_buckets.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tumble::mesh {

namespace {

struct Part {
    collision::ConvexHull hull;
    double volume = 0.0;
    double reach = 0.0;  // how far it reaches out of the solid, as measured
};

bool inHull(const collision::ConvexHull& h, const Vec3& x) {
    return std::all_of(h.faces.begin(), h.faces.end(),
                       [&](const auto& f) { return f.normal.dot(x) <= f.offset; });
}

// The solid of all the pieces together: inside any one, or how far from the nearest.
class Union {
public:
    explicit Union(const std::vector<TriangleMesh>& shells) {
        pieces_.reserve(shells.size());
        for (const TriangleMesh& s : shells) pieces_.emplace_back(s);
    }
    double outside(const Vec3& x) const {
        double d = std::numeric_limits<double>::infinity();
        for (const Buckets& b : pieces_) {
            if (b.inside(x)) return 0.0;
            d = std::min(d, b.distance(x));
        }
        return d;
    }

private:
    std::vector<Buckets> pieces_;
};

// How far the hull of a and b reaches out of the solid: a's and b's own reaches, and samples
// of the joint hull outside both, on a grid of `step` (at most 24 a side).
double jointReach(const collision::ConvexHull& joint, const Part& a, const Part& b, const Union& solid,
                  double step) {
    collision::Aabb box;
    for (const Vec3& v : joint.vertices) box.add(v);
    const Vec3 extent = box.extent();
    step = std::max(step, extent.maxCoeff() / 24.0);
    double reach = std::max(a.reach, b.reach);
    auto look = [&](const Vec3& x) {
        if (!inHull(a.hull, x) && !inHull(b.hull, x)) reach = std::max(reach, solid.outside(x));
    };
    for (const Vec3& v : joint.vertices) look(v);
    const int n[3] = {static_cast<int>(extent.x() / step) + 1, static_cast<int>(extent.y() / step) + 1,
                      static_cast<int>(extent.z() / step) + 1};
    for (int i = 0; i < n[0]; ++i)
        for (int j = 0; j < n[1]; ++j)
            for (int k = 0; k < n[2]; ++k) {
                const Vec3 x = box.min + step * Vec3(i + 0.5, j + 0.5, k + 0.5);
                if (inHull(joint, x)) look(x);
            }
    return reach;
}

// The hull of a's and b's vertices (false where it cannot be made).
bool jointHull(const Part& a, const Part& b, collision::ConvexHull& out) {
    std::vector<Vec3> points = a.hull.vertices;
    points.insert(points.end(), b.hull.vertices.begin(), b.hull.vertices.end());
    try {
        out = convexHull(points);
    } catch (const HullError&) {
        return false;
    }
    return true;
}

// Merges parts down to `count`, the pair whose joint hull adds least volume first.
void mergeDown(std::vector<Part>& parts, int count, const Union& solid, double step,
               const std::function<void()>& check) {
    const double inf = std::numeric_limits<double>::infinity();
    auto costOf = [&](int i, int j) {
        collision::ConvexHull joint;
        if (!jointHull(parts[i], parts[j], joint)) return inf;
        return hullVolume(joint) - parts[i].volume - parts[j].volume;
    };
    const int n = static_cast<int>(parts.size());
    std::vector<std::vector<double>> cost(n, std::vector<double>(n, inf));
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) cost[i][j] = costOf(i, j);
    while (static_cast<int>(parts.size()) > count) {
        check();
        const int m = static_cast<int>(parts.size());
        int a = -1, b = -1;
        for (int i = 0; i < m; ++i)
            for (int j = i + 1; j < m; ++j)
                if (std::isfinite(cost[i][j]) && (a < 0 || cost[i][j] < cost[a][b])) a = i, b = j;
        if (a < 0) break;
        Part merged;
        jointHull(parts[a], parts[b], merged.hull);
        merged.volume = hullVolume(merged.hull);
        merged.reach = jointReach(merged.hull, parts[a], parts[b], solid, step);
        parts[a] = std::move(merged);
        parts.erase(parts.begin() + b);
        cost.erase(cost.begin() + b);
        for (auto& row : cost) row.erase(row.begin() + b);
        for (int i = 0; i < m - 1; ++i)
            if (i < a)
                cost[i][a] = costOf(i, a);
            else if (i > a)
                cost[a][i] = costOf(a, i);
    }
}

}  // namespace

ConvexParts convexParts(const TriangleMesh& mesh, const ConvexPartsOptions& options,
                        const ConvexPartsProgress& progress) {
    if (mesh.triangles.empty()) throw std::invalid_argument("convex parts: the mesh has no triangles");
    if (!isClosed(mesh))
        throw std::invalid_argument("convex parts: the mesh is not closed (it bounds no solid)");
    if (options.maxParts < 1 || options.maxParts > 256)
        throw std::invalid_argument("convex parts: max_parts must be from 1 to 256");
    if (options.resolution < 8 || options.resolution > 256)
        throw std::invalid_argument("convex parts: the resolution must be from 8 to 256");
    const std::vector<TriangleMesh> shells = shellsOf(mesh);
    for (std::size_t k = 0; k < shells.size(); ++k)
        if (meshVolume(shells[k]) <= 0)
            throw std::invalid_argument(
                shells.size() == 1 ? std::string("convex parts: the mesh faces inwards or is flat")
                                   : "convex parts: piece " + std::to_string(k + 1) + " of the mesh's " +
                                         std::to_string(shells.size()) + " faces inwards or is flat");
    if (progress && !progress(0.0)) throw ConvexPartsStopped();
    if (shells.size() == 1) return splitShell(mesh, options, options.tolerance, progress);

    // The tolerance's default from the whole mesh (1 % of its box's diagonal in its frame).
    double tolerance = options.tolerance;
    if (tolerance <= 0.0) {
        const collision::Pose frame = solidFrame(mesh);
        collision::Aabb box;
        for (const Vec3& v : mesh.vertices) box.add(frame.toLocal(v));
        tolerance = 0.01 * box.extent().norm();
    }
    double total = 0.0;
    for (const TriangleMesh& s : shells) total += meshVolume(s);
    ConvexParts out;
    out.tolerance = tolerance;
    std::vector<Part> parts;
    double done = 0.0;  // of the split's share of the progress
    for (const TriangleMesh& shell : shells) {
        const double share = meshVolume(shell) / total;
        const ConvexParts split = splitShell(shell, options, tolerance, [&](double d) {
            return !progress || progress(0.9 * (done + share * d));
        });
        out.meshVolume += split.meshVolume;
        for (std::size_t k = 0; k < split.parts.size(); ++k)
            parts.push_back({split.parts[k], hullVolume(split.parts[k]), split.reachOut[k]});
        done += share;
    }
    const Union solid(shells);
    mergeDown(parts, options.maxParts, solid, tolerance / 3.0, [&] {
        if (progress && !progress(0.95)) throw ConvexPartsStopped();
    });
    out.withinTolerance = true;
    for (Part& p : parts) {
        out.largestPokeOut = std::max(out.largestPokeOut, p.reach);
        out.withinTolerance = out.withinTolerance && p.reach <= tolerance;
        out.partsVolume += p.volume;
        out.reachOut.push_back(p.reach);
        out.parts.push_back(std::move(p.hull));
    }
    return out;
}

}  // namespace tumble::mesh
