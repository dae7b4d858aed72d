#include "guard/guard.h"

#include "guard/likely_cause.h"

#include <tumble/errors.h>

#include <cstdio>

namespace tumble {

namespace {

bool finite(const BodyState& s) {
    return s.x.allFinite() && s.q.coeffs().allFinite() && s.P.allFinite() && s.L.allFinite();
}

void fail(const Model& model, const State& state, int i) {
    const double time = state.time;
    char when[64];
    std::snprintf(when, sizeof when, "%.9g", time);
    throw SimulationError(i, model.bodies[i].name, time,
                          "body '" + model.bodies[i].name + "' (bodies[" + std::to_string(i) +
                              "]) became non-finite at t = " + when +
                              " s; likely cause: " + likelyCause(model, state, i));
}

}  // namespace

void checkFinite(const Model& model, const State& state) {
    for (int i : model.dynamicBodies) {
        if (!finite(state.bodies[i])) fail(model, state, i);
    }
    for (int i : model.kinematicBodies) {
        if (!finite(state.bodies[i])) fail(model, state, i);
    }
}

}  // namespace tumble
