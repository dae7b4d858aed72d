// Time of impact by conservative advancement (Mirtich 1996). At time s the shapes are
// d apart with unit normal n (out of B towards A). Over the rest of the step no point of
// A gets closer to B along n than the centres' relative displacement along n plus the arc
// each body's rotation can sweep: every point of a body lies within r (its bound about the
// centre of mass) of that centre, and slerp turns at a constant rate, so a point moves at
// most theta * r beyond its centre over the whole step. Hence
//     d(s + t) >= d(s) - t * mu,  mu = (dcB - dcA)·n + thetaA rA + thetaB rB,
// and advancing by (d - tolerance/2) / mu can never step past a contact: thin or fast
// bodies cannot tunnel. mu <= 0 means the pair only separates from here on.
//
// Pairs: convex shapes through GJK proxies; a plane through the lowest point of the other
// shape along the plane's normal (for a mesh, its lowest vertex: a set and its hull are
// equally far from a plane); a mesh per triangle, the triangles found by the BVH in the
// bounds of the other shape's whole sweep; mesh against mesh per triangle pair, each
// triangle of A querying B's BVH with its own swept bounds (costly for two large meshes
// that move close together; exact and conservative all the same).
#include "collision/toi.h"

#include "collision/bvh.h"
#include "collision/compound_pairs.h"
#include "collision/gjk.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace tumble::collision {

Pose Sweep::at(double s) const {
    const Quat q = q0.slerp(s, q1).normalized();
    Pose p;
    p.R = q.toRotationMatrix();
    p.p = centre(s) - p.R * localCenter;
    return p;
}

namespace {

constexpr int kMaxIterations = 500;

struct Probe {
    double distance;
    Vec3 normal, pointA, pointB;
};

double turn(const Sweep& s) {
    return s.q0.angularDistance(s.q1);
}
bool turns(const Sweep& s) {
    return turn(s) > 0.0;
}

// Conservative advancement over [0, sEnd]; bound(n, s) is mu for the normal n at time s.
// Once within tol, the gap left (up to tol) is closed to 1e-5 of tol by up to three secant
// steps through the last two probes, each kept only if the shapes are then apart by no more
// than before and not touching yet: for bodies moving straight at each other the moment is
// then early by 1e-5 tol / approach speed instead of up to tol / approach speed (a cradle's last
// ball left 5e-8 m early), and a refinement that would overshoot is dropped, so the answer
// is still never after the first contact.
// From window.from on; past window.notAfter the search stops with nothing (a caller that
// knows of an earlier impact); the secant steps may still go up to sEnd, so the answer is
// the same whenever it is kept.
template <class DistanceAt, class Bound>
std::optional<Impact> advance(DistanceAt&& distanceAt, Bound&& bound, double tol, double sEnd,
                              Window window = {}) {
    const double giveUp = window.notAfter;
    double s = window.from, sBefore = 0.0, dBefore = 0.0;
    for (int iter = 0;; ++iter) {
        const Probe p = distanceAt(s);
        // At the iteration cap the current time is still safe (never past a contact).
        if (p.distance <= tol || iter == kMaxIterations) {
            Impact hit{s, p.normal, 0.5 * (p.pointA + p.pointB)};
            const double gap = 1e-5 * tol;
            // (Up to three secant steps, each kept only as described. One, to 1e-3 of tol,
            // left a graze's moment early by 2e-10 m of gap at 0.57 m/s, its normal and so
            // its bounce off by 1.3e-8 m/s.)
            double d = p.distance;
            for (int k = 0; k < 3 && iter > 0 && d > gap && dBefore > d; ++k) {
                const double sNext = s + (d - gap) * (s - sBefore) / (dBefore - d);
                if (!(sNext > s && sNext <= sEnd)) break;
                const Probe q = distanceAt(sNext);
                if (!(q.distance >= 0.0 && q.distance <= d)) break;
                hit = Impact{sNext, q.normal, 0.5 * (q.pointA + q.pointB)};
                sBefore = s;
                dBefore = d;
                s = sNext;
                d = q.distance;
            }
            return hit;
        }
        const double mu = bound(p.normal, s);
        if (!(mu > 0.0)) return std::nullopt;
        sBefore = s;
        dBefore = p.distance;
        s += (p.distance - 0.5 * tol) / mu;
        if (!(s <= std::min(sEnd, giveUp))) return std::nullopt;
    }
}

bool isConvex(Kind k) {
    return k != Kind::Plane && k != Kind::Mesh;
}

// Bound on the distance of any point of a shape from the centre of mass, from its bound
// about its own origin (boundingRadius).
double reach(double bound, const Sweep& sw) {
    return bound + sw.localCenter.norm();
}

Probe probe(const ConvexProxy& a, const ConvexProxy& b) {
    const Distance d = gjkDistance(a, b);
    return {d.distance, d.normal, d.pointA, d.pointB};
}

// The centres' relative path's largest sag from its chord over the step (s (1 - s) <= 1/4),
// and the most its rate can differ from the chord's (|1 - 2 s| <= 1).
double sag(const Sweep& sa, const Sweep& sb) {
    return 0.25 * (sa.bow - sb.bow).norm();
}
double sagRate(const Sweep& sa, const Sweep& sb) {
    return (sa.bow - sb.bow).norm();
}

// Linear part of mu plus the rotation arcs, for two bodies of reaches rA, rB (and what the
// paths' bows can add to the chord's rate).
auto boundFor(const Sweep& sa, double rA, const Sweep& sb, double rB) {
    const Vec3 rel = (sb.c1 - sb.c0) - (sa.c1 - sa.c0);
    const double arcs = turn(sa) * rA + turn(sb) * rB + sagRate(sa, sb);
    return [rel, arcs](const Vec3& n, double) { return rel.dot(n) + arcs; };
}

// Bounding spheres about the centres of mass never come within tol: no impact. Their
// centres' separation is linear in s but for the bows' sag, so its minimum over [0, 1] is
// a segment's distance, less that sag.
bool spheresMiss(const Sweep& sa, double rA, const Sweep& sb, double rB, double tol) {
    const Vec3 d0 = sa.c0 - sb.c0, dd = (sa.c1 - sb.c1) - d0;
    const double t = dd.squaredNorm() > 0 ? std::clamp(-d0.dot(dd) / dd.squaredNorm(), 0.0, 1.0) : 0.0;
    return (d0 + t * dd).norm() - sag(sa, sb) - rA - rB > tol;
}

// The region of mesh-local space that a ball of radius r about the point at offsetLocal from
// the other body's centre (sweep `so`) can reach over the step, as a box in the mesh's
// frame (sweep `sm`). While the mesh does not turn, the other centre's position in the
// mesh's frame is linear in s (both centres move linearly), so the box of its two ends
// holds it; a turning other body moves the offset point on a sphere of its length about
// that centre.
Aabb sweptBoxInMesh(const Sweep& so, const Vec3& offsetLocal, double r, const Sweep& sm) {
    Aabb box;
    if (!turns(sm)) {
        const Mat3 Rm = sm.at(0).R;
        const bool fixedOffset = !turns(so);
        const Vec3 offset = fixedOffset ? Vec3(so.at(0).R * offsetLocal) : Vec3::Zero();
        for (int k = 0; k < 2; ++k) {
            const Vec3 c = (k ? so.c1 : so.c0) + offset - (k ? sm.c1 : sm.c0);
            box.add(Rm.transpose() * c + sm.localCenter);
        }
        return box.inflated((fixedOffset ? r : r + offsetLocal.norm()) + sag(so, sm));
    }
    // A turning mesh: the centres' separation is linear in s, largest at an end; any
    // orientation.
    const double far =
        std::max((so.c0 - sm.c0).norm(), (so.c1 - sm.c1).norm()) + offsetLocal.norm() + sag(so, sm);
    box.add(sm.localCenter);
    return box.inflated(far + r);
}

std::shared_ptr<const TriangleBvh> bvhOf(const MeshShape& m) {
    if (m.bvh) return m.bvh;
    return std::make_shared<TriangleBvh>(m.vertices, m.triangles);
}

ConvexProxy triangleAt(const MeshShape& m, int tri, const Pose& pose) {
    const auto& t = m.triangles[tri];
    return triangleProxy(pose.toWorld(m.vertices[t[0]]), pose.toWorld(m.vertices[t[1]]),
                         pose.toWorld(m.vertices[t[2]]));
}

// Centre (body frame) and radius of a triangle's bounding ball, and its reach about the
// body's centre of mass.
void triangleBall(const MeshShape& m, int tri, const Vec3& localCenter, Vec3& centre, double& radius,
                  double& reachCm) {
    const auto& t = m.triangles[tri];
    centre = (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0;
    radius = 0.0;
    reachCm = 0.0;
    for (int k : t) {
        radius = std::max(radius, (m.vertices[k] - centre).norm());
        reachCm = std::max(reachCm, (m.vertices[k] - localCenter).norm());
    }
}

// rA, rB: their reaches.
std::optional<Impact> convexConvex(const Shape& a, const Sweep& sa, double rA, const Shape& b, const Sweep& sb,
                                   double rB, double tol, Window window) {
    ConvexProxy A = proxyOf(a, Pose{}), B = proxyOf(b, Pose{});
    return advance(
        [&](double s) {
            A.moveTo(sa.at(s));
            B.moveTo(sb.at(s));
            return probe(A, B);
        },
                   boundFor(sa, rA, sb, rB), tol, 1.0, window);
}

// A (convex or mesh) against the plane B; rA: A's reach.
std::optional<Impact> againstPlane(const Shape& a, const Sweep& sa, double rA, const Shape& plane, const Sweep& sp,
                                   double tol, Window window) {
    const double thetaP = turn(sp);
    auto distanceAt = [&](double s) {
        const Pose pa = sa.at(s), pp = sp.at(s);
        const Vec3 n = pp.R * plane.normal;
        const double offset = n.dot(pp.p) + plane.distance;
        Vec3 low;
        if (a.kind == Kind::Mesh) {
            const auto& vs = a.mesh->vertices;
            low = pa.toWorld(vs[0]);
            for (const Vec3& v : vs) {
                const Vec3 w = pa.toWorld(v);
                if (w.dot(n) < low.dot(n)) low = w;
            }
        } else {
            const ConvexProxy A = proxyOf(a, pa);
            low = A.support(-n) - A.radius * n;
        }
        const double d = low.dot(n) - offset;
        return Probe{d, n, low, low - d * n};
    };
    const Vec3 rel = (sp.c1 - sp.c0) - (sa.c1 - sa.c0);
    const double armsLinear = rel.norm() + sagRate(sa, sp);
    auto bound = [&](const Vec3& n, double s) {
        double mu = rel.dot(n) + turn(sa) * rA + sagRate(sa, sp);
        // A turning plane: its points near A move by at most thetaP times their distance
        // from the plane's centre, which stays below the centres' gap now plus what the rest
        // of the step can add, plus A's reach.
        if (thetaP > 0) {
            const Vec3 gap = sa.centre(s) - sp.centre(s);
            mu += thetaP * (gap.norm() + armsLinear + rA);
        }
        return mu;
    };
    return advance(distanceAt, bound, tol, 1.0, window);
}

// A (convex) against the mesh B, triangle by triangle; rA: A's reach.
std::optional<Impact> convexMesh(const Shape& a, const Sweep& sa, double rA, const Shape& mesh, const Sweep& sm,
                                 double tol) {
    const MeshShape& m = *mesh.mesh;
    const auto bvh = bvhOf(m);
    ConvexProxy A = proxyOf(a, Pose{});
    const Aabb box = sweptBoxInMesh(sa, Vec3::Zero(), rA + tol, sm);
    std::optional<Impact> best;
    bvh->query(box, [&](int tri) {
        Vec3 centre;
        double radius, rT;
        triangleBall(m, tri, sm.localCenter, centre, radius, rT);
        const double sEnd = best ? best->s : 1.0;
        auto hit =
            advance(
                [&](double s) {
                    A.moveTo(sa.at(s));
                    return probe(A, triangleAt(m, tri, sm.at(s)));
                },
                    boundFor(sa, rA, sm, rT), tol, sEnd);
        if (hit && (!best || hit->s < best->s)) best = hit;
    });
    return best;
}

std::optional<Impact> meshMesh(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, double tol) {
    const MeshShape& ma = *a.mesh;
    const MeshShape& mb = *b.mesh;
    const auto bvhB = bvhOf(mb);
    std::optional<Impact> best;
    for (int i = 0; i < static_cast<int>(ma.triangles.size()); ++i) {
        Vec3 centre;
        double radius, rTa;
        triangleBall(ma, i, sa.localCenter, centre, radius, rTa);
        // Without turning the triangle's ball centre moves with the centre of mass.
        const Aabb box = turns(sa) ? sweptBoxInMesh(sa, Vec3::Zero(), rTa + tol, sb)
                                   : sweptBoxInMesh(sa, centre - sa.localCenter, radius + tol, sb);
        bvhB->query(box, [&](int j) {
            Vec3 cb;
            double rb, rTb;
            triangleBall(mb, j, sb.localCenter, cb, rb, rTb);
            const double sEnd = best ? best->s : 1.0;
            auto hit = advance(
                [&](double s) { return probe(triangleAt(ma, i, sa.at(s)), triangleAt(mb, j, sb.at(s))); },
                boundFor(sa, rTa, sb, rTb), tol, sEnd);
            if (hit && (!best || hit->s < best->s)) best = hit;
        });
    }
    return best;
}

std::optional<Impact> flipped(std::optional<Impact> i) {
    if (i) i->normal = -i->normal;
    return i;
}

}  // namespace

std::optional<Impact> timeOfImpact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                                   double tolerance, Window window) {
    if (a.kind == Kind::Plane && b.kind == Kind::Plane) return std::nullopt;
    // A tolerance of zero would only be reached in the limit; keep a rounding-level floor.
    // (Each bound once: a mesh's goes over all its vertices.)
    const double boundA = a.kind != Kind::Plane ? boundingRadius(a) : 0.0;
    const double boundB = b.kind != Kind::Plane ? boundingRadius(b) : 0.0;
    const double tol = std::max(tolerance, 1e-12 * (boundA + boundB));
    const double rA = reach(boundA, sa), rB = reach(boundB, sb);
    if (a.kind == Kind::Compound || b.kind == Kind::Compound) {
        // The whole bodies' balls first: most pairs end there, before any pair of parts.
        if (a.kind != Kind::Plane && b.kind != Kind::Plane && spheresMiss(sa, rA, sb, rB, tol))
            return std::nullopt;
        return compoundImpact(a, sa, b, sb, tolerance, window);
    }
    if (b.kind == Kind::Plane) return againstPlane(a, sa, rA, b, sb, tol, window);
    if (a.kind == Kind::Plane) return flipped(againstPlane(b, sb, rB, a, sa, tol, window));
    if (spheresMiss(sa, rA, sb, rB, tol)) return std::nullopt;
    if (isConvex(a.kind) && isConvex(b.kind)) return convexConvex(a, sa, rA, b, sb, rB, tol, window);
    if (isConvex(a.kind)) return convexMesh(a, sa, rA, b, sb, tol);
    if (isConvex(b.kind)) return flipped(convexMesh(b, sb, rB, a, sa, tol));
    return meshMesh(a, sa, b, sb, tol);
}

}  // namespace tumble::collision
