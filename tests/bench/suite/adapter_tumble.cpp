// Tumble's adapter: the scene as it is, the mode is the integrator's name, one World::step
// per step. A mode may carry options (adapter_tumble.h): "+end-of-step", impacts resolved at
// the end of the step (settings.impacts), as the speed part runs the contact scenes a second
// time; "+2-threads", the same on two threads (World::setThreads), the third time;
// "+solve-all", every island solved every step (World::skipStillIslands(false)), to measure
// what taking the still islands' answer as known saves.
#include "adapter_tumble.h"

#include <tumble/errors.h>
#include <tumble/integrators.h>
#include <tumble/model.h>

#include <cctype>

namespace tumble::bench {

std::vector<std::string> TumbleAdapter::modes() const {
    std::vector<std::string> names;
    for (const IntegratorInfo& info : integrators()) names.emplace_back(info.name);
    return names;
}

bool TumbleAdapter::load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) {
    // The integrator, then the options (adapter_tumble.h).
    std::vector<std::string> parts;
    for (size_t start = 0;;) {
        const size_t plus = mode.find('+', start);
        parts.push_back(mode.substr(start, plus - start));
        if (plus == std::string::npos) break;
        start = plus + 1;
    }
    // The scene is compiled as it is and the run's settings set on the model after: a copy
    // of the scene to change them held a second SceneDesc at loading, half a megabyte of a
    // 910-body scene's peak memory that no peer's adapter has.
    Settings settings = scene.settings;
    settings.dt = dt;
    settings.integrator = parts[0];
    int threads = 1;
    bool solveAll = false;
    for (size_t k = 1; k < parts.size(); ++k) {
        const std::string& p = parts[k];
        if ("+" + p == kEndOfStep) {
            settings.impacts = ImpactTiming::EndOfStep;
        } else if (p == "solve-all") {
            solveAll = true;
        } else if (p.ends_with("-threads") && std::isdigit(static_cast<unsigned char>(p[0]))) {
            threads = std::stoi(p);
        } else {
            if (why) *why = "unknown option +" + p + " in mode " + mode;
            return false;
        }
    }
    const IntegratorInfo* integrator = findIntegrator(parts[0]);
    if (!integrator) {
        if (why) *why = "no integrator named " + parts[0];
        return false;
    }
    try {
        Model model = compile(scene);
        model.settings = settings;
        model.integrator = integrator;
        State state = initialState(model, scene);
        world_.emplace(std::move(model), std::move(state));
        world_->setThreads(threads);
        if (solveAll) world_->skipStillIslands(false);
    } catch (const std::exception& e) {
        if (why) *why = e.what();
        return false;
    }
    dt_ = dt;
    threads_ = threads;
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
