// The joints that hold orientation as well as position: hinge (the anchors together, the
// axes in line: 3 linear rows and 2 angular ones across the axis), slider (A's anchor on
// B's axis line and the relative orientation kept: 2 linear rows across the axis and 3
// angular) and fixed (3 and 3). One set of formulas for the three, used by the velocity
// rows (joints.cpp: prepare, update, remember) and the position projection.
//
// Rows: a linear row along the unit direction d acts at A's anchor pA, on B's material point
// there (B's arm rB = pA - xB: exact for a slider whose anchors are apart along the axis);
// its error is d · (pA - pB). An angular row along e acts on the relative turn; its error is
// e · c, with c the rotation vector taking B's frame (times the kept relative orientation)
// to A's (slider, fixed), or aB × aA for a hinge's axes (both move like A's turn minus B's).
// A hinge's or slider's motor and limits are scalar rows along its free axis: the motor's
// impulse clamped to its force times the step, a limit's one-sided with a speculative
// target (the coordinate may reach the limit within the step, no further; past it, no
// velocity back: the projection moves it back without adding energy).
#pragma once

#include <limits>

#include "model/joint_coordinate.h"
#include "solver/contact_solver.h"

#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble::joint {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

using AxisRow = ContactSolverScratch::AxisRow;

inline bool isGeneral(JointType t) {
    return t == JointType::Hinge || t == JointType::Slider || t == JointType::Fixed || t == JointType::SixAxis;
}

/// How many free axes joint j has: a hinge's or slider's one, a six-axis joint's not locked.
inline int freeAxes(const JointModel& j) {
    return j.type == JointType::Hinge || j.type == JointType::Slider ? 1 : static_cast<int>(j.axes.size());
}

/// The free axis k of joint j's settings (a hinge or slider: j itself).
inline const JointAxis& freeAxis(const JointModel& j, int k) {
    return j.type == JointType::SixAxis ? j.axes[k] : static_cast<const JointAxis&>(j);
}

/// The rows of joint `j` with its bodies at `a` and `b` (null: the world): their
/// directions, Jacobians (JA, JB: a column per row, v then ω) and, in `error`, the
/// position error along them. Kinv is not set. With `axes`, the free axes' rows too
/// (freeAxes(j) of them: JAx, JBx and coord; `settings` set). A hinge's coordinate is its
/// angle within π of `near` (State::hingeAngles, hingeNear), or within [-π, π] when `near`
/// is NaN. A six-axis joint's angular rows are exact at any turn: each is the gradient of
/// its rotation-vector coordinate (the inverse of SO(3)'s left Jacobian).
void generalRows(const JointModel& j, const BodyState& a, const BodyState* b,
                 ContactSolverScratch::GeneralRow& rows, Vector6* error = nullptr,
                 double near = std::numeric_limits<double>::quiet_NaN(), AxisRow* axes = nullptr);

/// Sets rows.m and the Jacobians JA, JB of the rows' directions (lin's first nl columns,
/// acting at the arms rA of A and rB of B; ang's first na, turning A against B).
void fillJacobians(ContactSolverScratch::GeneralRow& rows, const Vec3& rA, const Vec3& rB);

/// Sets state.hingeAngles from the poses now (World, at the end of every step).
void trackHingeAngles(const Model& model, State& state);

/// K = JAᵀ M_A⁻¹ JA' + JBᵀ M_B⁻¹ JB' over the first m rows (JA', JB': the impulse's rows,
/// which may be taken at another pose; the same rows give the symmetric effective mass),
/// padded with the identity to 6 × 6.
Matrix6 generalMass(const ContactSolverScratch::GeneralRow& now, const ContactSolverScratch::GeneralRow& then,
                    const SolverBody& A, const SolverBody& B);

/// The relative velocity along the rows (the first m entries).
Vector6 generalVelocity(const ContactSolverScratch::GeneralRow& r, const SolverBody& A, const SolverBody& B);

/// Applies an impulse given as (linear, angular) to one body's velocities.
void applyToBody(SolverBody& body, const Vector6& impulse);

/// Applies the row impulses `lambda` to A (+) and B (−, through JB) velocities.
void applyGeneral(const ContactSolverScratch::GeneralRow& r, SolverBody& A, SolverBody* B,
                  const Vector6& lambda);

/// Moves A and B (poses) as the row impulses `lambda` would in unit time: x += M⁻¹ J λ,
/// turned by I⁻¹ J λ. A body not `movable` is left.
void nudgeGeneral(const ContactSolverScratch::GeneralRow& r, const SolverBody& A, BodyState& a, bool moveA,
                  const SolverBody& B, BodyState* b, bool moveB, const Vector6& lambda);

/// A free axis: the effective mass along it (0: nothing can move), the coordinate's rate
/// now, an impulse along it applied to the velocities, and the poses moved by one (as
/// nudgeGeneral).
double axisMass(const AxisRow& r, const SolverBody& A, const SolverBody& B);
double axisVelocity(const AxisRow& r, const SolverBody& A, const SolverBody& B);
void applyAxis(const AxisRow& r, SolverBody& A, SolverBody* B, double lambda);
void nudgeAxis(const AxisRow& r, const SolverBody& A, BodyState& a, bool moveA, const SolverBody& B, BodyState* b,
               bool moveB, double lambda);

}  // namespace tumble::joint
