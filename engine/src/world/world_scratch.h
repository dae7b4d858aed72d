// The scratch space of a World (world.cpp, world_islands.cpp): what the stages keep
// between calls, so that a step allocates nothing once the scene has run a while.
#pragma once

#include <tumble/world.h>

#include "collision/detect.h"
#include "common/stage_clock.h"
#include "common/workers.h"
#include "dynamics/integrate.h"
#include "guard/energy_guard.h"
#include "impacts/impact.h"
#include "islands/islands.h"
#include "islands/sleep.h"
#include "islands/still_islands.h"
#include "solver/contact_solver.h"
#include "solver/settle_overlap.h"

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
    SettleScratch settle;
    SleepScratch sleep;
    StillScratch still;
    EnergyGuard energy;
    // The motion at the start of the (sub-)step: time, bodies, rest times and sleep flags
    // (copyMotion). Its contact memory and touching pairs are not kept: nothing from the
    // start of a sub-step to its cut changes them, so a cut takes them as they are.
    State before;
    std::vector<double> sizes;      // bounding radius per body
    std::vector<double> thickness;  // narrowest width per body (collision::thickness)
    std::vector<int> awake;         // awake dynamic bodies, when sleeping is on
    std::vector<int> seeds;
    std::vector<BodyState> atMoment;  // at a cut, the bodies brought to its moment (impactAt)
    std::vector<collision::ImpactEvent> impacts;  // of the whole step
    double touchTolerance = 0.0;
    bool contacts = false;  // needsContacts(model): can two bodies ever touch (the model never changes)
    double resting = 0.0;   // the resting speed of the step being taken (restingSpeed)
    double margin = 0.0;    // contact points are found this far apart (contactMargin)
    double stepStart0 = 0.0, stepLength = 0.0;  // the step being taken: its start time, its h
    collision::ManifoldList setAside;           // at a cut, the impacting pairs' (impactAt)
    std::vector<std::size_t> setAsideAt;        // ... and their places among the contacts
    // Parked islands (see the top of this file); parkedCount == 0: none this step.
    IslandScratch islands;
    std::vector<std::uint8_t> parked;
    int parkedCount = 0;
    State stepStart;  // to take the step again (World::saveStepStart): all but the memory and touching
    std::vector<ContactMemory> cutMemory;  // the memory a cut can change, as it was
    std::vector<std::size_t> cutMemoryAt;  // ... and its places in State::contacts
    std::size_t memoryAtStart = 0;         // the memory's length at the step's start
    std::vector<std::uint64_t> touchingAtStart;
    EnergyLedger ledgerAtStart;
    std::vector<std::uint8_t> realAsleep;    // the sleep flags without the parked ones
    collision::ManifoldList parkedContacts;  // at the end of their free step
    // Several islands with an impact (World::startGroups): each is cut on its own while the
    // others stand as parked ones do; island g's bodies are groupBodies[groupBegin[g],
    // groupBegin[g + 1]). group: the one being cut (-1: not so).
    std::vector<int> groupBodies, groupBegin, groupOfRoot;
    int group = -1;
    std::vector<std::uint8_t> parkedIslands;  // park()'s flags, while s.parked holds the standing
    int parkedIslandCount = 0;
    collision::ManifoldList groupContacts;  // of the islands done, at their ends: a run each
    std::vector<collision::Pose> groupEnd;  // ... and their bodies' poses where those were found
    std::vector<std::size_t> groupRuns;     // where each run begins in groupContacts
    std::vector<std::size_t> groupRunEnds;  // ... and ends (World::endGroups' merge)
    std::unique_ptr<Workers> workers;        // setThreads(n > 1)
    // A step whose joints stayed open is taken again in halves (World::stepJointed): what
    // it starts from, per depth of splitting.
    struct JointRedo {
        State state;
        EnergyLedger ledger;
        EnergyGuard guard;
    };
    // A step's start, and its end when it is weighed against its halves (World::stepJointed).
    struct JointRedoPair {
        JointRedo start, end;
    };
    std::vector<JointRedoPair> jointRedo, composedRedo;  // per depth of splitting
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

// `list`, which is what it was less the entries `aside` taken from the places `at`
// (ascending) and in the same order, made what it was: each entry back in its place.
template <class List>
void putBackInPlaces(List& list, const List& aside, const std::vector<std::size_t>& at) {
    size_t kept = list.size();
    list.resize(kept + aside.size());
    size_t back = aside.size();
    for (size_t k = list.size(); back > 0 && k-- > 0;) {
        if (at[back - 1] == k) {
            list[k] = aside[--back];
        } else {
            list[k] = list[--kept];
        }
    }
}

}  // namespace tumble
