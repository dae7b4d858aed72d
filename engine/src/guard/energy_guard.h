// Stage: guard (energy). Stops a run whose mechanical energy runs away, long before the
// state overflows, naming the body that gained most, the time and the likely cause.
//
// Without driving forces the energy of a scene (kinetic + gravity + springs) never rises:
// contacts, friction and damping take energy out, position correction only lifts a body
// out of an overlap. What can legitimately put energy in is bounded: the work of applied
// forces and torques (at most |F| |v_point| per second), springs switched on later, and
// kinematic bodies pushing. A run is stopped when the energy rises above its start by
// more than kEnergyGuardFactor times (that bound + a scale of the scene: its starting kinetic and
// spring energy, m |g| size per body, the sag of each spring under gravity). An unstable
// step makes the energy grow geometrically, so a large factor still stops it within a
// few dozen steps, while no correct scene comes near it.
//
// The same check stops a run whose integrator cannot follow a body's spin at the step
// (Euler and symplectic Euler past 0.5 rad a step, RK4 past 1.5): such a body turns over to
// another axis, its kinetic energy up to 5.8 times, long before anything runs away.
//
// Cheap: one O(bodies + forces) pass every kEnergyGuardEvery steps, nothing per step.
#pragma once

#include <tumble/model.h>

#include <cstdint>
#include <vector>

namespace tumble {

/// A run stops when its energy rises above the start by more than this times (input bound + scale).
constexpr double kEnergyGuardFactor = 1000.0;
/// Steps between two checks.
constexpr int kEnergyGuardEvery = 8;

struct EnergyGuard {
    bool armed = false;
    int steps = 0;                       // since the last check
    double lastTime = 0.0;               // of the last check
    double start = 0.0;                  // total energy at the start (J)
    double scale = 0.0;                  // J, see above
    double input = 0.0;                  // bound of the work put in since the start (J)
    double kinematicSpeed = 0.0;         // fastest point of a moving kinematic body (m/s)
    double worst = 0.0;                  // largest rise / (scale + input) seen at a check
    std::vector<double> bodyStart;       // energy per body at the start
    std::vector<double> bodyNow;         // scratch
    std::vector<double> speed;           // per force: |v_point| (or |ω| for a torque) at the last check
    std::vector<std::uint8_t> springOn;  // per force: a spring active at the last check
};

/// Starts watching from `state` (a run starts there); does nothing when
/// settings.energyGuard is off or the state does not match the model.
void armEnergyGuard(const Model& model, const State& state, EnergyGuard& guard);

/// Called after every step; every kEnergyGuardEvery steps, checks (checkEnergy).
void guardEnergy(const Model& model, const State& state, EnergyGuard& guard);

/// Adds what could have been put in since the last check, and throws SimulationError when
/// the energy has run away or a body spins faster than the integrator follows.
void checkEnergy(const Model& model, const State& state, EnergyGuard& guard);

/// Energy per body (kinetic + gravity, and the springs acting on it) into `out`; their sum.
double bodyEnergies(const Model& model, const State& state, std::vector<double>& out);

}  // namespace tumble
