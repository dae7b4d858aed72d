// A dynamic AABB tree: leaves (one per body) can be inserted and removed one at a time, so a
// body that moves a little costs nothing and one that moves far costs O(log n). A new leaf
// goes down the branch that grows the surface area least, down to a leaf it then shares a
// new parent with; after every change the path to the root is rebalanced by rotations on
// the children's heights. Children are unordered, so one kind of rotation covers every case
// and the tree stays AVL balanced (height <= 1.44 log2(n + 2)) whatever the insertion order. Nodes are pooled in one array with a free list, so
// after the first updates nothing is allocated. Used by the broadphase; the stored boxes are
// whatever the caller gives (the broadphase gives fattened boxes for moving bodies).
#pragma once

#include <tumble/collision.h>

#include <vector>

namespace tumble::collision {

class AabbTree {
public:
    static constexpr int kNull = -1;

    /// Adds a leaf holding `body` with `box`; returns the leaf's id (stable until removed).
    int insert(const Aabb& box, int body);
    void remove(int leaf);
    void clear();

    const Aabb& box(int leaf) const { return nodes_[leaf].box; }
    int body(int leaf) const { return nodes_[leaf].body; }
    int height() const { return root_ == kNull ? 0 : nodes_[root_].height + 1; }
    int leafCount() const { return leaves_; }

    /// Calls visit(int body) for every leaf whose box overlaps `box` (closed boxes).
    template <class Visit> void query(const Aabb& box, Visit&& visit) const;

    /// Checks the parent links, heights and that every box encloses its children's;
    /// for the tests.
    bool valid() const;

private:
    struct Node {
        Aabb box;
        int parent = kNull;
        int child1 = kNull;  // kNull for a leaf
        int child2 = kNull;
        int height = 0;      // 0 for a leaf
        int body = -1;       // leaf only
        bool leaf() const { return child1 == kNull; }
    };

    int allocate();
    void release(int node);
    void insertLeaf(int leaf);
    void removeLeaf(int leaf);
    int rotate(int a);
    void refitUpwards(int node);
    bool validSubtree(int node, int parent, int& leaves) const;

    std::vector<Node> nodes_;
    int root_ = kNull;
    int free_ = kNull;  // free list threaded through Node::parent
    int leaves_ = 0;
    mutable std::vector<int> stack_;  // query scratch; keeps its capacity
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
            visit(n.body);
        } else {
            stack_.push_back(n.child2);
            stack_.push_back(n.child1);
        }
    }
}

}  // namespace tumble::collision
