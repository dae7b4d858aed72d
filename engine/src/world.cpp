// World::step, the orchestrator: one call per stage, each timed into the profile.
#include <tumble/world.h>

#include "guard.h"
#include "integrate.h"

#include <chrono>

namespace tumble {

struct World::Scratch {
    IntegrateScratch integrate;
};

World::World(const SceneDesc& scene) : World(compile(scene), State{}) {
    state_ = initialState(model_, scene);
}

World::World(Model model, State state)
    : model_(std::move(model)), state_(std::move(state)), scratch_(std::make_shared<Scratch>()) {}

void World::step(double h) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const double forcesBefore = profile_.forces;

    integrate(model_, state_, h, scratch_->integrate, profile_);  // calls the forces stage
    state_.time += h;
    checkFinite(model_, state_);

    const double total = std::chrono::duration<double>(Clock::now() - t0).count();
    profile_.integrate += total - (profile_.forces - forcesBefore);
    ++profile_.steps;
}

}  // namespace tumble
