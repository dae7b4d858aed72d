#include <tumble/integrators.h>

#include <array>

namespace tumble {

namespace {

// The default comes first. Orders are the ones measured by tests/engine/tst_integrators.
constexpr std::array<IntegratorInfo, 5> kIntegrators{{
    {Integrator::Splitting, "splitting", 2, 2,
     "symplectic splitting: velocity Verlet for translation, exact rotations about the "
     "principal axes for rotation; keeps |L| exactly and a free body's energy to rounding "
     "at any spin"},
    {Integrator::Splitting4, "splitting-4", 2, 2,
     "splitting with a fourth-order free rotation (three composed splittings): a tumbling "
     "body's orientation 20-100x closer at the same step, its rotation three times the work; "
     "a mechanism alone (joints, nothing that touches, no limit, motor or rope) is stepped "
     "at fourth order, other scenes' joints and contacts at second (a note says so)"},
    {Integrator::Rk4, "rk4", 4, 4, "classical fourth-order Runge-Kutta on (x, q, P, L)"},
    {Integrator::SymplecticEuler, "symplectic-euler", 1, 1,
     "semi-implicit Euler: momenta first, then pose with the new velocities"},
    {Integrator::Euler, "euler", 1, 1, "explicit Euler on (x, q, P, L), the paper's simplest"},
}};

}  // namespace

std::span<const IntegratorInfo> integrators() {
    return kIntegrators;
}

const IntegratorInfo& defaultIntegrator() {
    return kIntegrators[0];
}

const IntegratorInfo* findIntegrator(std::string_view name) {
    for (const IntegratorInfo& info : kIntegrators) {
        if (name == info.name) return &info;
    }
    return nullptr;
}

}  // namespace tumble
