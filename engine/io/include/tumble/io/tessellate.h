// Render meshes for the exporters: every shape as triangles with normals, in the body
// frame, counter-clockwise seen from outside. Plain C++ (the viewport draws with Qt3D's
// own primitives; these are for files).
#pragma once

#include <tumble/scene.h>

#include <cstdint>
#include <vector>

namespace tumble::io {

struct RenderMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;           ///< unit, one per position
    std::vector<std::uint32_t> indices;  ///< three per triangle
};

/// `segments`: around the axis of a sphere, capsule or cylinder (at least 3; rings along
/// it are segments / 2). Spheres, capsules and cylinder sides have smooth normals; boxes,
/// caps and meshes flat ones (a mesh's triangles each get their own three vertices).
/// A plane, infinite in the scene, becomes a square of side 2 * planeHalfSize centred on
/// the point of the plane nearest the body frame's origin, facing its free side.
/// A mesh without meshData gives an empty RenderMesh. A compound gives its parts' meshes
/// placed in the body frame, part after part (an exporter that wants one mesh per part
/// tessellates each part's shape).
RenderMesh tessellate(const ShapeDesc& shape, int segments = 32, double planeHalfSize = 50.0);

}  // namespace tumble::io
