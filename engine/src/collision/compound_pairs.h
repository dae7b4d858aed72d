// Compound shapes (collision::Compound: a body of several parts) against any shape: the
// parts near the other shape are found by their boxes in the body frame, and each pair of
// parts goes through the ordinary pair routines. A manifold names its parts.
#pragma once

#include <tumble/collision.h>

#include "collision/toi.h"

#include <optional>
#include <vector>

namespace tumble::collision {

/// A part of a shape placed in the world: its number (0 for a shape that is not a compound),
/// pose and world box grown by a margin.
struct PlacedPart {
    int part = 0;
    Pose pose;
    Aabb box;
};

/// Appends every part of `shape` at `pose` to `out`, in part order (the shape itself for a
/// shape that is not a compound).
void placeParts(const Shape& shape, const Pose& pose, double margin, std::vector<PlacedPart>& out);

/// Appends the manifolds between a at pa and b at pb, one of them (or both) a compound:
/// the pairs of parts whose world boxes, grown by the margin, overlap. Each manifold's
/// partA and partB name its parts (0 for a shape that is not a compound), and its points'
/// feature ids are mixed with them, so two parts' contacts are never taken for each other's.
/// `readyA`, `readyB`: if given, every part of a (of b) placed at pa (pb) by placeParts with
/// this margin, made once for all the body's pairs.
void collideCompound(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                     ManifoldList& out, const PlacedPart* readyA = nullptr,
                     const PlacedPart* readyB = nullptr);

/// The sweep of a part placed at `part` in the body whose sweep is `body`: the same path of
/// the centre of mass, the part's frame turned with the body.
Sweep partSweep(const Sweep& body, const Pose& part);

/// Forgets the part sweeps kept by body number between the pairs of one search: called
/// before each search for impacts, so that nothing kept from another step, scene or model is
/// taken for this one's.
void forgetPartSweeps();

/// How far two solids of thicknesses ta and tb (0: a surface; infinite: a plane) may move
/// against each other in a step before one can pass through the other: their thicknesses
/// together, or, when they touch at the step's end, half the thinner (past its middle the
/// end's normal would point out of its far side). Surfaces touching at the end are trusted.
double passLimit(double ta, double tb, bool touching);

/// Whether some part of a may have passed through some part of b, or past its middle, over
/// the step (the end-of-step mode's test for a moment of impact): a pair of parts whose swept
/// balls meet, moving against each other by passLimit of their thicknesses or more. A
/// spinning chair's leg far from the other chair's parts moves it nothing.
/// bodyA, bodyB: the bodies' numbers in the search for impacts (forgetPartSweeps starts one),
/// under which each thread keeps their part sweeps for their other pairs; -1: not kept.
bool partsMayPass(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, double tolerance,
                  bool touching, int bodyA = -1, int bodyB = -1);

/// timeOfImpact for a pair with a compound: the earliest of its pairs of parts (bodyA, bodyB
/// as for partsMayPass).
std::optional<Impact> compoundImpact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                                     double tolerance, Window window = {}, int bodyA = -1, int bodyB = -1);

}  // namespace tumble::collision
