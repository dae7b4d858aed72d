// A bounding-volume hierarchy of axis-aligned boxes over a triangle mesh's triangles, in the
// mesh (body) frame. Built once per mesh, top-down, splitting the triangles at the median of
// their box centres along the longest axis of the centres' spread: every split halves the
// count, so the tree is balanced (depth <= 32 for any int-sized mesh) and the traversal
// stacks below can be fixed arrays. Nodes live in one flat array, the two children of a node
// side by side; a leaf holds up to kLeafSize triangles, sorted by index, so the build and
// the visiting order are deterministic.
//
// The triangles' own boxes are kept (in leaf order), so `query` is exact: it visits exactly
// the triangles whose box overlaps the query box (closed boxes: touching counts).
// `raycast` and `queryPairs` are conservative: rounding is allowed for, so no triangle (pair)
// whose box truly meets the segment (the other triangle's box) is ever missed; a few extra
// may be visited. Callers run the exact narrow tests on what they are given.
#pragma once

#include <tumble/collision.h>

#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace tumble::collision {

class TriangleBvh {
public:
    static constexpr int kLeafSize = 4;

    /// Indices must be valid vertex indices (throws std::out_of_range otherwise).
    TriangleBvh(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles);

    /// Of the whole mesh, mesh frame; empty for a mesh without triangles.
    const Aabb& bounds() const { return nodes_.empty() ? empty_ : nodes_[0].box; }
    int triangleCount() const { return static_cast<int>(order_.size()); }
    int nodeCount() const { return static_cast<int>(nodes_.size()); }

    /// Calls visit(int triangle) for every triangle whose box overlaps `box` (mesh frame).
    template <class Visit> void query(const Aabb& box, Visit&& visit) const;

    /// Calls visit(int triangle) for every triangle whose box the segment origin + t direction,
    /// t in [0, maxLength], crosses (mesh frame); with a unit direction t is the length.
    /// maxLength may be infinite (a ray). For ray casts and parity tests.
    template <class Visit>
    void raycast(const Vec3& origin, const Vec3& direction, double maxLength, Visit&& visit) const;

    /// Pairs of triangles (i of this, j of other) whose boxes overlap, `other` placed in this
    /// mesh's frame by `otherToThis`. The other mesh's boxes are carried over as the box of the
    /// rotated box, so a pair may be reported whose exact boxes just miss. visit(int i, int j).
    template <class Visit>
    void queryPairs(const TriangleBvh& other, const Pose& otherToThis, Visit&& visit) const;

private:
    struct Node {
        Aabb box;
        int first = 0;  // leaf: first slot in order_/boxes_; inner: left child (right is +1)
        int count = 0;  // leaf: number of triangles (> 0); inner: 0
        bool leaf() const { return count > 0; }
    };
    static constexpr int kStackSize = 64;  // > 2 * depth, the most a pair traversal holds

    void build(int index, int begin, int end, const std::vector<Vec3>& centres,
               const std::vector<Aabb>& triBoxes);

    // Box of `b` placed by `pose`, grown by a bound on the rounding of the transform.
    static Aabb transformed(const Aabb& b, const Pose& pose, const Mat3& absR);
    static bool segmentHits(const Aabb& b, const Vec3& o, const Vec3& d, const Vec3& inv,
                            double maxLength);

    std::vector<Node> nodes_;
    std::vector<int> order_;   // triangle indices in leaf order
    std::vector<Aabb> boxes_;  // boxes_[k] is the box of triangle order_[k]
    Aabb empty_;
};

template <class Visit> void TriangleBvh::query(const Aabb& box, Visit&& visit) const {
    if (nodes_.empty()) return;
    std::array<int, kStackSize> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (!n.box.overlaps(box)) continue;
        if (n.leaf()) {
            for (int k = n.first; k < n.first + n.count; ++k)
                if (boxes_[k].overlaps(box)) visit(order_[k]);
        } else {
            stack[top++] = n.first + 1;
            stack[top++] = n.first;
        }
    }
}

template <class Visit>
void TriangleBvh::raycast(const Vec3& origin, const Vec3& direction, double maxLength,
                          Visit&& visit) const {
    if (nodes_.empty()) return;
    // 1/0 = inf is wanted: the slab test below then leaves that axis to the origin's position.
    const Vec3 inv = direction.cwiseInverse();
    std::array<int, kStackSize> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (!segmentHits(n.box, origin, direction, inv, maxLength)) continue;
        if (n.leaf()) {
            for (int k = n.first; k < n.first + n.count; ++k)
                if (segmentHits(boxes_[k], origin, direction, inv, maxLength)) visit(order_[k]);
        } else {
            stack[top++] = n.first + 1;
            stack[top++] = n.first;
        }
    }
}

template <class Visit>
void TriangleBvh::queryPairs(const TriangleBvh& other, const Pose& otherToThis, Visit&& visit) const {
    if (nodes_.empty() || other.nodes_.empty()) return;
    const Mat3 absR = otherToThis.R.cwiseAbs();
    // Size of a node, to descend the larger one first: keeps both sides' boxes comparable.
    auto size = [](const Aabb& b) { return (b.max - b.min).sum(); };
    std::array<std::array<int, 2>, kStackSize> stack;
    int top = 0;
    stack[top++] = {0, 0};
    while (top > 0) {
        const auto [a, b] = stack[--top];
        const Node& na = nodes_[a];
        const Node& nb = other.nodes_[b];
        const Aabb boxB = transformed(nb.box, otherToThis, absR);
        if (!na.box.overlaps(boxB)) continue;
        if (na.leaf() && nb.leaf()) {
            for (int kb = nb.first; kb < nb.first + nb.count; ++kb) {
                const Aabb tb = transformed(other.boxes_[kb], otherToThis, absR);
                if (!na.box.overlaps(tb)) continue;
                for (int ka = na.first; ka < na.first + na.count; ++ka)
                    if (boxes_[ka].overlaps(tb)) visit(order_[ka], other.order_[kb]);
            }
        } else if (nb.leaf() || (!na.leaf() && size(na.box) >= size(nb.box))) {
            stack[top++] = {na.first + 1, b};
            stack[top++] = {na.first, b};
        } else {
            stack[top++] = {a, nb.first + 1};
            stack[top++] = {a, nb.first};
        }
    }
}

inline Aabb TriangleBvh::transformed(const Aabb& b, const Pose& pose, const Mat3& absR) {
    const Vec3 c = 0.5 * (b.min + b.max);
    const Vec3 h = 0.5 * (b.max - b.min);
    const Vec3 centre = pose.R * c + pose.p;
    // A few ulps of every term that went into the result, with a wide safety factor.
    const Vec3 slack = 1e-14 * (absR * (c.cwiseAbs() + h) + pose.p.cwiseAbs());
    const Vec3 half = absR * h + slack;
    return {centre - half, centre + half};
}

inline bool TriangleBvh::segmentHits(const Aabb& b, const Vec3& o, const Vec3& d,
                                     const Vec3& inv, double maxLength) {
    // Slab test; the far ends are grown by 1 + 2 gamma(3) to cover the rounding of
    // (bound - origin) * inv (Ize, "Robust BVH ray traversal", 2013). The signs of the
    // differences are exact, so nothing behind the origin is let in by the growth.
    // An axis the segment hardly moves along (1/d infinite: d zero or subnormal) is
    // left to the origin's position when d is zero, and not used to cut at all otherwise.
    constexpr double kGrow = 1.0 + 2.0 * 3.0 * std::numeric_limits<double>::epsilon();
    double tmin = 0.0;
    double tmax = maxLength;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::isinf(inv[axis])) {
            if (d[axis] == 0.0 && (o[axis] < b.min[axis] || o[axis] > b.max[axis]))
                return false;
            continue;
        }
        double t0 = (b.min[axis] - o[axis]) * inv[axis];
        double t1 = (b.max[axis] - o[axis]) * inv[axis];
        if (t0 > t1) std::swap(t0, t1);
        t1 *= kGrow;
        if (t0 > tmin) tmin = t0;
        if (t1 < tmax) tmax = t1;
    }
    return tmin <= tmax;
}

}  // namespace tumble::collision
