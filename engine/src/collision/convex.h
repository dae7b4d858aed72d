// The general narrowphase: any two convex shapes, and a convex shape against a triangle mesh.
#pragma once

#include <tumble/collision.h>

#include <vector>

namespace tumble::collision {

/// Contacts between two convex shapes of any kind (Sphere, Box, Capsule, Cylinder, Hull),
/// appended to `out` as manifolds (bodyA/bodyB left for the caller; normal out of b towards a).
/// Appends nothing when the shapes are farther apart than `margin`.
void collideConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ManifoldList& out);
/// The same; when the shapes are farther apart than `margin` (nothing appended), `apart`
/// gets the unit direction out of b towards a along which GJK found them apart.
void collideConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                   ManifoldList& out, Vec3& apart);

/// A convex shape against a triangle mesh (Shape kind Mesh) through the mesh's BVH.
/// The convex is A, the mesh is B: normals point out of the mesh towards the convex.
void collideConvexMesh(const Shape& convex, const Pose& pc, const Shape& mesh, const Pose& pm, double margin,
                       ManifoldList& out);

}  // namespace tumble::collision
