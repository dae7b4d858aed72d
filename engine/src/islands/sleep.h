// Stage: islands and sleeping. Dynamic bodies that touch form islands (through contacts
// with other dynamic bodies; the ground and kinematic bodies do not join islands). A body
// is at rest while it moves slower than kSleepSpeed and turns slower than kSleepSpin; an
// island whose bodies have all rested for kTimeToSleep falls asleep: its bodies stop, are
// no longer integrated, and leave the broadphase's moving set, so they cost next to
// nothing. A sleeping body wakes, with every sleeping body it rests on or that rests on
// it, when an awake body touches it or when one of its applied forces switches on.
#pragma once

#include "common/pool_gate.h"

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/profile.h>

#include <vector>

namespace tumble {

constexpr double kSleepSpeed = 0.01;  // m/s
constexpr double kSleepSpin = 0.035;  // rad/s (2 degrees a second)
constexpr double kTimeToSleep = 0.5;  // s

struct SleepScratch {
    Workers* pool = nullptr;  // the world's worker threads; null: this thread only
    PoolGate restGate;        // whether the rest times are worth the pool
    std::vector<int> parent;
    std::vector<double> islandRest;
    std::vector<std::uint8_t> blocked;
};

/// After the solve: rest times, islands, and islands falling asleep. True when any fell asleep.
bool updateSleep(const Model& model, State& state, const collision::ManifoldList& contacts,
                 double touchTolerance, double h, SleepScratch& scratch, EnergyLedger& ledger);

/// Wakes the sleeping bodies an awake body touches (`contacts`, `impacts`) or whose applied
/// forces act at state.time, with their sleeping neighbours. True when any woke. Bodies with
/// parked[i] set (World::step's parked islands; empty: none) are left alone.
bool wakeTouched(const Model& model, State& state, const collision::ManifoldList& contacts,
                 const std::vector<collision::ImpactEvent>& impacts,
                 const std::vector<std::uint8_t>& parked = {});

/// The dynamic bodies that are awake, in index order.
void awakeBodies(const Model& model, const State& state, std::vector<int>& out);

}  // namespace tumble
