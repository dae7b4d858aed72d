// An animated body's keys as the editor edits them (issue 50 item 2). The body's position
// and orientation in the document are always where its path has it at t = 0 (what frame 0
// draws, and where a run starts it); moving it there moves the key at t = 0, or adds one.
#pragma once

#include <tumble/scene.h>

namespace tumble::ui {

/// Whether an animated body's keys make a path (times in order, finite positions, non-zero
/// orientations): what the engine checks in full (compile_keys.cpp), for the editor's drawing.
bool keysMakeAPath(const BodyDesc& b);

/// `after` is `before` edited. For an animated body with keys: a new pose (position or
/// orientation) with the keys as they were is a move at frame 0: the key at t = 0 takes it,
/// or a key is added there. Then the pose is set to the path's at t = 0 (the keys may have
/// changed it). Other bodies are left as they are.
void followKeys(const BodyDesc& before, BodyDesc& after);

/// Keys the pose (`position`, `orientation`: the body frame's) at time `t`: the key at t
/// (within 1e-9 s) takes it, or one is added in time order. A body that is not animated
/// becomes so, giving up what an animated body cannot have (mass, density, inertia, centre
/// of mass, forces, velocities); its keys start with this one.
void insertKey(BodyDesc& b, double t, const Vec3& position, const Quat& orientation);

/// Moves key k to time `t`, keeping the keys in time order; false (nothing changed) when
/// another key is at t (within 1e-9 s) or k is not a key.
bool moveKey(BodyDesc& b, int k, double t);

/// Removes the key at index k, unless it is the last one (an animated body needs one);
/// false when it is not removed.
bool removeKey(BodyDesc& b, int k);

}  // namespace tumble::ui
