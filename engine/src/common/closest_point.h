// The point of a triangle nearest a point: the narrowphase's mesh pairs, the reference
// collision tests and the convex decomposition's distances share it.
#pragma once

#include <tumble/math.h>

namespace tumble {

/// The closest point to p of the triangle (a, b, c), degenerate triangles included.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace tumble
