// K x = b for a square matrix of small blocks (up to 6 × 6) whose block pattern is a chordal
// graph: block Gaussian elimination in a perfect elimination order, which makes no block
// that is not already in the pattern. The joints of a group whose moving bodies form a tree
// (a chain, a ragdoll, a robot arm on its base) have such a pattern: two joints' block is
// not zero when they share a body, and the joints at one body are all joined to each other.
// Eliminating a group's joints from its leaves inwards costs a few small blocks a joint,
// where a dense LU of the whole K costs its size cubed (a ragdoll's 40 rows: 17 % of
// ragdoll-pile's step went to Eigen's dense LU).
#pragma once

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace tumble {

using Block = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

/// How to eliminate a pattern: the nodes' order and, at each node's turn, the blocks its
/// elimination reads and changes (indices into the pattern's pairs), found once for the
/// Newton steps that solve with it.
struct Elimination {
    std::vector<int> order;
    std::vector<int> diagonal;  ///< per node, its (v, v)
    /// Per step s (order[s] = v): its later neighbours k (those still there at its turn) at
    /// later[begin[s] ..< begin[s + 1]], with the indices of (k, v) and (v, k); and the
    /// updates (k, l) -= (k, v) (v, l) over them at update[updateBegin[s] ..].
    std::vector<int> begin, later, column, row;
    struct Update {
        int target, left, right;  ///< (k, l), (k, v), (v, l)
    };
    std::vector<int> updateBegin;
    std::vector<Update> update;
    bool empty() const { return order.empty(); }
};

/// The elimination of the graph of `count` nodes whose edges are `pairs` (each (k, l) with
/// its (l, k), sorted ascending, every (k, k) there) in a perfect elimination order: each
/// node, at its turn, has its later neighbours all joined to each other. Empty when there is
/// none (the graph has a ring of four or more without a chord).
Elimination eliminationOf(int count, const std::vector<std::pair<int, int>>& pairs);

/// Solves K x = b where K's non-zero blocks are `blocks[i]` at the pattern's pairs[i], node
/// k's rows at offsets[k], sizes[k] of them. The blocks are overwritten. A pivot block that
/// is singular gives a result that is not finite.
Eigen::VectorXd solveByElimination(const Elimination& plan, std::vector<Block>& blocks,
                                   const std::vector<int>& offsets, const std::vector<int>& sizes,
                                   Eigen::VectorXd b);

}  // namespace tumble
