// Collision groups and the pairs of bodies kept apart (issue 50 item 3): checked and
// compiled into the model's filter (Model::groupCollides, pairsApart, mayCollide).
#pragma once

#include <tumble/collision_groups.h>
#include <tumble/model.h>
#include <tumble/scene.h>

namespace tumble {

/// Throws SceneError naming the field: settings.collision_groups[k] empty, repeated or past
/// the 64th; settings.groups_apart[k][m] not a group; bodies[i].collision_group not a group;
/// no_collide[k][m] not a body, or a body with itself.
void validateCollisionGroups(const SceneDesc& scene);

/// Fills the model's filter from a validated scene (after its bodies are compiled).
void compileCollisionGroups(const SceneDesc& scene, Model& m);

}  // namespace tumble
