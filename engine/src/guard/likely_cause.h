// Why a run blew up: the guards (guard.h, energy_guard.h) name the body and the time, and
// this names the likely cause, from what the model says and the integrator's stability
// limits, so that the message says what to change.
#pragma once

#include <tumble/model.h>

#include <string>

namespace tumble {

/// Largest ω·dt at which the integrator stays stable on an undamped harmonic oscillator
/// (0 for explicit Euler: it gains energy at any step).
double oscillatorLimit(Integrator id);

/// One sentence, starting lower case, with the likely cause of body `body` blowing up and
/// what to change, e.g. "dt = 0.01 s is too large for spring forces[0] of body 'bob'
/// (k = 1e+05 N/m, m = 1 kg: needs dt < 0.0089 s with rk4)". Checked in this order: a spring
/// or damping too stiff for the step with this integrator (on the body first, then on any
/// body), a kinematic body moving far in one step, a fast spin, else the contact solver.
/// `state` may be non-finite for `body`.
std::string likelyCause(const Model& model, const State& state, int body);

}  // namespace tumble
