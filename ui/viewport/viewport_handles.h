// The math of the viewport's move and rotate handles, apart from Qt3D and the widget: a
// drag is a function of the mouse rays at press and now, the handle's axis and origin, and
// the snapping step, so tests can compute what a drag must do and compare.
#pragma once

#include "document/joint_presets.h"

#include <tumble/scene.h>

#include <optional>

namespace tumble::ui::handles {

/// The parameter s of the point origin + s * axis (axis of unit length) nearest to the ray
/// rayOrigin + t * rayDir (t free); nothing when the ray is (nearly) parallel to the axis,
/// where a drag along it is not defined.
std::optional<double> axisParameter(const Vec3& rayOrigin, const Vec3& rayDir, const Vec3& origin,
                                    const Vec3& axis);

/// Where the ray meets the plane through `origin` with normal `axis` (t >= 0); nothing when
/// the ray runs (nearly) along the plane or points away from it.
std::optional<Vec3> planeHit(const Vec3& rayOrigin, const Vec3& rayDir, const Vec3& origin, const Vec3& axis);

/// The right-handed angle about `axis` (unit) that turns `from` towards `to`, both taken in
/// the plane normal to `axis`, in (-pi, pi].
double signedAngle(const Vec3& from, const Vec3& to, const Vec3& axis);

/// `value` rounded to the nearest multiple of `step`; `value` itself when step <= 0.
double snap(double value, double step);

/// The body moved by `distance` along `axis`.
BodyDesc moved(const BodyDesc& body, const Vec3& axis, double distance);
/// The body turned by `angle` (radians) about the world line through `pivot` along `axis`:
/// its orientation turns, and its position turns about the pivot.
BodyDesc rotated(const BodyDesc& body, const Vec3& pivot, const Vec3& axis, double angle);

/// Where part `part` of the compound `body` stands in the world (its frame's origin).
Vec3 partOrigin(const BodyDesc& body, int part);
/// The body with its part `part` moved by `distance` along the world `axis` (its position
/// kept in the body's frame), or turned by `angle` about the world `axis` through the part's
/// own origin. The body itself stays where it is.
BodyDesc partMoved(const BodyDesc& body, int part, const Vec3& axis, double distance);
BodyDesc partRotated(const BodyDesc& body, int part, const Vec3& axis, double angle);

/// The joint with its anchor on body A (worldAnchorA, document/joint_presets.h: where a
/// selected joint's handles stand) moved by `distance` along `axis` (world). Both anchors move
/// together (they describe the one point where the bodies are joined), each kept in its
/// own body's frame; a distance or rope joint's ends are apart, and only A's moves.
JointDesc movedAnchor(const SceneDesc& scene, const JointDesc& j, const Vec3& axis, double distance);
/// The joint with its axis (and B's own axis, if it has one) turned by `angle` about the
/// world `axis`; each stays in its own body's frame. A joint without an axis is unchanged.
JointDesc turnedAxis(const SceneDesc& scene, const JointDesc& j, const Vec3& axis, double angle);

/// A ball joint with its limit grip `grip` (ballLimitGrip, document/joint_presets.h) dragged
/// to where the ray points: a cone's half-angle becomes the angle from n of the ray's hit on
/// the plane of n and the grip's direction (a round cone stays round), a twist bound the
/// angle about n from e1 of its hit on the plane normal to n; rounded to `step` rad (0: not)
/// and kept valid (a half-angle within [1°, 179°], the twist range within [−π, π] with
/// lower ≤ upper). The joint as it is where the ray meets no such plane.
JointDesc draggedBallLimit(const BallLimitFrame& f, const JointDesc& j, int grip, const Vec3& rayOrigin,
                           const Vec3& rayDir, double step);

}  // namespace tumble::ui::handles
