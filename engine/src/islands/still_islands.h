// Islands at their fixed point (World::step, the contact solver). A group of bodies resting
// on each other and on static ones that the last step left exactly as it found them (pose
// and momentum to the bit, momentum zero, every remembered contact impulse unchanged) will
// be left so again by a step of the same length: the step is a function of the island's
// state, its contacts' memory and h alone, as long as nothing else reaches it (no force
// but gravity within either step, no joint, no moving kinematic body, no contact with a
// body that moved, no overlap waiting on the energy budget the islands share).
// The contact solver then takes such an island's answer as it stands instead of solving it
// again; every sum it shares with the other islands (the energy balance, the warm start's
// check) is given the island's terms as they were, so the other islands' answers do not
// change either. The state is the same bit for bit as with every island solved
// (tst_still_islands); only the energy ledger's split between contact and friction losses
// may differ by rounding (the skipped blocks' friction is booked as last computed).
//
// Sleeping stops bodies that move slowly; this stops none: it skips only the work whose
// answer is known. With sleeping off, a pile at rest costs the integrator and the
// narrowphase's look-up of its pairs, no solve.
#pragma once

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/state.h>

#include <cstdint>
#include <vector>

namespace tumble {

struct StillScratch {
    bool enabled = true;
    double h = 0.0;  // the length of the step they were found still in
    std::vector<BodyState>
        start;             // each dynamic body at the start of this step (Model::dynamicBodies' order)
    bool started = false;  // start holds this step's
    std::vector<std::uint8_t> still;    // per body: left as it was by the last step (this step's candidates)
    std::vector<std::uint8_t> now;      // the candidates of one solve, after closeStillIslands
    std::vector<std::uint8_t> changed;  // per body: a remembered impulse of its contacts changed this step
    std::vector<std::uint8_t>
        driven;  // per body: a force term acts on it within this step, or a joint holds it
};

/// At the start of a step of length h: the bodies as they start, and the candidates found
/// at the end of the last step if it was as long (else none).
void startStillStep(const Model& model, const State& state, double h, StillScratch& s);

/// Of `flags` (per body), drops every body that touches, through `contacts`, a dynamic body
/// not flagged or a kinematic body that moves, and so on through its island.
void closeStillIslands(const Model& model, const collision::ManifoldList& contacts,
                       std::vector<std::uint8_t>& flags);

/// At the end of the step: the bodies that it left exactly as they were, at rest, their
/// contacts' memory unchanged, in islands of such bodies (`contacts`: the step's last).
void endStillStep(const Model& model, const State& state, const collision::ManifoldList& contacts,
                  StillScratch& s);

/// Forgets what was found (a new state, a changed setting).
void forgetStill(StillScratch& s);

}  // namespace tumble
