// Small geometric helpers shared by the dedicated pair routines.
#pragma once

#include <tumble/collision.h>

#include <vector>

namespace tumble::collision {

/// Closest point to q on the segment [p0, p1].
Vec3 closestOnSegment(const Vec3& p0, const Vec3& p1, const Vec3& q);

/// Closest points between segments [p0, p1] and [q0, q1]: *s on the first, *t on the second
/// (parameters in [0, 1]). Parallel segments get the midpoint of their overlap.
void closestBetweenSegments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1,
                            double* s, double* t);

/// A contact candidate before reduction: position midway between the surfaces.
struct Candidate {
    Vec3 position;
    double depth;
    std::uint32_t feature;
};

/// Keeps at most four of the candidates for a manifold with the given normal: the deepest,
/// then the points that span the largest area in the contact plane, so that a face resting
/// on a face keeps its corners. Appends the manifold when any candidate is left.
void addReduced(const std::vector<Candidate>& candidates, const Vec3& normal, ManifoldList& out);

/// Any unit vector perpendicular to the unit vector n.
Vec3 anyPerpendicular(const Vec3& n);

}  // namespace tumble::collision
