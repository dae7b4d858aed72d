// Filling the holes of an open surface, so that a mesh modelled as open shells (a spider's
// legs left open where they meet its body) bounds a solid that can be split into convex parts.
#pragma once

#include <tumble/mass.h>

#include <string>

namespace tumble::mesh {

struct HoleFilling {
    int turned = 0;       ///< triangles turned to wind like their neighbours
    int holes = 0;        ///< loops of open edges closed, each by a fan about its middle
    int shells = 0;       ///< connected pieces of the surface
    int openShells = 0;   ///< of them, those that had holes
    bool closed = false;  ///< isClosed(the result)
};

/// The mesh made to bound a solid where it can be: triangles turned to wind like their
/// neighbours; every loop of open edges (an edge with no twin running the other way) closed
/// by a fan of triangles from a new vertex at the loop's mean, so that each open edge gets its
/// twin (a loop is followed from open edge to open edge; at a vertex where two loops meet,
/// the first unused); each connected piece then facing outwards. The result may still not be
/// closed where edges are shared by more than two triangles; `filling` says.
TriangleMesh fillHoles(const TriangleMesh& mesh, HoleFilling* filling = nullptr);

/// The mesh's connected pieces (triangles joined through shared vertices), each with only
/// its own vertices, in the order of their first triangles.
std::vector<TriangleMesh> shellsOf(const TriangleMesh& mesh);

/// Why a mesh that filling did not close cannot be split into convex parts, for a message.
std::string notClosedForParts(const HoleFilling& filling);

}  // namespace tumble::mesh
