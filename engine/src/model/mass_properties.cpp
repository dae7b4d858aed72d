// Closed-form mass properties of the primitives, the check that an inertia tensor is
// physical, and exact polyhedral integration for closed triangle meshes.
#include <tumble/mass.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace tumble {

using std::numbers::pi;

double shapeVolume(const ShapeDesc& s) {
    const double r = s.radius;
    const double h = s.halfHeight;
    switch (s.type) {
        case ShapeType::Sphere: return 4.0 / 3.0 * pi * r * r * r;
        case ShapeType::Box: return 8.0 * s.halfExtents.prod();
        case ShapeType::Cylinder: return pi * r * r * 2.0 * h;
        case ShapeType::Capsule: return pi * r * r * 2.0 * h + 4.0 / 3.0 * pi * r * r * r;
        case ShapeType::Plane:
        case ShapeType::Mesh:
        case ShapeType::Compound: return 0.0;
    }
    return 0.0;
}

MassProperties primitiveMassProperties(const ShapeDesc& s, double m) {
    MassProperties mp;
    mp.mass = m;
    const double r = s.radius;
    const double h = s.halfHeight;
    Vec3 d = Vec3::Zero();  // principal moments; the primitives are centred and axis-aligned
    switch (s.type) {
        case ShapeType::Sphere: d.setConstant(0.4 * m * r * r); break;
        case ShapeType::Box: {
            const Vec3 e2 = s.halfExtents.cwiseProduct(s.halfExtents);
            d = m / 3.0 * Vec3(e2.y() + e2.z(), e2.x() + e2.z(), e2.x() + e2.y());
            break;
        }
        case ShapeType::Cylinder: {
            const double side = m * (3.0 * r * r + 4.0 * h * h) / 12.0;
            d = Vec3(side, 0.5 * m * r * r, side);
            break;
        }
        case ShapeType::Capsule: {
            // Mass shared by volume between the cylinder and the two hemispheres. Each
            // hemisphere's centroid sits 3r/8 beyond the end of the segment.
            const double vc = pi * r * r * 2.0 * h;
            const double vs = 4.0 / 3.0 * pi * r * r * r;
            const double mc = m * vc / (vc + vs);
            const double ms = m - mc;
            const double axial = 0.5 * mc * r * r + 0.4 * ms * r * r;
            const double side =
                mc * (3.0 * r * r + 4.0 * h * h) / 12.0 + ms * (0.4 * r * r + h * h + 0.75 * h * r);
            d = Vec3(side, axial, side);
            break;
        }
        case ShapeType::Plane:
        case ShapeType::Mesh:
        case ShapeType::Compound: break;
    }
    mp.inertia = d.asDiagonal();
    return mp;
}

bool isClosed(const TriangleMesh& mesh) {
    // Each directed edge must appear once, and its reverse once.
    std::map<std::pair<int, int>, int> directed;
    for (const auto& t : mesh.triangles) {
        for (int k = 0; k < 3; ++k) {
            if (++directed[{t[k], t[(k + 1) % 3]}] > 1) return false;
        }
    }
    for (const auto& [edge, count] : directed) {
        if (!directed.contains({edge.second, edge.first})) return false;
    }
    return !mesh.triangles.empty();
}

MassProperties meshMassProperties(const TriangleMesh& mesh, double density, double* volumeOut) {
    // Each triangle (a, b, c) and the origin span a tetrahedron of signed volume
    // det[a b c] / 6. Its second moment  ∫ p pᵀ dV  is  det/120 · (Σ vᵢvᵢᵀ + (Σ vᵢ)(Σ vᵢ)ᵀ),
    // the exact integral of a linear map of the unit tetrahedron. Summed over a closed
    // surface, the parts outside the solid cancel.
    double volume = 0.0;
    Vec3 first = Vec3::Zero();   // ∫ p dV
    Mat3 second = Mat3::Zero();  // ∫ p pᵀ dV
    for (const auto& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[t[0]];
        const Vec3& b = mesh.vertices[t[1]];
        const Vec3& c = mesh.vertices[t[2]];
        const double det = a.dot(b.cross(c));
        const Vec3 sum = a + b + c;
        volume += det / 6.0;
        first += det / 24.0 * sum;
        second +=
            det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
    }
    if (volumeOut) *volumeOut = volume;
    MassProperties mp;
    if (volume == 0.0) return mp;
    mp.mass = density * volume;
    mp.centerOfMass = first / volume;
    // Second moment about the centre of mass, then I = tr(C) 1 - C.
    const Mat3 c = density * (second - volume * mp.centerOfMass * mp.centerOfMass.transpose());
    mp.inertia = c.trace() * Mat3::Identity() - c;
    return mp;
}

std::string inertiaProblem(const Mat3& I) {
    if (!I.allFinite()) return "must be finite";
    const double scale = I.cwiseAbs().maxCoeff();
    if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) return "must be symmetric";
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(I);
    const Vec3 d = eig.eigenvalues();  // ascending
    if (!(d[0] > 0.0)) return "must be positive definite";
    // The largest principal moment may not exceed the sum of the other two.
    if (d[2] > (d[0] + d[1]) * (1.0 + 1e-12)) {
        return "principal moments break the triangle inequality (no mass distribution has them)";
    }
    return {};
}

}  // namespace tumble
