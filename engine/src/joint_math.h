// Small pieces the joint stage's files share (joints.cpp, joint_projection.cpp).
#pragma once

#include "solver_body.h"

#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble::joint {

inline constexpr double kDegenerate = 1e-12;  // m: anchors this close have no line between them
inline constexpr double kHeld = 1e-13;        // m: the position error projection stops at
inline constexpr int kMostGroupJoints = 64;    // the most joints in one dense solve (joint_projection.cpp)

inline bool movable(const Model& model, const State& state, int i) {
    return i >= 0 && model.bodies[i].motion == Motion::Dynamic && !state.isAsleep(i);
}

inline bool active(const Model& model, const State& state, const JointModel& j) {
    return !state.jointBroken(j.index) && (movable(model, state, j.a) || movable(model, state, j.b));
}

inline Mat3 skew(const Vec3& r) {
    Mat3 m;
    m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    return m;
}

/// Gives a solver body the impulse (linear, angular) of RATTLE's start projection, the
/// angular part through the inverse inertia at the start's orientation `then`, where the
/// impulse's arm was taken. Through the present inertia, a capsule's pull at its end (along
/// a line through its axis) had a share along the axis as it stands after the free step, times
/// 1/I_axial: rounding grew the capsule's spin about its own axis, which nothing drives, to
/// 53 rad/s in 6 s on a double pendulum with splitting-4 (energy +309 %; issue 45).
inline void giveStartImpulse(SolverBody& b, const BodyModel& body, const Quat& then, const Vec3& linear,
                             const Vec3& angular) {
    const Mat3 R = then.toRotationMatrix();
    b.v += b.invMass * linear;
    b.w += R * (body.invInertia * (R.transpose() * angular));
    b.touched = true;
}

/// How the anchor at the arm `now` moves per unit impulse applied at the arm `then` (the
/// same arm at the step's start): J / m + (I⁻¹ (then × J)) × now, as a matrix.
inline Mat3 moveFor(const SolverBody& b, const Vec3& now, const Vec3& then) {
    return b.invMass * Mat3::Identity() - skew(now) * b.invI * skew(then);
}

}  // namespace tumble::joint
