// Mass properties: closed forms for the primitives and exact polyhedral integration
// for closed triangle meshes.
#pragma once

#include <tumble/math.h>
#include <tumble/scene.h>

#include <array>
#include <vector>

namespace tumble {

/// Mass, centre of mass (body frame) and inertia tensor about the centre of mass
/// (body axes) of a solid of uniform density.
struct MassProperties {
    double mass = 0.0;
    Vec3 centerOfMass = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
};

/// Volume of a primitive shape (m³). Planes and meshes have none here.
double shapeVolume(const ShapeDesc& shape);

/// Mass properties of a primitive of the given mass (sphere, box, capsule, cylinder).
MassProperties primitiveMassProperties(const ShapeDesc& shape, double mass);

struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
};

/// True when every edge is shared by exactly two triangles that run it in opposite
/// directions: the surface bounds a solid and the volume integrals below hold.
bool isClosed(const TriangleMesh& mesh);

/// Volume, centre of mass and inertia of the solid bounded by a closed mesh of uniform
/// density. The volume integrals of (15) are turned into a sum over the surface
/// triangles (each with the origin spans a signed tetrahedron), so the result is exact
/// for any closed polyhedron, convex or not. `volume` receives the signed volume.
MassProperties meshMassProperties(const TriangleMesh& mesh, double density, double* volume = nullptr);

/// Why an inertia tensor is not physical, or empty when it is: it must be symmetric,
/// positive definite, and its principal moments must obey the triangle inequality.
std::string inertiaProblem(const Mat3& inertia);

}  // namespace tumble
