// Convex hulls as the collision stages use them (tumble::collision::ConvexHull): built from
// a point cloud by qhull (reentrant C API), with coplanar facets merged into polygons, or
// written directly for a box.
#pragma once

#include <tumble/collision.h>
#include <tumble/math.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace tumble::mesh {

/// The hull cannot be built: too few points, all of them on a plane or a line, or
/// non-finite input. what() says which, in words a user can act on.
class HullError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The convex hull of `points` (at least 4, not all coplanar, all finite).
/// - vertices: only the points on the hull (a copy of them; interior points are dropped);
/// - faces: one per plane of the hull, coplanar facets merged into a convex polygon, with
///   an outward unit normal, offset = normal·v for v on the face (points inside have
///   normal·p < offset), vertices counter-clockwise seen from outside;
/// - edges: each undirected edge of the merged polygons once;
/// - interiorPoint: the mean of the hull's vertices.
/// Throws HullError for flat or degenerate input.
collision::ConvexHull convexHull(const std::vector<Vec3>& points);

/// A box centred at the origin, axis-aligned, with the given half extents (all > 0):
/// 8 vertices, 6 quad faces, 12 edges, interiorPoint at the origin. No qhull involved.
collision::ConvexHull boxHull(const Vec3& halfExtents);

}  // namespace tumble::mesh
