// Broadphase over two dynamic AABB trees and a list of unbounded bodies (see broadphase.h).
#include "collision/broadphase.h"

#include <algorithm>
#include <stdexcept>

namespace tumble::collision {

namespace {

// Fat boxes grow by this fraction of the larger of the box's longest side and the typical
// one: a body can drift that far before it is re-inserted, while queries see boxes only a
// little larger than the true ones (filtered exactly anyway).
constexpr double kFatFraction = 0.1;

bool isEmpty(const Aabb& b) {
    // Written with negations so that a NaN bound makes the box empty.
    return !(b.min.x() <= b.max.x() && b.min.y() <= b.max.y() && b.min.z() <= b.max.z());
}

bool isBounded(const Aabb& b) { return b.min.allFinite() && b.max.allFinite(); }

bool encloses(const Aabb& outer, const Aabb& inner) {
    return (outer.min.array() <= inner.min.array()).all() &&
           (inner.max.array() <= outer.max.array()).all();
}

bool sameBox(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

}  // namespace

void Broadphase::reset(std::size_t count, const std::vector<Aabb>& bounds) {
    movingTree_.clear();
    staticTree_.clear();
    proxies_.assign(count, Proxy{});
    double sum = 0.0;
    int finite = 0;
    for (const Aabb& b : bounds) {
        if (isEmpty(b) || !isBounded(b)) continue;
        sum += b.extent().maxCoeff();
        ++finite;
    }
    typicalSize_ = finite > 0 ? sum / finite : 0.0;
}

Aabb Broadphase::fattened(const Aabb& box) const {
    return box.inflated(kFatFraction * std::max(box.extent().maxCoeff(), typicalSize_));
}

void Broadphase::update(const std::vector<Aabb>& bounds, const std::vector<std::uint8_t>& moving) {
    if (bounds.size() != moving.size())
        throw std::invalid_argument("Broadphase::update: bounds and moving differ in size");
    const int n = static_cast<int>(bounds.size());
    if (proxies_.size() != bounds.size()) reset(bounds.size(), bounds);

    reinserted_ = 0;
    movingBodies_.clear();
    unbounded_.clear();
    for (int i = 0; i < n; ++i) {
        const Aabb& box = bounds[i];
        Set set = Set::None;
        if (!isEmpty(box)) set = !isBounded(box) ? Set::Unbounded : moving[i] ? Set::Moving : Set::Static;
        Proxy& p = proxies_[i];

        bool reinsert = p.set != set;
        if (!reinsert && set == Set::Moving) {
            const Aabb& fat = movingTree_.box(p.leaf);
            const double slack = kFatFraction * std::max(box.extent().maxCoeff(), typicalSize_);
            reinsert = !encloses(fat, box) || (fat.extent() - box.extent()).sum() > 12.0 * slack;
        } else if (!reinsert && set == Set::Static) {
            reinsert = !sameBox(staticTree_.box(p.leaf), box);
        }
        if (reinsert) {
            if (p.set == Set::Moving) movingTree_.remove(p.leaf);
            if (p.set == Set::Static) staticTree_.remove(p.leaf);
            p.leaf = AabbTree::kNull;
            if (set == Set::Moving) p.leaf = movingTree_.insert(fattened(box), i);
            if (set == Set::Static) p.leaf = staticTree_.insert(box, i);
            if (p.leaf != AabbTree::kNull) ++reinserted_;
            p.set = set;
        }
        if (set == Set::Moving) movingBodies_.push_back(i);
        if (set == Set::Unbounded) unbounded_.push_back(i);
    }

    pairs_.clear();
    for (int i : movingBodies_) {
        const Aabb& box = bounds[i];
        // Each moving-moving pair is met from both ends; the lower index keeps it.
        movingTree_.query(box, [&](int j) {
            if (j > i && box.overlaps(bounds[j])) pairs_.emplace_back(i, j);
        });
        // The static tree holds exact boxes: a hit is an overlap.
        staticTree_.query(box, [&](int s) { addPair(i, s); });
    }
    for (std::size_t k = 0; k < unbounded_.size(); ++k) {
        const int u = unbounded_[k];
        const Aabb& box = bounds[u];
        if (moving[u]) {
            for (int j = 0; j < n; ++j) {
                const Set s = proxies_[j].set;
                if ((s == Set::Moving || s == Set::Static) && box.overlaps(bounds[j])) addPair(u, j);
            }
        } else {
            for (int j : movingBodies_)
                if (box.overlaps(bounds[j])) addPair(u, j);
        }
        for (std::size_t l = k + 1; l < unbounded_.size(); ++l) {
            const int v = unbounded_[l];
            if ((moving[u] || moving[v]) && box.overlaps(bounds[v])) pairs_.emplace_back(u, v);
        }
    }
    std::sort(pairs_.begin(), pairs_.end());
}

std::vector<std::pair<int, int>> bruteForcePairs(const std::vector<Aabb>& bounds,
                                                 const std::vector<std::uint8_t>& moving) {
    if (bounds.size() != moving.size())
        throw std::invalid_argument("bruteForcePairs: bounds and moving differ in size");
    std::vector<std::pair<int, int>> pairs;
    const int n = static_cast<int>(bounds.size());
    for (int i = 0; i < n; ++i) {
        if (isEmpty(bounds[i])) continue;
        for (int j = i + 1; j < n; ++j) {
            if ((moving[i] || moving[j]) && !isEmpty(bounds[j]) && bounds[i].overlaps(bounds[j]))
                pairs.emplace_back(i, j);
        }
    }
    return pairs;
}

}  // namespace tumble::collision
