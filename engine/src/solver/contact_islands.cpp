#include "solver/contact_islands.h"

#include "common/make_room.h"
#include "common/workers.h"
#include "islands/islands.h"
#include "solver/joint_math.h"

#include <algorithm>
#include <atomic>
#include <chrono>

namespace tumble {

using collision::Manifold;
using collision::ManifoldList;

namespace {

// Islands with fewer contact points in all stay on one thread (static-field's 40 points on
// two threads: 0.004 -> 0.023 ms a step of solve, making the lanes and handing them out).
constexpr size_t kLanePoints = 512;

}  // namespace

// The contacts' islands: manifolds linked through the bodies that can move (dynamic and
// awake; a static, kinematic or sleeping body moves the same whatever its partners do, so
// it links nothing). Each island is solved to its own fixed point, with its own warm-start
// check and energy limit, one after another (only one island's rows in memory at a time)
// or, on the worker threads, one per lane at a time (solveIslands). Returns how many there are; with two or more, island k's manifolds
// are s.islandManifolds[s.islandBegin[k] .. s.islandBegin[k + 1]), in the contacts' order,
// the islands numbered as the contacts first name them. A manifold none of whose bodies
// can move is in none (the solve passes over it).
int contactIslands(const Model& model, const State& state, const ManifoldList& contacts,
                   ContactSolverScratch& s) {
    const size_t n = model.bodies.size();
    if (s.parent.size() != n) s.parent.assign(n, 0), s.islandOfRoot.assign(n, -1);
    auto movable = [&](int b) { return joint::movable(model, state, b); };  // (as loadBody gives a mass)
    for (const Manifold& m : contacts) s.parent[m.bodyA] = m.bodyA, s.parent[m.bodyB] = m.bodyB;
    for (const Manifold& m : contacts) {
        if (!movable(m.bodyA) || !movable(m.bodyB)) continue;
        const int ra = islandRoot(s.parent, m.bodyA), rb = islandRoot(s.parent, m.bodyB);
        if (ra != rb) s.parent[std::max(ra, rb)] = std::min(ra, rb);
    }
    s.islandOf.resize(contacts.size());
    s.roots.clear();
    for (size_t k = 0; k < contacts.size(); ++k) {
        const Manifold& m = contacts[k];
        const int body = movable(m.bodyA) ? m.bodyA : movable(m.bodyB) ? m.bodyB : -1;
        if (body < 0) {
            s.islandOf[k] = -1;
            continue;
        }
        const int r = islandRoot(s.parent, body);
        if (s.islandOfRoot[r] < 0) s.islandOfRoot[r] = static_cast<int>(s.roots.size()), s.roots.push_back(r);
        s.islandOf[k] = s.islandOfRoot[r];
    }
    const int islands = static_cast<int>(s.roots.size());
    for (int r : s.roots) s.islandOfRoot[r] = -1;
    if (islands <= 1) return islands;
    s.islandBegin.assign(islands + 1, 0);
    for (int i : s.islandOf)
        if (i >= 0) ++s.islandBegin[i + 1];
    for (int k = 0; k < islands; ++k) s.islandBegin[k + 1] += s.islandBegin[k];
    s.islandFill.assign(s.islandBegin.begin(), s.islandBegin.end() - 1);
    s.islandManifolds.resize(s.islandBegin[islands]);
    for (size_t k = 0; k < contacts.size(); ++k)
        if (s.islandOf[k] >= 0) s.islandManifolds[s.islandFill[s.islandOf[k]]++] = static_cast<int>(k);
    return islands;
}

namespace {

void addLedger(EnergyLedger& to, const EnergyLedger& from) {
    to.lostInContacts += from.lostInContacts;
    to.lostInFriction += from.lostInFriction;
    to.positionCorrection += from.positionCorrection;
    to.lostInJoints += from.lostInJoints;
    to.doneByKinematic += from.doneByKinematic;
}

void islandContactsOf(const ManifoldList& contacts, const ContactSolverScratch& s, int k, ManifoldList& out) {
    out.clear();
    for (int m = s.islandBegin[k]; m < s.islandBegin[k + 1]; ++m) out.push_back(contacts[s.islandManifolds[m]]);
}

// The lanes, one per thread, made and sized once per model and number of threads (outside
// the gate's timing: the first pooled run would otherwise book their allocation as the
// pool's overhead).
void sizeLanes(const Model& model, ContactSolverScratch& s) {
    const int threads = s.pool->threads();
    while (static_cast<int>(s.lanes.size()) < threads) s.lanes.push_back(std::make_unique<ContactSolverScratch>());
    for (int c = 0; c < threads; ++c)
        if (s.lanes[c]->bodies.size() != model.bodies.size()) sizeContactSolver(model, *s.lanes[c]);
}

// The lanes made ready for a solve: each with the memory index as s has it and nothing taken
// yet. Their new memory goes to their own `fresh` (never to State::contacts, which the other
// lanes read while they solve).
void prepareLanes(const Model& model, ContactSolverScratch& s) {
    for (int c = 0; c < s.pool->threads(); ++c) {
        ContactSolverScratch& lane = *s.lanes[c];
        lane.memory = s.memory;
        lane.used.assign(s.used.size(), 0);
        lane.still = s.still;
        lane.laneChanged.resize(model.bodies.size(), 0);  // (all 0: cleared as they are merged)
        lane.memoryChanged = s.memoryChanged ? &lane.laneChanged : nullptr;
        lane.toFresh = true;
        lane.fresh.clear();
        lane.stillBodies = 0;
    }
}

// The islands solved on the pool, each lane taking the next island (largest first) until
// none is left; then what they found merged into s in island order: the memory (after
// State::contacts's, or in s.fresh), the points taken, the bodies marked. A still body's
// kept terms (warmKinetic, frictionShare) live in s: copied to the lane for its island and
// back after (only the movable bodies', which belong to that island alone).
void solveOnLanes(const Model& model, State& state, const State& before, const ManifoldList& contacts,
                  const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s,
                  int islands) {
    prepareLanes(model, s);
    s.islandOrder.resize(islands);
    for (int k = 0; k < islands; ++k) s.islandOrder[k] = k;
    auto size = [&](int k) { return s.islandBegin[k + 1] - s.islandBegin[k]; };
    std::sort(s.islandOrder.begin(), s.islandOrder.end(),
              [&](int a, int b) { return size(a) > size(b) || (size(a) == size(b) && a < b); });
    std::atomic<int> next{0};
    auto movable = [&](int i) { return joint::movable(model, state, i); };
    s.pool->run(s.pool->threads(), [&](int c) {
        ContactSolverScratch& lane = *s.lanes[c];
        for (int j = next.fetch_add(1); j < islands; j = next.fetch_add(1)) {
            const int k = s.islandOrder[j];
            islandContactsOf(contacts, s, k, lane.islandContacts);
            for (const Manifold& m : lane.islandContacts)
                for (int i : {m.bodyA, m.bodyB})
                    if (movable(i)) lane.warmKinetic[i] = s.warmKinetic[i], lane.frictionShare[i] = s.frictionShare[i];
            ContactSolverScratch::IslandOut& out = s.islandOut[k];
            out.lane = c;
            out.begin = lane.fresh.size();
            solveIsland(model, state, before, lane.islandContacts, sizes, cfg, lane, out.ledger, false);
            out.end = lane.fresh.size();
            for (int i : lane.involved)
                if (movable(i)) s.warmKinetic[i] = lane.warmKinetic[i], s.frictionShare[i] = lane.frictionShare[i];
        }
    });
    std::vector<ContactMemory>& to = s.toFresh ? s.fresh : state.contacts;
    size_t added = 0;
    for (const ContactSolverScratch::IslandOut& out : s.islandOut) added += out.end - out.begin;
    makeRoom(to, to.size() + added);
    for (const ContactSolverScratch::IslandOut& out : s.islandOut) {
        const std::vector<ContactMemory>& from = s.lanes[out.lane]->fresh;
        to.insert(to.end(), from.begin() + static_cast<std::ptrdiff_t>(out.begin),
                  from.begin() + static_cast<std::ptrdiff_t>(out.end));
    }
    for (int c = 0; c < s.pool->threads(); ++c) {
        ContactSolverScratch& lane = *s.lanes[c];
        s.stillBodies += lane.stillBodies;
        for (size_t k = 0; k < lane.used.size(); ++k) s.used[k] |= lane.used[k];
        if (!s.memoryChanged) continue;
        std::vector<std::uint8_t>& changed = *s.memoryChanged;
        for (size_t i = 0; i < lane.laneChanged.size(); ++i)
            if (lane.laneChanged[i]) changed[i] = 1, lane.laneChanged[i] = 0;
    }
}

}  // namespace

void solveIslands(const Model& model, State& state, const State& before, const ManifoldList& contacts,
                  const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s,
                  EnergyLedger& ledger, int islands, size_t points) {
    // Each island books its own ledger, added up in island order (the same sums on the lanes).
    s.islandOut.assign(islands, {});
    // (Fewer points are never worth the lanes: a scene that small would pay for making them.)
    const bool timed = s.pool && s.pool->threads() > 1 && points >= kLanePoints;
    const bool pooled = timed && s.islandsGate.worthIt(s.pool, static_cast<int>(points));
    if (pooled) sizeLanes(model, s);
    const auto start = std::chrono::steady_clock::now();
    if (pooled) {
        ++s.pooledSolves;
        solveOnLanes(model, state, before, contacts, sizes, cfg, s, islands);
    } else {
        for (int k = 0; k < islands; ++k) {
            islandContactsOf(contacts, s, k, s.islandContacts);
            solveIsland(model, state, before, s.islandContacts, sizes, cfg, s, s.islandOut[k].ledger, false);
        }
    }
    if (timed)
        s.islandsGate.record(
            s.pool, static_cast<int>(points),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), pooled);
    for (const ContactSolverScratch::IslandOut& out : s.islandOut) addLedger(ledger, out.ledger);
}

}  // namespace tumble
