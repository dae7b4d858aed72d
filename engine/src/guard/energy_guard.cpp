#include "guard/energy_guard.h"

#include "common/number_text.h"

#include "guard/likely_cause.h"

#include <tumble/errors.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace tumble {

namespace {

double radius(const BodyModel& b) {
    const double r = boundingRadius(b.collider);
    return std::isfinite(r) ? r : 0.0;
}

double springEnergy(const ForceTerm& f, const BodyState& s) {
    const double stretch = (s.x + s.q * f.arm - f.anchor).norm() - f.restLength;
    return 0.5 * f.stiffness * stretch * stretch;
}

// How fast the point a force or torque works through can move: |v + ω × r| ≤ |v| + |ω| |r|,
// with |ω| = |I⁻¹ L| ≤ |L| / I_min. Unlike ω itself, which swings as a body tumbles, L
// changes only with the torques, so its value at the two ends of an interval bounds it.
double workingSpeed(const Model& m, const State& state, const ForceTerm& f) {
    const BodyModel& b = m.bodies[f.body];
    const BodyState& s = state.bodies[f.body];
    const double iMin = b.principalMoments.minCoeff();
    const double spin = iMin > 0.0 ? s.L.norm() / iMin : 0.0;
    if (f.type == ForceType::Torque) return spin;
    return b.invMass * s.P.norm() + spin * f.arm.norm();
}

[[noreturn]] void fail(const Model& m, const State& state, const EnergyGuard& g, double total) {
    int worst = m.dynamicBodies.front();
    double gain = -std::numeric_limits<double>::infinity();
    for (int i : m.dynamicBodies) {
        const double d = g.bodyNow[i] - g.bodyStart[i];
        if (!(d <= gain)) {  // NaN counts as the most
            gain = d;
            worst = i;
        }
    }
    const BodyModel& b = m.bodies[worst];
    char when[64];
    std::snprintf(when, sizeof when, "%.9g", state.time);
    throw SimulationError(worst, b.name, state.time,
                          "body '" + b.name + "' (bodies[" + std::to_string(worst) +
                              "]) ran away at t = " + when + " s: its energy rose by " + numberText(gain, 3) +
                              " J, the scene's from " + numberText(g.start, 3) + " J to " +
                              numberText(total, 3) + " J, far beyond what its forces can put in (" +
                              numberText(g.input, 3) + " J); likely cause: " + likelyCause(m, state, worst));
}

// The turn per step past which an integrator no longer follows a free spin. Measured on a
// box (half extents 0.5, 0.2, 0.1) spun about its major axis with a slight wobble, 10 s at
// 1/60 s: RK4 kept the energy to 1.7e-5 up to 1.6 rad a step and turned the box over to
// its minor axis at 1.8 (kinetic energy x5.8, L unchanged); Euler and symplectic Euler
// lost 0.15 % at 0.05 rad a step and turned it over from 0.2. Their limit, 0.5, stops what
// goes wrong within a second or two and leaves slower spins to the user (a teaching scene
// shows Euler's drift). The splittings sub-step a fast spin themselves: no limit.
double turnLimit(Integrator id) {
    switch (id) {
        case Integrator::Euler:
        case Integrator::SymplecticEuler: return 0.5;
        case Integrator::Rk4: return 1.5;
        case Integrator::Splitting:
        case Integrator::Splitting4: break;
    }
    return std::numeric_limits<double>::infinity();
}

// Stops the run, naming the body, when a body spins faster than the integrator follows at
// the scene's step (turnLimit): the motion would be wrong (a flip to another axis) long
// before the energy ran away.
void checkSpin(const Model& m, const State& state) {
    const double limit = turnLimit(m.integrator->id);
    if (!std::isfinite(limit)) return;
    const double dt = m.settings.dt;
    for (int i : m.dynamicBodies) {
        if (state.isAsleep(i)) continue;
        // Three equal moments (a ball, a cube): ω stays along L, there is no other axis to
        // turn over to, and a rolling ball at 1/30 s with Euler is a fair scene.
        const Vec3& I = m.bodies[i].principalMoments;
        if (I.maxCoeff() - I.minCoeff() <= 1e-12 * I.maxCoeff()) continue;
        const double omega = derive(m.bodies[i], state.bodies[i]).omega.norm();
        if (!(omega * dt > limit)) continue;
        const BodyModel& b = m.bodies[i];
        char when[64];
        std::snprintf(when, sizeof when, "%.9g", state.time);
        throw SimulationError(i, b.name, state.time,
                              "body '" + b.name + "' (bodies[" + std::to_string(i) + "]) spins at " +
                                  numberText(omega, 3) + " rad/s at t = " + when + " s, " +
                                  numberText(omega * dt, 3) + " rad per step: more than " +
                                  m.integrator->name + " follows (" + numberText(limit, 3) +
                                  " rad a step; past it a spinning body turns over to another axis); use "
                                  "splitting, which sub-steps a fast spin, or dt <= " +
                                  numberText(limit / omega, 3) + " s");
    }
}

}  // namespace

double bodyEnergies(const Model& m, const State& state, std::vector<double>& out) {
    out.assign(m.bodies.size(), 0.0);
    double total = 0.0;
    for (int i : m.dynamicBodies) {
        const BodyModel& b = m.bodies[i];
        const BodyState& s = state.bodies[i];
        const Derived d = derive(b, s);
        out[i] = 0.5 * (s.P.dot(d.v) + s.L.dot(d.omega)) - b.mass * m.settings.gravity.dot(s.x);
    }
    for (const ForceTerm& f : m.forces) {
        if (f.type == ForceType::Spring && f.activeAt(state.time))
            out[f.body] += springEnergy(f, state.bodies[f.body]);
    }
    for (int i : m.dynamicBodies) total += out[i];
    return total;
}

void armEnergyGuard(const Model& m, const State& state, EnergyGuard& g) {
    g.armed = false;
    if (!m.settings.energyGuard || m.dynamicBodies.empty() || state.bodies.size() != m.bodies.size()) return;
    g.armed = true;
    g.steps = 0;
    g.lastTime = state.time;
    g.input = 0.0;
    g.worst = 0.0;
    g.start = bodyEnergies(m, state, g.bodyStart);

    // The scale: kinetic and spring energy at the start, each body lifted by its size and
    // moving its size per second, the energy of each spring's sag under gravity.
    const double gravity = m.settings.gravity.norm();
    g.kinematicSpeed = 0.0;
    for (int k : m.kinematicBodies) {
        const BodyModel& b = m.bodies[k];
        g.kinematicSpeed = std::max(g.kinematicSpeed, b.topSpeed(radius(b)));
    }
    g.scale = 0.0;
    for (int i : m.dynamicBodies) {
        const BodyModel& b = m.bodies[i];
        const BodyState& s = state.bodies[i];
        const Derived d = derive(b, s);
        const double r = radius(b);
        const double push = 2.0 * g.kinematicSpeed;  // what a kinematic body can throw it at
        g.scale +=
            0.5 * (s.P.dot(d.v) + s.L.dot(d.omega)) + b.mass * (gravity * r + 0.5 * (r * r + push * push));
    }
    g.speed.assign(m.forces.size(), 0.0);
    g.springOn.assign(m.forces.size(), 0);
    for (std::size_t n = 0; n < m.forces.size(); ++n) {
        const ForceTerm& f = m.forces[n];
        if (f.type == ForceType::Spring) {
            const double weight = m.bodies[f.body].mass * gravity;
            if (f.stiffness > 0.0) g.scale += weight * weight / f.stiffness;
            g.springOn[n] = f.activeAt(state.time);
            if (g.springOn[n]) g.scale += springEnergy(f, state.bodies[f.body]);
        } else {
            g.speed[n] = workingSpeed(m, state, f);
        }
    }
}

void guardEnergy(const Model& m, const State& state, EnergyGuard& g) {
    if (!g.armed || ++g.steps < kEnergyGuardEvery) return;
    g.steps = 0;
    checkEnergy(m, state, g);
}

void checkEnergy(const Model& m, const State& state, EnergyGuard& g) {
    if (!g.armed) return;
    const double last = g.lastTime;
    const double h = state.time - last;
    g.lastTime = state.time;

    // What could have been put in since the last check: applied forces and torques at the
    // faster of the two ends, springs switched on, kinematic bodies lifting what they carry.
    for (std::size_t n = 0; n < m.forces.size(); ++n) {
        const ForceTerm& f = m.forces[n];
        if (f.type == ForceType::Spring) {
            const bool on = f.activeAt(state.time);
            if (on && !g.springOn[n]) g.input += springEnergy(f, state.bodies[f.body]);
            g.springOn[n] = on;
            continue;
        }
        const double s = workingSpeed(m, state, f);
        if (f.start < state.time && f.end > last) g.input += f.vector.norm() * std::max(s, g.speed[n]) * h;
        g.speed[n] = s;
    }
    if (g.kinematicSpeed > 0.0) {
        for (int i : m.dynamicBodies)
            g.input += m.bodies[i].mass * m.settings.gravity.norm() * g.kinematicSpeed * h;
    }

    const double total = bodyEnergies(m, state, g.bodyNow);
    const double ratio = (total - g.start) / (g.scale + g.input);
    g.worst = std::max(g.worst, ratio);
    if (!(ratio <= kEnergyGuardFactor)) fail(m, state, g, total);
    checkSpin(m, state);
}

}  // namespace tumble
