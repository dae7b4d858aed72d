// Dynamic AABB tree: top-down rebuild, insertion by least surface-area cost, removal.
#include "collision/aabb_tree.h"

#include "common/workers.h"

#include <algorithm>
#include <bit>
#include <cassert>

namespace tumble::collision {

namespace {

// A rebuild of this many leaves or more builds its two halves on two threads (a pool's run
// costs some 10 us; the build of 4 096 leaves some 0.3 ms).
constexpr int kParallelBuild = 4096;

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

bool sameBox(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

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
    nodes_[node].child2 = kNull;
    nodes_[node].height = -1;
    free_ = node;
}

void AabbTree::reset(int bodyCount) {
    nodes_.clear();
    leafOf_.assign(static_cast<std::size_t>(bodyCount), kNull);
    root_ = kNull;
    free_ = kNull;
    leaves_ = 0;
    unlinked_ = 0;
    changes_ = 0;
}

int AabbTree::newLeaf(int body, const Aabb& box) {
    assert(body >= 0 && body < static_cast<int>(leafOf_.size()) && leafOf_[body] == kNull);
    const int leaf = allocate();
    nodes_[leaf].box = box;
    nodes_[leaf].child2 = body;
    leafOf_[body] = leaf;
    ++leaves_;
    return leaf;
}

void AabbTree::add(int body, const Aabb& box) {
    newLeaf(body, box);
    ++unlinked_;
}

void AabbTree::insert(int body, const Aabb& box) {
    insertLeaf(newLeaf(body, box));
    ++changes_;
}

void AabbTree::remove(int body) {
    const int leaf = leafOf_[body];
    assert(leaf != kNull);
    if (nodes_[leaf].parent == kNull && leaf != root_) {
        --unlinked_;
    } else {
        removeLeaf(leaf);
        ++changes_;
    }
    release(leaf);
    leafOf_[body] = kNull;
    --leaves_;
}

bool AabbTree::needsRebuild() const {
    if (unlinked_ > 0) return true;
    if (changes_ > leaves_ / 4 + 16) return true;
    const int balanced = std::bit_width(static_cast<unsigned>(leaves_));  // ~ceil(log2 n) + 1
    return height() > 2 * balanced + 8;
}

void AabbTree::insertLeaf(int leaf) {
    if (root_ == kNull) {
        root_ = leaf;
        nodes_[leaf].parent = kNull;
        return;
    }
    // Walk down while going on is cheaper than pairing the leaf with the whole branch here.
    // Pairing here costs the new parent's area; going on costs the growth of this node (paid
    // the same by every ancestor, so only this level's is counted) plus what the child adds:
    // its own growth, or the new parent's area if the child is a leaf.
    const Aabb leafBox = nodes_[leaf].box;
    int index = root_;
    while (!nodes_[index].leaf()) {
        const Node& n = nodes_[index];
        const double combinedArea = area(merged(n.box, leafBox));
        const double here = 2.0 * combinedArea;
        const double inherited = 2.0 * (combinedArea - area(n.box));
        auto descendCost = [&](int child) {
            const Node& c = nodes_[child];
            const double grown = area(merged(c.box, leafBox));
            return (c.leaf() ? grown : grown - area(c.box)) + inherited;
        };
        const double cost1 = descendCost(n.child1);
        const double cost2 = descendCost(n.child2);
        if (here < cost1 && here < cost2) break;
        index = cost1 <= cost2 ? n.child1 : n.child2;
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

// From `node` towards the root: height and box from the children, until nothing changes.
void AabbTree::refitUpwards(int node) {
    while (node != kNull) {
        Node& n = nodes_[node];
        const int height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
        const Aabb box = merged(nodes_[n.child1].box, nodes_[n.child2].box);
        if (height == n.height && sameBox(box, n.box)) return;
        n.height = height;
        n.box = box;
        node = n.parent;
    }
}

void AabbTree::rebuild(Workers* pool) {
    // Built over the old nodes, which the list of leaves has copied: a second array of
    // nodes to build into and swap with kept the tree's memory twice (and more) over
    // between rebuilds. The list lives for the rebuild only (one allocation of its exact
    // size, where the rebuild itself is O(n log n)). Room for some insertions after it, so
    // that nodes_ does not grow while the number of leaves stays put.
    std::vector<Leaf> leaves;
    leaves.reserve(static_cast<std::size_t>(leaves_));
    for (const Node& n : nodes_)
        if (n.height == 0) leaves.push_back({n.box, n.body()});  // in id order
    nodes_.clear();
    nodes_.reserve(2 * leaves.size() + 64);
    root_ = leaves.empty() ? kNull : 0;
    if (!leaves.empty()) {
        nodes_.resize(2 * leaves.size() - 1);  // a tree of n leaves has 2 n - 1 nodes
        buildRange(leaves, 0, static_cast<int>(leaves.size()), 0, pool);
    }
    free_ = kNull;
    unlinked_ = 0;
    changes_ = 0;
}

// Builds the subtree over leaves[begin, end) into nodes_[index, index + 2 (end - begin) - 1),
// its root at index, then its left subtree, then its right (depth-first order). Each
// subtree's place is known before it is built, so that the two halves of a large tree can
// be built at once (`pool`, at the top only: the pool takes one run at a time).
void AabbTree::buildRange(std::vector<Leaf>& leaves, int begin, int end, int index, Workers* pool) {
    if (end - begin == 1) {
        const Leaf& leaf = leaves[begin];
        nodes_[index].box = leaf.box;
        nodes_[index].child2 = leaf.body;
        leafOf_[leaf.body] = index;
        return;
    }
    Aabb centres;  // of the doubled centres min + max: the same order, one operation less
    for (int k = begin; k < end; ++k) centres.add(leaves[k].box.min + leaves[k].box.max);
    int axis = 0;
    centres.extent().maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    // Ties broken by body: a strict total order, so the halves do not depend on the library.
    std::nth_element(leaves.begin() + begin, leaves.begin() + mid, leaves.begin() + end,
                     [&](const Leaf& a, const Leaf& b) {
                         const double ca = a.box.min[axis] + a.box.max[axis];
                         const double cb = b.box.min[axis] + b.box.max[axis];
                         return ca < cb || (ca == cb && a.body < b.body);
                     });
    const int left = index + 1, right = index + 2 * (mid - begin);
    if (pool && pool->threads() > 1 && end - begin >= kParallelBuild) {
        pool->run(2, [&](int half) {
            if (half == 0)
                buildRange(leaves, begin, mid, left, nullptr);
            else
                buildRange(leaves, mid, end, right, nullptr);
        });
    } else {
        buildRange(leaves, begin, mid, left, nullptr);
        buildRange(leaves, mid, end, right, nullptr);
    }
    Node& n = nodes_[index];
    n.child1 = left;
    n.child2 = right;
    n.box = merged(nodes_[left].box, nodes_[right].box);
    n.height = 1 + std::max(nodes_[left].height, nodes_[right].height);
    nodes_[left].parent = index;
    nodes_[right].parent = index;
}

bool AabbTree::valid() const {
    int reachable = 0;
    if (root_ != kNull && (nodes_[root_].parent != kNull || !validSubtree(root_, kNull, reachable)))
        return false;
    int unlinked = 0;
    for (int id = 0; id < static_cast<int>(nodes_.size()); ++id) {
        const Node& n = nodes_[id];
        if (n.height == 0 && n.parent == kNull && id != root_) ++unlinked;
    }
    int found = 0;
    for (int body = 0; body < static_cast<int>(leafOf_.size()); ++body) {
        const int leaf = leafOf_[body];
        if (leaf == kNull) continue;
        if (nodes_[leaf].height != 0 || nodes_[leaf].body() != body) return false;
        ++found;
    }
    return unlinked == unlinked_ && reachable + unlinked == leaves_ && found == leaves_;
}

bool AabbTree::validSubtree(int node, int parent, int& leaves) const {
    const Node& n = nodes_[node];
    if (n.parent != parent) return false;
    if (n.leaf()) {
        ++leaves;
        return n.height == 0;
    }
    const Node& c1 = nodes_[n.child1];
    const Node& c2 = nodes_[n.child2];
    if (n.height != 1 + std::max(c1.height, c2.height)) return false;
    if (!sameBox(merged(c1.box, c2.box), n.box)) return false;
    return validSubtree(n.child1, node, leaves) && validSubtree(n.child2, node, leaves);
}

}  // namespace tumble::collision
