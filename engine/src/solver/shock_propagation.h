// The contact solver's last sweep, from the ground up (shock propagation): see
// shock_propagation.cpp and docs/architecture.md "Collision response".
#pragma once

#include "solver/contact_solver.h"

namespace tumble {

/// Level by level from the bodies that cannot move, the lower bodies held still while the
/// contacts between them and the next level are solved, `passes` times; the blocks'
/// friction impulses are kept for the warm start where the support is at rest (moving
/// slower than `stillSpeed` where it holds the upper body), else applied only (shockT).
/// `converged`: the solver's passes ended at their fixed point, so a level whose lower
/// bodies cannot move anyway (nothing to hold still) would change nothing while nothing
/// below it has: it is skipped. Such a level's blocks are otherwise solved as they are,
/// with the passes' quiet skipping (updateBlock, `quietSpeed`).
void shockPass(ContactSolverScratch& s, int passes, bool converged, double quietSpeed, double stillSpeed);

}  // namespace tumble
