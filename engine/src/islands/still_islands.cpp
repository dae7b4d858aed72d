#include "islands/still_islands.h"

#include <cstring>

namespace tumble {

namespace {

// Bit for bit: -0 and +0 differ, as they do in the state's hash.
bool same(const BodyState& a, const BodyState& b) {
    auto eq = [](const auto& x, const auto& y) {
        return std::memcmp(x.data(), y.data(), sizeof(double) * 3) == 0;
    };
    return eq(a.x, b.x) && eq(a.P, b.P) && eq(a.L, b.L) &&
           std::memcmp(a.q.coeffs().data(), b.q.coeffs().data(), sizeof(double) * 4) == 0;
}

bool moves(const BodyModel& b) {
    return b.motion == Motion::Kinematic && !b.standsStill();
}

}  // namespace

void startStillStep(const Model& model, const State& state, double h, StillScratch& s) {
    if (!s.enabled) return;
    const size_t n = model.bodies.size();
    // A force acting within the step (its window meets [t, t + h]) is something the last
    // step may not have had, or this one may not have: its body is not taken as still.
    s.driven.assign(n, 0);
    const double t0 = state.time, t1 = state.time + h;
    for (const ForceTerm& f : model.forces)
        if (f.start <= t1 && f.end > t0) s.driven[f.body] = 1;
    for (size_t i = 0; i < model.jointed.size(); ++i) s.driven[i] |= model.jointed[i];
    if (s.still.size() != n || h != s.h) s.still.assign(n, 0);
    for (size_t i = 0; i < n; ++i) s.still[i] &= static_cast<std::uint8_t>(!s.driven[i]);
    s.h = h;
    s.start.resize(model.dynamicBodies.size());
    for (size_t k = 0; k < model.dynamicBodies.size(); ++k) s.start[k] = state.bodies[model.dynamicBodies[k]];
    s.started = true;
    s.changed.assign(n, 0);
}

void closeStillIslands(const Model& model, const collision::ManifoldList& contacts,
                       std::vector<std::uint8_t>& flags) {
    // A body that loses its flag can take a neighbour's with it, which may come earlier in
    // the list: again until a pass drops none (as deep as the largest island is wide).
    for (bool dropped = true; dropped;) {
        dropped = false;
        for (const collision::Manifold& m : contacts) {
            const BodyModel& A = model.bodies[m.bodyA];
            const BodyModel& B = model.bodies[m.bodyB];
            const bool stillA = A.motion == Motion::Dynamic ? flags[m.bodyA] != 0 : !moves(A);
            const bool stillB = B.motion == Motion::Dynamic ? flags[m.bodyB] != 0 : !moves(B);
            if (stillA == stillB) continue;
            if (A.motion == Motion::Dynamic && flags[m.bodyA]) flags[m.bodyA] = 0, dropped = true;
            if (B.motion == Motion::Dynamic && flags[m.bodyB]) flags[m.bodyB] = 0, dropped = true;
        }
    }
}

void endStillStep(const Model& model, const State& state, const collision::ManifoldList& contacts,
                  StillScratch& s) {
    if (!s.enabled || !s.started) return;
    s.still.assign(model.bodies.size(), 0);
    for (size_t k = 0; k < model.dynamicBodies.size(); ++k) {
        const int i = model.dynamicBodies[k];
        const BodyState& b = state.bodies[i];
        s.still[i] = !s.driven[i] && !s.changed[i] && !state.isAsleep(i) && b.P.isZero(0.0) &&
                     b.L.isZero(0.0) && same(b, s.start[k]);
    }
    closeStillIslands(model, contacts, s.still);
}

void forgetStill(StillScratch& s) {
    s.still.clear();
    s.start.clear();
    s.started = false;
}

}  // namespace tumble
