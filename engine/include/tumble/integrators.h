// The integrators, picked by name (settings.integrator, --integrator).
#pragma once

#include <span>
#include <string_view>

namespace tumble {

enum class Integrator { Euler, SymplecticEuler, Rk4, Splitting, Splitting4 };

struct IntegratorInfo {
    Integrator id;
    const char* name;
    int order;                ///< global order of accuracy, measured in tests/engine
    int forceEvaluations;     ///< per step
    const char* description;
};

/// Every integrator, the default first.
std::span<const IntegratorInfo> integrators();

/// The integrator used when a scene names none.
const IntegratorInfo& defaultIntegrator();

/// The integrator of that name, or nullptr.
const IntegratorInfo* findIntegrator(std::string_view name);

}  // namespace tumble
