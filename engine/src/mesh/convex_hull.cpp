// Convex hulls through qhull's reentrant C API. qhull merges coplanar facets by default
// ('C-0' in 3-d), so a box's hull comes back as 6 quads; what it does not give is a
// vertex order for a merged facet, so each face's vertices are sorted here by angle about
// their centroid in the face plane (valid because every face is a convex polygon).
// Degenerate input is refused before qhull sees it, with a reason a user can act on;
// anything qhull still refuses is reported with the first line of its own message.
#include <tumble/convex_hull.h>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

namespace tumble::mesh {

using collision::ConvexHull;

namespace {

// Sorts a convex polygon's vertices counter-clockwise seen from the side `normal` points to.
void orderCounterClockwise(std::vector<int>& face, const Vec3& normal, const std::vector<Vec3>& vertices) {
    Vec3 centroid = Vec3::Zero();
    for (int v : face) centroid += vertices[v];
    centroid /= static_cast<double>(face.size());
    const Vec3 u = normal.unitOrthogonal();
    const Vec3 w = normal.cross(u);  // (u, w, normal) is right-handed
    std::vector<std::pair<double, int>> byAngle;
    byAngle.reserve(face.size());
    for (int v : face) {
        const Vec3 d = vertices[v] - centroid;
        byAngle.emplace_back(std::atan2(d.dot(w), d.dot(u)), v);
    }
    std::sort(byAngle.begin(), byAngle.end());
    for (size_t k = 0; k < face.size(); ++k) face[k] = byAngle[k].second;
}

// A face as found: its outward normal and its vertices in any order.
struct RawFace {
    Vec3 normal;
    std::vector<int> vertices;
};

// The hull's faces from `raw`: each face's vertices in order, its plane, and the edges; every
// list exactly as long as it needs to be (a hull is made once and kept as long as its body).
void finish(ConvexHull& hull, std::vector<RawFace>& raw) {
    std::set<std::array<int, 2>> edges;
    size_t indices = 0;
    for (const RawFace& f : raw) indices += f.vertices.size();
    hull.faces.clear();
    hull.faces.reserve(raw.size());
    hull.faceVertices.clear();
    hull.faceVertices.reserve(indices);
    for (RawFace& f : raw) {
        orderCounterClockwise(f.vertices, f.normal, hull.vertices);
        // The plane through the face's own vertices, placed so that none is outside it.
        double offset = -std::numeric_limits<double>::infinity();
        for (int v : f.vertices) offset = std::max(offset, f.normal.dot(hull.vertices[v]));
        for (size_t k = 0; k < f.vertices.size(); ++k) {
            const int a = f.vertices[k];
            const int b = f.vertices[(k + 1) % f.vertices.size()];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
        hull.addFace(f.normal, offset, f.vertices);
    }
    hull.vertices.shrink_to_fit();
    hull.edges.assign(edges.begin(), edges.end());
    hull.interiorPoint = Vec3::Zero();
    for (const Vec3& v : hull.vertices) hull.interiorPoint += v;
    hull.interiorPoint /= static_cast<double>(hull.vertices.size());
}

// Refuses input that has no 3-d hull, saying why: qhull's own messages for these cases
// ("initial simplex is flat") are accurate but cryptic.
void checkSpansSpace(const std::vector<Vec3>& points) {
    if (points.size() < 4) {
        throw HullError("a convex hull needs at least 4 points that are not on one plane; there are " +
                        std::to_string(points.size()));
    }
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) {
        if (!p.allFinite()) throw HullError("a point is not finite");
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double size = (hi - lo).norm();
    if (!(size > 0.0)) throw HullError("all points coincide");
    if (!std::isfinite(size)) throw HullError("the points are too far apart to be represented");
    // A well-spread triangle of the cloud, as qhull picks its initial simplex: the plane of
    // a flat cloud is then known to rounding, and so is its thickness off that plane.
    const double flat = 1e-10 * size;
    const Vec3& a = *std::min_element(points.begin(), points.end(),
                                      [](const Vec3& p, const Vec3& q) { return p.x() < q.x(); });
    auto farthest = [&](auto&& distance) {
        return *std::max_element(points.begin(), points.end(),
                                 [&](const Vec3& p, const Vec3& q) { return distance(p) < distance(q); });
    };
    const Vec3 b = farthest([&](const Vec3& p) { return (p - a).norm(); });
    const Vec3 axis = (b - a).normalized();
    auto offLine = [&](const Vec3& p) { return (p - a - axis.dot(p - a) * axis).norm(); };
    const Vec3 c = farthest(offLine);
    if (offLine(c) <= flat) throw HullError("all points lie on one line");
    const Vec3 normal = (b - a).cross(c - a).normalized();
    auto offPlane = [&](const Vec3& p) { return std::abs(normal.dot(p - a)); };
    if (offPlane(farthest(offPlane)) <= flat)
        throw HullError("all points lie on one plane (the mesh is flat)");
}

std::string firstLine(const std::string& text) {
    const auto end = text.find('\n');
    return end == std::string::npos ? text : text.substr(0, end);
}

}  // namespace

ConvexHull convexHull(const std::vector<Vec3>& points) {
    checkSpansSpace(points);
    std::vector<coordT> coords;
    coords.reserve(3 * points.size());
    for (const Vec3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});

    // qhull prints its errors to a FILE; keep them for the message instead of stderr.
    char* errText = nullptr;
    size_t errSize = 0;
    FILE* errFile = open_memstream(&errText, &errSize);
    qhT qhStorage;
    qhT* qh = &qhStorage;
    QHULL_LIB_CHECK
    qh_zero(qh, errFile);
    char options[] = "qhull";
    const int exitCode =
        qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr, errFile);
    ConvexHull hull;
    std::vector<RawFace> raw;
    if (exitCode == 0) {
        // Hull vertices in the order of the input points, so the result does not depend
        // on qhull's internal lists.
        std::vector<int> used;
        vertexT* vertex;
        FORALLvertices used.push_back(qh_pointid(qh, vertex->point));
        std::sort(used.begin(), used.end());
        std::map<int, int> index;
        for (int id : used) {
            index[id] = static_cast<int>(hull.vertices.size());
            hull.vertices.push_back(points[static_cast<size_t>(id)]);
        }
        facetT* facet;
        vertexT** vertexp;
        FORALLfacets {
            RawFace f;
            f.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]).normalized();
            FOREACHvertex_(facet->vertices) f.vertices.push_back(index.at(qh_pointid(qh, vertex->point)));
            raw.push_back(std::move(f));
        }
    }
    int curLong = 0, totLong = 0;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curLong, &totLong);
    std::fclose(errFile);
    const std::string message = errText ? firstLine(errText) : std::string();
    std::free(errText);
    if (exitCode != 0) {
        throw HullError("qhull could not build the hull: " +
                        (message.empty() ? "error " + std::to_string(exitCode) : message));
    }
    finish(hull, raw);
    return hull;
}

ConvexHull boxHull(const Vec3& h) {
    ConvexHull hull;
    // Vertex k has the sign of +x when bit 0 is set, +y for bit 1, +z for bit 2.
    for (int k = 0; k < 8; ++k) {
        hull.vertices.emplace_back(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z());
    }
    std::vector<RawFace> raw;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            RawFace f;
            f.normal = Vec3::Zero();
            f.normal[axis] = side ? 1.0 : -1.0;
            for (int k = 0; k < 8; ++k) {
                if (((k >> axis) & 1) == side) f.vertices.push_back(k);
            }
            raw.push_back(std::move(f));
        }
    }
    finish(hull, raw);
    hull.interiorPoint = Vec3::Zero();  // exact, rather than a mean that rounds
    return hull;
}

}  // namespace tumble::mesh
