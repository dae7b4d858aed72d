#include "mesh/solid_frame.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <vector>

namespace tumble::mesh {

collision::Pose solidFrame(const TriangleMesh& mesh) {
    const MassProperties mp = meshMassProperties(mesh, 1.0);
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(mp.inertia);
    Mat3 axes = eig.eigenvectors();
    std::array<double, 3> lean{};
    for (int k = 0; k < 3; ++k) {
        const Vec3 u = axes.col(k).normalized();
        double third = 0.0, size = 0.0;
        for (const Vec3& v : mesh.vertices) {
            const double d = u.dot(v - mp.centerOfMass);
            third += d * d * d;
            size += std::abs(d * d * d);
        }
        axes.col(k) = third < 0.0 ? Vec3(-u) : u;
        lean[k] = size > 0.0 ? std::abs(third) / size : 0.0;
    }
    const Vec3 moments = eig.eigenvalues();
    const double alike = 1e-6 * moments.cwiseAbs().maxCoeff();
    const bool low = std::abs(moments[0] - moments[1]) <= alike,
               high = std::abs(moments[1] - moments[2]) <= alike;
    const int round = low && !high ? 2 : high && !low ? 0 : -1;  // the axis it is round about
    if (round >= 0) {
        const Vec3 axis = axes.col(round), a = axes.col((round + 1) % 3), b = axis.cross(a);
        // Each vertex's place across the axis as r e^(i theta); its m-th harmonic r e^(i m theta).
        std::vector<std::complex<double>> turn, power;
        double weight = 0.0;
        for (const Vec3& v : mesh.vertices) {
            const Vec3 d = v - mp.centerOfMass;
            const std::complex<double> z(a.dot(d), b.dot(d));
            weight += std::abs(z);
            turn.push_back(std::abs(z) > 0.0 ? z / std::abs(z) : 0.0);
            power.push_back(z);
        }
        for (int m = 1; m <= 256; ++m) {
            std::complex<double> c = 0.0;
            for (std::size_t k = 0; k < power.size(); ++k) {
                if (m > 1) power[k] *= turn[k];
                c += power[k];
            }
            if (std::abs(c) <= 1e-6 * weight) continue;
            // (the round axis second, whichever moment it has)
            const double phi = std::arg(c) / m;
            axes.col(0) = std::cos(phi) * a + std::sin(phi) * b;
            axes.col(1) = axis;
            axes.col(2) = axes.col(0).cross(axis);
            break;
        }
    } else {
        // The axis whose sign the vertices tell least (a mirror-symmetric bracket's) is set
        // by the other two.
        const int least = static_cast<int>(std::min_element(lean.begin(), lean.end()) - lean.begin());
        axes.col(least) = axes.col((least + 1) % 3).cross(axes.col((least + 2) % 3)).normalized();
    }
    if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // (round, no harmonic found)
    collision::Pose frame;
    frame.R = axes;
    frame.p = mp.centerOfMass;
    return frame;
}

// The hull carried by the rigid motion `to`.
void carry(collision::ConvexHull& hull, const collision::Pose& to) {
    for (Vec3& v : hull.vertices) v = to.toWorld(v);
    for (auto& f : hull.faces) {
        f.normal = to.R * f.normal;
        f.offset += f.normal.dot(to.p);
    }
    hull.interiorPoint = to.toWorld(hull.interiorPoint);
}

}  // namespace tumble::mesh
