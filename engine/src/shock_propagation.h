// The contact solver's last sweep, from the ground up (shock propagation): see
// shock_propagation.cpp and docs/architecture.md "Collision response".
#pragma once

#include "contact_solver.h"

namespace tumble {

/// Level by level from the bodies that cannot move, the lower bodies held still while the
/// contacts between them and the next level are solved, `passes` times; the blocks'
/// friction impulses are kept for the warm start. `converged`: the solver's passes ended
/// at an exact fixed point, so a level whose lower bodies cannot move anyway (nothing to
/// hold still) would change nothing while nothing below it has: it is skipped.
void shockPass(ContactSolverScratch& s, int passes, bool converged);

}  // namespace tumble
