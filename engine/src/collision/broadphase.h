// The broadphase: which pairs of bodies have overlapping world boxes.
//
// Why dynamic AABB trees and not sweep-and-prune: sorting along one axis leaves every pair
// that overlaps on that axis to be checked, about n^2 w / L of them for n boxes of size w in
// a cube of side L; at constant density L grows as n^(1/3), so the work grows as n^(5/3)
// (some 10^8 checks for 100 000 bodies). A tree finds the overlapping pairs by descending
// against itself in about O(n + pairs) at any density, and with fattened boxes a body that
// moves a little does not touch the tree at all.
//
// Three sets, each body in exactly one:
// - moving bodies with finite boxes, in a tree of boxes fattened by a margin (a body is
//   re-inserted only when its box leaves its fat box, or when the fat box became much
//   larger than needed; the fat box reaches ahead by two of the last update's shifts, so a
//   falling body is not re-inserted at every step); pairs among them come from the tree's
//   descent against itself;
// - static bodies with finite boxes, in a tree of their exact boxes, descended only against
//   the moving tree: static-static pairs are never looked at;
// - unbounded bodies (a box with an infinite bound: planes), kept in a list and checked
//   against every body they could pair with; an unbounded body given a half-space (a plane
//   that stands still) pairs only with the boxes that reach into it: one dot product per
//   box, so a far ground plane costs no narrowphase and no time of impact.
// Bodies whose box is empty (min > max on some axis, or NaN) pair with nothing.
// A body may change sets (wakes up, falls asleep) from one update to the next. A tree is
// rebuilt top-down when a quarter of it has changed since its last rebuild (see aabb_tree.h),
// so an update costs O(n + pairs + changes * log n) and, now and then, O(n log n).
#pragma once

#include "collision/aabb_tree.h"

#include <tumble/collision.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace tumble::collision {

/// The solid side of a plane, normal·p <= offset, in world coordinates.
struct HalfSpace {
    Vec3 normal = Vec3(0, 1, 0);
    double offset = 0.0;
    bool valid = false;  ///< false: no half-space known, the infinite box is used

    /// True when some point of `box` is on the solid side (or on the plane).
    bool reaches(const Aabb& box) const {
        const Vec3 c = 0.5 * (box.min + box.max), e = 0.5 * (box.max - box.min);
        return normal.dot(c) - normal.cwiseAbs().dot(e) <= offset;
    }
};

class Broadphase {
public:
    /// bounds[i]: world box of body i (planes have infinite boxes); moving[i]: false for
    /// static bodies. Recomputes the candidate pairs: every (i, j), i < j, whose boxes overlap
    /// (closed boxes: touching counts) and at least one of which is moving. Static-static
    /// pairs are never produced and never tested. A different body count starts afresh.
    /// Throws std::invalid_argument if the two vectors differ in size.
    void update(const std::vector<Aabb>& bounds, const std::vector<std::uint8_t>& moving);

    /// Worker threads for the trees' rebuilds (null: this thread only); the pairs are the
    /// same either way.
    void setPool(Workers* pool) { pool_ = pool; }

    /// The same, where an unbounded body i with halfSpaces[i].valid pairs only with boxes
    /// that reach its half-space (halfSpaces empty: none has one).
    void update(const std::vector<Aabb>& bounds, const std::vector<std::uint8_t>& moving,
                const std::vector<HalfSpace>& halfSpaces);

    /// Sorted ascending by (i, j), no duplicates: deterministic whatever the input history.
    const std::vector<std::pair<int, int>>& pairs() const { return pairs_; }
    /// Removes the pairs (a, b) for which drop(a, b) holds, keeping the others' order.
    template <class Drop>
    void dropPairs(Drop&& drop) {
        std::erase_if(pairs_, [&](const std::pair<int, int>& p) { return drop(p.first, p.second); });
    }

    /// Calls visit(j) for every body j whose box in the trees (as of the last update: swept
    /// and fattened; a sleeping body's with the static ones) overlaps `box`, and for every
    /// unbounded body (a plane).
    template <class Visit>
    void query(const Aabb& box, Visit&& visit) const {
        movingTree_.query(box, visit);
        staticTree_.query(box, visit);
        for (int u : unbounded_) visit(u);
    }

    /// Moving and static bodies (re-)inserted into a tree by the last update, and whether
    /// it rebuilt a tree; for benchmarks.
    int reinserted() const { return reinserted_; }
    bool rebuilt() const { return rebuilt_; }
    const AabbTree& movingTree() const { return movingTree_; }
    const AabbTree& staticTree() const { return staticTree_; }

private:
    Workers* pool_ = nullptr;
    enum class Set : std::uint8_t { None, Moving, Static, Unbounded };

    void reset(int count, const std::vector<Aabb>& bounds);
    Aabb fattened(const Aabb& box, const Vec3& shift) const;
    void addPair(int a, int b) { pairs_.emplace_back(a < b ? a : b, a < b ? b : a); }
    void updateCandidates(bool fromScratch);

    AabbTree movingTree_;
    AabbTree staticTree_;
    std::vector<Set> sets_;
    std::vector<Aabb> stored_;          // the box in the body's tree, read in body order
    std::vector<Vec3> lastCentre_;      // a moving body's box centre at the last update
    std::vector<std::uint8_t> stillFor_;  // updates a body has stood still in the moving tree
    std::vector<Vec3> insertedExtent_;    // a moving body's box extent when it was last inserted
    std::vector<double> turnReach_;       // > 0: its fat box holds this cube about its centre (turning)
    std::vector<int> movingBodies_;     // bounded moving bodies, ascending
    std::vector<int> unbounded_;        // ascending
    std::vector<std::pair<int, int>> pairs_;
    std::vector<std::pair<int, int>> candidates_;  // fat boxes overlapping, sorted (updateCandidates)
    std::vector<std::uint8_t> dirty_;   // per body: its fat box changed or it changed sets
    std::vector<int> dirtyBodies_;      // those bodies, ascending
    double typicalSize_ = 0.0;          // mean largest side of the finite boxes at reset
    int reinserted_ = 0;
    bool rebuilt_ = false;
    bool fresh_ = false;                // trees just reset: add leaves, then rebuild
};

/// O(n^2) reference for the tests: the same contract as Broadphase::update + pairs().
std::vector<std::pair<int, int>> bruteForcePairs(const std::vector<Aabb>& bounds,
                                                 const std::vector<std::uint8_t>& moving);

}  // namespace tumble::collision
