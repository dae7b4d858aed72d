#include "model/joint_coordinate.h"

#include <cmath>

namespace tumble {

double JointModel::servoTargetAt(double t) const {
    if (servoKeys.empty()) return servoTarget;
    if (t <= servoKeys.front().time) return servoKeys.front().target;
    if (t >= servoKeys.back().time) return servoKeys.back().target;
    std::size_t k = 1;
    while (servoKeys[k].time < t) ++k;
    const JointDesc::ServoKey &a = servoKeys[k - 1], &b = servoKeys[k];
    return a.target + (b.target - a.target) * (t - a.time) / (b.time - a.time);
}

}  // namespace tumble

namespace tumble::joint {

double hingeAngle(const JointModel& j, const BodyState& a, const BodyState* b, double near) {
    const Quat qb = b ? b->q : Quat::Identity();
    Quat e = a.q * (qb * j.relative).conjugate();  // A turned from its place in the scene
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    const double raw = 2.0 * std::atan2(e.vec().dot(a.q * j.axisA), e.w());
    // Counted on past a half turn: the turn nearest to the last step's angle (raw itself,
    // to the bit, while the two are within a half turn).
    if (std::isnan(near) || std::abs(raw - near) <= M_PI) return raw;
    return near + std::remainder(raw - near, 2.0 * M_PI);
}

double jointCoordinate(const JointModel& j, const BodyState& a, const BodyState* b, const State& state) {
    if (j.type == JointType::Hinge) return hingeAngle(j, a, b, hingeNear(state, j));
    const Quat qb = b ? b->q : Quat::Identity();
    const Vec3 pB = b ? Vec3(b->x + qb * j.anchorB) : j.anchorB;
    return (qb * j.axisB).dot(a.x + a.q * j.anchorA - pB);
}

double jointSpringEnergy(const Model& model, const State& state) {
    double energy = 0.0;
    for (const JointModel& j : model.joints) {
        if (!j.spring || j.springStiffness == 0.0 || state.jointBroken(j.index)) continue;
        const double stretch =
            jointCoordinate(j, state.bodies[j.a], j.b >= 0 ? &state.bodies[j.b] : nullptr, state) - j.springRest;
        energy += 0.5 * j.springStiffness * stretch * stretch;
    }
    return energy;
}

}  // namespace tumble::joint
