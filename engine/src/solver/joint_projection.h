// The joints' position projection as one Newton solve per group of joints that share moving
// bodies (joint_projection.cpp): a chain's or a ragdoll's joints move together, where
// Gauss-Seidel over them converges slowly (a 50-link chain was left open by 1 % of its
// length after 100 passes).
#pragma once

#include "solver/contact_solver.h"

#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble {

/// Newton iterations (at most `iterations`) on the ball and distance joints of every group:
/// all rows solved together, by a dense LU up to 64 joints, along the chain for a longer
/// chain of ball joints (block-tridiagonal elimination, linear in its length), else by a
/// sparse LU. With `from` the impulses act at the
/// arms and along the lines of that state (the step's start, RATTLE's), and with h > 0 they
/// also change the solver bodies' velocities by J / h; without, at the present ones,
/// positions only. Stops a group when its error is below 1e-13 m or stops falling. Ropes,
/// and what a group's Newton steps leave (a whipping chain far from its linearisation),
/// are left to the Gauss-Seidel passes (joints.cpp).
void projectGroups(const Model& model, State& state, ContactSolverScratch& s, double h, const State* from,
                   int iterations);

/// The largest error (as the last positions-only pass found it, ContactSolverScratch::
/// jointChecks) of the active joints whose group, every joint type counted, has at most 64
/// joints: what a shorter step would close. Larger groups are left out: where a whipping
/// 100-link chain's Newton steps stall, its Gauss-Seidel passes leave it open by up to 2 mm
/// (1 cm before the chains' Newton solve) at any step, and halving the step for them cost
/// eight times the step (World::stepJointed).
double smallGroupsOpen(const Model& model, const State& state, const ContactSolverScratch& s);

}  // namespace tumble
