// The bodies the scene tree's Add menu creates: 1 kg, unit-sized, placed above what the
// scene already holds so that a new body never starts inside another one.
#pragma once

#include <tumble/scene.h>

namespace tumble::ui {

/// A body of `type` with the editor's defaults (name = the shape's name, 1 kg, restitution
/// and friction 0.5), dropped above every body of `scene`: its lowest point sits 0.5 m over
/// the highest point of the others, and never below y = 0.5 m. A plane is a static floor
/// through the origin. A mesh body has no file yet: the import dialog fills it in.
BodyDesc presetBody(ShapeType type, const SceneDesc& scene);

/// The highest world y reached by a body of `scene` other than a plane (0 when none is).
double pileTop(const SceneDesc& scene);

/// `body` moved straight up (x, z and orientation kept) so that its lowest point sits
/// 0.5 m over `top`. Planes are returned as they are.
BodyDesc placedAbove(BodyDesc body, double top);

/// The radius of a sphere about the body's origin that holds its whole shape (0 for a plane,
/// 1 for a mesh not loaded).
double boundingRadius(const ShapeDesc& shape);

/// Half the size of the body's box along the world axes, about its position: exact for an
/// unturned sphere, box, capsule and cylinder, its bounding sphere's for anything else.
Vec3 halfSize(const BodyDesc& body);

/// Half the height of a body's bounding box along the world y axis, about its position
/// (a bound: the box of a rotated shape is taken from its bounding sphere). 0 for planes.
double halfHeightAboveOrigin(const BodyDesc& body);

}  // namespace tumble::ui
