// Small vocabulary types and helpers over Eigen, shared by the whole engine.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// The cross-product matrix: skew(a) * b == a.cross(b) (the paper's (3), corrected).
inline Mat3 skew(const Vec3& a) {
    Mat3 m;
    m << 0, -a.z(), a.y(),
         a.z(), 0, -a.x(),
        -a.y(), a.x(), 0;
    return m;
}

/// The rotation by the rotation vector w (axis * angle) as a unit quaternion.
/// Exact for every angle; uses the Taylor series near zero.
inline Quat expMap(const Vec3& w) {
    const double angle = w.norm();
    const double half = 0.5 * angle;
    double s;  // sin(half) / angle
    if (angle < 1e-4) {
        s = 0.5 - angle * angle / 48.0;
    } else {
        s = std::sin(half) / angle;
    }
    return Quat(std::cos(half), s * w.x(), s * w.y(), s * w.z());
}

}  // namespace tumble
