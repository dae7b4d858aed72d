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

/// timeOfImpact for a pair with a compound: the earliest of its pairs of parts.
std::optional<Impact> compoundImpact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                                     double tolerance);

}  // namespace tumble::collision
