// A scene's collision groups by name (issue 50 item 3; docs/scene-format.md "Collision groups").
#pragma once

#include <tumble/scene.h>

#include <string>
#include <vector>

namespace tumble {

/// The most collision groups a scene may name, "default" included (one bit each).
inline constexpr int kMostCollisionGroups = 64;

/// The scene's groups in the order the file names them, with "default" first when it does
/// not name it: a group's index is its place here.
std::vector<std::string> collisionGroupNames(const Settings& settings);

}  // namespace tumble
