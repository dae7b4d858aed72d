#include "solver/block_regions.h"

#include "common/workers.h"
#include "solver/contact_rows.h"

#include <algorithm>

namespace tumble {

namespace {

// Islands with fewer blocks keep their manifolds' order: their passes are too short to share
// (chair-pile's islands of 260 blocks, split: 8.2-10.1 -> 11.1-11.2 ms a step on one thread).
constexpr size_t kSplitBlocks = 1024;

// The blocks [begin, end) of a region, forwards or backwards, stamped from `tick` + 1 on.
// With `wants` (the two regions, on the pool or not), a block that needs an entry in s.subsets
// is listed there and given it after both (the pool does not grow while two regions read it). Returns how many it updated; `changed`: whether any
// changed, written once at the end (the two regions' flags lie side by side, and written at
// every block they had the two threads fighting over one cache line).
long regionPass(ContactSolverScratch& s, int begin, int end, bool back, double quietSpeed, long tick,
                std::vector<int>* wants, bool& changed) {
    long updates = 0;
    bool any = false;
    for (int j = begin; j < end; ++j) {
        const int k = back ? begin + end - 1 - j : j;
        if (blockQuiet(s, k)) continue;
        any |= updateBlockAt(s, k, quietSpeed, tick + ++updates, wants);
    }
    changed = changed || any;
    return updates;
}

}  // namespace

// The regions: the island's movable bodies (each body's centre as the solve loaded it) cut
// along the axis their centres spread over most, where the bodies' blocks are half on either
// side (each body weighs as many blocks as it has; at the same place, the lower index first).
// Each block's group: its movable bodies' region, or 2 (the boundary) when they lie in both.
// The blocks keep the manifolds' order within a group. (Cut at the bodies' median, the
// pyramid's regions had 3 400 and 3 700 blocks, and the thread with the smaller waited.)
bool splitBlocks(const Model& model, const collision::ManifoldList& contacts, ContactSolverScratch& s) {
    s.split = false;
    const int nb = static_cast<int>(s.blockManifold.size());
    if (static_cast<size_t>(nb) < kSplitBlocks || !model.joints.empty()) return false;
    if (s.bodyBlocks.size() != s.bodies.size()) s.bodyBlocks.assign(s.bodies.size(), 0);
    for (int k = 0; k < nb; ++k) {
        const collision::Manifold& m = contacts[s.blockManifold[k]];
        for (int i : {m.bodyA, m.bodyB})
            if (s.bodies[i].invMass > 0.0) ++s.bodyBlocks[i];
    }
    Vec3 low = Vec3::Constant(HUGE_VAL), high = -low;
    s.cut.clear();
    for (int i : s.involved)
        if (s.bodies[i].invMass > 0.0)
            low = low.cwiseMin(s.bodies[i].x), high = high.cwiseMax(s.bodies[i].x), s.cut.push_back(i);
    int axis = 0;
    (high - low).maxCoeff(&axis);
    std::sort(s.cut.begin(), s.cut.end(), [&](int a, int b) {
        const double xa = s.bodies[a].x[axis], xb = s.bodies[b].x[axis];
        return xa < xb || (xa == xb && a < b);
    });
    long total = 0, below = 0;
    for (int i : s.cut) total += s.bodyBlocks[i];
    s.bodyRegion.resize(s.bodies.size());
    for (int i : s.cut) {
        s.bodyRegion[i] = 2 * below < total ? 0 : 1;
        below += s.bodyBlocks[i];
        s.bodyBlocks[i] = 0;  // (all 0 between solves)
    }
    s.blockRegion.resize(nb);
    int count[3] = {};
    for (int k = 0; k < nb; ++k) {
        const collision::Manifold& m = contacts[s.blockManifold[k]];
        const int a = s.bodies[m.bodyA].invMass > 0.0 ? s.bodyRegion[m.bodyA] : -1;
        const int b = s.bodies[m.bodyB].invMass > 0.0 ? s.bodyRegion[m.bodyB] : -1;
        const int g = a < 0 ? b : b < 0 || a == b ? a : 2;
        s.blockRegion[k] = static_cast<std::int8_t>(g);
        ++count[g];
    }
    s.regionBegin = {0, count[0], count[0] + count[1], nb};
    int fill[3] = {s.regionBegin[0], s.regionBegin[1], s.regionBegin[2]};
    s.regionBlocks.resize(nb);
    for (int k = 0; k < nb; ++k) s.regionBlocks[fill[s.blockRegion[k]]++] = k;
    s.split = true;
    return true;
}

bool onRegions(ContactSolverScratch& s, const std::function<void(int)>& work) {
    if (s.pool && s.pool->threads() > 1) {
        s.pool->run(2, work);
        return true;
    }
    work(0);
    work(1);
    return false;
}

bool iterateRegions(ContactSolverScratch& s, int pass, double quietSpeed) {
    const bool back = pass % 2;
    bool changed = false;
    const auto& at = s.regionBegin;
    auto boundary = [&] { s.tick += regionPass(s, at[2], at[3], back, quietSpeed, s.tick, nullptr, changed); };
    if (back) boundary();
    // The two regions from the same stamp: a block of one is never compared with a body of the
    // other. The stamps after them start past both.
    const long tick = s.tick;
    long updates[2] = {0, 0};
    bool regionChanged[2] = {false, false};
    const bool pooled = onRegions(s, [&](int r) {
        updates[r] = regionPass(s, at[r], at[r + 1], back, quietSpeed, tick, &s.wants[r], regionChanged[r]);
    });
    s.pooledRegions += pooled;
    for (std::vector<int>& wants : s.wants) {
        for (int k : wants) {
            ContactSolverScratch::Block& block = s.blocks[k];
            if (block.subsets >= 0) continue;
            block.subsets = static_cast<int>(s.subsets.size());
            s.subsets.emplace_back();
        }
        wants.clear();
    }
    s.tick = tick + std::max(updates[0], updates[1]);
    changed = changed || regionChanged[0] || regionChanged[1];
    if (!back) boundary();
    return changed;
}

}  // namespace tumble
