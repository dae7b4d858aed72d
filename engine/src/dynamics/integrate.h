// Stage: integrate. Advances every awake dynamic body and every kinematic body by one step with the
// model's integrator; static bodies are never touched. The integrators call the forces
// stage as often as they need (1, 2 or 4 times a step).
#pragma once

#include <tumble/forces.h>
#include <tumble/model.h>
#include <tumble/profile.h>

#include "common/pool_gate.h"

#include <vector>

namespace tumble {

class Workers;  // workers.h: only the .cpp files that hand work to the pool include it

struct IntegrateScratch {
    std::vector<Wrench> wrench;
    std::vector<BodyState> start, stage;
    struct Rate {
        Vec3 x, P, L;
        Eigen::Vector4d q;  // w, x, y, z
    };
    std::vector<Rate> rates[4];
    /// The dynamic bodies to advance (the awake ones); null: every dynamic body.
    const std::vector<int>* awake = nullptr;
    /// The world's worker threads for the drift of the splitting integrators; null: this thread.
    Workers* pool = nullptr;
    PoolGate drift;  // whether the bodies are worth the pool (workers.h)
};

void integrate(const Model& model, State& state, double h, IntegrateScratch& scratch, Profile& profile);

}  // namespace tumble
