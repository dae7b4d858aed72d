// Compile stage: the scene's joints (compile_joints.cpp).
#pragma once

#include <tumble/model.h>
#include <tumble/scene.h>

namespace tumble {

/// Throws SceneError naming joints[i].field: an empty or repeated name, a body that does not
/// exist, a joint of a body with itself, one between bodies that cannot move, a non-finite
/// anchor or length.
void validateJoints(const SceneDesc& scene);

/// Fills m.joints and m.jointed (validated scene; `start`: the scene's initial state, for
/// lengths taken from it). A rope of length 0 throws SceneError.
void compileJoints(const SceneDesc& scene, const State& start, Model& m);

}  // namespace tumble
