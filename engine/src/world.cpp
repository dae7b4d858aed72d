// World::step, the orchestrator: one call per stage, each timed into the profile.
#include <tumble/world.h>

#include "detect.h"
#include "guard.h"
#include "integrate.h"

#include <chrono>

namespace tumble {

struct World::Scratch {
    IntegrateScratch integrate;
    DetectScratch detect;
    State before;
};

World::World(const SceneDesc& scene) : World(compile(scene), State{}) {
    state_ = initialState(model_, scene);
}

World::World(Model model, State state)
    : model_(std::move(model)), state_(std::move(state)), scratch_(std::make_shared<Scratch>()) {}

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

void World::step(double h) {
    const bool contacts = needsContacts(model_);
    DetectScratch& d = scratch_->detect;
    if (contacts) scratch_->before = state_;

    auto t = Clock::now();
    const double forcesBefore = profile_.forces;
    integrate(model_, state_, h, scratch_->integrate, profile_);  // calls the forces stage
    state_.time += h;
    checkFinite(model_, state_);
    profile_.integrate += since(t) - (profile_.forces - forcesBefore);
    ++profile_.steps;
    if (!contacts) return;  // nothing can touch: the contact stages are skipped

    t = Clock::now();
    bodyPoses(model_, scratch_->before, d.start);
    bodyPoses(model_, state_, d.end);
    findPairs(model_, d);
    profile_.broadphase += since(t);
    profile_.pairs += static_cast<long>(d.broadphase.pairs().size());

    t = Clock::now();
    std::swap(d.previous, d.contacts);
    findContacts(model_, d, 0.0);
    profile_.narrowphase += since(t);
    for (const auto& m : d.contacts) profile_.contactPoints += m.count;

    t = Clock::now();
    findImpacts(model_, scratch_->before, state_, state_.time - h, h, d);
    profile_.timeOfImpact += since(t);
    profile_.impacts += static_cast<long>(d.impacts.size());
}

const std::vector<collision::Manifold>& World::contacts() const { return scratch_->detect.contacts; }

const std::vector<collision::ImpactEvent>& World::impacts() const { return scratch_->detect.impacts; }

}  // namespace tumble
