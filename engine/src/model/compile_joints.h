// Compile stage: the scene's joints (compile_joints.cpp).
#pragma once

#include <tumble/model.h>
#include <tumble/scene.h>

namespace tumble {

// validateJoints, the joints' validation, is public (tumble/model.h).

/// Fills m.joints and m.jointed (validated scene; `start`: the scene's initial state, for
/// lengths taken from it). A rope of length 0 throws SceneError.
void compileJoints(const SceneDesc& scene, const State& start, Model& m);

}  // namespace tumble
