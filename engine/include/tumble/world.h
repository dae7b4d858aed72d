// The simulation: a Model, a State and the step that advances one by the other.
#pragma once

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/profile.h>
#include <tumble/state.h>

#include <functional>
#include <memory>

namespace tumble {

class World {
public:
    /// Compiles the scene (throws SceneError) and sets the initial state.
    explicit World(const SceneDesc& scene);
    World(Model model, State state);

    const Model& model() const { return model_; }
    const State& state() const { return state_; }
    /// Replaces the state (a frame of the timeline, an edit); the contacts found so far are
    /// forgotten, the remembered impulses, touching pairs and sleep data come with `state`,
    /// so stepping on from a recorded state repeats the recorded run exactly.
    void setState(const State& state);
    void setTime(double t) { state_.time = t; }
    /// The stage profile so far, its times in seconds.
    Profile profile() const;
    const EnergyLedger& ledger() const { return ledger_; }

    /// Advances the state by h seconds: forces -> integrate -> broadphase -> narrowphase ->
    /// time of impact (cutting the step at each first touch for the impact impulses) ->
    /// contact solver -> sleeping. Throws SimulationError, naming the body, the time and the
    /// likely cause, when a body's state becomes non-finite or (settings.energyGuard) the
    /// scene's energy runs away. A step after which a joint is left open (its projection did
    /// not converge: a whipping chain at 1/30 s) is taken again as two steps of h/2, and
    /// each of those likewise once more (at most four pieces). A mechanism alone (joints
    /// without limits, motors or breaking, no damping, no two bodies that can touch) with
    /// the splitting-4 integrator takes three such steps, of h/(2 - 2^(1/3)), a negative
    /// middle one and the first again: a fourth-order step (docs/architecture.md "Joints").
    /// A force that switches on or off inside the step cuts it there, so that it acts for
    /// exactly its interval whatever the step; one within a billionth of the step of its
    /// start is taken as switching at the start (a time summed from steps of 1/30 s reads
    /// 0.9999999999999999 where the force starts at 1).
    void step(double h);

    /// Worker threads for the stages whose items are independent (narrow phase and time of
    /// impact over pairs, the splitting integrators' drift over bodies), the calling thread
    /// included; 1 (the default) runs everything on the calling thread. The result is the
    /// same bit for bit for any number. n < 1 throws std::invalid_argument.
    void setThreads(int n);
    int threads() const;

    /// Islands that the last step left exactly as it found them, at rest, are not solved
    /// again while nothing reaches them: their answer is known (still_islands.h). On by
    /// default; off, every island is solved every step, with the same state bit for bit
    /// (for checking that).
    void skipStillIslands(bool on);

    /// The contact manifolds at the end of the last step (bodyA < bodyB).
    const collision::ManifoldList& contacts() const;
    /// The deepest overlap of two bodies as they stand now (m, 0 when none overlap), over
    /// the pairs of contacts(): what a recorded frame shows. (The manifolds' own depths are
    /// those found at the end of the free step, before the contact solver placed the bodies:
    /// a box resting on the ground overlaps it there by g h² / 2.)
    double deepestOverlap() const;
    /// The pairs that came into contact during the last step, with the time of first touch.
    const std::vector<collision::ImpactEvent>& impacts() const;

private:
    void stepPiece(double h);                // step() between two force switch times
    void stepWhole(double h);                // one step of h, as step() describes
    // stepWhole, in halves while the joints stay open or (`weigh`) gave energy
    void stepJointed(double h, int splits, bool weigh = true);
    void stepComposed(double h, int splits = 0);  // a fourth-order composition of stepJointed
    double jointedKinetic() const;                // of the jointed bodies
    bool splitFor(double h, int splits, bool composed, double gained, double kinetic, bool held,
                  bool allHeld);             // (stepJointed)
    void prepareJointedSteps();              // (the constructor: what those need of the model)
    void advance(double h);            // integrate the awake bodies by h
    void detect(double t0, double h, bool onlyUnsafe);  // broadphase, narrowphase, time of impact, waking
    void impactsAtStart();             // touching bodies that approach as a run starts
    void settle();                     // overlap beyond the margin left by the solve
    void impactAt(double t0);          // cut the step at the first impact and resolve it
    void forgetSearches();             // the searches for impacts kept within a step
    void finishStep(const State& before, const collision::ManifoldList& contacts);
    void park();                       // the islands without an impact keep their free step
    bool leaveParked();
    void dropParked();
    void unpark(bool unwind);
    bool startGroups();             // several islands with an impact: each cut on its own
    bool nextGroup();
    void setUpGroup(int g);
    void endGroups(bool unwind);
    void saveStepStart();
    void restoreStepStart();
    bool parkedOrStill(int body) const;
    void forgetSleepUnlessSleeping();

    Model model_;
    State state_;
    Profile profile_;
    EnergyLedger ledger_;
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

/// Advances the world from frame `frame - 1` (the world is at that frame's time) to frame
/// `frame`, with exactly the steps simulate() takes there; returns the number of steps.
/// Re-simulating from a recorded frame with it gives the recorded frames bit for bit.
long advanceFrame(World& world, int frame);

}  // namespace tumble
