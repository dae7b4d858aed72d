// Top-down build of the triangle BVH: median split of the box centres along the axis of
// their greatest spread (see bvh.h for why the median).
#include "collision/bvh.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tumble::collision {

TriangleBvh::TriangleBvh(const std::vector<Vec3>& vertices,
                         const std::vector<std::array<int, 3>>& triangles) {
    const int n = static_cast<int>(triangles.size());
    const int nv = static_cast<int>(vertices.size());
    std::vector<Aabb> triBoxes(triangles.size());
    std::vector<Vec3> centres(triangles.size());
    for (int t = 0; t < n; ++t) {
        for (int corner : triangles[t]) {
            if (corner < 0 || corner >= nv)
                throw std::out_of_range("TriangleBvh: triangle " + std::to_string(t) +
                                        " has vertex index " + std::to_string(corner));
            triBoxes[t].add(vertices[corner]);
        }
        centres[t] = triBoxes[t].center();
    }
    order_.resize(triangles.size());
    for (int t = 0; t < n; ++t) order_[t] = t;
    if (n == 0) return;
    // Halving down to leaves of kLeafSize / 2 or more: at most 4 n / kLeafSize leaves.
    nodes_.reserve(static_cast<std::size_t>(8 * (n / kLeafSize + 1)));
    nodes_.emplace_back();
    build(0, 0, n, centres, triBoxes);
    boxes_.resize(order_.size());
    for (int k = 0; k < n; ++k) boxes_[k] = triBoxes[order_[k]];
}

// Fills node `index` with the triangles order_[begin, end), appending its descendants.
void TriangleBvh::build(int index, int begin, int end, const std::vector<Vec3>& centres,
                        const std::vector<Aabb>& triBoxes) {
    Aabb box;
    Aabb centreBox;
    for (int k = begin; k < end; ++k) {
        box.add(triBoxes[order_[k]]);
        centreBox.add(centres[order_[k]]);
    }
    nodes_[index].box = box;
    if (end - begin <= kLeafSize) {
        std::sort(order_.begin() + begin, order_.begin() + end);
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return;
    }
    int axis = 0;
    centreBox.extent().maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    // Ties broken by index: a strict total order, so the halves do not depend on the
    // library's nth_element.
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) {
                         const double ca = centres[a][axis];
                         const double cb = centres[b][axis];
                         return ca < cb || (ca == cb && a < b);
                     });
    const int left = static_cast<int>(nodes_.size());
    nodes_[index].first = left;
    nodes_[index].count = 0;
    nodes_.emplace_back();
    nodes_.emplace_back();
    build(left, begin, mid, centres, triBoxes);
    build(left + 1, mid, end, centres, triBoxes);
}

}  // namespace tumble::collision
