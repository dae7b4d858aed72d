// Contact manifolds from one penetration query: the supporting features of two convex
// proxies along the contact normal, clipped against each other (Sutherland-Hodgman), and
// the reduction of many candidate points to the four that keep the contact area.
#pragma once

#include "collision/gjk.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tumble::collision::detail {

/// The feature of a shape that faces a direction: a point, a segment (capsule, cylinder
/// side) or a convex polygon (box or hull face, cylinder cap, triangle), on the surface.
struct Feature {
    static constexpr int kMax = 128;  ///< polygons with more vertices fall back to a point
    int count = 0;
    std::array<Vec3, kMax> v;
    Vec3 normal = Vec3::Zero();  ///< polygon: outward unit normal; vertices counter-clockwise about it
    bool face = false;
    std::uint32_t id = 0;  ///< which feature of the shape (face index, cap...)
};

/// The feature of `p` facing the unit direction `dir` (pointing away from the shape).
Feature supportingFeature(const ConvexProxy& p, const Vec3& dir);

struct Candidate {
    Vec3 position;  ///< midway between the surfaces
    double depth;
    std::uint32_t feature;
};

/// The contact points of two proxies whose penetration is `pen` (pen.hit): a face of one
/// clipped against the other's facing feature when a face is within ~10 degrees of the
/// normal, else the single deepest point. Writes the normal used (a face normal when one
/// was clipped against, else pen.normal; out of b towards a). Points with depth > -margin.
void contactPoints(const ConvexProxy& a, const ConvexProxy& b, const Penetration& pen, double margin,
                   Vec3& normal, std::vector<Candidate>& out);

/// At most four of the candidates: the deepest, the farthest from it, then the two that
/// span the largest area in the plane normal to `normal`. Appends a manifold if any.
void appendReduced(const std::vector<Candidate>& candidates, const Vec3& normal, ManifoldList& out);

/// Combines feature ids (order matters).
inline std::uint32_t mixId(std::uint32_t h, std::uint32_t x) {
    return h ^ (x + 0x9e3779b9u + (h << 6) + (h >> 2));
}

}  // namespace tumble::collision::detail
