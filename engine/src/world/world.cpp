// World::step, the orchestrator: one call per stage, each timed into the profile.
//
// A step integrates every awake body to the end of the step and finds the contacts there.
// If a pair that did not touch at the start came into contact within the step, the step
// is cut at the first such moment: the bodies are integrated again from the start to that
// moment, the impulses of the impact are applied there (impact.h), and the rest of the
// step is taken the same way (at most kMaxCuts times a step; later impacts are left to
// the contact solver, but for those whose end of the step would be wrong, as end-of-step
// mode finds them: a body through a thin one or past its middle, cut up to
// kMaxUnsafeCuts). The step ends with the contact solver (contact_solver.h), the overlap it
// left beyond the margin pushed out (settle_overlap.h; exact impacts only), and sleeping.
// With settings.impacts = end-of-step, only pairs whose end of the step can be wrong cut
// it (a fast body through a thin one, or past its middle: findImpacts); the others'
// impacts are resolved at the end.
//
// Only the islands with an impact are cut (islands.h): the others are "parked" at the end
// of their free step, flagged asleep so that no stage moves or pairs them, and their
// contacts are solved over the whole step at the end. Should a cut island's new path meet a
// parked body after all, the step is taken again from its start with every body cut.
#include <tumble/contact_query.h>
#include <tumble/world.h>

#include "solver/joint_general.h"
#include "world/world_scratch.h"

#include "common/stage_clock.h"
#include "guard/guard.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace tumble {

namespace {

constexpr int kMaxCuts = 8;         // moments of impact handled exactly per step
constexpr int kMaxUnsafeCuts = 64;  // ... and then those whose end of the step would be wrong (see below)
constexpr double kImpactTolerance = 1e-6;  // of the smaller body's size: how near "touching" is

// The stages are timed in ticks of stage_clock (profile() turns them into seconds).
double since(std::uint64_t t) {
    return stage_clock::since(t);
}

// The same bits in every field (not memcmp of the whole: the quaternion's alignment leaves
// padding bytes in BodyState, whose contents are whatever the memory held).
bool sameBits(const BodyState& a, const BodyState& b) {
    auto same = [](const double* x, const double* y, size_t n) { return std::memcmp(x, y, n * sizeof(double)) == 0; };
    return same(a.x.data(), b.x.data(), 3) && same(a.q.coeffs().data(), b.q.coeffs().data(), 4) &&
           same(a.P.data(), b.P.data(), 3) && same(a.L.data(), b.L.data(), 3);
}

// Back-to-back stages timed with one clock reading between them.
struct Lap {
    std::uint64_t t = stage_clock::now();
    double next() {
        const std::uint64_t now = stage_clock::now();
        const double d = static_cast<double>(now - t);
        t = now;
        return d;
    }
};

// Contacts approaching slower than this are resting, not bouncing: twice what gravity adds
// in the step being taken (h, not settings.dt: a caller may step shorter or longer), so a
// body resting under gravity never bounces on its support.
double restingSpeed(const Model& model, double h) {
    return 2.0 * model.settings.gravity.norm() * h;
}

ContactSolverSettings solverSettings(const Model& model, double resting, double touchTolerance, double margin,
                                     double h) {
    ContactSolverSettings cfg;
    cfg.iterations = model.settings.solverIterations;
    cfg.h = h;
    cfg.restingSpeed = resting;
    cfg.touchTolerance = touchTolerance;
    cfg.margin = margin;
    // Blocks whose updates change the velocities by rounding alone are left alone (a resting
    // pile's blocks hover in their last bits for all twenty passes): far below any speed a
    // contact tells apart, and zero without gravity, where the passes run to the exact fixed
    // point.
    cfg.quietSpeed = 1e-10 * resting;
    return cfg;
}

// How far apart contact points are still found: what gravity closes in a step, on top of
// the touch tolerance. A resting contact that opens by a few micrometres (a box rocking,
// a correction) keeps its points and their remembered impulses: without them the box on
// top lost its contact for a step while the ones below still pushed with its weight, and
// the warm start kicked the box between them to 1.2 m/s (pyramid-15 at 1/30 s under a
// ball). Points apart are harmless to the solver: their target lets the gap close, no more.
double contactMargin(const Model& model, double touchTolerance, double h) {
    return touchTolerance + model.settings.gravity.norm() * h * h;
}

}  // namespace

World::World(const SceneDesc& scene) : World(compile(scene), State{}) {
    state_ = initialState(model_, scene);
    armEnergyGuard(model_, state_, scratch_->energy);
}

World::World(Model model, State state)
    : model_(std::move(model)), state_(std::move(state)), scratch_(std::make_shared<Scratch>()) {
    for (const BodyModel& b : model_.bodies) {
        scratch_->sizes.push_back(boundingRadius(b.collider));
        scratch_->thickness.push_back(collision::thickness(b.collider));
    }
    scratch_->touchTolerance = touchTolerance(model_);  // (contact_query.h)
    scratch_->contacts =
        needsContacts(model_) || !model_.joints.empty();  // joints are solved with the contacts
    prepareJointedSteps();
    if (scratch_->contacts) {
        // The contact stages' per-body arrays, at loading rather than in the first step.
        sizeContactSolver(model_, scratch_->solver);
        sizeImpacts(model_, scratch_->impact);
    }
    forgetSleepUnlessSleeping();
    armEnergyGuard(model_, state_, scratch_->energy);
}

void World::setThreads(int n) {
    if (n < 1) throw std::invalid_argument("threads must be at least 1, not " + std::to_string(n));
    Scratch& s = *scratch_;
    if (n == threads()) return;
    s.workers = n > 1 ? std::make_unique<Workers>(n) : nullptr;
    s.detect.pool = s.workers.get();
    s.integrate.pool = s.workers.get();
    s.sleep.pool = s.workers.get();
    s.solver.pool = s.workers.get();
}

void World::skipStillIslands(bool on) {
    scratch_->still.enabled = on;
    forgetStill(scratch_->still);
}

int World::threads() const {
    return scratch_->workers ? scratch_->workers->threads() : 1;
}

// With sleeping off every body is simulated: sleep flags brought in by a state are dropped.
void World::forgetSleepUnlessSleeping() {
    if (model_.settings.sleeping) return;
    // Pairs of sleeping bodies were never tested, so they are missing from `touching`.
    if (std::find(state_.asleep.begin(), state_.asleep.end(), 1) != state_.asleep.end())
        state_.touchingKnown = false;
    state_.asleep.clear();
    state_.restTime.clear();
}

void World::setState(const State& state) {
    state_ = state;
    scratch_->detect.contacts.clear();
    scratch_->detect.lastPairs.keys.clear();  // nothing is taken from before the new state
    // Static bodies may stand elsewhere in this state: their poses and boxes again.
    scratch_->detect.start.clear();
    scratch_->detect.jointPairsBroken = -1;  // its joints may have broken, or not yet
    scratch_->detect.end.clear();
    scratch_->detect.swept.clear();
    forgetStill(scratch_->still);  // found in another run
    forgetSleepUnlessSleeping();
    armEnergyGuard(model_, state_, scratch_->energy);  // a run from this state
}

void World::advance(double h) {
    Scratch& s = *scratch_;
    if (!state_.asleep.empty()) {  // sleeping bodies, or parked ones
        awakeBodies(model_, state_, s.awake);
        s.integrate.awake = &s.awake;
    } else {
        s.integrate.awake = nullptr;
    }
    const auto t = stage_clock::now();
    const double forcesBefore = profile_.forces;
    integrate(model_, state_, h, s.integrate, profile_);  // calls the forces stage
    state_.time += h;
    checkFinite(model_, state_);
    profile_.integrate += since(t) - (profile_.forces - forcesBefore);
    profile_.awakeBodySteps +=
        static_cast<long>(s.integrate.awake ? s.awake.size() : model_.dynamicBodies.size());
}

void World::detect(double t0, double h, bool onlyUnsafe) {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    Lap lap;
    bodyPoses(model_, s.before, d.start, d.pool, &d.startGate);
    bodyPoses(model_, state_, d.end, d.pool, &d.endGate);
    findPairs(model_, state_, s.margin, d);
    profile_.pairs += static_cast<long>(d.broadphase.pairs().size());
    profile_.broadphase += lap.next();

    findContacts(model_, d, s.margin);
    profile_.narrowphase += lap.next();

    findImpacts(model_, s.before, state_, t0, h, kImpactTolerance, s.resting, s.sizes,
                model_.settings.impacts == ImpactTiming::EndOfStep || onlyUnsafe ? &s.thickness : nullptr, d);
    profile_.timeOfImpact += lap.next();

    // An awake body touching a sleeping one wakes it, and the contacts are found again
    // with the woken bodies among the moving ones.
    if (model_.settings.sleeping && wakeTouched(model_, state_, d.contacts, d.impacts, s.parked)) {
        const auto t = stage_clock::now();
        findPairs(model_, state_, s.margin, d);
        findContacts(model_, d, s.margin);
        profile_.narrowphase += since(t);
    }
}

// Cuts the step at the first impact: back to the start of the sub-step, forward to the
// moment, impulses there.
void World::impactAt(double t0) {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    const auto t = stage_clock::now();
    double first = d.impacts.front().time;
    for (const auto& e : d.impacts) first = std::min(first, e.time);
    s.seeds.clear();
    for (const auto& e : d.impacts) {
        if (e.time > first + 1e-12 * std::max(1.0, std::abs(first))) continue;
        s.impacts.push_back(e);
        s.seeds.push_back(e.bodyA);
        s.seeds.push_back(e.bodyB);
    }
    profile_.impactSolve += since(t);
    // Back to the start of the sub-step, keeping who was woken since (the contact memory
    // and the touching pairs are as they were then: only the solver and the step's end
    // change them).
    state_.time = s.before.time;
    state_.bodies = s.before.bodies;
    if (first > t0) advance(first - t0);
    state_.time = first;
    s.atMoment = state_.bodies;  // (to tell whose path the cut changes)

    const auto t2 = stage_clock::now();
    bodyPoses(model_, state_, d.end);
    findContacts(model_, d, s.margin);
    if (s.parkedCount > 0) dropParked();
    if (first > t0) {
        // The piece of the step up to the moment is a step of its own for the contacts that
        // were already there: a pile resting under the impact must not fall freely for that
        // piece (it sank by up to g h² / 2 at each cut, and moved). The impacting pairs are
        // left to the impact loop below.
        // The impacting pairs' manifolds (a few) are set aside with their places while the
        // others are solved where they stand (a copy of the others was 51 KB of hull-rain's
        // peak), then put back.
        const auto moment = s.impacts.end() - static_cast<long>(s.seeds.size() / 2);
        s.setAside.clear();
        s.setAsideAt.clear();
        size_t resting = 0;
        for (size_t k = 0; k < d.contacts.size(); ++k) {
            const collision::Manifold& m = d.contacts[k];
            const bool impacting = std::any_of(moment, s.impacts.end(), [&](const collision::ImpactEvent& e) {
                return e.bodyA == m.bodyA && e.bodyB == m.bodyB;
            });
            if (impacting) {
                s.setAside.push_back(m);
                s.setAsideAt.push_back(k);
            } else if (resting++ != k) {
                d.contacts[resting - 1] = m;
            }
        }
        d.contacts.resize(resting);
        if (!d.contacts.empty()) {
            // A quarter of the iterations: this piece only keeps the pile standing until the
            // moment; the solve at the end of the step starts from its impulses.
            ContactSolverSettings piece =
                solverSettings(model_, s.resting, s.touchTolerance, s.margin, first - t0);
            piece.iterations = std::max(1, piece.iterations / 4);
            solveContacts(model_, state_, s.before, d.contacts, s.sizes, piece, s.solver, ledger_);
            checkFinite(model_, state_);
        }
        putBackInPlaces(d.contacts, s.setAside, s.setAsideAt);
    }
    const ImpactResult r = resolveImpacts(model_, state_, d.contacts, s.seeds, s.touchTolerance, s.resting,
                                          s.impact, ledger_, &s.solver);
    ++profile_.impactMoments;
    if (r.limited) ++profile_.impactSweepLimits;
    touchingPairs(d.contacts, s.touchTolerance, d.touching);  // at the start of the rest of the step
    // A body the cut left as its own motion brought it to the moment (no impulse, nothing
    // solved) goes on along the path it had: the searches of its pairs still hold.
    d.pathFrom.resize(model_.bodies.size(), -1);
    for (int i : model_.dynamicBodies)
        if (!sameBits(s.atMoment[i], state_.bodies[i])) d.pathFrom[i] = d.subStep + 1;
    profile_.impactSolve += since(t2);
}

// The searches for moments of impact kept from earlier sub-steps (DetectScratch::noImpact)
// are of this step's paths only.
void World::forgetSearches() {
    DetectScratch& d = scratch_->detect;
    d.noImpact.clear();
    if (d.subStep > 0) d.pathFrom.assign(model_.bodies.size(), -1);  // (only a cut sets them)
}

Profile World::profile() const {
    Profile p = profile_;
    p.impactSearches = scratch_->detect.impactSearches;
    p.impactSearchesKept = scratch_->detect.impactSearchesKept;
    p.pairsReused = scratch_->detect.reusedPairs;
    p.pooledRuns = scratch_->workers ? scratch_->workers->runs() : 0;
    p.pooledIslandSolves = scratch_->solver.pooledSolves;
    p.pooledRegions = scratch_->solver.pooledRegions;
    p.pairsApart = scratch_->detect.apartPairs;
    const double k = scratch_->clockRate.secondsPerTick();
    for (double* t : {&p.forces, &p.integrate, &p.broadphase, &p.narrowphase, &p.timeOfImpact, &p.impactSolve,
                      &p.solve, &p.sleep})
        *t *= k;
    return p;
}

void World::stepWhole(double h) {
    Scratch& s = *scratch_;
    DetectScratch& d = s.detect;
    const double tEnd = state_.time + h;
    s.stepStart0 = state_.time;
    s.stepLength = h;
    ++profile_.steps;
    s.resting = restingSpeed(model_, std::abs(h));  // (a composed step's middle piece is negative)
    s.margin = contactMargin(model_, s.touchTolerance, h);
    if (!s.contacts) {  // nothing can touch: the contact stages are skipped
        advance(h);
        guardEnergy(model_, state_, s.energy);
        return;
    }
    if (model_.settings.sleeping) wakeTouched(model_, state_, {}, {});  // forces switching on
    startStillStep(model_, state_, h, s.still);
    s.solver.memoryChanged = s.still.enabled ? &s.still.changed : nullptr;
    if (!model_.joints.empty()) refreshJointPairs(model_, state_, d);
    if (state_.touchingKnown) {
        d.touching = state_.touching;  // the last step's: pairs touching at the start
    } else {
        // The first step from a state: what touches already is resting contact, not an impact.
        auto t = stage_clock::now();
        bodyPoses(model_, state_, d.start);
        d.end = d.start;
        findPairs(model_, state_, s.margin, d);
        profile_.broadphase += since(t);
        t = stage_clock::now();
        findContacts(model_, d, s.margin);
        touchingPairs(d.contacts, s.touchTolerance, d.touching);
        profile_.narrowphase += since(t);
        // Bodies that touch and approach as the run starts (a cradle's first ball set
        // moving against the row) meet now, at the start of the step: left to the end of
        // the step they would overlap for a step and the impact would come one step late.
        // (Later steps start from the contact solver's answer, where nothing approaches.)
        impactsAtStart();
    }
    s.impacts.clear();
    s.parkedCount = 0;
    s.parked.clear();
    s.detect.standing = nullptr;
    s.group = -1;
    forgetSearches();
    bool mayPark = true;
    for (int cut = 0;; ++cut) {
        copyMotion(state_, s.before);
        const double t0 = state_.time;
        advance(t0 == s.stepStart0 ? h : tEnd - t0);  // (h itself for the whole step: see finishStep)
        state_.time = tEnd;
        d.subStep = cut;
        detect(t0, tEnd - t0, cut >= kMaxCuts);
        if (cut == 0 && mayPark && s.group < 0 && !d.impacts.empty()) {
            park();
            if (startGroups()) {  // several islands with an impact: each cut on its own
                cut = -1;
                continue;
            }
        }
        if (s.parkedCount > 0 && (cut > 0 || s.group > 0) && !leaveParked()) {
            // A cut body's new path meets a parked one: the whole step again, every body cut.
            endGroups(true);
            unpark(true);
            forgetSearches();
            ++profile_.islandRestarts;
            mayPark = false;
            cut = -1;
            continue;
        }
        if (cut == kMaxUnsafeCuts) s.impacts.insert(s.impacts.end(), d.impacts.begin(), d.impacts.end());
        if (d.impacts.empty() || cut == kMaxUnsafeCuts) {
            if (s.group < 0) break;
            finishStep(s.before, d.contacts);  // this island's end, the others standing
            if (!nextGroup()) break;
            cut = -1;
        } else {
            impactAt(t0);
        }
    }

    // The end of the step: the cut islands from their last cut (each island's own, in group
    // mode), then the parked ones from the start of the step, each with the other set
    // standing still.
    if (s.group >= 0)
        endGroups(false);
    else
        finishStep(s.before, d.contacts);
    if (s.parkedCount > 0) {
        for (int i : model_.dynamicBodies) {
            if (!s.parked[i]) s.realAsleep[i] = state_.asleep[i];  // woken by a cut body, maybe
            state_.asleep[i] = s.parked[i] ? 0 : 1;
        }
        finishStep(s.stepStart, s.parkedContacts);
        unpark(false);
    }
    if (model_.settings.impacts == ImpactTiming::Exact)
        settle();  // (end-of-step: overlap as the step closed it)

    if (model_.settings.sleeping) {
        const auto t = stage_clock::now();
        updateSleep(model_, state_, d.contacts, s.touchTolerance, h, s.sleep, ledger_);
        profile_.sleep += since(t);
    }
    touchingPairs(d.contacts, s.touchTolerance, state_.touching);
    state_.touchingKnown = true;
    endStillStep(model_, state_, d.contacts, s.still);
    joint::trackHingeAngles(model_, state_);
    for (const auto& m : d.contacts) profile_.contactPoints += m.count;
    profile_.impacts += static_cast<long>(s.impacts.size());
    guardEnergy(model_, state_, s.energy);
}

// Overlap beyond the margin that the contact solver left (settle_overlap.h), moved out
// before the step's poses are shown.
void World::settle() {
    Scratch& s = *scratch_;
    const auto t = stage_clock::now();
    const SettleResult r =
        settleOverlap(model_, state_, s.detect.end, s.detect.contacts, s.sizes, s.detect.broadphase,
                      s.resting, s.detect.jointPairs, s.jointedBodies, s.margin, s.settle, ledger_);
    profile_.settledBodies += r.moved;
    profile_.solve += since(t);
}

void World::impactsAtStart() {
    Scratch& s = *scratch_;
    const auto t = stage_clock::now();
    approachingBodies(model_, state_, state_, s.detect.contacts, s.touchTolerance, s.resting, s.seeds);
    if (!s.seeds.empty()) {
        const ImpactResult r = resolveImpacts(model_, state_, s.detect.contacts, s.seeds, s.touchTolerance,
                                              s.resting, s.impact, ledger_, &s.solver);
        ++profile_.impactMoments;
        if (r.limited) ++profile_.impactSweepLimits;
    }
    profile_.impactSolve += since(t);
}

// Bounces that no time of impact found (bodies that touched at the start of the step and
// now approach fast) get the impact loop at the end of the step; then the contact solver
// over the last part of the step, from `before`.
void World::finishStep(const State& before, const collision::ManifoldList& contacts) {
    Scratch& s = *scratch_;
    Lap lap;
    approachingBodies(model_, before, state_, contacts, s.touchTolerance, s.resting, s.seeds);
    if (!s.seeds.empty()) {
        const ImpactResult r = resolveImpacts(model_, state_, contacts, s.seeds, s.touchTolerance, s.resting,
                                              s.impact, ledger_, &s.solver, &before);
        ++profile_.impactMoments;
        if (r.limited) ++profile_.impactSweepLimits;
    }
    profile_.impactSolve += lap.next();

    // A solve over the whole step is a solve over h, the step asked for: the time's
    // difference tEnd - t0 differs from h in its last bits from step to step, and every
    // remembered impulse was then scaled by a ratio a rounding away from 1, so that a pile
    // at rest never remembered the same impulses twice. Over the whole step, the still
    // islands' answer is known (still_islands.h).
    const bool whole = before.time == s.stepStart0;
    const double h = whole ? s.stepLength : state_.time - before.time;
    const bool skip = whole && s.still.enabled && s.still.started;
    if (skip) {
        s.still.now = s.still.still;
        closeStillIslands(model_, contacts, s.still.now);
        s.solver.still = &s.still.now;
    }
    solveContacts(model_, state_, before, contacts, s.sizes,
                  solverSettings(model_, s.resting, s.touchTolerance, s.margin, h), s.solver, ledger_);
    s.solver.still = nullptr;
    s.solver.stepJointsOpen = std::max(s.solver.stepJointsOpen, s.solver.jointsOpen);
    s.solver.stepJointsOpenAll = std::max(s.solver.stepJointsOpenAll, s.solver.jointsOpenAll);
    s.solver.composedJointsOpenAll = std::max(s.solver.composedJointsOpenAll, s.solver.jointsOpenAll);
    if (skip) profile_.stillBodySteps += s.solver.stillBodies;
    checkFinite(model_, state_);
    profile_.solve += lap.next();
}

const collision::ManifoldList& World::contacts() const {
    return scratch_->detect.contacts;
}

const std::vector<collision::ImpactEvent>& World::impacts() const {
    return scratch_->impacts;
}

}  // namespace tumble
