// A solid mesh's own frame (centre of mass, principal axes), in which a split into convex
// parts does not depend on the pose the mesh was given.
#pragma once

#include <tumble/collision.h>
#include <tumble/mass.h>

namespace tumble::mesh {

/// The closed mesh's own frame: its solid's centre of mass and principal axes, each axis's
/// sign set by the side its vertices lean to (the third moment) and the frame right-handed.
/// A mesh turned and shifted has the same frame turned and shifted with it. Where two
/// principal moments are equal (round about an axis: a mug, a torus) the round axis is the
/// second and the two across it are turned to the lowest harmonic of the vertices' angles
/// about it (a 16-sided tube's sixteenth), the same in any pose up to the mesh's own
/// symmetry; with three equal, the axes are any.
collision::Pose solidFrame(const TriangleMesh& mesh);

/// The hull carried by the rigid motion `to` (its vertices, faces and interior point).
void carry(collision::ConvexHull& hull, const collision::Pose& to);

}  // namespace tumble::mesh
