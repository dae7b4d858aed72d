// A dynamic AABB tree over bodies: one leaf per body, found by the body's index. Nodes are
// pooled in one array with a free list, so steady use allocates nothing.
//
// Two ways to place leaves, because they trade quality for cost differently:
// - rebuild(): top-down over all leaves, splitting at the median of the box centres along
//   the axis of their greatest spread. Balanced (height ceil(log2 n) + 1), of good quality,
//   O(n log n); and it lays the nodes out afresh in depth-first order, so a traversal reads
//   memory mostly forwards (at 100 000 bodies this matters more than anything else).
// - insert(): one leaf in O(depth), going down the branch whose area grows least and
//   stopping where pairing with the whole branch is cheaper than going on (surface-area
//   cost, as in Box2D's tree). Cheap, but a tree made only of insertions and removals
//   slowly loses quality and balance. (AVL-style height rotations were tried: they keep the
//   height but mix unrelated boxes and made queries several times slower.)
// So the owner inserts one at a time and calls rebuild() when needsRebuild() says that
// enough has changed; a large batch is best add()ed unlinked and placed by one rebuild.
#pragma once

#include <tumble/collision.h>

#include <utility>
#include <vector>

namespace tumble {
class Workers;
}

namespace tumble::collision {

class AabbTree {
public:
    static constexpr int kNull = -1;

    /// Empties the tree and makes room for bodies 0 .. bodyCount - 1.
    void reset(int bodyCount);

    /// Links a leaf for `body` (in range, not in the tree) into the tree.
    void insert(int body, const Aabb& box);
    /// Adds a leaf for `body` that traversals see only after the next rebuild().
    void add(int body, const Aabb& box);
    void remove(int body);
    bool contains(int body) const { return leafOf_[body] != kNull; }
    const Aabb& box(int body) const { return nodes_[leafOf_[body]].box; }

    /// Remakes the tree top-down over every leaf (linked or added).
    /// With `pool`, a large tree's two halves are built on two threads: the same nodes in
    /// the same places as on one.
    void rebuild(Workers* pool = nullptr);
    /// True when leaves wait unlinked, or the insertions and removals since the last
    /// rebuild pass a quarter of the leaves, or the height passes twice the balanced one.
    bool needsRebuild() const;

    /// Levels of the tree: 0 when empty, 1 for a single leaf.
    int height() const { return root_ == kNull ? 0 : nodes_[root_].height + 1; }
    int leafCount() const { return leaves_; }

    /// Calls visit(int body) for every linked leaf whose box overlaps `box` (closed boxes).
    template <class Visit> void query(const Aabb& box, Visit&& visit) const;

    /// Calls visit(int bodyA, int bodyB) once for every pair of distinct linked leaves whose
    /// boxes overlap, by a simultaneous descent of the tree against itself: each overlapping
    /// pair of nodes is met once, so the cost is about the nodes plus the pairs, without
    /// the root-to-leaf walk of one query per leaf.
    template <class Visit> void selfPairs(Visit&& visit) const;

    /// Calls visit(int bodyOfThis, int bodyOfOther) for every pair of linked leaves, one in
    /// each tree, whose boxes overlap.
    template <class Visit> void pairsWith(const AabbTree& other, Visit&& visit) const;

    /// Parent links, heights, every box the union of its children's, every leaf reachable
    /// or waiting and found by its body; for the tests.
    bool valid() const;

private:
    // One cache line per node: a leaf keeps its body where an inner node keeps child2.
    struct alignas(64) Node {
        Aabb box;
        int parent = kNull;
        int child1 = kNull;  // kNull for a leaf
        int child2 = kNull;  // a leaf's body
        int height = 0;      // 0 for a leaf, -1 for a free node
        bool leaf() const { return child1 == kNull; }
        int body() const { return child2; }
    };
    static_assert(sizeof(Node) == 64);

    int allocate();
    void release(int node);
    int newLeaf(int body, const Aabb& box);
    void insertLeaf(int leaf);
    void removeLeaf(int leaf);
    void refitUpwards(int node);
    struct Leaf {  // rebuild's copy of a leaf
        Aabb box;
        int body = kNull;
    };
    void buildRange(std::vector<Leaf>& leaves, int begin, int end, int index, Workers* pool);
    bool validSubtree(int node, int parent, int& leaves) const;
    // Which of a and b to open next in a pair descent: the taller, a on ties.
    static bool openFirst(const Node& a, const Node& b) {
        return b.leaf() || (!a.leaf() && a.height >= b.height);
    }

    std::vector<Node> nodes_;
    std::vector<int> leafOf_;      // per body: its leaf or kNull
    int root_ = kNull;
    int free_ = kNull;          // free list threaded through Node::parent
    int leaves_ = 0;            // linked and unlinked
    int unlinked_ = 0;
    int changes_ = 0;           // insertions and removals since the last rebuild
    mutable std::vector<int> stack_;
    mutable std::vector<std::pair<int, int>> pairStack_;
};

template <class Visit> void AabbTree::query(const Aabb& box, Visit&& visit) const {
    if (root_ == kNull) return;
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
        const Node& n = nodes_[stack_.back()];
        stack_.pop_back();
        if (!n.box.overlaps(box)) continue;
        if (n.leaf()) {
            visit(n.body());
        } else {
            stack_.push_back(n.child2);
            stack_.push_back(n.child1);
        }
    }
}

template <class Visit> void AabbTree::selfPairs(Visit&& visit) const {
    if (root_ == kNull) return;
    // (a, a) stands for the pairs within a's subtree, (a, b) for those across a and b.
    pairStack_.clear();
    pairStack_.emplace_back(root_, root_);
    while (!pairStack_.empty()) {
        const auto [a, b] = pairStack_.back();
        pairStack_.pop_back();
        const Node& na = nodes_[a];
        if (a == b) {
            if (na.leaf()) continue;
            pairStack_.emplace_back(na.child2, na.child2);
            pairStack_.emplace_back(na.child1, na.child2);
            pairStack_.emplace_back(na.child1, na.child1);
            continue;
        }
        const Node& nb = nodes_[b];
        if (!na.box.overlaps(nb.box)) continue;
        if (na.leaf() && nb.leaf()) {
            visit(na.body(), nb.body());
        } else if (openFirst(na, nb)) {
            pairStack_.emplace_back(na.child2, b);
            pairStack_.emplace_back(na.child1, b);
        } else {
            pairStack_.emplace_back(a, nb.child2);
            pairStack_.emplace_back(a, nb.child1);
        }
    }
}

template <class Visit> void AabbTree::pairsWith(const AabbTree& other, Visit&& visit) const {
    if (root_ == kNull || other.root_ == kNull) return;
    pairStack_.clear();
    pairStack_.emplace_back(root_, other.root_);
    while (!pairStack_.empty()) {
        const auto [a, b] = pairStack_.back();
        pairStack_.pop_back();
        const Node& na = nodes_[a];
        const Node& nb = other.nodes_[b];
        if (!na.box.overlaps(nb.box)) continue;
        if (na.leaf() && nb.leaf()) {
            visit(na.body(), nb.body());
        } else if (openFirst(na, nb)) {
            pairStack_.emplace_back(na.child2, b);
            pairStack_.emplace_back(na.child1, b);
        } else {
            pairStack_.emplace_back(a, nb.child2);
            pairStack_.emplace_back(a, nb.child1);
        }
    }
}

}  // namespace tumble::collision
