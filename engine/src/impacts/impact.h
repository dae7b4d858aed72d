// Stage: impulses at a moment of impact, the paper's section 4. The step has been cut at
// the time of first touch of one or more pairs; here every contact point of the bodies
// that touch them (directly or through a chain of touching dynamic bodies) that is still
// approaching gets the impulse j n of (27), with restitution ε = max(εA, εB), and the
// sweep over the points is repeated until none approaches (or a bound is hit).
//
// The points of one manifold are solved together: the impulses that give every
// approaching point its target velocity -ε v⁻ at once, the least-norm solution when the
// points are dependent (four corners of a face), so a body landing flat gets the
// symmetric answer. Different manifolds are taken one after the other, which is what
// carries an impact down a row of touching balls (Newton's cradle). A point approaching
// slower than `restingSpeed` is settling, not bouncing: the loop leaves it to the contact
// solver.
// Each normal impulse is followed by a Coulomb friction impulse at the point, at most
// μ j, that stops the sliding if it can.
#pragma once

#include "solver/contact_solver.h"
#include "solver/solver_body.h"

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/profile.h>

#include <cstdint>
#include <vector>

namespace tumble {

struct ImpactScratch {
    std::vector<SolverBody> bodies;  // with a contact solver's scratch, its own (borrowed by resolveImpacts)
    std::vector<std::uint8_t> inIsland;
    std::vector<std::uint8_t> seen;  // bodiesOf's flags
    std::vector<int> manifolds;      // in the order of the contacts
    std::vector<int> involved;       // the bodies loaded, ascending
    // collectIsland's search: each body's touching manifolds (byBody[first[b] .. first[b+1]))
    std::vector<int> first, fill, byBody, queue;
    // The same for joints: each body's joint partners (partners[jointFirst[b] ..]).
    std::vector<int> jointFirst, jointFill, partners;
    std::vector<std::uint8_t> taken;
    // The sweeps' bookkeeping: when each body last got an impulse, when each manifold of the
    // island was last solved, and whether it had points approaching then.
    std::vector<long> changedAt, checkedAt;
    std::vector<std::uint8_t> approached;
    std::vector<long> jointCheckedAt;  // per joint row: when it was last updated
};

struct ImpactResult {
    int sweeps = 0;
    bool limited = false;  ///< stopped by the bound with points still approaching
};

/// Sizes the scratch's per-body arrays for `model` (World's constructor).
void sizeImpacts(const Model& model, ImpactScratch& scratch);

/// `contacts`: the manifolds at the moment of impact; `seeds`: the bodies of the pairs that
/// first touch now. A point counts as touching when its depth is at least -touchTolerance.
/// Updates the momenta in `state` and the ledger.
/// The bodies of the touching contacts that approach faster than `speed`, now and with the
/// velocities of `before` (the start of the step): bounces that no time of impact found,
/// e.g. of bodies touching at the start of the step. A contact that approaches only
/// because of this step's forces (a body pressed onto its support) is resting, not bouncing.
void approachingBodies(const Model& model, const State& before, const State& state,
                       const collision::ManifoldList& contacts, double touchTolerance, double speed,
                       std::vector<int>& seeds);

/// With joints, the bodies joined to the island's are in it too, and the joints' rows
/// (impulsive: joints.h) are swept with the manifolds until nothing approaches and no joint
/// moves, so that an impact passes through a joint as through a contact; `joints`: the
/// contact solver's scratch, whose joint rows this uses (its bodies are swapped in); given
/// one, the impact works on that scratch's solver bodies too.
/// `chordFrom`: the state at the start of the step whose end this is (the end-of-step
/// bounces): animated bodies move as over the step's solve, by their chords from it; none
/// (a moment of impact): at their paths' velocities there.
ImpactResult resolveImpacts(const Model& model, State& state, const collision::ManifoldList& contacts,
                            const std::vector<int>& seeds, double touchTolerance, double restingSpeed,
                            ImpactScratch& scratch, EnergyLedger& ledger,
                            ContactSolverScratch* joints = nullptr, const State* chordFrom = nullptr);

}  // namespace tumble
