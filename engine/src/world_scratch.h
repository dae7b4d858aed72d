// The scratch space of a World (world.cpp, world_islands.cpp): what the stages keep
// between calls, so that a step allocates nothing once the scene has run a while.
#pragma once

#include <tumble/world.h>

#include "contact_solver.h"
#include "detect.h"
#include "energy_guard.h"
#include "impact.h"
#include "integrate.h"
#include "islands.h"
#include "sleep.h"
#include "still_islands.h"
#include "stage_clock.h"
#include "workers.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace tumble {

struct World::Scratch {
    stage_clock::Rate clockRate;  // the profile's ticks to seconds (World::profile)
    IntegrateScratch integrate;
    DetectScratch detect;
    ImpactScratch impact;
    ContactSolverScratch solver;
    SleepScratch sleep;
    StillScratch still;
    EnergyGuard energy;
    // The motion at the start of the (sub-)step: time, bodies, rest times and sleep flags
    // (copyMotion). Its contact memory and touching pairs are not kept: nothing from the
    // start of a sub-step to its cut changes them, so a cut takes them as they are.
    State before;
    std::vector<double> sizes;      // bounding radius per body
    std::vector<double> thickness;  // narrowest width per body (collision::thickness)
    std::vector<int> awake;     // awake dynamic bodies, when sleeping is on
    std::vector<int> seeds;
    std::vector<collision::ImpactEvent> impacts;  // of the whole step
    double touchTolerance = 0.0;
    bool contacts = false;  // needsContacts(model): can two bodies ever touch (the model never changes)
    double resting = 0.0;  // the resting speed of the step being taken (restingSpeed)
    double margin = 0.0;   // contact points are found this far apart (contactMargin)
    double stepStart0 = 0.0, stepLength = 0.0;  // the step being taken: its start time, its h
    std::vector<collision::Manifold> restingContacts;  // at a cut, all but the impacting pairs'
    // Parked islands (see the top of this file); parkedCount == 0: none this step.
    IslandScratch islands;
    std::vector<std::uint8_t> parked;
    int parkedCount = 0;
    State stepStart;                                   // to take the step again
    std::vector<std::uint64_t> touchingAtStart;
    EnergyLedger ledgerAtStart;
    std::vector<std::uint8_t> realAsleep;              // the sleep flags without the parked ones
    std::vector<collision::Manifold> parkedContacts;   // at the end of their free step
    std::unique_ptr<Workers> workers;  // setThreads(n > 1)
    // A step whose joints stayed open is taken again in halves (World::stepJointed): what
    // it starts from, per depth of splitting.
    struct JointRedo {
        State state;
        EnergyLedger ledger;
        EnergyGuard guard;
    };
    std::vector<JointRedo> jointRedo;
    std::vector<int> jointedBodies;  // dynamic bodies with a joint (the model never changes)
    double jointedWeight = 0.0;      // Σ m |g| r over them: the floor of the energy a split checks
    bool jointsPassive = true;       // no motor, no joint to a kinematic body that moves
    bool composed = false;           // a mechanism stepped by World::stepComposed
};

// What a cut goes back to: the state without its contact memory and touching pairs, which
// a pile has thousands of and a sub-step does not change.
inline void copyMotion(const State& from, State& to) {
    to.time = from.time;
    to.bodies = from.bodies;
    to.restTime = from.restTime;
    to.asleep = from.asleep;
}

}  // namespace tumble
