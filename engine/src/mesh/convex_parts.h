// Convex decomposition of a closed, possibly concave mesh (issue 49's `"collision":
// "convex-parts"`): the solid is cut by planes, piece by piece, until the convex hull of
// every piece stays within `tolerance` of the solid, or there are `maxParts` pieces.
//
// The pieces partition the solid (each is the solid inside a convex region: the half-spaces
// of the cuts on its way), so their hulls cover it, overlap only where a hull reaches past
// its own cut, and together exceed the solid's volume by their concavity. A piece's hull is
// that of the surface clipped to its region and of the interior samples next to its cuts (the
// corners of a cut inside the solid: the hull may fall short of such a corner by a sample
// spacing, never reach out past the solid there).
//
// How a cut is chosen: of the candidates (the planes of the faces at the mesh's reflex
// edges that cross the piece, and planes across the world's and the piece's principal axes
// at seven even steps), the one whose two halves' hulls hold the least volume. A piece is
// cut while its hull reaches out of the solid by more than the tolerance, then while the
// hulls hold 3 % more than the solid. How far a hull reaches out is measured on a grid of
// cells a third of the tolerance wide (inside or out by scanlines, each a ray crossing the
// surface; an outside cell's reach is its distance to the nearest inside cell).
//
// STATUS (issue 49, not wired to scenes yet): exact for solids of flat faces whose concave
// corners its reflex planes cut (a U-bracket in three boxes, in any pose). Curved concave
// solids are not yet within targets: the choice looks one cut ahead, and a torus's or a
// mug wall's first cuts gain nothing until a second one (a mug without handle: 16 parts,
// 8.7 % over its volume; a torus: 16 parts, 7-55 % and 30 s); lookahead, merging and speed
// are the next steps (the closing notes).
#pragma once

#include <tumble/collision.h>
#include <tumble/mass.h>

#include <vector>

namespace tumble::mesh {

struct ConvexPartsOptions {
    int maxParts = 16;  ///< at least 1
    double tolerance =
        0.0;              ///< m: how far a part may reach out of the solid; <= 0: 1 % of the mesh's diagonal
    int resolution = 48;  ///< interior samples along the mesh's longest side
};

struct ConvexParts {
    std::vector<collision::ConvexHull> parts;  ///< in the mesh's frame
    double meshVolume = 0.0;                   ///< the closed mesh's (exact)
    double partsVolume = 0.0;                  ///< the sum of the parts' hull volumes (exact)
    double tolerance = 0.0;                    ///< as used (m)
    /// The farthest any part reaches out of the solid, as measured (m); at most `tolerance`
    /// when `withinTolerance`.
    double largestPokeOut = 0.0;
    bool withinTolerance = false;  ///< false: maxParts was reached first
};

/// Volume of a convex hull (its faces' offsets times their areas, over three).
double hullVolume(const collision::ConvexHull& hull);

/// The convex parts of the solid bounded by `mesh`, which must be closed and face outwards
/// (isClosed; prepareMesh makes it so). Throws std::invalid_argument for an open or empty
/// mesh, or options out of range.
ConvexParts convexParts(const TriangleMesh& mesh, const ConvexPartsOptions& options = {});

/// How far `point` lies outside the solid bounded by the closed `mesh` (0 inside): its
/// distance to the nearest triangle when a ray from it crosses the surface an even number of
/// times. Exact, O(triangles): for tests and the final measure.
double distanceOutside(const TriangleMesh& mesh, const Vec3& point);

}  // namespace tumble::mesh
