#include "panels/property_euler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::ui {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

Quat eulerDegreesToQuat(const Vec3& d) {
    const Quat q = Eigen::AngleAxisd(d.z() * kDeg, Vec3::UnitZ()) *
                   Eigen::AngleAxisd(d.y() * kDeg, Vec3::UnitY()) *
                   Eigen::AngleAxisd(d.x() * kDeg, Vec3::UnitX());
    return q.normalized();
}

Vec3 quatToEulerDegrees(const Quat& q) {
    // R = Rz Ry Rx: R(2,0) = -sin y, R(2,1) = cos y sin x, R(2,2) = cos y cos x,
    // R(1,0) = cos y sin z, R(0,0) = cos y cos z.
    const Mat3 R = q.normalized().toRotationMatrix();
    const double sy = std::clamp(-R(2, 0), -1.0, 1.0);
    double x, y, z;
    if (std::abs(sy) > 1.0 - 1e-12) {
        // Gimbal lock: only x - z (y = +90) or x + z (y = -90) is defined; put it all in z.
        y = std::copysign(std::numbers::pi / 2, sy);
        x = 0.0;
        z = std::atan2(-R(0, 1), R(1, 1));
    } else {
        y = std::asin(sy);
        x = std::atan2(R(2, 1), R(2, 2));
        z = std::atan2(R(1, 0), R(0, 0));
    }
    Vec3 d(x / kDeg, y / kDeg, z / kDeg);
    for (int k = 0; k < 3; ++k) {
        if (std::abs(d[k]) < 1e-12) d[k] = 0.0;
        if (d[k] <= -180.0 + 1e-12) d[k] += 360.0;
    }
    return d;
}

bool sameRotation(const Quat& a, const Quat& b, double tolerance) {
    const auto ca = a.normalized().coeffs(), cb = b.normalized().coeffs();
    return (ca - cb).cwiseAbs().maxCoeff() <= tolerance || (ca + cb).cwiseAbs().maxCoeff() <= tolerance;
}

}  // namespace tumble::ui
