// The joints Edit > Add Joint (and the scene tree's Joint button) makes for the selected
// bodies, placed where a user would put them first. Qt-free.
#pragma once

#include <tumble/scene.h>

#include <optional>
#include <string>
#include <vector>

namespace tumble::ui {

/// A joint of `type` for `selection` (body indices of `scene`):
/// - two bodies: between them; ball, hinge, slider and fixed anchored at the midpoint of
///   their positions, distance and rope at each body's origin (their length: the distance
///   in the scene). body_a is the dynamic one when only the other cannot move;
/// - one body: to the world; ball, hinge, slider and fixed anchored at its position,
///   distance and rope at a world point 1 m above it (a pendulum's string).
/// A hinge turns about the world's y axis (a door, a turntable) and a slider slides along
/// the world's x axis, as the bodies are placed; both are given in body_a's frame.
/// Nothing, with `why` set, when the selection is not one or two bodies, or has no dynamic
/// one. The name is the type's (the document makes it unique).
std::optional<JointDesc> presetJoint(JointType type, const SceneDesc& scene, const std::vector<int>& selection,
                                     std::string* why);

}  // namespace tumble::ui
