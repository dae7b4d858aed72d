// GJK distance and EPA penetration between convex shapes in world coordinates.
// A shape is seen as a core (point, segment, box, cylinder, hull, triangle) swept by a
// sphere of `radius`: spheres and capsules are a point / segment plus a radius. GJK runs on
// the cores and the radii are subtracted afterwards, which is exact for round shapes; EPA
// only runs when the cores themselves overlap.
#pragma once

#include <tumble/collision.h>

#include <array>

namespace tumble::collision {

/// A convex shape as GJK sees it: a core (point, segment, box, cylinder, hull, triangle) plus
/// a radius (sphere = point + r, capsule = segment + r). Works in world coordinates.
struct ConvexProxy {
    enum class Core { Point, Segment, Box, Cylinder, Hull, Triangle };
    Core core = Core::Point;
    Pose pose;                         ///< places the core (identity for a triangle)
    double radius = 0.0;               ///< rounding added around the core
    Vec3 halfExtents = Vec3::Zero();   ///< Box: half extents; Segment: y = half length;
                                       ///< Cylinder: x = radius, y = half height
    const ConvexHull* hull = nullptr;  ///< Hull core, in the pose's frame (not owned)
    std::array<Vec3, 3> triangle{};    ///< Triangle core, world points
    /// A hull of at most kTurned vertices: each vertex turned into the world (R v, not
    /// moved by the pose's translation), made once by proxyOf. A support query is then
    /// one dot product per vertex instead of two turns of the direction and the point
    /// around them (GJK and EPA ask one proxy for many support points: hull-rain's rocks
    /// were asked 8 400 times a step). The point is the same either way (of two vertices
    /// tied along the direction, rounding may pick the other).
    static constexpr int kTurned = 8;
    std::array<Vec3, kTurned> turned;  // (not initialised: only the first turnedCount are set)
    int turnedCount = 0;

    /// Places the proxy at `to` (its turned vertices turned again): then it is what proxyOf
    /// gives for `to`, made without going over the hull's vertices for its extent (the time
    /// of impact asks for one shape at many poses).
    void moveTo(const Pose& to);
    /// The farthest point of the core along `dir` (world); any unit or non-unit direction.
    Vec3 support(const Vec3& dir) const;
    /// A point strictly inside the core (or on it for point/segment/triangle).
    Vec3 center() const;
    /// An upper bound of the core's extent from center() (for relative tolerances).
    double size() const { return extent; }

    double extent = 0.0;  ///< set by proxyOf / triangleProxy
};

ConvexProxy proxyOf(const Shape& s, const Pose& pose);  // Sphere, Box, Capsule, Cylinder, Hull
ConvexProxy triangleProxy(const Vec3& a, const Vec3& b, const Vec3& c);  // world points

/// Closest points on the FULL shapes (radius included); distance <= 0 / overlap when touching.
/// When the shapes overlap, distance is minus the penetration depth (through EPA when the
/// cores overlap) and the points are the deepest points of each shape.
struct Distance {
    double distance = 0.0;
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
    bool overlap = false;
    /// Unit, out of B towards A: the direction that separates the shapes fastest (the way
    /// out when overlapping). More accurate than normalising pointA - pointB.
    Vec3 normal = Vec3(0, 1, 0);
};
Distance gjkDistance(const ConvexProxy& a, const ConvexProxy& b);

/// Distance between the CORES only (radii ignored): the building block of the above.
Distance gjkCoreDistance(const ConvexProxy& a, const ConvexProxy& b);

/// normal out of B towards A; depth > 0 overlapping, negative = separation (when within margin).
/// pointA / pointB: the deepest points of A and B along the normal (on their surfaces).
struct Penetration {
    bool hit = false;
    Vec3 normal = Vec3(0, 1, 0);
    double depth = 0.0;
    Vec3 pointA = Vec3::Zero(), pointB = Vec3::Zero();
};
/// GJK, then EPA when the cores overlap. hit is false when the shapes are farther apart
/// than `margin`.
Penetration penetration(const ConvexProxy& a, const ConvexProxy& b, double margin);

namespace detail {
/// One vertex of a GJK / EPA simplex, relative to a reference point (for precision far
/// from the world origin): w = a - b, a and b support points of the two cores.
struct SimplexVertex {
    Vec3 w, a, b;
};
/// Support point of the cores' Minkowski difference A - B along dir, relative to `origin`.
SimplexVertex supportVertex(const ConvexProxy& a, const ConvexProxy& b, const Vec3& dir, const Vec3& origin);
/// EPA from a GJK simplex (1 to 4 vertices) that contains the origin. Returns the core
/// penetration (normal out of B towards A, depth of the cores >= ~0, core points relative
/// to `origin`), radii not applied.
Penetration epa(const ConvexProxy& a, const ConvexProxy& b, const SimplexVertex* simplex, int count,
                const Vec3& origin, double scale);
/// Closest point to the origin on the triangle (a, b, c): barycentric weights.
std::array<double, 3> closestOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c);
}  // namespace detail

}  // namespace tumble::collision
