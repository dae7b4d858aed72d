// The simulation: a Model, a State and the step that advances one by the other.
#pragma once

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/state.h>

#include <functional>
#include <memory>

namespace tumble {

/// Wall-clock time spent in each stage, accumulated over steps (seconds).
struct Profile {
    double forces = 0.0;
    double integrate = 0.0;
    double broadphase = 0.0;
    double narrowphase = 0.0;
    double timeOfImpact = 0.0;
    long steps = 0;
    long forceEvaluations = 0;
    long pairs = 0;          ///< broadphase pairs, summed over steps
    long contactPoints = 0;  ///< narrowphase contact points, summed over steps
    long impacts = 0;        ///< pairs that came into contact within a step
};

class World {
public:
    /// Compiles the scene (throws SceneError) and sets the initial state.
    explicit World(const SceneDesc& scene);
    World(Model model, State state);

    const Model& model() const { return model_; }
    const State& state() const { return state_; }
    void setState(const State& state) { state_ = state; }
    void setTime(double t) { state_.time = t; }
    const Profile& profile() const { return profile_; }

    /// Advances the state by h seconds: forces -> integrate -> broadphase -> narrowphase ->
    /// time of impact. Throws SimulationError when a body's state becomes non-finite.
    void step(double h);

    /// The contact manifolds at the end of the last step (bodyA < bodyB).
    const std::vector<collision::Manifold>& contacts() const;
    /// The pairs that came into contact during the last step, with the time of first touch.
    const std::vector<collision::ImpactEvent>& impacts() const;

private:
    Model model_;
    State state_;
    Profile profile_;
    struct Scratch;
    std::shared_ptr<Scratch> scratch_;
};

/// Summary of a run.
struct RunResult {
    long steps = 0;
    int frames = 0;
};

/// Runs the model's duration, landing exactly on every frame time k / frame_rate
/// (k = 0 .. round(duration * frame_rate)) and on every force start and end time.
/// Within each such interval the steps are equal and no longer than settings.dt.
/// `onFrame` receives every frame, the first at t = 0.
RunResult simulate(World& world, const std::function<void(int frame, const State&)>& onFrame);

/// The number of recorded frames of a run: round(duration * frame_rate) + 1.
int frameCount(const Settings& settings);

}  // namespace tumble
