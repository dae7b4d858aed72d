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
             ManifoldList& out);

/// True when `collide` takes a and b (in either order) to the general convex path, GJK and
/// EPA: two convex shapes without a dedicated routine (a hull or a cylinder is one of them).
bool generalConvex(Kind a, Kind b);

/// As collide, for a pair of generalConvex kinds: when nothing is appended (the shapes are
/// farther apart than the margin), `apart` gets a unit direction out of b towards a along
/// which they are that far apart, else it is left as it was.
void collide(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
             ManifoldList& out, Vec3& apart);

/// True when a at pa lies farther than `margin` from b at pb along the unit direction n
/// (out of b towards a): a's lowest point along n is above b's highest by more than the
/// margin (and a hair, 1e-9 of their sizes, for rounding). Then there is nothing to find:
/// the distance is at least that gap, and collide would append nothing. Two support
/// points instead of GJK for two convex shapes that stay apart (hull-rain: four in five of
/// its hull pairs).
bool apartAlong(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, const Vec3& n, double margin);

/// The dedicated routines, each for the pair in this order (b is the second kind named).
void sphereSphere(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, ManifoldList& out);
void sphereCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, ManifoldList& out);
void sphereBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, ManifoldList& out);
void capsuleCapsule(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, ManifoldList& out);
void capsuleBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, ManifoldList& out);
void boxBox(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin, ManifoldList& out);
/// Any convex shape (sphere, box, capsule, cylinder, hull) against a plane.
void convexPlane(const Shape& a, const Pose& pa, const Shape& plane, const Pose& pp, double margin, ManifoldList& out);

/// The plane's unit normal and offset in the world: normal·p == offset on the plane.
void worldPlane(const Shape& plane, const Pose& pose, Vec3& normal, double& offset);

}  // namespace tumble::collision
