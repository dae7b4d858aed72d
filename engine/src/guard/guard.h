// Stage: guard. Stops a run whose state stopped being finite, naming the body, the time and
// the likely cause (likely_cause.h). The energy guard (energy_guard.h) stops most runs
// that blow up earlier, while the state is still finite.
#pragma once

#include <tumble/model.h>

namespace tumble {

/// Throws SimulationError for the first moving body with a non-finite x, q, P or L.
void checkFinite(const Model& model, const State& state);

}  // namespace tumble
