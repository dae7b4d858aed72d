// Exact ray casts against the scene's shapes, for picking in the viewport: an adapter over
// the engine's ray cast (tumble/raycast.h, RayStart::Surface). Qt-free and deterministic:
// the click that selects a body is a function of the camera and the scene only, so tests
// can aim at a body and know what they will hit.
#pragma once

#include <tumble/scene.h>

#include <optional>

namespace tumble::ui {

/// A ray origin + t * direction, t >= 0; `direction` need not be unit length, but distances
/// are in units of its length (unit length: metres).
struct Ray {
    Vec3 origin = Vec3::Zero();
    Vec3 direction = Vec3(0, 0, -1);
};

// Each returns the smallest t >= 0 at which the ray meets the surface, or nothing. A ray
// that starts inside a closed shape hits where it leaves. Local shapes sit at the origin of
// their frame; capsule and cylinder axes are y (as in ShapeDesc).
std::optional<double> raySphere(const Ray& ray, const Vec3& centre, double radius);
std::optional<double> rayBox(const Ray& ray, const Vec3& halfExtents);
std::optional<double> rayCapsule(const Ray& ray, double radius, double halfHeight);
std::optional<double> rayCylinder(const Ray& ray, double radius, double halfHeight);
/// The plane n·p = distance, from either side.
std::optional<double> rayPlane(const Ray& ray, const Vec3& normal, double distance);
/// Either face of the triangle.
std::optional<double> rayTriangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c);
std::optional<double> rayMesh(const Ray& ray, const TriangleMesh& mesh);

/// A world ray against `shape` placed at `position` with `orientation` (body to world).
/// A mesh shape without meshData is never hit.
std::optional<double> rayShape(const Ray& worldRay, const ShapeDesc& shape, const Vec3& position,
                               const Quat& orientation);

}  // namespace tumble::ui
