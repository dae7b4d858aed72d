// The narrowphase: contact manifolds between two shapes at their poses. `collide` picks a
// dedicated routine for the common pairs and the general convex path (GJK + EPA + clipping)
// for the rest; it swaps the arguments when a routine is written for the other order and
// flips the normal back, so every caller sees the conventions of tumble/collision.h
// (normal out of b towards a, depth > 0 overlapping).
#pragma once

#include <tumble/collision.h>

#include <vector>

namespace tumble::collision {

/// Appends the manifolds between a at pa and b at pb (bodyA/bodyB left unset). Points with
/// depth > -margin are reported. Plane-plane gives nothing.
void collide(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
             std::vector<Manifold>& out);

/// The dedicated routines, each for the pair in this order (b is the second kind named).
void sphereSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, std::vector<Manifold>& out);
void sphereCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, std::vector<Manifold>& out);
void sphereBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, std::vector<Manifold>& out);
void capsuleCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, std::vector<Manifold>& out);
void capsuleBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, std::vector<Manifold>& out);
void boxBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, std::vector<Manifold>& out);
/// Any convex shape (sphere, box, capsule, cylinder, hull) against a plane.
void convexPlane(const Shape& a, const Pose& pa, const Shape& plane, const Pose& pp, double margin, std::vector<Manifold>& out);

/// The plane's unit normal and offset in the world: normal·p == offset on the plane.
void worldPlane(const Shape& plane, const Pose& pose, Vec3& normal, double& offset);

}  // namespace tumble::collision
