// Dedicated routines for pairs with a round shape: a sphere is a point with a radius and a
// capsule a segment with a radius, so each pair reduces to the closest points of two cores
// (closed form) and the radii are subtracted. Parallel capsules give two points, so that a
// capsule lying on another does not rock on a single contact.
#include "collision/contact_util.h"
#include "collision/narrowphase.h"

#include <cmath>

namespace tumble::collision {

namespace {

struct Segment {
    Vec3 p0, p1;
};

Segment capsuleSegment(const Shape& s, const Pose& pose) {
    const Vec3 axis = pose.R.col(1) * s.halfHeight;
    return {pose.p - axis, pose.p + axis};
}

// Two round cores touching at closest points ca (on a's core) and cb (on b's core).
// `fallback` is the normal to use when the cores meet (distance zero).
bool roundContact(const Vec3& ca, double ra, const Vec3& cb, double rb, double margin,
                  const Vec3& fallback, Vec3* normal, Candidate* out, std::uint32_t feature) {
    const Vec3 d = ca - cb;
    const double dist = d.norm();
    const double depth = ra + rb - dist;
    if (!(depth > -margin)) return false;
    *normal = dist > 1e-12 * (ra + rb) ? Vec3(d / dist) : fallback;
    const Vec3 surfaceA = ca - *normal * ra;
    const Vec3 surfaceB = cb + *normal * rb;
    *out = {0.5 * (surfaceA + surfaceB), depth, feature};
    return true;
}

}  // namespace

void sphereSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                  ManifoldList& out) {
    Vec3 n;
    Candidate c;
    if (roundContact(pa.p, a.radius, pb.p, b.radius, margin, Vec3::UnitY(), &n, &c, 0)) {
        addReduced({c}, n, out);
    }
}

void sphereCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ManifoldList& out) {
    const Segment s = capsuleSegment(b, pb);
    const Vec3 q = closestOnSegment(s.p0, s.p1, pa.p);
    Vec3 n;
    Candidate c;
    if (roundContact(pa.p, a.radius, q, b.radius, margin, anyPerpendicular(pb.R.col(1)), &n, &c, 0)) {
        addReduced({c}, n, out);
    }
}

void capsuleCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                    ManifoldList& out) {
    const Segment sa = capsuleSegment(a, pa);
    const Segment sb = capsuleSegment(b, pb);
    const Vec3 da = sa.p1 - sa.p0, db = sb.p1 - sb.p0;
    const Vec3 cross = da.cross(db);
    const Vec3 fallback = cross.squaredNorm() > 0.0 ? Vec3(cross.normalized()) : anyPerpendicular(pb.R.col(1));
    std::vector<Candidate> points;
    Vec3 n;
    Candidate c;
    const double la = da.norm(), lb = db.norm();
    const bool parallel = la > 0.0 && lb > 0.0 && cross.norm() <= 1e-3 * la * lb;
    if (parallel) {
        // The overlap of b's segment projected on a's: a contact at each end of it.
        const Vec3 u = da / la;
        double t0 = (sb.p0 - sa.p0).dot(u), t1 = (sb.p1 - sa.p0).dot(u);
        if (t0 > t1) std::swap(t0, t1);
        t0 = std::max(t0, 0.0);
        t1 = std::min(t1, la);
        if (t1 > t0 + 1e-9 * la) {
            for (int k = 0; k < 2; ++k) {
                const Vec3 qa = sa.p0 + u * (k == 0 ? t0 : t1);
                const Vec3 qb = closestOnSegment(sb.p0, sb.p1, qa);
                if (roundContact(qa, a.radius, qb, b.radius, margin, fallback, &n, &c, static_cast<std::uint32_t>(k + 1))) {
                    points.push_back(c);
                }
            }
            if (points.size() == 2) {
                addReduced(points, n, out);  // parallel: both ends share the normal
                return;
            }
            points.clear();
        }
    }
    double s, t;
    closestBetweenSegments(sa.p0, sa.p1, sb.p0, sb.p1, &s, &t);
    if (roundContact(sa.p0 + s * da, a.radius, sb.p0 + t * db, b.radius, margin, fallback, &n, &c, 0)) {
        addReduced({c}, n, out);
    }
}

void sphereBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
               ManifoldList& out) {
    const Vec3 c = pb.toLocal(pa.p);  // sphere centre in the box frame
    const Vec3& h = b.halfExtents;
    const Vec3 clamped = c.cwiseMax(-h).cwiseMin(h);
    Vec3 nLocal;
    double depth;
    Vec3 surfaceB;  // box frame
    if (clamped != c) {
        const Vec3 d = c - clamped;
        const double dist = d.norm();
        depth = a.radius - dist;
        if (!(depth > -margin)) return;
        nLocal = d / dist;
        surfaceB = clamped;
    } else {
        // Centre inside: push out through the nearest face.
        int axis = 0;
        double least = h[0] - std::abs(c[0]);
        for (int k = 1; k < 3; ++k) {
            const double gap = h[k] - std::abs(c[k]);
            if (gap < least) least = gap, axis = k;
        }
        nLocal = Vec3::Zero();
        nLocal[axis] = c[axis] >= 0.0 ? 1.0 : -1.0;
        depth = a.radius + least;
        surfaceB = c;
        surfaceB[axis] = nLocal[axis] * h[axis];
    }
    const Vec3 n = pb.directionToWorld(nLocal);
    const Vec3 surfaceA = pa.p - n * a.radius;
    addReduced({{0.5 * (surfaceA + pb.toWorld(surfaceB)), depth, 0}}, n, out);
}

void capsuleBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                ManifoldList& out) {
    // In the box frame: the segment's closest approach to the box by sampling is not exact,
    // so treat each end and the closest point of the segment to the box as spheres, and keep
    // the deepest with the normal it gives. The ends make the lying-flat manifold of two points.
    const Segment s = capsuleSegment(a, pa);
    const Shape ball = Shape::sphere(a.radius);
    // Closest point of the segment to the box: minimise the box distance along the segment
    // (a convex function of the parameter) by golden-section search.
    auto boxDistance = [&](double t) {
        const Vec3 q = pb.toLocal(s.p0 + t * (s.p1 - s.p0));
        const Vec3 d = q - q.cwiseMax(-b.halfExtents).cwiseMin(b.halfExtents);
        const double outside = d.norm();
        if (outside > 0.0) return outside;
        return -(b.halfExtents - q.cwiseAbs()).minCoeff();
    };
    double lo = 0.0, hi = 1.0;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = boxDistance(x1), f2 = boxDistance(x2);
    for (int i = 0; i < 60 && hi - lo > 1e-12; ++i) {
        if (f1 < f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = boxDistance(x1);
        else lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = boxDistance(x2);
    }
    const double tMid = 0.5 * (lo + hi);
    ManifoldList one;
    Pose at = pa;
    at.p = s.p0 + tMid * (s.p1 - s.p0);
    sphereBox(ball, at, b, pb, margin, one);
    if (one.empty()) return;
    const Vec3 n = one[0].normal;
    const Candidate mid{one[0].points[0].position, one[0].points[0].depth, 0};
    // The ends, when the capsule lies along the contact plane, measured along the same normal.
    std::vector<Candidate> points;
    for (int k = 0; k < 2; ++k) {
        if (std::abs(tMid - k) < 1e-9) continue;  // the middle point is this end
        ManifoldList e;
        at.p = k == 0 ? s.p0 : s.p1;
        sphereBox(ball, at, b, pb, margin, e);
        if (!e.empty() && e[0].normal.dot(n) > 0.999) {
            points.push_back({e[0].points[0].position, e[0].points[0].depth, static_cast<std::uint32_t>(k + 1)});
        }
    }
    if (points.size() < 2) points.push_back(mid);  // two ends in contact bound the middle
    addReduced(points, n, out);
}

}  // namespace tumble::collision
