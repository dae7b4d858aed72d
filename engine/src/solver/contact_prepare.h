// The contact solver's rows made from one island's manifolds (solveIsland's first part): the
// points to solve, each manifold's block, their effective masses, targets and friction frames.
#pragma once

#include "solver/contact_solver.h"

namespace tumble {

/// Fills s.points, s.geometry and s.blocks from `contacts` for the bodies as s.bodies has
/// them (solveIsland loaded them), and lists in s.stillMoving the bodies of manifolds taken
/// as last solved. The blocks are in the manifolds' order, or region by region for an island
/// large enough to split (block_regions.h). They are made on the worker threads when s.pool
/// pays (the same bits on any number of threads: each block is made from its own manifold alone).
void prepareContacts(const Model& model, const State& state, const State& before,
                     const collision::ManifoldList& contacts, const std::vector<double>& sizes,
                     const ContactSolverSettings& cfg, ContactSolverScratch& s);

}  // namespace tumble
