// Cleaning an imported triangle mesh before it is used for mass properties or collision:
// vertices that are the same point are welded, triangles with no area and repeated
// triangles are dropped, unused vertices removed.
#pragma once

#include <tumble/mass.h>

namespace tumble::mesh {

/// Vertices closer than this fraction of the mesh's bounding-box diagonal are one vertex.
/// Files often store a vertex once per face (each with its own normal or texture
/// coordinate), and formats that store floats round the copies to ~1e-7 relative; 1e-6
/// welds those copies while staying far below any feature one would model (a micrometre
/// on a one-metre object).
inline constexpr double kWeldRelative = 1e-6;

struct CleanStats {
    int weldedVertices = 0;       ///< vertices merged into an earlier one
    int degenerateTriangles = 0;  ///< dropped: two corners the same, or thinner than the tolerance
    int duplicateTriangles = 0;   ///< dropped: the same three vertices in the same turning order
    int unusedVertices = 0;       ///< dropped: no triangle uses them (after the above)
};

/// kWeldRelative times the diagonal of the vertices' bounding box (0 when there are none).
double weldTolerance(const std::vector<Vec3>& vertices);

/// The cleaned mesh. Welding is greedy in vertex order: a vertex joins the first earlier
/// kept vertex within `tolerance` (Euclidean), so the result is deterministic. A triangle
/// is degenerate when, after welding, two of its corners are one vertex or its height over
/// its longest edge is at most `tolerance`. Of repeated triangles (same vertices, same
/// turning order) the first is kept; a triangle and its reverse are both kept. Kept
/// vertices and triangles stay in their original order. Throws std::invalid_argument for a
/// vertex that is not finite or an index that is out of range.
TriangleMesh cleanMesh(const TriangleMesh& mesh, double tolerance, CleanStats* stats = nullptr);

/// cleanMesh with weldTolerance(mesh.vertices).
TriangleMesh cleanMesh(const TriangleMesh& mesh, CleanStats* stats = nullptr);

}  // namespace tumble::mesh
