// Orientation in the property panel: Euler angles in degrees; the file keeps the quaternion.
//
// Convention: intrinsic Z-Y'-X'' (yaw about z, then pitch about the new y, then roll about
// the newest x), which is the same rotation as extrinsic X, then Y, then Z about the world
// axes:  q = Rz(z) * Ry(y) * Rx(x),  angles = (x, y, z).  Both directions below use it.
#pragma once

#include <tumble/math.h>

namespace tumble::ui {

/// (x, y, z) in degrees -> q = Rz(z) Ry(y) Rx(x).
Quat eulerDegreesToQuat(const Vec3& degrees);

/// The inverse: y in [-90, 90], x and z in (-180, 180]. At y = ±90 (gimbal lock) x is 0.
Vec3 quatToEulerDegrees(const Quat& q);

/// The same rotation (q and -q are one rotation), to within `tolerance` per coefficient.
bool sameRotation(const Quat& a, const Quat& b, double tolerance = 1e-9);

}  // namespace tumble::ui
