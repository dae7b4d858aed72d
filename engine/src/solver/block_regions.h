// A large island's velocity passes on two threads (issue 53). The island's movable bodies are
// split in two regions at the median of their centres along the island's longest side; the
// blocks whose movable bodies lie in one region are that region's, the others (across the
// cut) the boundary's. A pass takes the two regions side by side, then the boundary: the two
// regions' blocks share no body that can move (a body that cannot move is read, never
// written: contact_rows.cpp), so they commute exactly, and the pass is the same as one
// taking region 0, region 1 and the boundary one after another, on any number of threads.
//
// Why regions and not a colouring of the blocks (no two blocks of a colour share a body,
// the colours one after another, as Jolt's large island splitter does): a colouring sends each
// body's blocks to different colours, so every block update fetches its bodies from far in
// the cache, where blocks in the manifolds' order (a body's blocks near each other) find them
// still in the nearest. Measured on pyramid-1240 (median of 5 runs, this 2-core machine): the
// colouring took one thread from 29.9 to 32.9 ms a step and two threads to 32.7; the second
// core gave less than the order cost.
#pragma once

#include "solver/contact_solver.h"

#include <functional>

namespace tumble {

/// Splits the blocks the island is about to have (s.blockManifold's manifolds, before their
/// points are placed: contact_prepare.cpp) when the island is large enough and the model has
/// no joints: s.split, s.regionBegin, and s.regionBlocks, the blocks in region order. Returns
/// whether it split them.
bool splitBlocks(const Model& model, const collision::ManifoldList& contacts, ContactSolverScratch& s);

/// Runs work(0) and work(1), a region each, side by side on s.pool when it has two threads or
/// more, else one after the other; returns whether the pool took them.
bool onRegions(ContactSolverScratch& s, const std::function<void(int)>& work);

/// One pass over the split blocks, placed region by region (as iterate in contact_solver.cpp:
/// forwards on even passes, backwards on odd ones, the regions and the boundary in that
/// order). Returns whether any block changed.
bool iterateRegions(ContactSolverScratch& s, int pass, double quietSpeed);

}  // namespace tumble
