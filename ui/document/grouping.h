// Group and Ungroup (issue 49 item 4): several bodies made one compound body, each keeping
// its place in the world, its shape, its mass and its material; and a compound made back
// into a body per part. Plain functions on a scene, so that the document applies each as
// one undo step (Document::group, ungroup) and the tests check them without a window.
#pragma once

#include <tumble/scene.h>

#include <optional>
#include <string>
#include <vector>

namespace tumble::ui {

struct Regrouped {
    SceneDesc scene;
    std::vector<int> bodies;  ///< the new bodies' indices in `scene`
};

/// The scene with `indices` (two or more) made one compound body, in place of the first: its
/// frame at the mean of their positions, unturned; each body a part in its place, of its
/// own density (its mass over its volume when it had a mass), friction and restitution. A
/// compound among them gives its parts. The group is dynamic if any of them is, its velocity
/// the bodies' mean by mass (their spin only when they all spin alike). Joints between the
/// grouped bodies go (they are one body now); joints to others move their anchors and axes
/// into the group's frame. Nothing, with the reason in `why`, for fewer than two bodies, a
/// plane, a body with forces (move them to the group first), or a mesh body whose mesh is
/// not loaded or not closed (its volume is needed).
std::optional<Regrouped> groupBodies(const SceneDesc& scene, std::vector<int> indices, std::string* why);

/// The scene with the compound body `index` made a body per part, each where the part is
/// in the world, of the part's density (or the compound's density, or its share of the
/// compound's mass by volume), friction and restitution, moving with the compound's velocity
/// at its place. Nothing, with the reason in `why`, for a body that is not a compound, or one
/// a joint holds (move the joint to a part first).
std::optional<Regrouped> ungroupBody(const SceneDesc& scene, int index, std::string* why);

}  // namespace tumble::ui
