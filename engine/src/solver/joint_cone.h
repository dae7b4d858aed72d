// A ball joint's swing cone and twist limits (issue 51): the angles and rows of a ball
// joint whose `axis` A and B carry (A's twist axis, B's cone axis).
//
// Swing: the angle φ between A's axis a and B's axis n, kept within the cone's half-angle in
// the direction a leans: θ(d) = 1 / √((d₁/θ₁)² + (d₂/θ₂)²) for the unit lean d = (a − (a·n) n)
// normalised, with d₁, d₂ its parts along two cross axes that turn with B (compile_joints.cpp:
// A's first frame axis across its axis as the scene places A, then n × it); a circle when
// θ₁ = θ₂. Its row turns A against B
// about u = n × a / |n × a| (which opens φ).
// Twist: A's turn about its axis relative to B's, from the swing-twist split of A's rotation
// since the scene placed the two (0 there), within [−π, π]; its row turns about the mean of
// A's axis a and where the placement puts it, m: (a + m) / (1 + a·m), whose dot product with
// the relative spin is the twist's rate.
// Both rows are one-sided and speculative, as a hinge's limits (joint_general.h): the angle
// may reach its bound within the step, no further; past it, no rate back, and the position
// projection (projectLimitedBall) turns the bodies back with the anchors held.
#pragma once

#include "solver/contact_solver.h"

#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble::joint {

struct BallAngles {
    bool swingKnown = false;  ///< false when the axes are in line (no lean direction)
    Vec3 swingAxis = Vec3::Zero();  ///< u: turning A about it opens the swing
    /// The rate of φ − θ(ψ) (how far past the cone) per turn of A relative to B: u on a
    /// circular cone; on an elliptical one also the bound's change as the lean turns. The
    /// position projection's row (its Newton steps); the velocity rows keep u, which stays
    /// bounded as the lean's direction does not near the cone's axis.
    Vec3 swingRow = Vec3::Zero();
    double swing = 0.0, swingBound = 0.0;  ///< φ and θ(d)
    Vec3 twistAxis = Vec3::Zero();
    double twist = 0.0;
};

/// The swing and twist of ball joint `j` (swingLimited or twistLimited) at these poses.
BallAngles ballAngles(const JointModel& j, const BodyState& a, const BodyState* b);

/// How far past its cone or twist limits joint `j` is (rad, ≥ 0).
double ballLimitsPast(const JointModel& j, const BallAngles& angles);

/// A Newton step of a limited ball joint's position projection (as projectGeneral's for a
/// hinge): its point rows with the rows of the bounds it is past, solved together, so that
/// turning it back within its cone or twist range keeps its anchors together; with `from`
/// and h ≠ 0 the move is also given to the solver bodies' velocities (RATTLE). Returns the
/// error it found (m or rad).
double projectLimitedBall(State& state, ContactSolverScratch& s, double h, const State* from, const State& at,
                          const JointModel& j, bool moveA, bool moveB, const SolverBody& A, const SolverBody& B);

/// The bounds a limited ball joint is past (more than kHeld) at these poses, as
/// limitedBallRows takes them (0: the cone, 1: the twist's lower bound, 2: its upper), in
/// `bounds`; how many.
int ballBoundsPast(const JointModel& j, const BodyState& a, const BodyState* b, int* bounds);

/// A limited ball joint's three point rows and after them the rows of `bounds` (as
/// ballBoundsPast gives them), held at the bound, at these poses; in `error` the anchors'
/// gap and each angle's distance past its bound (negative inside). For a group's Newton
/// steps (joint_projection.cpp), which keep the bounds they started with.
void limitedBallRows(const JointModel& j, const BodyState& a, const BodyState* b, const int* bounds, int count,
                     ContactSolverScratch::GeneralRow& rows, Eigen::Matrix<double, 6, 1>* error);

}  // namespace tumble::joint
