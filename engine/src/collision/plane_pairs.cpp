// Convex shapes against a static plane: the paper's plane test E(p) = n·p - d (19) on the
// points of each shape that can be lowest. A polyhedron's candidates are its vertices; a
// round shape's are its core points moved by the radius; a cylinder's are the lowest point of
// each cap rim, and four rim points per cap when the cap lies nearly flat, so a standing
// cylinder rests on a stable manifold.
#include "collision/contact_util.h"
#include "collision/narrowphase.h"

#include <cmath>

namespace tumble::collision {

void worldPlane(const Shape& plane, const Pose& pose, Vec3& normal, double& offset) {
    normal = pose.directionToWorld(plane.normal);
    // A point of the plane in its own frame is normal * distance.
    offset = normal.dot(pose.toWorld(plane.normal * plane.distance));
}

namespace {

struct PlaneTest {
    Vec3 n;
    double d;
    double margin;
    std::vector<Candidate>* out;

    // A core point at radius r from the surface.
    void test(const Vec3& core, double r, std::uint32_t feature) const {
        const double e = n.dot(core) - d;  // E(p) of the core point
        const double depth = r - e;
        if (depth > -margin) out->push_back({core - n * (r + e) * 0.5, depth, feature});
    }
};

}  // namespace

void convexPlane(const Shape& a, const Pose& pa, const Shape& plane, const Pose& pp, double margin,
                 ManifoldList& out) {
    thread_local std::vector<Candidate> c;  // kept between calls, per thread
    c.clear();
    PlaneTest t{Vec3::Zero(), 0.0, margin, &c};
    worldPlane(plane, pp, t.n, t.d);
    switch (a.kind) {
    case Kind::Sphere: t.test(pa.p, a.radius, 0); break;
    case Kind::Capsule: {
        const Vec3 axis = pa.R.col(1) * a.halfHeight;
        t.test(pa.p - axis, a.radius, 1);
        t.test(pa.p + axis, a.radius, 2);
        break;
    }
    case Kind::Box:
        for (std::uint32_t k = 0; k < 8; ++k) {
            const Vec3 corner((k & 1) ? a.halfExtents.x() : -a.halfExtents.x(),
                              (k & 2) ? a.halfExtents.y() : -a.halfExtents.y(),
                              (k & 4) ? a.halfExtents.z() : -a.halfExtents.z());
            t.test(pa.toWorld(corner), 0.0, k);
        }
        break;
    case Kind::Hull:
        for (size_t k = 0; k < a.hull->vertices.size(); ++k) {
            t.test(pa.toWorld(a.hull->vertices[k]), 0.0, static_cast<std::uint32_t>(k));
        }
        break;
    case Kind::Cylinder: {
        const Vec3 axis = pa.R.col(1);
        // The rim direction that goes most against the plane normal.
        Vec3 down = -(t.n - axis * axis.dot(t.n));
        const double lateral = down.norm();
        const bool flat = lateral < 0.05;  // cap within ~3° of the plane: use four rim points
        down = lateral > 1e-12 ? Vec3(down / lateral) : anyPerpendicular(axis);
        const Vec3 side = axis.cross(down);
        for (int cap = 0; cap < 2; ++cap) {
            const Vec3 centre = pa.p + axis * (cap == 0 ? -a.halfHeight : a.halfHeight);
            const std::uint32_t base = static_cast<std::uint32_t>(cap * 4);
            t.test(centre + down * a.radius, 0.0, base);
            if (flat) {
                t.test(centre - down * a.radius, 0.0, base + 1);
                t.test(centre + side * a.radius, 0.0, base + 2);
                t.test(centre - side * a.radius, 0.0, base + 3);
            }
        }
        break;
    }
    case Kind::Plane:
    case Kind::Mesh:
    case Kind::Compound: return;  // not convex shapes: the dispatcher sends them elsewhere
    }
    addReduced(c, t.n, out);
}

}  // namespace tumble::collision
