// The paper's collision tests as the reference method. Every loop is exhaustive and every
// test is the plain one: correctness is the point here, speed is the fast paths' business.
#include "collision/reference.h"

#include "collision/bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <utility>

namespace tumble::collision::reference {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Box corners: bit 0 picks +x, bit 1 +y, bit 2 +z. Faces counter-clockwise from outside.
const int kBoxQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

Polyhedron boxPolyhedron(const Vec3& h, const Pose& pose) {
    Polyhedron poly;
    for (int i = 0; i < 8; ++i) {
        const Vec3 local(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
        poly.vertices.push_back(pose.toWorld(local));
    }
    for (const auto& q : kBoxQuads) poly.faces.push_back({Vec3::Zero(), 0.0, {q[0], q[1], q[2], q[3]}});
    return poly;
}

// Normal and offset of every face from its first three vertices (planar polygons).
void facePlanes(Polyhedron& poly) {
    for (auto& f : poly.faces) {
        const Vec3& a = poly.vertices[f.vertices[0]];
        const Vec3 n = (poly.vertices[f.vertices[1]] - a).cross(poly.vertices[f.vertices[2]] - a);
        const double len = n.norm();
        f.normal = len > 0.0 ? Vec3(n / len) : Vec3::Zero();  // zero: a degenerate triangle
        f.offset = f.normal.dot(a);
    }
}

void edgesFromFaces(Polyhedron& poly) {
    std::set<std::pair<int, int>> edges;
    for (const auto& f : poly.faces) {
        const int n = static_cast<int>(f.vertices.size());
        for (int k = 0; k < n; ++k) {
            const int i = f.vertices[k], j = f.vertices[(k + 1) % n];
            if (i != j) edges.insert({std::min(i, j), std::max(i, j)});
        }
    }
    for (const auto& [i, j] : edges) poly.edges.push_back({i, j});
}

// Strictly between the two sides, or on a face polygon: helpers for the crossing test.
bool insidePolygon(const Polyhedron& poly, const Polyhedron::Face& f, const Vec3& x) {
    const int n = static_cast<int>(f.vertices.size());
    for (int k = 0; k < n; ++k) {
        const Vec3& a = poly.vertices[f.vertices[k]];
        const Vec3& b = poly.vertices[f.vertices[(k + 1) % n]];
        if ((b - a).cross(x - a).dot(f.normal) < 0.0) return false;
    }
    return true;
}

std::uint64_t splitmix(std::uint64_t& s) {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// One ray against one triangle, mesh frame. Counts a clean crossing, flags a crossing near
// an edge or a vertex (or a ray in the triangle's plane) as ambiguous.
struct RayCount {
    int crossings = 0;
    bool ambiguous = false;
    double nearest = kInf;
};

void rayTriangle(const Vec3& o, const Vec3& d, const Vec3& v0, const Vec3& v1, const Vec3& v2,
                 double originTol, RayCount& rc) {
    const Vec3 n = (v1 - v0).cross(v2 - v0);
    const double area2 = n.norm();
    if (area2 == 0.0) return;  // degenerate: its neighbours carry the surface
    const Vec3 nh = n / area2;
    const double s0 = nh.dot(o - v0);
    const double dn = nh.dot(d);
    if (dn == 0.0) {
        if (std::abs(s0) <= originTol) rc.ambiguous = true;  // the ray runs in its plane
        return;
    }
    const double t = -s0 / dn;
    if (t <= originTol) return;  // behind, or the origin lies on it
    const Vec3 x = o + t * d;
    const double b0 = nh.dot((v1 - x).cross(v2 - x)) / area2;
    const double b1 = nh.dot((v2 - x).cross(v0 - x)) / area2;
    const double b2 = 1.0 - b0 - b1;
    // Tolerance in barycentric units: a fixed 1e-9 of the triangle, or the rounding of the
    // crossing (grows as the ray grazes the plane: the error of t is amplified by 1/|dn|).
    const double longest = std::max({(v1 - v0).norm(), (v2 - v1).norm(), (v0 - v2).norm()});
    const double height = area2 / longest;
    const double scale = (o - v0).norm() + t + longest;
    const double tol = 1e-9 + 64.0 * kEps * scale / (height * std::abs(dn));
    const double lo = std::min({b0, b1, b2});
    if (lo < -tol) return;
    if (lo <= tol) {
        rc.ambiguous = true;
        return;
    }
    ++rc.crossings;
    rc.nearest = std::min(rc.nearest, t);
}

}  // namespace

double planeValue(const Vec3& n, double d, const Vec3& p) {
    return n.dot(p) + d;
}

Polyhedron worldPolyhedron(const Shape& shape, const Pose& pose) {
    Polyhedron poly;
    switch (shape.kind) {
        case Kind::Box:
            poly = boxPolyhedron(shape.halfExtents, pose);
            facePlanes(poly);
            edgesFromFaces(poly);
            return poly;
        case Kind::Hull: {
            const ConvexHull& h = *shape.hull;
            for (const Vec3& v : h.vertices) poly.vertices.push_back(pose.toWorld(v));
            for (const auto& f : h.faces) {
                const Vec3 n = pose.directionToWorld(f.normal);
                const std::span<const int> v = h.verticesOf(f);
                poly.faces.push_back({n, f.offset + n.dot(pose.p), std::vector<int>(v.begin(), v.end())});
            }
            poly.edges = h.edges;
            return poly;
        }
        case Kind::Mesh: {
            const MeshShape& m = *shape.mesh;
            for (const Vec3& v : m.vertices) poly.vertices.push_back(pose.toWorld(v));
            for (const auto& t : m.triangles) poly.faces.push_back({Vec3::Zero(), 0.0, {t[0], t[1], t[2]}});
            facePlanes(poly);
            edgesFromFaces(poly);
            poly.convex = false;
            poly.closed = m.closed;
            return poly;
        }
        default: break;
    }
    throw std::invalid_argument(std::string("reference: not a polyhedron: ") + toString(shape.kind));
}

std::vector<PlaneHit> pointsAgainstPlane(const std::vector<Vec3>& points, const Vec3& n, double offset,
                                         double margin) {
    std::vector<PlaneHit> hits;
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
        const double e = planeValue(n, -offset, points[i]);
        if (e < margin) hits.push_back({i, -e});
    }
    return hits;
}

Inside pointInConvex(const Polyhedron& body, const Vec3& p) {
    Inside in;
    double worst = -kInf;  // max over the faces of E(p)
    for (int f = 0; f < static_cast<int>(body.faces.size()); ++f) {
        const auto& face = body.faces[f];
        const double e = planeValue(face.normal, -face.offset, p);
        if (e > worst) {
            worst = e;
            in.face = f;
        }
    }
    in.inside = worst < 0.0;
    in.depth = -worst;
    if (in.face >= 0) in.normal = body.faces[in.face].normal;
    return in;
}

Inside pointInConvex(const ConvexHull& hull, const Pose& pose, const Vec3& p) {
    Shape s;
    s.kind = Kind::Hull;
    s.hull = std::shared_ptr<const ConvexHull>(&hull, [](const ConvexHull*) {});
    return pointInConvex(worldPolyhedron(s, pose), p);
}

Vec3 parityRayDirection(int k) {
    std::uint64_t s = 0x5eed0000ull + static_cast<std::uint64_t>(k);
    const double u = static_cast<double>(splitmix(s) >> 11) * 0x1.0p-53;
    const double v = static_cast<double>(splitmix(s) >> 11) * 0x1.0p-53;
    const double z = 2.0 * u - 1.0;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * std::numbers::pi * v;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z).normalized();
}

Parity rayParity(const MeshShape& mesh, const Vec3& o) {
    // The mesh's reach from o, for the tolerance of "at the origin": the BVH's box when there
    // is one (this runs once per vertex of the other mesh in collideMeshMesh).
    double size = 0.0;
    if (mesh.bvh && !mesh.bvh->bounds().empty()) {
        const Aabb& b = mesh.bvh->bounds();
        size = std::max((b.max - o).cwiseAbs().maxCoeff(), (b.min - o).cwiseAbs().maxCoeff());
    } else {
        for (const Vec3& v : mesh.vertices) size = std::max(size, (v - o).cwiseAbs().maxCoeff());
    }
    const double originTol = 1e-12 * size;
    Parity result;
    for (int k = 0; k < kMaxParityRays; ++k) {
        const Vec3 d = parityRayDirection(k);
        RayCount rc;
        auto visit = [&](int t) {
            const auto& tri = mesh.triangles[t];
            rayTriangle(o, d, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]], originTol,
                        rc);
        };
        if (mesh.bvh) {
            mesh.bvh->raycast(o, d, kInf, visit);
        } else {
            for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) visit(t);
        }
        result.rays = k + 1;
        result.inside = rc.crossings % 2 == 1;
        result.nearestHit = rc.nearest;
        if (!rc.ambiguous) break;
    }
    return result;
}

bool pointInMesh(const MeshShape& mesh, const Pose& pose, const Vec3& p, int* rays) {
    const Parity r = rayParity(mesh, pose.toLocal(p));
    if (rays) *rays = r.rays;
    return r.inside;
}

double distanceToSurface(const Polyhedron& body, const Vec3& p, Vec3& closest, int* face) {
    double best = kInf;
    for (int f = 0; f < static_cast<int>(body.faces.size()); ++f) {
        const auto& vs = body.faces[f].vertices;
        for (std::size_t k = 1; k + 1 < vs.size(); ++k) {  // fan: the polygons are convex
            const Vec3 q = closestPointOnTriangle(p, body.vertices[vs[0]], body.vertices[vs[k]],
                                                  body.vertices[vs[k + 1]]);
            const double d = (q - p).norm();
            if (d < best) {
                best = d;
                closest = q;
                if (face) *face = f;
            }
        }
    }
    return best;
}

std::vector<EdgeFaceCrossing> edgeFaceCrossings(const Polyhedron& e, const Polyhedron& f) {
    std::vector<EdgeFaceCrossing> out;
    for (int i = 0; i < static_cast<int>(e.edges.size()); ++i) {
        const Vec3& p0 = e.vertices[e.edges[i][0]];
        const Vec3& p1 = e.vertices[e.edges[i][1]];
        for (int j = 0; j < static_cast<int>(f.faces.size()); ++j) {
            const auto& face = f.faces[j];
            if (face.normal.isZero()) continue;
            const double e0 = planeValue(face.normal, -face.offset, p0);
            const double e1 = planeValue(face.normal, -face.offset, p1);
            // A strict change of sign of (19) along the edge: it crosses the face's plane.
            if (!((e0 < 0.0 && e1 > 0.0) || (e0 > 0.0 && e1 < 0.0))) continue;
            const double t = e0 / (e0 - e1);
            const Vec3 x = p0 + t * (p1 - p0);
            if (insidePolygon(f, face, x)) out.push_back({i, j, t, x});
        }
    }
    return out;
}

double overlapAlong(const Polyhedron& a, const Polyhedron& b, const Vec3& n) {
    double maxB = -kInf, minA = kInf;
    for (const Vec3& v : b.vertices) maxB = std::max(maxB, n.dot(v));
    for (const Vec3& v : a.vertices) minA = std::min(minA, n.dot(v));
    return maxB - minA;
}

std::vector<AxisOverlap> separatingAxes(const Polyhedron& a, const Polyhedron& b) {
    std::vector<AxisOverlap> axes;
    // Both signs of each candidate: an extra direction only adds an overlap that is not
    // smaller than the minimum.
    auto consider = [&](const Vec3& n) {
        axes.push_back({n, overlapAlong(a, b, n)});
        axes.push_back({-n, overlapAlong(a, b, -n)});
    };
    for (const auto& f : b.faces) consider(f.normal);
    for (const auto& f : a.faces) consider(f.normal);
    for (const auto& ea : a.edges) {
        const Vec3 da = a.vertices[ea[1]] - a.vertices[ea[0]];
        for (const auto& eb : b.edges) {
            const Vec3 db = b.vertices[eb[1]] - b.vertices[eb[0]];
            const Vec3 u = da.cross(db);
            if (u.norm() <= 1e-9 * da.norm() * db.norm()) continue;
            consider(u.normalized());
        }
    }
    return axes;
}

namespace {

// The separating-axis minimum over the candidate axes (the first of equal ones).
void separatingAxisMinimum(const Polyhedron& a, const Polyhedron& b, RefContacts& rc) {
    rc.depth = kInf;
    for (const AxisOverlap& ax : separatingAxes(a, b)) {
        if (ax.overlap < rc.depth) {
            rc.depth = ax.overlap;
            rc.normal = ax.axis;
        }
    }
}

// Vertices of `body` inside `other` as reference points (normal out of `other`).
void verticesInside(const Polyhedron& body, const Polyhedron& other, const Shape& otherShape,
                    const Pose& otherPose, RefPoint::Kind kind, double sign, RefContacts& rc) {
    for (int i = 0; i < static_cast<int>(body.vertices.size()); ++i) {
        const Vec3& v = body.vertices[i];
        RefPoint pt;
        pt.kind = kind;
        pt.position = v;
        pt.feature = i;
        if (other.convex) {
            const Inside in = pointInConvex(other, v);
            if (!in.inside) continue;
            pt.depth = in.depth;
            pt.normal = sign * in.normal;
            pt.face = in.face;
        } else {
            if (!other.closed || !pointInMesh(*otherShape.mesh, otherPose, v)) continue;
            Vec3 c;
            pt.depth = distanceToSurface(other, v, c, &pt.face);
            // The way out is towards the closest surface point; on the surface, its face.
            pt.normal = sign * (pt.depth > 0.0 ? Vec3((c - v) / pt.depth) : other.faces[pt.face].normal);
        }
        rc.points.push_back(pt);
    }
}

RefContacts againstPlane(const Shape& a, const Pose& pa, const Shape& plane, const Pose& pp) {
    const Vec3 n = pp.directionToWorld(plane.normal);
    const double offset = plane.distance + n.dot(pp.p);
    const Polyhedron A = worldPolyhedron(a, pa);
    RefContacts rc;
    rc.normal = n;
    rc.depth = -kInf;
    for (const Vec3& v : A.vertices) rc.depth = std::max(rc.depth, -planeValue(n, -offset, v));
    for (const PlaneHit& h : pointsAgainstPlane(A.vertices, n, offset, 0.0)) {
        if (h.depth <= 0.0) continue;  // on the plane: touching, not penetrating
        rc.points.push_back({RefPoint::Kind::VertexOfAInB, A.vertices[h.vertex], n, h.depth, h.vertex, 0});
    }
    rc.penetrating = !rc.points.empty();
    return rc;
}

}  // namespace

RefContacts referenceContacts(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
    if (b.kind == Kind::Plane) return againstPlane(a, pa, b, pb);
    if (a.kind == Kind::Plane) {
        RefContacts rc = againstPlane(b, pb, a, pa);
        rc.normal = -rc.normal;
        for (auto& p : rc.points) {
            p.kind = RefPoint::Kind::VertexOfBInA;
            p.normal = -p.normal;
        }
        return rc;
    }
    const Polyhedron A = worldPolyhedron(a, pa);
    const Polyhedron B = worldPolyhedron(b, pb);
    RefContacts rc;
    verticesInside(A, B, b, pb, RefPoint::Kind::VertexOfAInB, 1.0, rc);
    verticesInside(B, A, a, pa, RefPoint::Kind::VertexOfBInA, -1.0, rc);
    for (const auto& c : edgeFaceCrossings(A, B))
        rc.points.push_back(
            {RefPoint::Kind::EdgeOfAFaceOfB, c.point, B.faces[c.face].normal, 0.0, c.edge, c.face});
    for (const auto& c : edgeFaceCrossings(B, A))
        rc.points.push_back(
            {RefPoint::Kind::EdgeOfBFaceOfA, c.point, -A.faces[c.face].normal, 0.0, c.edge, c.face});
    rc.penetrating = !rc.points.empty();
    if (A.convex && B.convex) {
        separatingAxisMinimum(A, B, rc);
    } else {
        // The deepest point; with crossings only (depth 0), the first crossing's face.
        rc.depth = 0.0;
        if (rc.penetrating) rc.normal = rc.points.front().normal;
        for (const auto& p : rc.points) {
            if (p.depth > rc.depth) {
                rc.depth = p.depth;
                rc.normal = p.normal;
            }
        }
    }
    return rc;
}

}  // namespace tumble::collision::reference
