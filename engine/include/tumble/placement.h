// Where a body can go without passing into another: what the editor's building tools ask
// (a new body set down on the surface under the view, Drop to Surface).
#pragma once

#include <tumble/model.h>
#include <tumble/state.h>

#include <optional>

namespace tumble {

/// How far body `body` can move from its pose in `state` straight along `direction` (not zero;
/// its length is ignored), its turn kept, before its surface comes within touchTolerance(model)
/// of another body's: one it may collide with (Model::mayCollide) and not joined to it by a
/// joint that keeps the two apart. That distance (m), at most `maxDistance`; nothing when the
/// way is clear that far. 0 when it touches or overlaps another already. Every other body
/// stands where `state` has it.
std::optional<double> travelToTouch(const Model& model, const State& state, int body, const Vec3& direction,
                                    double maxDistance);

}  // namespace tumble
