#include "model/joint_coordinate.h"

#include <cmath>

namespace tumble {

double JointAxis::servoTargetAt(double t) const {
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

Eigen::Matrix<double, 6, 1> sixAxisCoordinates(const JointModel& j, const BodyState& a, const BodyState* b) {
    const Quat qb = b ? b->q : Quat::Identity();
    const Vec3 pB = b ? Vec3(b->x + qb * j.anchorB) : j.anchorB;
    const Mat3 WB = qb.toRotationMatrix() * j.frameB;
    // A's turn from its place relative to B, as a rotation vector in B's frame axes.
    Quat e = a.q * (qb * j.relative).conjugate();
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    const double s = e.vec().norm();
    const Vec3 turn = s > 1e-12 ? Vec3((2.0 * std::atan2(s, e.w()) / s) * e.vec()) : Vec3(2.0 * e.vec());
    Eigen::Matrix<double, 6, 1> c;
    c << WB.transpose() * (a.x + a.q * j.anchorA - pB), WB.transpose() * turn;
    return c;
}

double axisCoordinate(const JointModel& j, const JointAxis& x, const BodyState& a, const BodyState* b,
                      const State& state) {
    if (x.axis < 0) return jointCoordinate(j, a, b, state);
    return sixAxisCoordinates(j, a, b)[x.axis];
}

double jointSpringEnergy(const Model& model, const State& state) {
    double energy = 0.0;
    auto add = [&](const JointModel& j, const JointAxis& x) {
        if (!x.spring || x.springStiffness == 0.0) return;
        double stretch =
            axisCoordinate(j, x, state.bodies[j.a], j.b >= 0 ? &state.bodies[j.b] : nullptr, state) - x.springRest;
        if (x.axis >= 3) stretch = std::remainder(stretch, 2.0 * M_PI);  // (the short way round, as the solver's)
        energy += 0.5 * x.springStiffness * stretch * stretch;
    };
    for (const JointModel& j : model.joints) {
        if (state.jointBroken(j.index)) continue;
        add(j, j);
        for (const JointAxis& x : j.axes) add(j, x);
    }
    return energy;
}

}  // namespace tumble::joint
