#include "islands/sleep.h"

#include "islands/islands.h"

#include "common/workers.h"

#include <algorithm>
#include <atomic>

namespace tumble {

using collision::Manifold;
using collision::ManifoldList;

namespace {

constexpr int kBodyGrain = 256;  // bodies per chunk on the worker threads

bool touches(const Manifold& m, double tol) {
    for (int i = 0; i < m.count; ++i)
        if (m.points[i].depth >= -tol) return true;
    return false;
}

bool dynamicBody(const Model& model, int b) {
    return model.bodies[b].motion == Motion::Dynamic;
}

bool forceActs(const Model& model, int body, double t) {
    for (const ForceTerm& f : model.forces)
        if (f.body == body && f.activeAt(t)) return true;
    return false;
}

void wake(State& state, int b) {
    state.asleep[b] = 0;
    state.restTime[b] = 0.0;
}

}  // namespace

void awakeBodies(const Model& model, const State& state, std::vector<int>& out) {
    out.clear();
    for (int i : model.dynamicBodies)
        if (!state.isAsleep(i)) out.push_back(i);
}

bool updateSleep(const Model& model, State& state, const ManifoldList& contacts, double tol, double h,
                 SleepScratch& s, EnergyLedger& ledger) {
    const int n = static_cast<int>(model.bodies.size());
    state.restTime.resize(n, 0.0);
    state.asleep.resize(n, 0);

    // Each body's rest time is its own: spread over the worker threads.
    std::atomic<bool> restedLongEnough{false};
    const std::vector<int>& dynamic = model.dynamicBodies;
    forEachChunk(s.pool, static_cast<int>(dynamic.size()), kBodyGrain, [&](int begin, int end) {
        bool rested = false;
        for (int k = begin; k < end; ++k) {
            const int i = dynamic[k];
            if (state.asleep[i]) continue;
            const BodyModel& b = model.bodies[i];
            const BodyState& bs = state.bodies[i];
            const Vec3 v = b.invMass * bs.P;  // derive()'s
            const Vec3 omega = angularVelocity(b, bs);
            const bool resting = v.squaredNorm() < kSleepSpeed * kSleepSpeed &&
                                 omega.squaredNorm() < kSleepSpin * kSleepSpin &&
                                 !forceActs(model, i, state.time);
            state.restTime[i] = resting ? state.restTime[i] + h : 0.0;
            rested = rested || state.restTime[i] >= kTimeToSleep;
        }
        if (rested) restedLongEnough.store(true, std::memory_order_relaxed);
    }, &s.restGate);
    // An island falls asleep when all its bodies rested long enough: none did, none sleeps.
    if (!restedLongEnough) return false;
    s.parent.resize(n);
    for (int i = 0; i < n; ++i) s.parent[i] = i;
    s.blocked.assign(n, 0);
    for (const Manifold& m : contacts) {
        if (!touches(m, tol)) continue;
        const int a = m.bodyA, b = m.bodyB;
        if (dynamicBody(model, a) && dynamicBody(model, b)) {
            s.parent[islandRoot(s.parent, a)] = islandRoot(s.parent, b);
        } else {
            // Resting on a moving kinematic body keeps the island awake.
            for (int k : {a, b})
                if (model.bodies[k].motion == Motion::Kinematic && !model.bodies[k].standsStill())
                    s.blocked[a == k ? b : a] = 1;
        }
    }
    // Joints are island edges too: a jointed assembly sleeps and wakes as one. A running
    // motor keeps its bodies awake.
    for (const JointModel& j : model.joints) {
        if (state.jointBroken(j.index)) continue;
        const auto running = [](const JointAxis& x) { return x.motor && x.motorMax > 0.0; };
        if (running(j) || std::any_of(j.axes.begin(), j.axes.end(), running)) {
            s.blocked[j.a] = 1;
            if (j.b >= 0) s.blocked[j.b] = 1;
        }
        if (j.b >= 0 && dynamicBody(model, j.a) && dynamicBody(model, j.b))
            s.parent[islandRoot(s.parent, j.a)] = islandRoot(s.parent, j.b);
    }
    s.islandRest.assign(n, 1e300);
    for (int i : model.dynamicBodies) {
        if (state.asleep[i]) continue;
        const int r = islandRoot(s.parent, i);
        s.islandRest[r] = std::min(s.islandRest[r], s.blocked[i] ? 0.0 : state.restTime[i]);
    }
    bool fell = false;
    for (int i : model.dynamicBodies) {
        if (state.asleep[i] || s.islandRest[islandRoot(s.parent, i)] < kTimeToSleep) continue;
        BodyState& b = state.bodies[i];
        const Derived d = derive(model.bodies[i], b);
        ledger.lostInContacts += 0.5 * (d.v.dot(b.P) + d.omega.dot(b.L));  // the little left at rest
        b.P.setZero();
        b.L.setZero();
        state.asleep[i] = 1;
        fell = true;
    }
    return fell;
}

bool wakeTouched(const Model& model, State& state, const ManifoldList& contacts,
                 const std::vector<collision::ImpactEvent>& impacts,
                 const std::vector<std::uint8_t>& parked) {
    if (state.asleep.empty()) return false;
    std::vector<int> stack;
    // A parked body is flagged asleep only while the step's impacts are cut (World::step):
    // it neither wakes nor wakes others.
    auto isParked = [&](int b) { return !parked.empty() && parked[b] != 0; };
    auto sleeps = [&](int b) { return state.isAsleep(b) && !isParked(b); };
    auto active = [&](int b) { return !model.bodies[b].standsStill() && !state.isAsleep(b); };
    auto touchPair = [&](int a, int b) {
        if (sleeps(a) && active(b)) stack.push_back(a);
        if (sleeps(b) && active(a)) stack.push_back(b);
    };
    for (const Manifold& m : contacts) touchPair(m.bodyA, m.bodyB);
    for (const auto& e : impacts) touchPair(e.bodyA, e.bodyB);
    for (int i : model.dynamicBodies)
        if (sleeps(i) && forceActs(model, i, state.time)) stack.push_back(i);
    bool woke = false;
    // Who rests on whom while asleep, from the remembered contacts: each body's partners,
    // made once when the first body wakes (scanning the whole memory for each woken body
    // was quadratic when a large pile woke).
    std::vector<int> first, partners;
    auto index = [&] {
        const size_t n = model.bodies.size();
        first.assign(n + 1, 0);
        // (A joint's bodies are partners too: an assembly wakes as one.)
        auto joined = [&](const JointModel& j) { return j.b >= 0 && !state.jointBroken(j.index); };
        for (const ContactMemory& c : state.contacts) ++first[c.bodyA + 1], ++first[c.bodyB + 1];
        for (const JointModel& j : model.joints)
            if (joined(j)) ++first[j.a + 1], ++first[j.b + 1];
        for (size_t i = 0; i < n; ++i) first[i + 1] += first[i];
        partners.resize(first[n]);
        std::vector<int> fill(first.begin(), first.end() - 1);
        for (const ContactMemory& c : state.contacts) {
            partners[fill[c.bodyA]++] = c.bodyB;
            partners[fill[c.bodyB]++] = c.bodyA;
        }
        for (const JointModel& j : model.joints) {
            if (!joined(j)) continue;
            partners[fill[j.a]++] = j.b;
            partners[fill[j.b]++] = j.a;
        }
    };
    while (!stack.empty()) {
        const int b = stack.back();
        stack.pop_back();
        if (!sleeps(b)) continue;
        wake(state, b);
        if (!woke) index();
        woke = true;
        // Its sleeping neighbours.
        for (int j = first[b]; j < first[b + 1]; ++j)
            if (sleeps(partners[j])) stack.push_back(partners[j]);
    }
    return woke;
}

}  // namespace tumble
