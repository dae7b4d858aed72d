// A mesh body's geometry made ready for compile(): cleaned, checked for closure and
// orientation, its convex hull built when needed, and its mass properties per unit density
// (from the closed surface, or from the convex hull when the surface is open).
#pragma once

#include "mesh/mesh_clean.h"
#include "mesh/mesh_holes.h"

#include <tumble/collision.h>
#include <tumble/mass.h>

#include <memory>
#include <string>

namespace tumble::mesh {

struct PreparedMesh {
    TriangleMesh surface;  ///< cleaned; facing outwards when closed
    CleanStats stats;
    bool closed = false;         ///< isClosed(surface)
    bool turnedOutward = false;  ///< the closed surface faced inwards; its triangles were reversed
    std::shared_ptr<const collision::ConvexHull> hull;  ///< when asked for or needed for mass
    std::string hullProblem;     ///< why `hull` is null although it was needed (flat input)
    bool massFromHull = false;   ///< the surface is open, so the hull's solid was integrated
    double volume = 0.0;         ///< of the solid integrated; 0 when it is flat
    MassProperties unitDensity;  ///< of that solid at density 1; meaningful when volume > 0
    HoleFilling filling;         ///< what filling the holes did (fillOpen; holes 0: none filled)
};

/// Cleans `raw` (cleanMesh with the default tolerance) and prepares it. `wantHull`: build
/// the hull (collision "convex-hull"). `wantMass`: integrate the solid; from the surface
/// when it is closed, else from the hull (built then even when `wantHull` is false).
/// A solid whose mean thickness (2 volume / surface area) is not above the weld tolerance
/// counts as flat: volume 0. Throws std::invalid_argument for non-finite vertices or bad
/// indices. A hull that cannot be built is not an error here: see hullProblem. `fillOpen`: an
/// open surface whose holes fillHoles can close is closed so (convex parts: a mesh modelled
/// as open shells still bounds a solid), and counts as closed from then on.
PreparedMesh prepareMesh(const TriangleMesh& raw, bool wantHull, bool wantMass, bool fillOpen = false);

/// The hull's faces as triangles (fans), counter-clockwise seen from outside.
TriangleMesh hullSurface(const collision::ConvexHull& hull);

}  // namespace tumble::mesh
