// A ray against one collision shape, in the shape's frame, with a unit direction.
// A convex shape meets a line in one interval [tIn, tOut], its entry and exit, each with the
// outward normal of the face crossed. Box, cylinder, hull and plane are intersections of
// simple convex pieces (half-spaces, an infinite tube), so their interval is the
// intersection of the pieces' intervals; the capsule is the union of a tube piece and two
// end spheres, and being convex its interval is the span of theirs. RayStart then picks the
// entry, the exit, or the origin itself. A mesh has no interval: its nearest triangle
// crossing, ties going to the lower triangle index so that the BVH's visiting order cannot
// change the answer.
#include <tumble/raycast.h>

#include "collision/bvh.h"

#include <cmath>
#include <limits>
#include <utility>

namespace tumble::collision {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Interval {
    double tIn = -kInf;
    double tOut = kInf;
    Vec3 nIn = Vec3::Zero();
    Vec3 nOut = Vec3::Zero();

    bool empty() const { return !(tIn <= tOut); }
};

Interval emptyInterval() {
    Interval iv;
    iv.tIn = kInf;
    iv.tOut = -kInf;
    return iv;
}

// Keeps the part of `a` that is also in `b`.
void intersect(Interval& a, const Interval& b) {
    if (b.tIn > a.tIn) {
        a.tIn = b.tIn;
        a.nIn = b.nIn;
    }
    if (b.tOut < a.tOut) {
        a.tOut = b.tOut;
        a.nOut = b.nOut;
    }
}

// Grows `a` to cover `b`: for pieces whose union is convex, the union of their intervals
// is one interval.
void span(Interval& a, const Interval& b) {
    if (b.empty()) return;
    if (a.empty()) {
        a = b;
        return;
    }
    if (b.tIn < a.tIn) {
        a.tIn = b.tIn;
        a.nIn = b.nIn;
    }
    if (b.tOut > a.tOut) {
        a.tOut = b.tOut;
        a.nOut = b.nOut;
    }
}

// The half-space n·p <= offset (n unit, outward).
Interval halfSpace(const Vec3& o, const Vec3& d, const Vec3& n, double offset) {
    const double denom = n.dot(d);
    const double room = offset - n.dot(o);  // >= 0: the origin is inside
    Interval iv;
    if (denom == 0.0) return room < 0.0 ? emptyInterval() : iv;
    const double t = room / denom;
    if (denom < 0.0) {
        iv.tIn = t;
        iv.nIn = n;
    } else {
        iv.tOut = t;
        iv.nOut = n;
    }
    return iv;
}

// Roots of a t² + 2 b t + c = 0 (half-b form), smallest first, without the cancellation of
// -b ± sqrt(b² - a c) when one root is near zero.
bool solveQuadratic(double a, double b, double c, double& t0, double& t1) {
    if (!(a > 0.0)) return false;
    const double disc = b * b - a * c;
    if (disc < 0.0) return false;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    if (q == 0.0) {
        t0 = t1 = 0.0;  // b = 0 and c = 0: grazing at the origin
        return true;
    }
    t0 = q / a;
    t1 = c / q;
    if (t0 > t1) std::swap(t0, t1);
    return true;
}

Interval sphere(const Vec3& o, const Vec3& d, const Vec3& centre, double r) {
    const Vec3 m = o - centre;
    double t0, t1;
    if (!(r > 0.0) || !solveQuadratic(d.squaredNorm(), m.dot(d), m.squaredNorm() - r * r, t0, t1)) {
        return emptyInterval();
    }
    return {t0, t1, (m + t0 * d) / r, (m + t1 * d) / r};
}

// The infinite tube x² + z² <= r² about the y axis.
Interval tube(const Vec3& o, const Vec3& d, double r) {
    const double a = d.x() * d.x() + d.z() * d.z();
    const double c = o.x() * o.x() + o.z() * o.z() - r * r;
    if (!(r > 0.0)) return emptyInterval();
    if (a == 0.0) return c <= 0.0 ? Interval{} : emptyInterval();  // along the axis
    double t0, t1;
    if (!solveQuadratic(a, o.x() * d.x() + o.z() * d.z(), c, t0, t1)) return emptyInterval();
    auto radial = [&](double t) {
        const Vec3 p = o + t * d;
        return Vec3(p.x() / r, 0.0, p.z() / r);
    };
    return {t0, t1, radial(t0), radial(t1)};
}

// The slab |y| <= h.
Interval slabY(const Vec3& o, const Vec3& d, double h) {
    Interval iv = halfSpace(o, d, Vec3::UnitY(), h);
    intersect(iv, halfSpace(o, d, -Vec3::UnitY(), h));
    return iv;
}

Interval box(const Vec3& o, const Vec3& d, const Vec3& h) {
    Interval iv;
    for (int axis = 0; axis < 3; ++axis) {
        const Vec3 n = Vec3::Unit(axis);
        intersect(iv, halfSpace(o, d, n, h[axis]));
        intersect(iv, halfSpace(o, d, -n, h[axis]));
    }
    return iv;
}

Interval cylinder(const Vec3& o, const Vec3& d, double r, double h) {
    Interval iv = tube(o, d, r);
    intersect(iv, slabY(o, d, h));
    return iv;
}

Interval capsule(const Vec3& o, const Vec3& d, double r, double h) {
    Interval iv = tube(o, d, r);
    intersect(iv, slabY(o, d, h));
    span(iv, sphere(o, d, Vec3(0, h, 0), r));
    span(iv, sphere(o, d, Vec3(0, -h, 0), r));
    return iv;
}

Interval hull(const Vec3& o, const Vec3& d, const ConvexHull& hull) {
    Interval iv;
    for (const ConvexHull::Face& f : hull.faces) {
        intersect(iv, halfSpace(o, d, f.normal, f.offset));
        if (iv.empty()) break;
    }
    return iv;
}

struct LocalHit {
    double t = 0.0;
    Vec3 normal = Vec3::Zero();  // shape frame
};

std::optional<LocalHit> choose(const Interval& iv, const Vec3& d, double maxT, RayStart start) {
    if (iv.empty() || !(iv.tOut >= 0.0)) return std::nullopt;
    LocalHit hit;
    if (iv.tIn >= 0.0) {
        hit = {iv.tIn, iv.nIn};
    } else if (start == RayStart::Solid) {
        hit = {0.0, -d};
    } else {
        hit = {iv.tOut, iv.nOut};
    }
    if (!std::isfinite(hit.t) || hit.t > maxT) return std::nullopt;
    return hit;
}

// Möller–Trumbore, either face. `front` is true when the ray enters through the face
// counter-clockwise from outside (det > 0).
bool rayTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c, double& t,
                 bool& front) {
    const Vec3 e1 = b - a;
    const Vec3 e2 = c - a;
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0 || !std::isfinite(det)) return false;
    const double inv = 1.0 / det;
    const Vec3 s = o - a;
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) return false;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    t = e2.dot(q) * inv;
    front = det > 0.0;
    return t >= 0.0;
}

std::optional<LocalHit> triangles(const std::vector<Vec3>& vertices,
                                  const std::vector<std::array<int, 3>>& tris, const TriangleBvh* bvh,
                                  const Vec3& o, const Vec3& d, double maxT, RayStart start, bool closed) {
    const int nv = static_cast<int>(vertices.size());
    double bestT = kInf;
    int best = -1;
    bool bestFront = false;
    auto consider = [&](int i) {
        const auto& tri = tris[static_cast<size_t>(i)];
        for (int v : tri)
            if (v < 0 || v >= nv) return;  // an unchecked description: skip, never crash
        double t;
        bool front;
        if (!rayTriangle(o, d, vertices[tri[0]], vertices[tri[1]], vertices[tri[2]], t, front)) return;
        if (t > maxT) return;
        if (t < bestT || (t == bestT && i < best)) {
            bestT = t;
            best = i;
            bestFront = front;
        }
    };
    if (bvh) {
        bvh->raycast(o, d, maxT, consider);
    } else {
        for (int i = 0; i < static_cast<int>(tris.size()); ++i) consider(i);
    }
    if (best < 0) return std::nullopt;
    // The nearest crossing of a closed surface leaves through a back face only from inside.
    if (start == RayStart::Solid && closed && !bestFront) return LocalHit{0.0, -d};
    const auto& tri = tris[static_cast<size_t>(best)];
    const Vec3 n = (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]);
    return LocalHit{bestT, n.normalized()};
}

// Unit direction, or nothing for a zero or non-finite one.
std::optional<Vec3> unitDirection(const Vec3& direction) {
    const double len = direction.norm();
    if (!(len > 0.0) || !std::isfinite(len)) return std::nullopt;
    return direction / len;
}

RayHit worldHit(const LocalHit& h, const Pose& pose, const Vec3& origin, const Vec3& d) {
    RayHit hit;
    hit.distance = h.t;
    hit.point = origin + h.t * d;
    hit.normal = pose.directionToWorld(h.normal);
    return hit;
}

}  // namespace

std::optional<RayHit> rayShape(const Shape& shape, const Pose& pose, const Vec3& origin,
                               const Vec3& direction, double maxDistance, RayStart start) {
    const auto du = unitDirection(direction);
    if (!du || !(maxDistance >= 0.0)) return std::nullopt;
    if (shape.kind == Kind::Compound) {
        // The nearest part; a later part only when strictly nearer (ties: the lower index).
        std::optional<RayHit> best;
        const auto& parts = shape.compound->parts;
        for (int k = 0; k < static_cast<int>(parts.size()); ++k) {
            auto hit = rayShape(parts[k].shape, pose * parts[k].pose, origin, *du,
                                best ? best->distance : maxDistance, start);
            if (hit && (!best || hit->distance < best->distance)) {
                best = hit;
                best->part = k;
            }
        }
        return best;
    }
    const Vec3 o = pose.toLocal(origin);
    const Vec3 d = pose.directionToLocal(*du);
    std::optional<LocalHit> local;
    switch (shape.kind) {
        case Kind::Sphere:
            local = choose(sphere(o, d, Vec3::Zero(), shape.radius), d, maxDistance, start);
            break;
        case Kind::Box: local = choose(box(o, d, shape.halfExtents), d, maxDistance, start); break;
        case Kind::Capsule:
            local = choose(capsule(o, d, shape.radius, shape.halfHeight), d, maxDistance, start);
            break;
        case Kind::Cylinder:
            local = choose(cylinder(o, d, shape.radius, shape.halfHeight), d, maxDistance, start);
            break;
        case Kind::Plane:
            if (shape.normal.isZero(0.0)) return std::nullopt;
            local = choose(halfSpace(o, d, shape.normal, shape.distance), d, maxDistance, start);
            break;
        case Kind::Hull:
            if (!shape.hull || shape.hull->faces.empty()) return std::nullopt;
            local = choose(hull(o, d, *shape.hull), d, maxDistance, start);
            break;
        case Kind::Mesh:
            if (!shape.mesh) return std::nullopt;
            local = triangles(shape.mesh->vertices, shape.mesh->triangles, shape.mesh->bvh.get(), o, d,
                              maxDistance, start, shape.mesh->closed);
            break;
        case Kind::Compound: break;  // above
    }
    if (!local) return std::nullopt;
    return worldHit(*local, pose, origin, *du);
}

std::optional<RayHit> rayTriangles(const std::vector<Vec3>& vertices,
                                   const std::vector<std::array<int, 3>>& tris, const Pose& pose,
                                   const Vec3& origin, const Vec3& direction, double maxDistance,
                                   RayStart start, bool closed) {
    const auto du = unitDirection(direction);
    if (!du || !(maxDistance >= 0.0)) return std::nullopt;
    const Vec3 d = pose.directionToLocal(*du);
    const auto local =
        triangles(vertices, tris, nullptr, pose.toLocal(origin), d, maxDistance, start, closed);
    if (!local) return std::nullopt;
    return worldHit(*local, pose, origin, *du);
}

}  // namespace tumble::collision
