// The contact solver's islands (contact_solver.cpp solves each): found from the manifolds,
// then solved one after another or, on the worker threads, several at once, each lane with
// a scratch of its own, with the same result bit for bit on any number of threads.
#pragma once

#include "solver/contact_solver.h"

namespace tumble {

/// The contacts' islands (see contact_islands.cpp). Returns how many there are; with two or
/// more, island k's manifolds are s.islandManifolds[s.islandBegin[k] .. s.islandBegin[k + 1]).
int contactIslands(const Model& model, const State& state, const collision::ManifoldList& contacts,
                   ContactSolverScratch& s);

/// Solves the `islands` (two or more; `points` contact points in all) that contactIslands
/// found, on s.pool when the islands are worth it (s.islandsGate), else one after another.
/// Their new memory goes after State::contacts (or to s.fresh, s.toFresh), island by island;
/// their ledgers are added to `ledger` in island order.
void solveIslands(const Model& model, State& state, const State& before, const collision::ManifoldList& contacts,
                  const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s,
                  EnergyLedger& ledger, int islands, size_t points);

/// The solve of one island (contact_solver.cpp): of all the contacts and joints when the
/// model has joints (`onlyIsland`: its memory replaces the solved pairs' in place).
void solveIsland(const Model& model, State& state, const State& before, const collision::ManifoldList& contacts,
                 const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s,
                 EnergyLedger& ledger, bool onlyIsland);

}  // namespace tumble
