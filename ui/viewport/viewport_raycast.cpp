// A thin adapter: every function here is the engine's ray cast (tumble/raycast.h) with
// RayStart::Surface, its distance turned back into units of the ray's direction.
#include "viewport/viewport_raycast.h"

#include <tumble/mass.h>
#include <tumble/raycast.h>

namespace tumble::ui {

namespace {

// The engine measures metres along the unit direction; these functions, in units of
// `direction`'s length.
std::optional<double> inRayUnits(const Ray& ray, const std::optional<RayHit>& hit) {
    if (!hit) return std::nullopt;
    return hit->distance / ray.direction.norm();
}

std::optional<double> atOrigin(const Ray& ray, const collision::Shape& shape,
                               const Vec3& centre = Vec3::Zero()) {
    collision::Pose pose;
    pose.p = centre;
    return inRayUnits(ray, collision::rayShape(shape, pose, ray.origin, ray.direction));
}

}  // namespace

std::optional<double> raySphere(const Ray& ray, const Vec3& centre, double radius) {
    return atOrigin(ray, collision::Shape::sphere(radius), centre);
}

std::optional<double> rayBox(const Ray& ray, const Vec3& halfExtents) {
    return atOrigin(ray, collision::Shape::box(halfExtents));
}

std::optional<double> rayCapsule(const Ray& ray, double radius, double halfHeight) {
    return atOrigin(ray, collision::Shape::capsule(radius, halfHeight));
}

std::optional<double> rayCylinder(const Ray& ray, double radius, double halfHeight) {
    return atOrigin(ray, collision::Shape::cylinder(radius, halfHeight));
}

std::optional<double> rayPlane(const Ray& ray, const Vec3& normal, double distance) {
    const double len = normal.norm();
    if (!(len > 0.0)) return std::nullopt;
    return atOrigin(ray, collision::Shape::plane(normal / len, distance / len));
}

std::optional<double> rayTriangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
    return inRayUnits(
        ray, collision::rayTriangles({a, b, c}, {{0, 1, 2}}, collision::Pose{}, ray.origin, ray.direction));
}

std::optional<double> rayMesh(const Ray& ray, const TriangleMesh& mesh) {
    return inRayUnits(ray, collision::rayTriangles(mesh.vertices, mesh.triangles, collision::Pose{},
                                                   ray.origin, ray.direction));
}

std::optional<double> rayShape(const Ray& worldRay, const ShapeDesc& shape, const Vec3& position,
                               const Quat& orientation) {
    return inRayUnits(worldRay,
                      rayShapeDesc(shape, position, orientation, worldRay.origin, worldRay.direction));
}

}  // namespace tumble::ui
