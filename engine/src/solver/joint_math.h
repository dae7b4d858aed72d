// Small pieces the joint stage's files share (joints.cpp, joint_projection.cpp).
#pragma once

#include "solver/solver_body.h"

#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble::joint {

inline constexpr double kDegenerate = 1e-12;  // m: anchors this close have no line between them
inline constexpr double kHeld = 1e-13;        // m: the position error projection stops at
inline constexpr int kMostGroupJoints = 64;   // the most joints in one dense solve (joint_projection.cpp)

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

/// How the anchor at the arm `now` moves per unit impulse applied at the arm `then` (the
/// same arm at the step's start): J / m + (I⁻¹ (then × J)) × now, as a matrix.
inline Mat3 moveFor(const SolverBody& b, const Vec3& now, const Vec3& then) {
    return b.invMass * Mat3::Identity() - skew(now) * b.invI * skew(then);
}

}  // namespace tumble::joint
