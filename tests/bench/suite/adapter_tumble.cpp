// Tumble's adapter: the scene as it is, the mode is the integrator's name, one World::step
// per step. A mode may end in "+end-of-step" (kEndOfStep): impacts resolved at the end of the
// step (settings.impacts), as the speed part runs the contact scenes a second time.
#include "adapter_tumble.h"

#include <tumble/errors.h>
#include <tumble/integrators.h>
#include <tumble/model.h>

namespace tumble::bench {

std::vector<std::string> TumbleAdapter::modes() const {
    std::vector<std::string> names;
    for (const IntegratorInfo& info : integrators()) names.emplace_back(info.name);
    return names;
}

bool TumbleAdapter::load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) {
    std::string integrator = mode;
    const bool endOfStep = integrator.ends_with(kEndOfStep);
    if (endOfStep) integrator.resize(integrator.size() - std::string_view(kEndOfStep).size());
    if (!findIntegrator(integrator)) {
        if (why) *why = "no integrator named " + integrator;
        return false;
    }
    SceneDesc s = scene;
    s.settings.dt = dt;
    s.settings.integrator = integrator;
    if (endOfStep) s.settings.impacts = ImpactTiming::EndOfStep;
    try {
        world_.emplace(s);
    } catch (const std::exception& e) {
        if (why) *why = e.what();
        return false;
    }
    dt_ = dt;
    return true;
}

BodySample TumbleAdapter::body(int i) const {
    const BodyModel& m = world_->model().bodies[i];
    const BodyState& s = world_->state().bodies[i];
    const Derived d = derive(m, s);
    return {s.x, s.q, d.v, d.omega};
}

int TumbleAdapter::contactCount() const {
    int n = 0;
    for (const collision::Manifold& m : world_->contacts()) n += m.count;
    return n;
}

std::unique_ptr<EngineAdapter> makeTumbleAdapter() {
    return std::make_unique<TumbleAdapter>();
}

}  // namespace tumble::bench
