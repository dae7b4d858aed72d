// The general convex pair: one GJK/EPA query for the normal and depth, then the facing
// features clipped for a multi-point manifold (see clip.cpp).
#include "collision/convex.h"

#include "collision/clip.h"
#include "collision/gjk.h"

namespace tumble::collision {

void collideConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ManifoldList& out) {
    Vec3 apart;
    collideConvex(a, pa, b, pb, margin, out, apart);
}

void collideConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ManifoldList& out, Vec3& apart) {
    const ConvexProxy A = proxyOf(a, pa);
    const ConvexProxy B = proxyOf(b, pb);
    const Penetration pen = penetration(A, B, margin);
    if (!pen.hit) {
        apart = pen.normal;  // apart: GJK's closest points, out of B towards A
        return;
    }
    thread_local std::vector<detail::Candidate> points;  // kept between calls (contactPoints clears it)
    Vec3 normal;
    detail::contactPoints(A, B, pen, margin, normal, points);
    detail::appendReduced(points, normal, out);
}

}  // namespace tumble::collision
