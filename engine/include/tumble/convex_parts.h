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
// Where no cut gains one ahead (a ring's first cut, a tube's: each half's hull is as large as
// its share of the whole), the reflex planes and the middle cuts are scored two ahead.
//
// Pieces are split up to twice the parts asked for, then neighbours merged back (the pair
// whose joint hull adds least first).
//
// The split is made in the solid's own frame (mesh/solid_frame.h: centre of mass, principal
// axes), so a turned mesh splits as it does upright. A mesh of several closed pieces that
// overlap (a spider's legs in its body) is split piece by piece and the parts merged back
// down to the number asked for (convex_parts_shells.cpp). An open mesh is first made to bound
// a solid by convexPartsOfShape: triangles wound against their neighbours turned, holes
// filled with fans (mesh/mesh_holes.h).
//
// A scene's mesh with `"collision": "convex-parts"` is split by convexPartsOfShape, which
// compile() calls when the shape does not carry its parts already (ShapeDesc::convexParts,
// filled from the sidecar cache by the scene loader or by the editor in the background).
// Tested (tst_engine_convex_parts, tst_io_mesh_import; upright and turned): a U-bracket in its
// three boxes exactly; a torus within 1.7 % of its volume in 16 parts, its hole open; a mug
// without handle within 5 % in 16; a plus of two overlapping boxes in its two boxes exactly;
// the assimp spider within 5 % and the tolerance in 48 parts; every solid covered.
#pragma once

#include <tumble/collision.h>
#include <tumble/mass.h>

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

namespace tumble {
struct ShapeDesc;  // tumble/scene.h
}

namespace tumble::mesh {

struct ConvexPartsOptions {
    int maxParts = 16;  ///< at least 1
    double tolerance =
        0.0;              ///< m: how far a part may reach out of the solid; <= 0: 1 % of the mesh's diagonal
    int resolution = 48;  ///< interior samples along the mesh's longest side
    /// Threads that try the candidate cuts side by side (0: one per core); the parts are the
    /// same whatever the number.
    int threads = 0;
};

struct ConvexParts {
    std::vector<collision::ConvexHull> parts;  ///< in the mesh's frame
    double meshVolume = 0.0;                   ///< the closed mesh's (exact)
    double partsVolume = 0.0;                  ///< the sum of the parts' hull volumes (exact)
    double tolerance = 0.0;                    ///< as used (m)
    /// The farthest any part reaches out of the solid, as measured (m); at most `tolerance`
    /// when `withinTolerance`.
    double largestPokeOut = 0.0;
    std::vector<double> reachOut;  ///< each part's farthest reach out of the solid, as measured (m)
    /// Holes filled to close an open mesh before it was split (convexPartsOfShape: a mesh
    /// left open where its pieces meet still bounds a solid); 0: it was closed.
    int filledHoles = 0;
    bool withinTolerance = false;  ///< false: maxParts was reached first
    /// What the parts were made from, when made by convexPartsOfShape: the hash of the mesh
    /// as read (meshHash of ShapeDesc::meshData) and the options asked for (tolerance 0: the
    /// default); a shape whose mesh or options differ needs them made again.
    std::uint64_t meshHash = 0;
    ConvexPartsOptions options;
    double seconds = 0.0;  ///< how long they took to make (s)
};

/// Called now and then during a split with the share done (0 to 1, rising); returning false
/// stops the split, which then throws ConvexPartsStopped. Called on the splitting thread.
using ConvexPartsProgress = std::function<bool(double done)>;

/// A split stopped by its progress callback.
struct ConvexPartsStopped : std::runtime_error {
    ConvexPartsStopped() : std::runtime_error("the split into convex parts was stopped") {}
};

/// Volume of a convex hull (its faces' offsets times their areas, over three).
double hullVolume(const collision::ConvexHull& hull);

/// The convex parts of the solid bounded by `mesh`, which must be closed and face outwards
/// (isClosed; prepareMesh makes it so). A mesh of several pieces (each closed, overlapping
/// where they meet) is split piece by piece and the parts merged back down to maxParts.
/// Throws std::invalid_argument for an open or empty mesh, a piece facing inwards, or
/// options out of range.
ConvexParts convexParts(const TriangleMesh& mesh, const ConvexPartsOptions& options = {},
                        const ConvexPartsProgress& progress = {});

/// A hash of the mesh's vertices (their bits) and triangles: equal meshes, equal hashes.
std::uint64_t meshHash(const TriangleMesh& mesh);

/// The options a mesh shape with collision convex-parts asks for (max_parts, tolerance).
ConvexPartsOptions convexPartsOptionsOf(const ShapeDesc& shape);

/// True when `parts` were made from this shape's mesh (meshData) with its options.
bool convexPartsFit(const ConvexParts& parts, const ShapeDesc& shape);

/// The convex parts of a mesh shape (its meshData cleaned as compile cleans it, an open one
/// closed by filling its holes) with its options, timed, with the mesh's hash. Throws
/// std::invalid_argument when the shape has no mesh, or the cleaned mesh is not closed and
/// filling its holes does not close it (it bounds no solid to split).
ConvexParts convexPartsOfShape(const ShapeDesc& shape, const ConvexPartsProgress& progress = {});

/// How far each point lies outside the solid bounded by the closed `mesh` (0 inside): its
/// distance to the nearest triangle when a ray from it crosses the surface an even number of
/// times. Exact (the triangles in buckets): for tests.
std::vector<double> distancesOutside(const TriangleMesh& mesh, const std::vector<Vec3>& points);

}  // namespace tumble::mesh
