// Dynamic AABB tree: insertion by least surface-area growth, removal, and height rotations.
#include "collision/aabb_tree.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>

namespace tumble::collision {

namespace {

// Half the surface area: the expected cost of visiting a box is proportional to it.
double area(const Aabb& b) {
    const Vec3 e = b.max - b.min;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

Aabb merged(const Aabb& a, const Aabb& b) {
    Aabb m = a;
    m.add(b);
    return m;
}

}  // namespace

int AabbTree::allocate() {
    if (free_ == kNull) {
        nodes_.emplace_back();
        return static_cast<int>(nodes_.size()) - 1;
    }
    const int node = free_;
    free_ = nodes_[node].parent;
    nodes_[node] = Node{};
    return node;
}

void AabbTree::release(int node) {
    nodes_[node].parent = free_;
    nodes_[node].child1 = kNull;
    nodes_[node].height = -1;
    free_ = node;
}

void AabbTree::clear() {
    nodes_.clear();
    root_ = kNull;
    free_ = kNull;
    leaves_ = 0;
}

int AabbTree::insert(const Aabb& box, int body) {
    const int leaf = allocate();
    nodes_[leaf].box = box;
    nodes_[leaf].body = body;
    insertLeaf(leaf);
    ++leaves_;
    return leaf;
}

void AabbTree::remove(int leaf) {
    assert(leaf >= 0 && leaf < static_cast<int>(nodes_.size()) && nodes_[leaf].leaf());
    removeLeaf(leaf);
    release(leaf);
    --leaves_;
}

void AabbTree::insertLeaf(int leaf) {
    if (root_ == kNull) {
        root_ = leaf;
        nodes_[leaf].parent = kNull;
        return;
    }
    // Walk down to the leaf to pair with, into the child whose subtree grows least: a new
    // parent there costs its area when the child is a leaf, else the child's growth (the
    // growth of the current node is the same either way). Always ending at a leaf keeps every
    // change at one level of height, which the rotations can absorb: the tree stays AVL
    // balanced, height <= 1.44 log2(n + 2).
    const Aabb leafBox = nodes_[leaf].box;
    int index = root_;
    while (!nodes_[index].leaf()) {
        const Node& n = nodes_[index];
        auto descendCost = [&](int child) {
            const Node& c = nodes_[child];
            const double grown = area(merged(c.box, leafBox));
            return c.leaf() ? grown : grown - area(c.box);
        };
        index = descendCost(n.child1) <= descendCost(n.child2) ? n.child1 : n.child2;
    }

    const int sibling = index;
    const int oldParent = nodes_[sibling].parent;
    const int parent = allocate();
    nodes_[parent].parent = oldParent;
    nodes_[parent].box = merged(leafBox, nodes_[sibling].box);
    nodes_[parent].height = nodes_[sibling].height + 1;
    nodes_[parent].child1 = sibling;
    nodes_[parent].child2 = leaf;
    nodes_[sibling].parent = parent;
    nodes_[leaf].parent = parent;
    if (oldParent == kNull) {
        root_ = parent;
    } else if (nodes_[oldParent].child1 == sibling) {
        nodes_[oldParent].child1 = parent;
    } else {
        nodes_[oldParent].child2 = parent;
    }
    refitUpwards(oldParent);
}

void AabbTree::removeLeaf(int leaf) {
    if (leaf == root_) {
        root_ = kNull;
        return;
    }
    const int parent = nodes_[leaf].parent;
    const int grand = nodes_[parent].parent;
    const int sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    release(parent);
    nodes_[sibling].parent = grand;
    if (grand == kNull) {
        root_ = sibling;
        return;
    }
    if (nodes_[grand].child1 == parent) {
        nodes_[grand].child1 = sibling;
    } else {
        nodes_[grand].child2 = sibling;
    }
    refitUpwards(grand);
}

// From `node` to the root: rebalance, then recompute height and box from the children.
void AabbTree::refitUpwards(int node) {
    while (node != kNull) {
        node = rotate(node);
        Node& n = nodes_[node];
        n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
        n.box = merged(nodes_[n.child1].box, nodes_[n.child2].box);
        node = n.parent;
    }
}

// If one child of `a` is two levels taller than the other (one insertion or removal never
// unbalances more), lifts that child into a's place with a as its child; of the lifted
// child's two children, the taller stays with it and the shorter goes to a. Both nodes are
// then balanced. Returns the node now at a's place.
int AabbTree::rotate(int a) {
    Node& na = nodes_[a];
    if (na.leaf()) return a;
    const int b = na.child1;
    const int c = na.child2;
    const int balance = nodes_[c].height - nodes_[b].height;
    if (balance >= -1 && balance <= 1) return a;

    // `up` is the taller child, `stay` the other; `up` takes a's place with a as a child.
    const int up = balance > 1 ? c : b;
    const int stay = balance > 1 ? b : c;
    Node& nu = nodes_[up];
    const int f = nu.child1;
    const int g = nu.child2;

    nu.parent = na.parent;
    if (na.parent == kNull) {
        root_ = up;
    } else if (nodes_[na.parent].child1 == a) {
        nodes_[na.parent].child1 = up;
    } else {
        nodes_[na.parent].child2 = up;
    }
    na.parent = up;

    // The taller grandchild stays under `up`; the shorter one joins `stay` under a.
    const bool fTaller = nodes_[f].height > nodes_[g].height;
    const int keep = fTaller ? f : g;
    const int move = fTaller ? g : f;
    nu.child1 = a;
    nu.child2 = keep;
    na.child1 = stay;
    na.child2 = move;
    nodes_[move].parent = a;

    na.box = merged(nodes_[stay].box, nodes_[move].box);
    na.height = 1 + std::max(nodes_[stay].height, nodes_[move].height);
    nu.box = merged(na.box, nodes_[keep].box);
    nu.height = 1 + std::max(na.height, nodes_[keep].height);
    return up;
}

bool AabbTree::valid() const {
    if (root_ == kNull) return leaves_ == 0;
    int leaves = 0;
    return nodes_[root_].parent == kNull && validSubtree(root_, kNull, leaves) && leaves == leaves_;
}

bool AabbTree::validSubtree(int node, int parent, int& leaves) const {
    const Node& n = nodes_[node];
    if (n.parent != parent) return false;
    if (n.leaf()) {
        ++leaves;
        return n.height == 0 && n.child2 == kNull;
    }
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    if (n.height != 1 + std::max(c1.height, c2.height)) return false;
    if (std::abs(c1.height - c2.height) > 1) return false;
    const Aabb m = merged(c1.box, c2.box);
    if (m.min != n.box.min || m.max != n.box.max) return false;
    return validSubtree(n.child1, node, leaves) && validSubtree(n.child2, node, leaves);
}

}  // namespace tumble::collision
