// Concave dynamic meshes (Shape kind Mesh used as it is) against a plane and against each
// other, by the paper's tests: the plane test (19) for a mesh's vertices, and for two meshes
// ray parity for the vertices of each inside the other plus edge-face crossings for the
// penetrations no vertex shows (Fig. 3), through the meshes' BVHs.
#pragma once

#include <tumble/collision.h>

#include <vector>

namespace tumble::collision {

/// A triangle mesh against a plane: its vertices by the plane test (19). One manifold with
/// the plane's normal (out of the plane towards the mesh), the deepest vertex and up to
/// three more spread over the support; points with depth > -margin.
void collideMeshPlane(const Shape& mesh, const Pose& pm, const Shape& plane, const Pose& pp, double margin,
                      ManifoldList& out);

/// Two triangle meshes: vertices of each inside the other by ray parity (closed meshes),
/// plus edge-face crossings, through the BVHs (TriangleBvh::queryPairs / query).
/// - a vertex of a inside b: depth = distance to b's surface, normal = the way out (out of b);
///   a vertex of a outside b within margin of b's surface: a near contact, depth = -distance;
///   the same for the vertices of b, with the normal negated;
/// - an edge passing through the other mesh with no vertex inside it (Fig. 3): a point at
///   its deepest place, depth and normal of the edge against the edge of the other mesh it
///   passes (the separating axis of the two edges).
/// Normal out of b towards a; points grouped into manifolds by similar normal, up to 4
/// points each, several manifolds allowed; bodyA/bodyB left for the caller. A mesh
/// without a BVH gets a temporary one.
void collideMeshMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                     ManifoldList& out);

}  // namespace tumble::collision
