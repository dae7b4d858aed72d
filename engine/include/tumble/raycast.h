// Ray casts: the nearest surface a ray meets among the bodies of a compiled model, of a
// scene description (without compiling it), or of one shape. Exact closed forms for the
// primitives, slabs over the faces of a convex hull, Möller–Trumbore over a mesh's
// triangles (through its BVH when it has one). Deterministic: the same ray gives the same
// hit, bit for bit; ties go to the lower body index (and, in a mesh, the lower triangle
// index), so the editor's picking is a function of the camera and the scene only.
//
// Conventions, for every function here:
// - `direction` need not be unit length (it must not be zero); distances are in metres
//   along it, from `origin`; only hits with 0 <= distance <= maxDistance count.
// - The normal is the shape's outward unit normal at the hit point, in the world. A plane's
//   outside is its free side (normal·p > distance); a mesh's outside is the side its
//   triangles run counter-clockwise on, as given.
// - A ray that starts inside a solid shape: see RayStart.
#pragma once

#include <tumble/collision.h>
#include <tumble/math.h>
#include <tumble/scene.h>

#include <array>
#include <limits>
#include <optional>
#include <vector>

namespace tumble {

struct Model;
struct State;

/// What a ray that starts inside a solid shape hits.
enum class RayStart {
    /// The first crossing of the surface: from inside, the point where the ray leaves (its
    /// normal points along the ray). The viewport draws the inside of a body the camera is
    /// in, and whatever stands in front of that far wall; this selects what is under the
    /// cursor. A plane is met from either side; a mesh is a surface.
    Surface,
    /// The solid itself: from inside (or on the surface) the hit is at distance 0, at the
    /// origin, with normal -direction (unit). "Is the origin blocked?". A plane's solid is
    /// the half-space behind it; a mesh has an inside only when it is closed.
    Solid,
};

struct RayHit {
    int body = -1;               ///< model or scene body index; -1 from the per-shape casts
    int part = -1;               ///< the part of a compound hit; -1 for a shape that is not one
    double distance = 0.0;       ///< m, from the origin along the unit direction
    Vec3 point = Vec3::Zero();   ///< world
    Vec3 normal = Vec3::Zero();  ///< world, unit, outward (see the conventions above)
};

inline constexpr double kRayUnbounded = std::numeric_limits<double>::infinity();

/// The nearest body the ray meets in `state` (body frames placed as bodyFramePosition and
/// q give them), through each body's collider: a mesh compiled as a convex hull is hit as
/// that hull.
std::optional<RayHit> rayCast(const Model& model, const State& state, const Vec3& origin,
                              const Vec3& direction, double maxDistance = kRayUnbounded,
                              RayStart start = RayStart::Surface);

/// The nearest body of a scene description, at its initial pose (position, orientation),
/// without compiling it: what the editor shows. A mesh body is hit on its meshData
/// triangles (already scaled), whatever its collision mode; one without meshData is never
/// hit. Meshes are searched triangle by triangle (a BVH would cost more to build than one
/// ray saves); compile the scene and use rayCast for many rays.
std::optional<RayHit> rayCastScene(const SceneDesc& scene, const Vec3& origin, const Vec3& direction,
                                   double maxDistance = kRayUnbounded, RayStart start = RayStart::Surface);

/// One shape description with its body frame at `position` and `orientation` (body to
/// world; normalised here), as rayCastScene sees it. body is -1 in the hit.
std::optional<RayHit> rayShapeDesc(const ShapeDesc& shape, const Vec3& position, const Quat& orientation,
                                   const Vec3& origin, const Vec3& direction,
                                   double maxDistance = kRayUnbounded, RayStart start = RayStart::Surface);

namespace collision {

/// One collision shape placed by `pose` (R a rotation). A mesh with a BVH is searched
/// through it, one without triangle by triangle; both give the same hit. body is -1.
std::optional<RayHit> rayShape(const Shape& shape, const Pose& pose, const Vec3& origin,
                               const Vec3& direction, double maxDistance = kRayUnbounded,
                               RayStart start = RayStart::Surface);

/// Triangles (vertices in the frame `pose` places) hit on either face, triangle by
/// triangle. `closed` says whether they bound a solid (for RayStart::Solid).
std::optional<RayHit> rayTriangles(const std::vector<Vec3>& vertices,
                                   const std::vector<std::array<int, 3>>& triangles, const Pose& pose,
                                   const Vec3& origin, const Vec3& direction,
                                   double maxDistance = kRayUnbounded, RayStart start = RayStart::Surface,
                                   bool closed = false);

}  // namespace collision

}  // namespace tumble
