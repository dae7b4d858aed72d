// Tumble behind the benchmark's engine interface. The benchmark reaches the World through
// it for what only Tumble gives (the profile per stage, the broadphase pairs).
#pragma once

#include "engine_adapter.h"

#include <tumble/world.h>

#include <optional>

namespace tumble::bench {

/// A mode is an integrator's name with options after it, each behind a '+':
/// "+end-of-step" resolves impacts at the end of the step (settings.impacts), "+N-threads"
/// steps on N threads (World::setThreads).
inline constexpr const char* kEndOfStep = "+end-of-step";
inline constexpr const char* kTwoThreads = "+2-threads";

class TumbleAdapter : public EngineAdapter {
public:
    std::string name() const override { return "tumble"; }
    /// Tumble's integrators by name (tumble/integrators.h), the default first.
    std::vector<std::string> modes() const override;
    bool load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) override;
    void step() override { world_->step(dt_); }
    double time() const override { return world_->state().time; }
    int bodyCount() const override { return static_cast<int>(world_->state().bodies.size()); }
    BodySample body(int i) const override;
    int contactCount() const override;

    World& world() { return *world_; }
    const World& world() const { return *world_; }

private:
    std::optional<World> world_;
    double dt_ = 0.0;
    int threads_ = 1;
};

}  // namespace tumble::bench
