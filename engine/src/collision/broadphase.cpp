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
// A moving body's fat box also reaches this many times its box's last shift ahead, along
// it (a body falling fast moves farther than the margin in one step).
constexpr double kAhead = 6.0;
// A body that stops moving stays in the moving tree for this many updates (while its box
// stays inside its fat one) before it joins the static tree: the islands World parks stand
// still for the rest of a step and move again in the next, and moving a few hundred bodies
// to the other tree and back, with two rebuilds, was 5 % of hull-rain's step.
constexpr int kStillUpdates = 16;

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

void Broadphase::reset(int count, const std::vector<Aabb>& bounds) {
    movingTree_.reset(count);
    staticTree_.reset(count);
    sets_.assign(static_cast<std::size_t>(count), Set::None);
    stored_.assign(static_cast<std::size_t>(count), Aabb{});
    lastCentre_.assign(static_cast<std::size_t>(count), Vec3::Zero());
    stillFor_.assign(static_cast<std::size_t>(count), 0);
    insertedExtent_.assign(static_cast<std::size_t>(count), Vec3::Zero());
    turnReach_.assign(static_cast<std::size_t>(count), 0.0);
    double sum = 0.0;
    int finite = 0;
    for (const Aabb& b : bounds) {
        if (isEmpty(b) || !isBounded(b)) continue;
        sum += b.extent().maxCoeff();
        ++finite;
    }
    typicalSize_ = finite > 0 ? sum / finite : 0.0;
    fresh_ = true;
}

Aabb Broadphase::fattened(const Aabb& box, const Vec3& shift) const {
    Aabb fat = box.inflated(kFatFraction * std::max(box.extent().maxCoeff(), typicalSize_));
    for (int k = 0; k < 3; ++k) (shift[k] > 0.0 ? fat.max[k] : fat.min[k]) += kAhead * shift[k];
    return fat;
}

void Broadphase::update(const std::vector<Aabb>& bounds, const std::vector<std::uint8_t>& moving) {
    update(bounds, moving, {});
}

void Broadphase::update(const std::vector<Aabb>& bounds, const std::vector<std::uint8_t>& moving,
                        const std::vector<HalfSpace>& halfSpaces) {
    if (bounds.size() != moving.size() || (!halfSpaces.empty() && halfSpaces.size() != bounds.size()))
        throw std::invalid_argument("Broadphase::update: bounds, moving and half-spaces differ in size");
    const int n = static_cast<int>(bounds.size());
    if (sets_.size() != bounds.size()) reset(n, bounds);

    reinserted_ = 0;
    movingBodies_.clear();
    unbounded_.clear();
    dirty_.assign(static_cast<std::size_t>(n), 0);
    dirtyBodies_.clear();
    for (int i = 0; i < n; ++i) {
        const Aabb& box = bounds[i];
        Set set = Set::None;
        if (!isEmpty(box)) set = !isBounded(box) ? Set::Unbounded : moving[i] ? Set::Moving : Set::Static;
        const Set old = sets_[i];
        // Standing still in the moving tree: paired as a still body (pairs_ below), left
        // where it is.
        const bool still = set == Set::Static && old == Set::Moving && stillFor_[i] < kStillUpdates &&
                           encloses(stored_[i], box);
        if (still) {
            set = Set::Moving;
            ++stillFor_[i];
        } else {
            stillFor_[i] = 0;
        }

        bool reinsert = old != set;
        Vec3 shift = Vec3::Zero();
        if (set == Set::Moving && !still) {
            const Vec3 centre = 0.5 * (box.min + box.max);
            if (old == Set::Moving) shift = centre - lastCentre_[i];
            if (!shift.allFinite()) shift.setZero();
            lastCentre_[i] = centre;
        }
        const double slack = kFatFraction * std::max(box.extent().maxCoeff(), typicalSize_);
        if (!reinsert && set == Set::Moving && !still) {
            const Aabb& fat = stored_[i];
            const double ahead = kAhead * shift.cwiseAbs().sum();
            // A turning body's fat box is measured against the cube it was given (below).
            const Vec3 held = box.extent().cwiseMax(Vec3::Constant(2.0 * turnReach_[i]));
            reinsert = !encloses(fat, box) || (fat.extent() - held).sum() > 12.0 * slack + 2.0 * ahead;
        } else if (!reinsert && set == Set::Static) {
            reinsert = !sameBox(stored_[i], box);
        }
        if (reinsert) {
            if (old == Set::Moving) movingTree_.remove(i);
            if (old == Set::Static) staticTree_.remove(i);
            if (set == Set::Moving || set == Set::Static) {
                AabbTree& tree = set == Set::Moving ? movingTree_ : staticTree_;
                stored_[i] = set == Set::Moving ? fattened(box, shift) : box;
                // A body whose box changed its shape while it hardly moved is turning: its fat
                // box takes in the cube of the box's diagonal about its centre, which holds a
                // body turning about its middle in any pose (free-10000's spinning boxes left
                // their fat boxes every few steps: 500 of 10 000 re-inserted a step and a
                // rebuild every fourth, for no pair).
                if (set == Set::Moving) {
                    const bool turned = old == Set::Moving &&
                                        (box.extent() - insertedExtent_[i]).cwiseAbs().maxCoeff() > slack &&
                                        shift.norm() < slack;
                    insertedExtent_[i] = box.extent();
                    turnReach_[i] = turned ? 0.5 * box.extent().norm() + slack : 0.0;
                    if (turned) {
                        const Vec3 centre = 0.5 * (box.min + box.max);
                        stored_[i].add(Aabb{centre.array() - turnReach_[i], centre.array() + turnReach_[i]});
                    }
                }
                if (fresh_) {
                    tree.add(i, stored_[i]);
                } else {
                    tree.insert(i, stored_[i]);
                }
                ++reinserted_;
            }
            sets_[i] = set;
            dirty_[i] = 1;  // its fat box changed or went: its candidates are found again
            dirtyBodies_.push_back(i);
        }
        if (set == Set::Moving && moving[i]) movingBodies_.push_back(i);
        if (set == Set::Unbounded) unbounded_.push_back(i);
    }
    const bool fresh = fresh_;
    fresh_ = false;
    rebuilt_ = false;
    for (AabbTree* tree : {&movingTree_, &staticTree_}) {
        if (tree->needsRebuild()) {
            tree->rebuild(pool_);
            rebuilt_ = true;
        }
    }
    updateCandidates(fresh || 4 * dirtyBodies_.size() > static_cast<std::size_t>(n));

    // Fat boxes overlapping say nothing yet: every candidate is checked on the true boxes
    // (in the candidates' order, so these pairs come out sorted), and two bodies standing
    // still in the moving tree make no pair.
    pairs_.clear();
    for (const auto& [a, b] : candidates_)
        if ((moving[a] || moving[b]) && bounds[a].overlaps(bounds[b])) pairs_.emplace_back(a, b);
    const std::size_t boundedPairs = pairs_.size();
    const HalfSpace none;
    for (std::size_t k = 0; k < unbounded_.size(); ++k) {
        const int u = unbounded_[k];
        const Aabb& box = bounds[u];
        const HalfSpace& half = halfSpaces.empty() ? none : halfSpaces[u];
        auto pairsWith = [&](int j) { return box.overlaps(bounds[j]) && (!half.valid || half.reaches(bounds[j])); };
        if (moving[u]) {
            for (int j = 0; j < n; ++j) {
                const Set s = sets_[j];
                if ((s == Set::Moving || s == Set::Static) && pairsWith(j)) addPair(u, j);
            }
        } else {
            for (int j : movingBodies_)
                if (pairsWith(j)) addPair(u, j);
        }
        for (std::size_t l = k + 1; l < unbounded_.size(); ++l) {
            const int v = unbounded_[l];
            if ((moving[u] || moving[v]) && box.overlaps(bounds[v])) pairs_.emplace_back(u, v);
        }
    }
    if (pairs_.size() > boundedPairs) {  // the unbounded bodies' pairs, merged in
        std::sort(pairs_.begin() + static_cast<std::ptrdiff_t>(boundedPairs), pairs_.end());
        std::inplace_merge(pairs_.begin(), pairs_.begin() + static_cast<std::ptrdiff_t>(boundedPairs), pairs_.end());
    }
}

// The candidates are the pairs whose fat boxes overlap, one moving and the other moving or
// static. A pair's answer changes only when one of its fat boxes does, i.e. when one of its
// bodies was re-inserted or changed sets (dirty): the other pairs are kept as they were, and
// each dirty body asks the trees for its own. From scratch (both trees descended) after a
// reset or when many bodies are dirty.
void Broadphase::updateCandidates(bool fromScratch) {
    if (fromScratch) {
        candidates_.clear();
        auto add = [&](int a, int b) { candidates_.emplace_back(a < b ? a : b, a < b ? b : a); };
        movingTree_.selfPairs(add);
        movingTree_.pairsWith(staticTree_, add);
        std::sort(candidates_.begin(), candidates_.end());
        return;
    }
    if (dirtyBodies_.empty()) return;
    std::erase_if(candidates_, [&](const std::pair<int, int>& c) { return dirty_[c.first] || dirty_[c.second]; });
    const std::size_t kept = candidates_.size();
    for (int i : dirtyBodies_) {
        auto add = [&](int j) { candidates_.emplace_back(i < j ? i : j, i < j ? j : i); };
        if (sets_[i] == Set::Moving) {
            // A pair of two dirty moving bodies is found by both: the lower one adds it.
            movingTree_.query(stored_[i], [&](int j) {
                if (j != i && (!dirty_[j] || i < j)) add(j);
            });
            staticTree_.query(stored_[i], add);
        } else if (sets_[i] == Set::Static) {
            // A dirty moving body found this pair from its side already.
            movingTree_.query(stored_[i], [&](int j) {
                if (!dirty_[j]) add(j);
            });
        }
    }
    const auto middle = candidates_.begin() + static_cast<std::ptrdiff_t>(kept);
    std::sort(middle, candidates_.end());
    std::inplace_merge(candidates_.begin(), middle, candidates_.end());
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
