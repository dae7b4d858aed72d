// The paper's collision tests (section 3), written plainly as the REFERENCE the fast paths
// are checked against. Slow on purpose: every vertex against every face, every edge against
// every face, no culling beyond what cannot change the answer.
//
// - The plane test E(p) = a x + b y + c z + d (19): with a unit outward normal (a, b, c),
//   E(p) is the signed distance of p to the plane, > 0 in front, <= 0 on or behind.
// - A vertex of one convex body is inside the other when E(p) < 0 for every face plane.
// - A vertex against a concave closed mesh: ray parity, with another ray when a crossing
//   falls on (within a tolerance of) an edge or a vertex, or the ray grazes a triangle.
// - Penetrations with no vertex inside (the paper's Fig. 3) are caught by the edge-face
//   test: every edge of one body against every face polygon of the other.
//
// Depth and normal of the reference (what a cross-check compares):
// - A point of the reference carries its own depth and normal. A vertex of A inside B:
//   depth = distance from the vertex to B's boundary (for a convex B, to B's nearest face
//   plane; for a mesh, to the nearest triangle), normal = the direction A moves to take the
//   vertex out along that shortest way (B's face normal, out of B). A vertex of B inside A:
//   the same with the roles swapped and the normal negated. An edge-face crossing lies on
//   both surfaces: depth 0, normal = the crossed face's normal oriented out of B.
// - The pair's depth and normal, two convex bodies: the separating-axis minimum. For each
//   candidate axis n (face normals of B, negated face normals of A, and the cross products
//   of an edge of A with an edge of B) the overlap is how far A must move along n to clear
//   B: overlap(n) = max over B of n·x - min over A of n·x; for a face axis of B that is
//   the deepest vertex of A behind that face plane by the plane test. The reference depth
//   is the smallest overlap, the normal its axis: the minimum translation that separates
//   two convex polyhedra, which is what box-box SAT and GJK/EPA report. (It is >= the
//   deepest vertex depth above; equal when one vertex pokes into one face.)
// - The pair's depth and normal when a mesh is involved: the deepest point above (a lower
//   bound of the minimum translation).
// - For two convex bodies the reference points are exactly the vertices of the
//   intersection polytope A ∩ B, so "within the reference's contact region" means inside
//   both bodies, which the cross-check tests with the plane test.
#pragma once

#include "common/closest_point.h"

#include <tumble/collision.h>

#include <array>
#include <vector>

namespace tumble::collision::reference {

/// E(p) of (19) for the plane n·x + d = 0: n·p + d. With a unit n, the signed distance,
/// > 0 on the side n points to.
double planeValue(const Vec3& n, double d, const Vec3& p);

/// A polyhedron placed in the world: the form every test below works on.
struct Polyhedron {
    struct Face {
        Vec3 normal;                ///< outward unit normal (world)
        double offset = 0.0;        ///< normal·x == offset on the face: E(x) = normal·x - offset
        std::vector<int> vertices;  ///< counter-clockwise seen from outside
    };
    std::vector<Vec3> vertices;  ///< world
    std::vector<Face> faces;
    std::vector<std::array<int, 2>> edges;  ///< each undirected edge once
    bool convex = true;                     ///< false: a triangle mesh, inside tested by ray parity
    bool closed = true;                     ///< false: an open mesh, no inside (only edge-face crossings)
};

/// A Box, Hull or Mesh shape at a pose, in the world. Throws std::invalid_argument for
/// other kinds.
Polyhedron worldPolyhedron(const Shape& shape, const Pose& pose);

/// Points against a plane by (19): every point with E(p) < margin, as a contact whose
/// depth is -E(p) (the plane is B: normal = n, position midway = p + n depth / 2).
struct PlaneHit {
    int vertex = -1;
    double depth = 0.0;
};
std::vector<PlaneHit> pointsAgainstPlane(const std::vector<Vec3>& points, const Vec3& n, double offset,
                                         double margin);

/// A world point against a convex polyhedron, every face by the plane test.
struct Inside {
    bool inside = false;         ///< E(p) < 0 for every face
    double depth = 0.0;          ///< distance to the nearest face plane (-max E), > 0 inside
    int face = -1;               ///< that face
    Vec3 normal = Vec3::Zero();  ///< its outward normal
};
Inside pointInConvex(const Polyhedron& body, const Vec3& p);
/// The same against a ConvexHull at a pose.
Inside pointInConvex(const ConvexHull& hull, const Pose& pose, const Vec3& p);

/// The k-th direction ray parity casts (mesh frame): a fixed, deterministic pseudo-random
/// sequence of unit vectors; k = 0 is the first ray. Exposed so tests can aim at edges.
Vec3 parityRayDirection(int k);

/// Ray parity for a point in the mesh frame. Rays are cast along parityRayDirection(0),
/// (1), ...; a ray is discarded when a crossing is within a tolerance of a triangle's edge
/// or vertex (1e-9 of the triangle's height, or the rounding of the crossing if larger), or
/// the ray runs in the plane of a triangle it meets. Uses mesh.bvh when present, else every
/// triangle. Crossings closer than rounding to the origin are not counted, so a point on
/// the surface may be reported either way. After kMaxParityRays discarded rays (the point
/// sits on an edge) the last ray's count decides. The mesh must be closed.
struct Parity {
    bool inside = false;
    int rays = 0;             ///< rays cast, >= 1
    double nearestHit = 0.0;  ///< distance to the nearest crossing of the deciding ray
                              ///< (infinite when none): the surface is at most that far
};
constexpr int kMaxParityRays = 32;
Parity rayParity(const MeshShape& mesh, const Vec3& localPoint);

/// Ray parity for a world point against the closed mesh at pose. `rays` (optional)
/// receives the number of rays cast.
bool pointInMesh(const MeshShape& mesh, const Pose& pose, const Vec3& p, int* rays = nullptr);

using ::tumble::closestPointOnTriangle;  // (common/closest_point.h)

/// Distance from p to the closest point of the faces' polygons (all of them; a mesh's
/// faces are its triangles), that point, and (optional) the face it lies on.
double distanceToSurface(const Polyhedron& body, const Vec3& p, Vec3& closest, int* face = nullptr);

/// An edge of one polyhedron piercing a face polygon of the other.
struct EdgeFaceCrossing {
    int edge = -1;   ///< index into edges of the first
    int face = -1;   ///< index into faces of the second
    double t = 0.0;  ///< along the edge, from edges[edge][0] (0) to [1] (1)
    Vec3 point;      ///< the crossing, world
};
/// Every edge of `edgesOf` against every face of `facesOf`: the points where an edge
/// crosses a face's plane strictly inside the face polygon. An edge lying in a face's plane
/// crosses nothing.
std::vector<EdgeFaceCrossing> edgeFaceCrossings(const Polyhedron& edgesOf, const Polyhedron& facesOf);

/// One point of the reference contacts (see the header comment for depth and normal).
struct RefPoint {
    enum class Kind { VertexOfAInB, VertexOfBInA, EdgeOfAFaceOfB, EdgeOfBFaceOfA };
    Kind kind = Kind::VertexOfAInB;
    Vec3 position;  ///< the vertex or the crossing itself, world
    Vec3 normal;    ///< out of B towards A
    double depth = 0.0;
    int feature = -1;  ///< the vertex, or the edge
    int face = -1;     ///< B's (A's) nearest face, or the crossed face
};

struct RefContacts {
    bool penetrating = false;     ///< some vertex inside, or some edge crossing a face
    double depth = 0.0;           ///< the pair's depth (header comment); < 0: separation
    Vec3 normal = Vec3(0, 1, 0);  ///< out of B towards A
    std::vector<RefPoint> points;
};

/// Reference contacts between two polyhedra (Box, Hull or Mesh) at their poses. For two
/// convex bodies `depth` is the separating-axis minimum also when they are apart (then < 0:
/// the largest gap along a candidate axis, a lower bound of the distance).
RefContacts referenceContacts(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb);

/// Every candidate separating axis of two convex polyhedra with its overlap: the face
/// normals of B and of A and the normalised cross products of an edge of A with an edge of
/// B (parallel edges skipped: the faces cover them), each in both directions. The smallest
/// overlap is referenceContacts' depth.
struct AxisOverlap {
    Vec3 axis;
    double overlap = 0.0;
};
std::vector<AxisOverlap> separatingAxes(const Polyhedron& a, const Polyhedron& b);

/// The separating-axis overlap of two convex polyhedra along n (how far A must move along n
/// to clear B): max over B of n·x - min over A of n·x.
double overlapAlong(const Polyhedron& a, const Polyhedron& b, const Vec3& n);

}  // namespace tumble::collision::reference
