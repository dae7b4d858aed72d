#include "guard.h"

#include <tumble/errors.h>

#include <cstdio>

namespace tumble {

namespace {

bool finite(const BodyState& s) {
    return s.x.allFinite() && s.q.coeffs().allFinite() && s.P.allFinite() && s.L.allFinite();
}

void fail(const Model& model, int i, double time) {
    char when[64];
    std::snprintf(when, sizeof when, "%.9g", time);
    throw SimulationError(i, model.bodies[i].name, time,
                          "body '" + model.bodies[i].name + "' (bodies[" + std::to_string(i) +
                              "]) became non-finite at t = " + when +
                              " s; a step too large for the forces acting on it is the usual cause");
}

}  // namespace

void checkFinite(const Model& model, const State& state) {
    for (int i : model.dynamicBodies) {
        if (!finite(state.bodies[i])) fail(model, i, state.time);
    }
    for (int i : model.kinematicBodies) {
        if (!finite(state.bodies[i])) fail(model, i, state.time);
    }
}

}  // namespace tumble
