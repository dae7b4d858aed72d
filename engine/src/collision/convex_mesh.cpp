// A convex shape against a triangle mesh: each triangle the convex's box touches (through
// the mesh's BVH) is a convex proxy of its own, met with GJK/EPA and clipped like any face.
// Before GJK, exact shortcuts: the triangle's plane, or a plane through one of its edges
// square to it, with the whole convex beyond it by more than the margin: no contact; the
// convex resting on the face (centre in front, lowest point over the triangle and crossing
// its plane inside it): the face's normal and depth, as below, without GJK/EPA.
//
// Internal edges: a convex sliding over a flat mesh meets the next triangle at its edge,
// where EPA's shortest way out can be sideways across that edge (a "ghost" contact that
// snags the slide). Without adjacency data the remedy is heuristic, in two passes:
// 1. a contact whose normal is the triangle's face normal (to ~0.1 deg), or within 10 deg
//    of it with the contact inside the triangle, takes the face normal exactly;
// 2. an edge or vertex contact takes its triangle's face normal too when the convex's
//    centre is in front of that triangle and the depth along the face normal is no more
//    than the deepest face contact of pass 1 (plus the margin and 5%): the convex is
//    resting on a surface that continues across the edge, not hitting the edge.
// A real outer edge (a table's rim) has no face contact that deep beside it, so it keeps
// its EPA normal. Contacts of similar normals (within ~5 deg) share a manifold.
#include "collision/bvh.h"
#include "collision/clip.h"
#include "collision/convex.h"
#include "collision/gjk.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::collision {

namespace {

constexpr double kExactFace = 1.0 - 1e-6;
constexpr double kNearFace = 0.985;  // cos(~10 deg)
constexpr double kInterior = 1e-6;   // barycentric weight below which a point is on an edge
constexpr double kGroupCos = 0.996;  // cos(~5 deg): one manifold

struct TriContact {
    int tri;
    ConvexProxy proxy;
    Vec3 faceNormal;
    Penetration pen;
    bool face;
};

// Barycentric weights of q (assumed in the plane) in the triangle.
Vec3 barycentric(const std::array<Vec3, 3>& t, const Vec3& q) {
    const Vec3 e0 = t[1] - t[0], e1 = t[2] - t[0], d = q - t[0];
    const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = d.dot(e0), d21 = d.dot(e1);
    const double den = d00 * d11 - d01 * d01;
    if (!(den > 0)) return Vec3(1, 0, 0);
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    return Vec3(1 - v - w, v, w);
}

// The penetration of the convex into the triangle's plane along its face normal n.
Penetration alongFace(const ConvexProxy& A, const ConvexProxy& T, const Vec3& n) {
    Penetration p;
    p.normal = n;
    p.pointA = A.support(-n) - A.radius * n;
    p.depth = (T.triangle[0] - p.pointA).dot(n);
    p.pointB = p.pointA + p.depth * n;
    p.hit = true;
    return p;
}

template <class Visit>
void trianglesNear(const MeshShape& m, const Aabb& box, Visit&& visit) {
    if (m.bvh) {
        m.bvh->query(box, visit);
        return;
    }
    for (int i = 0; i < static_cast<int>(m.triangles.size()); ++i) {
        Aabb t;
        for (int k : m.triangles[i]) t.add(m.vertices[k]);
        if (t.overlaps(box)) visit(i);
    }
}

}  // namespace

void collideConvexMesh(const Shape& convex, const Pose& pc, const Shape& meshShape, const Pose& pm,
                       double margin, ManifoldList& out) {
    const MeshShape& mesh = *meshShape.mesh;
    const ConvexProxy A = proxyOf(convex, pc);
    const Vec3 centre = A.center();
    Pose rel;  // the convex in the mesh frame
    rel.R = pm.R.transpose() * pc.R;
    rel.p = pm.R.transpose() * (pc.p - pm.p);
    const Aabb box = bounds(convex, rel).inflated(std::max(margin, 0.0));

    // Scratch kept per thread between calls (the worker pool runs pairs side by side): the
    // lists of a call were a good part of its cost in hull-rain (allocation per pair).
    struct Group {
        Vec3 normal;
        std::vector<detail::Candidate> points;
    };
    struct Scratch {
        std::vector<TriContact> contacts;
        std::vector<Group> groups;  // the first `used` are this call's
        std::vector<detail::Candidate> points;
    };
    thread_local Scratch scratch;
    std::vector<TriContact>& contacts = scratch.contacts;
    contacts.clear();
    double deepestFace = -std::numeric_limits<double>::infinity();
    trianglesNear(mesh, box, [&](int i) {
        const auto& tri = mesh.triangles[i];
        const ConvexProxy T =
            triangleProxy(pm.toWorld(mesh.vertices[tri[0]]), pm.toWorld(mesh.vertices[tri[1]]),
                          pm.toWorld(mesh.vertices[tri[2]]));
        const Vec3 n = (T.triangle[1] - T.triangle[0]).cross(T.triangle[2] - T.triangle[0]);
        if (!(n.squaredNorm() > 0)) return;  // degenerate triangle: its neighbours cover it
        const Vec3 nt = n.normalized();
        // The triangle's plane separates when the whole convex lies farther than the margin
        // on one side of it: then GJK would find no contact either.
        const double reach = std::max(margin, 0.0) + A.radius;
        const Vec3 low = A.support(-nt);
        const double below = (low - T.triangle[0]).dot(nt);  // the core's lowest point over the plane
        if (below > reach || (A.support(nt) - T.triangle[0]).dot(nt) < -reach) return;
        // Resting on the face, without GJK/EPA (hull-rain: two thirds of the hull-triangle
        // pairs): the core's centre in front of the plane, its lowest point over the
        // triangle, and the place where it meets the plane (that point's foot, or where the
        // way from the centre down to it crosses the plane) inside the triangle too. The
        // core then reaches the triangle there, from in front, and the face's normal and
        // depth are the contact's. (The lowest point alone is not enough: a box tipping
        // over a table's rim hangs its lowest corner below the top's plane, beyond the
        // rim, and must not be lifted by that corner's depth.)
        const double above = (centre - T.triangle[0]).dot(nt);
        bool onFace = false;
        if (above > 0.0) {
            const Vec3 foot = low - below * nt;
            const Vec3 meet = below >= 0.0 ? foot : Vec3(low + (centre - low) * (-below / (above - below)));
            const Vec3 w = barycentric(T.triangle, meet);
            onFace = w.minCoeff() > kInterior && (below >= 0.0 || barycentric(T.triangle, foot).minCoeff() > kInterior);
            // Beside the triangle: the plane through an edge the meeting place is beyond,
            // square to the triangle, separates when the whole core lies past it by more
            // than the reach (the neighbour's triangle holds the contact, if any).
            for (int e = 0; e < 3 && !onFace; ++e) {
                if (w[e] > kInterior) continue;
                const Vec3& p = T.triangle[(e + 1) % 3];
                Vec3 side = (T.triangle[(e + 2) % 3] - p).cross(nt);
                if (side.dot(T.triangle[e] - p) > 0.0) side = -side;
                side.normalize();
                if ((A.support(-side) - p).dot(side) > reach) return;
            }
        }
        Penetration pen;
        bool face = onFace;
        if (!onFace) {
            pen = penetration(A, T, margin);
            if (!pen.hit) return;
            const double c = pen.normal.dot(nt);
            const Vec3 w = barycentric(T.triangle, pen.pointB);
            const bool interior = w.minCoeff() > kInterior;
            face = c >= kExactFace || (c >= kNearFace && interior);
        }
        if (face) {
            pen = alongFace(A, T, nt);
            if (!(pen.depth > -margin)) return;
            deepestFace = std::max(deepestFace, pen.depth);
        }
        contacts.push_back({i, T, nt, pen, face});
    });

    const double scale = A.size() + A.radius;
    const double slack = std::max(margin, 0.0) + 0.05 * std::max(deepestFace, 0.0) + 1e-9 * scale;
    std::vector<Group>& groups = scratch.groups;
    std::vector<detail::Candidate>& points = scratch.points;
    std::size_t used = 0;
    for (TriContact& c : contacts) {
        if (!c.face && (centre - c.proxy.triangle[0]).dot(c.faceNormal) > 0) {
            const Penetration f = alongFace(A, c.proxy, c.faceNormal);
            if (f.depth > -margin && f.depth <= deepestFace + slack) c.pen = f;
        }
        Vec3 normal;
        detail::contactPoints(A, c.proxy, c.pen, margin, normal, points);
        Group* g = nullptr;
        for (std::size_t k = 0; k < used; ++k)
            if (groups[k].normal.dot(normal) >= kGroupCos) g = &groups[k];
        if (!g) {
            if (used == groups.size()) groups.emplace_back();
            g = &groups[used++];
            g->normal = normal;
            g->points.clear();
        }
        for (detail::Candidate p : points) {
            p.feature = detail::mixId(p.feature, static_cast<std::uint32_t>(c.tri));
            // Triangles sharing an edge or a vertex may both report a point there.
            bool dup = false;
            for (const auto& q : g->points)
                dup = dup || (q.position - p.position).squaredNorm() <= 1e-18 * scale * scale;
            if (!dup) g->points.push_back(p);
        }
    }
    for (std::size_t k = 0; k < used; ++k) detail::appendReduced(groups[k].points, groups[k].normal, out);
}

}  // namespace tumble::collision
