// Stage part of the contact solver: where the bodies it pushed end the step (issue 18, 44).
// From the step's start with their new velocities (symplectic Euler), except that a body
// sliding over all it touches moves by the mean of its start and end velocities in its
// tangent plane, and one that stopped within the step on a still support where it stopped.
#pragma once

#include "solver/contact_solver.h"

namespace tumble {

/// Places every body of the solve (s.involved) from `before` with the solved velocities;
/// `sliding`: the slip below which a manifold's surfaces hold (m/s).
void redoPoses(const Model& model, State& state, const State& before, double sliding,
               ContactSolverScratch& s);

}  // namespace tumble
