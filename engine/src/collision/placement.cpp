#include <tumble/placement.h>

#include <tumble/contact_query.h>

#include "collision/compound_pairs.h"
#include "collision/detect.h"
#include "collision/toi.h"

#include <algorithm>
#include <cmath>

namespace tumble {

namespace {

// Whether a joint between a and b keeps them from colliding (as the step's detection has it).
bool joinedApart(const Model& model, int a, int b) {
    return std::any_of(model.joints.begin(), model.joints.end(), [&](const JointModel& j) {
        return !j.collideConnected && ((j.a == a && j.b == b) || (j.a == b && j.b == a));
    });
}

}  // namespace

std::optional<double> travelToTouch(const Model& model, const State& state, int body, const Vec3& direction,
                                    double maxDistance) {
    const int n = static_cast<int>(model.bodies.size());
    if (body < 0 || body >= n || state.bodies.size() != model.bodies.size()) return std::nullopt;
    if (!(direction.norm() > 0.0) || !(maxDistance > 0.0) || !std::isfinite(maxDistance)) return std::nullopt;
    const Vec3 way = direction.normalized() * maxDistance;
    const BodyModel& A = model.bodies[body];
    const BodyState& a = state.bodies[body];
    // The body's straight path: its centre of mass from where it is to maxDistance along.
    collision::Sweep sa;
    sa.c0 = a.x;
    sa.c1 = a.x + way;
    sa.q0 = sa.q1 = a.q;
    sa.localCenter = A.centerOfMass;
    collision::Aabb swept = collision::bounds(A.collider, sa.at(0.0));
    swept.add(collision::bounds(A.collider, sa.at(1.0)));
    // Touching: within the step's tolerance (a floor for a model of unbounded bodies only).
    const double tolerance = std::max(touchTolerance(model), 1e-9);
    std::optional<double> nearest;
    for (int j = 0; j < n; ++j) {
        if (j == body || !model.mayCollide(body, j) || joinedApart(model, body, j)) continue;
        const BodyModel& B = model.bodies[j];
        const BodyState& b = state.bodies[j];
        collision::Sweep sb;
        sb.c0 = sb.c1 = b.x;
        sb.q0 = sb.q1 = b.q;
        sb.localCenter = B.centerOfMass;
        if (!swept.overlaps(collision::bounds(B.collider, sb.at(0.0)))) continue;
        const bool compound =
            A.collider.kind == collision::Kind::Compound || B.collider.kind == collision::Kind::Compound;
        const std::optional<collision::Impact> hit =
            compound ? collision::compoundImpact(A.collider, sa, B.collider, sb, tolerance)
                     : collision::timeOfImpact(A.collider, sa, B.collider, sb, tolerance);
        if (hit && (!nearest || hit->s * maxDistance < *nearest)) nearest = hit->s * maxDistance;
    }
    return nearest;
}

}  // namespace tumble
