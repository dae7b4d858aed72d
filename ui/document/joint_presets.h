// The joints Edit > Add Joint (and the scene tree's Joint button) makes for the selected
// bodies, placed where a user would put them first; and where a joint's bodies and anchors
// are in the scene as placed (the joint panel, the viewport's handles and picking). Qt-free.
#pragma once

#include <tumble/scene.h>

#include <optional>
#include <string>
#include <vector>

namespace tumble::ui {

/// A joint of `type` for `selection` (body indices of `scene`):
/// - two bodies (`selection` in the order they were picked): between them; the first picked
///   is the base (body_b) and the second the moving part (body_a), so that a positive motor
///   turns or slides the second picked the right-hand way along the axis; but body_a is the
///   dynamic one when only the other cannot move. Ball, hinge, slider and fixed anchored at
///   the midpoint of their positions, distance and rope at each body's origin (their
///   length: the distance in the scene);
/// - one body: to the world; ball, hinge, slider and fixed anchored at its position,
///   distance and rope at a world point 1 m above it (a pendulum's string).
/// A hinge turns about the world's y axis (a door, a turntable) and a slider slides along
/// the world's x axis, as the bodies are placed; both are given in body_a's frame.
/// Nothing, with `why` set, when the selection is not one or two bodies, or has no dynamic
/// one. The name is the type's (the document makes it unique).
std::optional<JointDesc> presetJoint(JointType type, const SceneDesc& scene, const std::vector<int>& selection,
                                     std::string* why);

/// Joint `j` with its bodies swapped (A the base's place, B the moving part's), meaning the
/// same: anchors and axes follow their bodies, a hinge's or slider's limits and motor speed
/// change sign (its coordinate is A's against B). Nothing for a joint to the world.
std::optional<JointDesc> swappedJoint(const SceneDesc& scene, const JointDesc& j);

/// Keys a joint's servo target at `time` (Edit > Insert Key with the joint selected): the
/// target it has there (its keys', or its fixed target, which then also keys t = 0), a key
/// already at that time kept. False when the joint has no servo.
bool insertServoKey(JointDesc& j, double time);

/// Where body `name` is placed (the world's frame for an empty name or one no body has).
struct BodyFrame {
    Vec3 p = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 toWorld(const Vec3& local) const { return p + q * local; }
    Vec3 toLocal(const Vec3& world) const { return q.conjugate() * (world - p); }
};
BodyFrame frameOf(const SceneDesc& scene, const std::string& name);

/// Joint `j`'s anchors in the world, with the scene's bodies as placed.
Vec3 worldAnchorA(const SceneDesc& scene, const JointDesc& j);
Vec3 worldAnchorB(const SceneDesc& scene, const JointDesc& j);

/// Where a ball joint's swing cone and twist range are drawn and dragged, as the scene
/// places the bodies (as compile_joints.cpp sets them): from anchor B about B's axis `n`
/// (axis_b, or A's axis as placed), `e1` A's first frame axis across its axis made square
/// to n (the first half-angle's direction, and zero twist), `size` long (1.2 × A's bounding
/// radius). Nothing for a joint that is not a ball with an axis and a limit.
struct BallLimitFrame {
    Vec3 anchor = Vec3::Zero(), n = Vec3::UnitY(), e1 = Vec3::UnitX();
    double size = 0.0;
};
std::optional<BallLimitFrame> ballLimitFrame(const SceneDesc& scene, const JointDesc& j);

/// A ball joint's limit grips in the world: 0 and 1 its cone's rim towards e1 and n × e1
/// (its half-angles), 2 and 3 the ends of its twist arc (a third of the size out). Nothing
/// for a limit it does not have.
std::optional<Vec3> ballLimitGrip(const BallLimitFrame& f, const JointDesc& j, int grip);

}  // namespace tumble::ui
