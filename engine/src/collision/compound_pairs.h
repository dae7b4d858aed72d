// Compound shapes (collision::Compound: a body of several parts) against any shape: the
// parts near the other shape are found by their boxes in the body frame, and each pair of
// parts goes through the ordinary pair routines. A manifold names its parts.
#pragma once

#include <tumble/collision.h>

#include "collision/toi.h"

#include <optional>

namespace tumble::collision {

/// Appends the manifolds between a at pa and b at pb, one of them (or both) a compound:
/// the pairs of parts whose world boxes, grown by the margin, overlap. Each manifold's
/// partA and partB name its parts (0 for a shape that is not a compound), and its points'
/// feature ids are mixed with them, so two parts' contacts are never taken for each other's.
void collideCompound(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                     ManifoldList& out);

/// The sweep of a part placed at `part` in the body whose sweep is `body`: the same path of
/// the centre of mass, the part's frame turned with the body.
Sweep partSweep(const Sweep& body, const Pose& part);

/// Forgets the part sweeps compoundImpact keeps between the pairs of one search (each
/// thread's last few bodies'): called before each search for impacts, so that nothing kept
/// from another step, scene or model is taken for this one's.
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
bool partsMayPass(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, double tolerance,
                  bool touching);

/// timeOfImpact for a pair with a compound: the earliest of its pairs of parts.
std::optional<Impact> compoundImpact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                                     double tolerance);

}  // namespace tumble::collision
