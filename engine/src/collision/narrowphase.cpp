// The pair dispatcher: one routine per unordered pair of kinds, written for one order; the
// other order swaps the arguments and flips the normals of what it produced.
#include "collision/narrowphase.h"

#include "collision/compound_pairs.h"
#include "collision/convex.h"
#include "collision/gjk.h"
#include "collision/mesh_pairs.h"

#include <algorithm>

namespace tumble::collision {

namespace {

using Routine = void (*)(const Shape&, const Pose&, const Shape&, const Pose&, double, ManifoldList&);

bool isConvex(Kind k) {
    return k != Kind::Plane && k != Kind::Mesh && k != Kind::Compound;
}

// The routine for (a, b) in this order, or nullptr when it is written for (b, a).
Routine routineFor(Kind a, Kind b) {
    auto is = [&](Kind x, Kind y) { return a == x && b == y; };
    if (is(Kind::Sphere, Kind::Sphere)) return sphereSphere;
    if (is(Kind::Sphere, Kind::Capsule)) return sphereCapsule;
    if (is(Kind::Sphere, Kind::Box)) return sphereBox;
    if (is(Kind::Capsule, Kind::Capsule)) return capsuleCapsule;
    if (is(Kind::Capsule, Kind::Box)) return capsuleBox;
    if (is(Kind::Box, Kind::Box)) return boxBox;
    if (isConvex(a) && b == Kind::Plane) return convexPlane;
    if (is(Kind::Mesh, Kind::Plane)) return collideMeshPlane;
    if (is(Kind::Mesh, Kind::Mesh)) return collideMeshMesh;
    if (isConvex(a) && b == Kind::Mesh) return collideConvexMesh;
    if (isConvex(a) && isConvex(b)) {
        // Pairs with a dedicated routine in the other order are swapped, not sent here.
        const bool dedicatedOtherWay = (is(Kind::Capsule, Kind::Sphere) || is(Kind::Box, Kind::Sphere) ||
                                        is(Kind::Box, Kind::Capsule));
        if (dedicatedOtherWay) return nullptr;
        return collideConvex;
    }
    return nullptr;
}

}  // namespace

bool generalConvex(Kind a, Kind b) {
    const Routine general = collideConvex;
    return routineFor(a, b) == general || routineFor(b, a) == general;
}

void collide(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
             ManifoldList& out, Vec3& apart) {
    const Routine general = collideConvex;
    if (routineFor(a.kind, b.kind) == general) {
        collideConvex(a, pa, b, pb, margin, out, apart);
        return;
    }
    if (routineFor(b.kind, a.kind) != general) {
        collide(a, pa, b, pb, margin, out);
        return;
    }
    const size_t first = out.size();
    Vec3 found = Vec3::Zero();
    collideConvex(b, pb, a, pa, margin, out, found);
    for (size_t i = first; i < out.size(); ++i) out[i].normal = -out[i].normal;
    if (out.size() == first) apart = -found;
}

bool apartAlong(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, const Vec3& n, double margin) {
    const ConvexProxy A = proxyOf(a, pa);
    const ConvexProxy B = proxyOf(b, pb);
    const double low = n.dot(A.support(-n)) - A.radius;  // a's lowest point along n
    const double high = n.dot(B.support(n)) + B.radius;  // b's highest
    const double hair = 1e-9 * (A.size() + B.size() + A.radius + B.radius);
    return low - high > std::max(margin, 0.0) + hair;
}

void collide(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
             ManifoldList& out) {
    if (a.kind == Kind::Plane && b.kind == Kind::Plane) return;
    if (a.kind == Kind::Compound || b.kind == Kind::Compound) {
        collideCompound(a, pa, b, pb, margin, out);
        return;
    }
    if (Routine r = routineFor(a.kind, b.kind)) {
        r(a, pa, b, pb, margin, out);
        return;
    }
    if (Routine r = routineFor(b.kind, a.kind)) {
        const size_t first = out.size();
        r(b, pb, a, pa, margin, out);
        for (size_t i = first; i < out.size(); ++i) out[i].normal = -out[i].normal;
    }
}

}  // namespace tumble::collision
