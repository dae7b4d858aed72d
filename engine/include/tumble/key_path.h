// A keyed path: an animated body's pose at any time from keys of time, position and
// orientation (BodyDesc::keys), with its velocity and angular velocity as the path's exact
// derivatives, so that whatever meets a keyed body sees the velocity its path has. The
// stepper places animated bodies on it (dynamics/integrate.cpp); the editor draws it.
//
// Linear: positions straight between keys at a constant speed, orientations turned at a
// constant rate about a fixed axis (slerp); the velocity jumps at a key (at a key, it is the
// velocity of the segment that starts there: the stepper lands on every key, so a step
// never spans two segments). Smooth: C1 in position and in rotation, easing in at the first
// key and out at the last (zero velocity there, so holding the pose before and after is C1
// too). Positions are cubic Hermite segments with Catmull-Rom tangents (centred differences
// over the neighbouring keys); rotations are q_k exp(h(u)) over a segment, h a cubic Hermite
// curve in the rotation vector from 0 to log(q_k^-1 q_k+1), its end tangents made so that
// the body's angular velocity at each key is the key's (the mean of the constant-rate
// velocities of the two segments beside it), through the right Jacobian of SO(3) (exact,
// closed form). A segment turns the short way: keys less than half a turn apart.
#pragma once

#include <tumble/math.h>
#include <tumble/scene.h>

#include <vector>

namespace tumble {

struct PathPoint {
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Vec3 velocity = Vec3::Zero();         ///< d position / dt
    Vec3 angularVelocity = Vec3::Zero();  ///< world frame, rad/s
};

class KeyPath {
public:
    /// Keys with strictly increasing times and non-zero quaternions (the caller checks), at
    /// least one. Quaternions are normalised and each turned to the hemisphere of the one
    /// before, so that a segment never turns the long way round.
    KeyPath(std::vector<BodyKey> keys, KeyInterpolation interpolation);

    PathPoint at(double t) const;

    /// The largest |v| + |ω| reach over the path: how fast a point `reach` from the body
    /// frame's origin can move (sampled: 32 points a segment and the keys).
    double fastest(double reach) const;

    const std::vector<BodyKey>& keys() const { return keys_; }
    KeyInterpolation interpolation() const { return interpolation_; }

private:
    std::vector<BodyKey> keys_;
    KeyInterpolation interpolation_;
    std::vector<Vec3> velocity_;  // smooth: d position / dt at each key
    std::vector<Vec3> spin_;      // smooth: angular velocity (world) at each key
};

}  // namespace tumble
