// The contact solver's rows: one manifold's normal impulses solved as a block and its
// friction at the centroid, on the velocities of ContactSolverScratch::bodies. Shared by the
// iterations (contact_solver.cpp) and the last sweep from the ground up
// (shock_propagation.cpp).
#pragma once

#include "solver/contact_solver.h"

namespace tumble {

/// The point's effective mass along n and the angular parts of its row (Point::armA ...),
/// for the bodies as they stand.
void preparePoint(const SolverBody& A, const SolverBody& B, const Vec3& rA, const Vec3& rB,
                  ContactSolverScratch::Point& p);
/// The block's K, its least-norm inverse, the friction frame and masses at the centroid, for
/// the bodies A and B as they stand (a body held still has zero inverse mass).
void prepareBlock(const SolverBody& A, const SolverBody& B, ContactSolverScratch::Block& block,
                  const ContactSolverScratch& s);
/// Applies a change of the block's friction impulses (tangential, twist).
void applyFriction(ContactSolverScratch& s, ContactSolverScratch::Block& block, const Eigen::Vector2d& dT,
                   double dTwist);
/// The normal impulses of one manifold together: the least-norm impulses that give every
/// point its target velocity, none pulling.
/// `pool`: where the block keeps the cache of its K's sub-inverses (Block::subsets, taken on
/// first need; clear the pool and the indices when K changes). With `wantsEntry`, no entry is
/// added: a block without one takes its sub-inverses afresh and sets *wantsEntry (a pass on a
/// worker thread, while other threads read the pool; the caller adds the entry after).
/// Returns the largest change of any of its impulses (0: none changed; this one and
/// frictionBlock, whose twist counts as the impulse at the patch radius).
double normalBlock(ContactSolverScratch& s, ContactSolverScratch::Block& block,
                   std::vector<SubsetInverses>& pool, bool* wantsEntry = nullptr);
/// The block's normal impulse, summed over its points.
double normalImpulse(const ContactSolverScratch& s, const ContactSolverScratch::Block& block);
/// How fast the bodies' surfaces slide over each other at the block's centroid, along t1 and t2.
Eigen::Vector2d slipVelocity(const ContactSolverScratch& s, const ContactSolverScratch::Block& block);
/// Friction of one manifold: stop the sliding and the twisting at the centroid, within the
/// Coulomb limits of the current normal impulses.
double frictionBlock(ContactSolverScratch& s, ContactSolverScratch::Block& block);
/// Block k of s.blocks, friction then normals, unless it is quiet: its last update changed
/// its impulses by at most its normal mass times quietSpeed, or times 1e-4 of how fast its
/// bodies move, whichever is more, and no block has changed its bodies since
/// (ContactSolverScratch::quietSince, changedAt). Returns whether it changed more than that
/// (and then stamps its bodies).
bool updateBlock(ContactSolverScratch& s, int k, double quietSpeed);
/// Whether block k is quiet and none of its bodies changed since (updateBlock skips it).
bool blockQuiet(const ContactSolverScratch& s, int k);
/// updateBlock's update of a block that is not quiet, stamped `tick` (block_regions.h stamps
/// two regions' blocks from the same count: they share no body that can move). With `wants`, a
/// block that needs an entry in s.subsets is listed there instead (normalBlock's wantsEntry).
bool updateBlockAt(ContactSolverScratch& s, int k, double quietSpeed, long tick, std::vector<int>* wants);

}  // namespace tumble
