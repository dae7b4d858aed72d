// A hinge's angle and a slider's offset at given poses (the coordinate their limits, motors,
// springs and servos act on), and the energy the joints' springs hold: below the solver, so
// that the model's energy can count it.
#pragma once

#include <limits>

#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble::joint {

/// A hinge's angle about its axis at these poses, within π of `near` (NaN: within [-π, π]);
/// 0 as the scene places the bodies.
double hingeAngle(const JointModel& j, const BodyState& a, const BodyState* b,
                  double near = std::numeric_limits<double>::quiet_NaN());

/// The angle the hinge `j` had at the end of the last step in `state` (NaN: unknown).
inline double hingeNear(const State& state, const JointModel& j) {
    return j.index < static_cast<int>(state.hingeAngles.size()) ? state.hingeAngles[j.index]
                                                                : std::numeric_limits<double>::quiet_NaN();
}

/// A hinge's angle (near the last step's, as `state` tracks it) or a slider's offset of A's
/// anchor from B's along B's axis, with the bodies at `a` and `b` (null: the world).
double jointCoordinate(const JointModel& j, const BodyState& a, const BodyState* b, const State& state);

/// A six-axis joint's coordinates with its bodies at `a` and `b` (null: the world): A's
/// anchor's offset from B's along B's joint frame axes (m), then the rotation vector of the
/// turn from B's frame to A's in those axes (rad, at most π long); all 0 as placed.
Eigen::Matrix<double, 6, 1> sixAxisCoordinates(const JointModel& j, const BodyState& a, const BodyState* b);

/// The coordinate of the free axis `x` of joint `j` (j itself for a hinge or slider).
double axisCoordinate(const JointModel& j, const JointAxis& x, const BodyState& a, const BodyState* b,
                      const State& state);

/// The energy the joints' springs hold in `state`: ½ k (coordinate − rest)² each.
double jointSpringEnergy(const Model& model, const State& state);

}  // namespace tumble::joint
