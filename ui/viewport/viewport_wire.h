// The collision shape of a body as line segments in its frame, for the viewport's
// "Show collision shapes": the primitives as outlines (great circles, edges, rims), a mesh
// as the edges of its convex hull, built by the engine's own hull code (or, when it collides
// by its triangles, as their edges). Qt-free.
#pragma once

#include <tumble/scene.h>

#include <array>
#include <vector>

namespace tumble::ui {

/// Segment endpoints, two per segment, in the body frame. Empty for a plane (the grid shows
/// it) and for a mesh body without loaded triangles. `pieces`, when given, gets one entry
/// per segment: the piece it outlines (a compound's part, a mesh's convex part; 0 for a
/// shape of one piece), so that each piece can be drawn in its own colour.
std::vector<Vec3> collisionWire(const ShapeDesc& shape, std::vector<int>* pieces = nullptr);

/// The colour of piece `k` of a collision wire, as red, green, blue from 0 to 1: piece 0 the
/// wire's cyan, the others hues far apart from each other (the golden angle).
std::array<float, 3> pieceColour(int k);

}  // namespace tumble::ui
