// The collision shape of a body as line segments in its frame, for the viewport's
// "Show collision shapes": the primitives as outlines (great circles, edges, rims), a mesh
// as the edges of its convex hull, built by the engine's own hull code (or, when it collides
// by its triangles, as their edges). Qt-free.
#pragma once

#include <tumble/scene.h>

#include <vector>

namespace tumble::ui {

/// Segment endpoints, two per segment, in the body frame. Empty for a plane (the grid shows
/// it) and for a mesh body without loaded triangles.
std::vector<Vec3> collisionWire(const ShapeDesc& shape);

}  // namespace tumble::ui
