// Animated bodies (issue 50 item 1): their keys checked, and compiled into a path the
// stepper places them on (tumble/key_path.h).
#pragma once

#include <tumble/model.h>
#include <tumble/scene.h>

#include <string>

namespace tumble {

/// Throws SceneError naming the field: an animated body without keys, with a velocity or
/// angular velocity of its own, or with a key whose time is not finite or not later than
/// the one before, whose position is not finite, or whose orientation is not finite or the
/// zero quaternion; keys on a body that is not animated. `path` is "bodies[i]".
void validateKeys(const BodyDesc& b, const std::string& path);

/// An animated body's model: kinematic, on the path of its keys; each key's time goes into
/// `switchTimes` (the stepper lands on them: a linear path's velocity jumps there).
void compileAnimated(const BodyDesc& d, BodyModel& b, std::vector<double>& switchTimes);

}  // namespace tumble
