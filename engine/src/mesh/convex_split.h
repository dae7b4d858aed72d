// The split of one closed shell into convex parts (convex_parts.cpp), for convexParts, which
// splits a mesh of several shells shell by shell (convex_parts_shells.cpp).
#pragma once

#include <tumble/convex_parts.h>

namespace tumble::mesh {

/// The signed volume the closed surface bounds (positive facing outwards).
double meshVolume(const TriangleMesh& mesh);

/// The convex parts of the solid bounded by the closed, outward `shell`, split in its own
/// frame (solidFrame) so that they do not depend on its pose; `tolerance` <= 0: 1 % of the
/// diagonal of its box in that frame. The options are taken as checked.
ConvexParts splitShell(const TriangleMesh& shell, const ConvexPartsOptions& options, double tolerance,
                       const ConvexPartsProgress& progress);

}  // namespace tumble::mesh
