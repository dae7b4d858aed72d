// Stages: broadphase, narrowphase and time of impact. They run after the integrator on the
// poses at the start and the end of the step, and leave the contacts at the end of the step
// and the impacts within it for the response.
#pragma once

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/profile.h>

#include "collision/broadphase.h"
#include "collision/compound_pairs.h"
#include "common/pool_gate.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace tumble {

class Workers;  // workers.h: only the .cpp files that hand work to the pool include it

struct DetectScratch {
    /// The pairs of bodies a joint joins that has not broken (sorted pair keys; they do not
    /// collide), kept by refreshJointPairs.
    std::vector<std::uint64_t> jointPairs;
    int jointPairsBroken = -1;           // the broken joints they were made with; -1: to be made
    std::vector<collision::Pose> start;  // body poses at the start of the step
    std::vector<collision::Pose> end;    // ... and at its end
    // Bodies that stand while others are cut (World::park: parked islands, and the islands
    // not being cut in group mode; null: none): their boxes cover their whole step, from
    // their poses at its start (standFrom), so that a cut body whose new path crosses one
    // pairs with it (and the step is taken again: World::leaveParked).
    const std::vector<std::uint8_t>* standing = nullptr;
    std::vector<collision::Pose> standFrom;
    std::vector<collision::Aabb> swept;  // world boxes covering the whole step
    double sweptMargin = 0.0;            // the margin they were grown by
    // Per body whose box costs a pass over its vertices (hull, mesh, compound): the poses its
    // box in `swept` was made from. A step cut at moments of impact asks findPairs again for
    // bodies that did not move since (parked islands: hull-rain 1.8 M boxes in 300 steps).
    struct BoxFrom {
        collision::Pose end, other;
        int with = -1;  // -1: none made; 0: from `end` alone; 1: and `other`
    };
    std::vector<BoxFrom> boxFrom;
    std::vector<std::uint8_t> moving;
    std::vector<collision::HalfSpace> halfSpaces;  // of the planes that stand still; empty if none
    collision::Broadphase broadphase;
    collision::ManifoldList contacts;
    std::vector<collision::ImpactEvent> impacts;
    std::vector<std::uint64_t> touching;  // sorted keys of the pairs touching at the start of the step
    // The pairs with contacts at the end, sorted by key, each with its first manifold's
    // index in contacts (findImpacts).
    std::vector<std::pair<std::uint64_t, int>> found;
    // The last narrowphase, for the pairs whose two bodies stand exactly where they stood
    // then (bit for bit): a pair's manifolds are a function of the two poses, the shapes and
    // the margin only, so they are taken as they were (findContacts).
    // A pair of convex shapes found apart keeps the direction that showed it, for the next
    // narrowphase to try first (collision::apartAlong): that needs no bit-for-bit pose, and
    // proves what GJK would find, so nothing depends on what this memory held either.
    struct PairMemory {
        std::vector<std::uint64_t> keys;          // the pairs, sorted
        std::vector<std::pair<int, int>> ranges;  // keys[k]'s manifolds: [first, second) of manifolds
        std::vector<Vec3> apart;                  // keys[k]'s direction apart (out of b towards a), or zero
        collision::ManifoldList manifolds;
        double margin = std::numeric_limits<double>::quiet_NaN();
    };
    PairMemory lastPairs;
    std::vector<Vec3> apart;                  // per broadphase pair of this narrowphase: as PairMemory::apart
    std::vector<collision::Pose> pairedPose;  // each body's pose when it was last in a pair
    long reusedPairs = 0;                     // pairs taken from lastPairs, summed
    long apartPairs = 0;                      // pairs shown apart by their last direction, summed
    // Two tallies per chunk of pairs, a cache line each (the threads count apart): findContacts
    // counts the pairs taken again and those shown apart, findImpacts its searches and those kept.
    struct alignas(64) ChunkTally {
        long n[2] = {0, 0};
    };
    std::vector<ChunkTally> chunkTally;
    Workers* pool = nullptr;                  // the world's worker threads; null: this thread only
    std::vector<collision::ManifoldList> chunkContacts;  // per chunk of pairs (with a pool)
    std::vector<std::vector<collision::ImpactEvent>> chunkImpacts;
    // Within one step: the pairs an exact search found without an impact (none, or only a
    // settling touch) from the start of sub-step `second` (the cuts before it) to the end
    // of the step, sorted by key. Such a pair still has none over a later sub-step while
    // neither body's path changed: a cut that leaves a body's pose and momenta as its own
    // motion brought them (no impulse, no contact solved) leaves its path as it was, the
    // forces being the body's own (findImpacts). Cleared at the step's start.
    std::vector<std::pair<std::uint64_t, int>> noImpact;
    std::vector<int> pathFrom;  // per body: the sub-step from which its path is new (-1: the step's)
    int subStep = 0;            // the sub-step being searched (the cuts taken so far)
    std::vector<int> noImpactFrom;  // per broadphase pair of this search: as noImpact's second, or -1
    long impactSearches = 0, impactSearchesKept = 0;
    PoolGate contactsGate, impactsGate, boxesGate, startGate, endGate;  // whether the pairs are worth the pool (workers.h)
    // The parts of the compound bodies in this narrowphase's pairs, placed at the end of the
    // step once for all their pairs: body i's from placed[placedAt[i]] (-1: none).
    std::vector<collision::PlacedPart> placed;
    std::vector<int> placedAt;
};

/// True when the model has two bodies that could ever touch (at least one not static);
/// otherwise the contact stages are skipped entirely.
bool needsContacts(const Model& model);

/// World pose of each body's frame. When `out` has a pose per body already, the static
/// bodies' are kept: a World clears it when a state is set (World::setState).
/// The pose of body `body` in state `s`: its frame (not its centre of mass) in the world.
collision::Pose bodyPose(const BodyModel& body, const BodyState& s);
/// With `pool`, the bodies are spread over its threads (when `gate` says they are worth it).
void bodyPoses(const Model& model, const State& state, std::vector<collision::Pose>& out,
               Workers* pool = nullptr, PoolGate* gate = nullptr);

/// Broadphase: pairs whose boxes, swept over the step and grown by `margin`, overlap. A
/// static body's box is computed again only when the margin changed or `s.swept` was
/// cleared.
/// Sleeping bodies stand with the static ones, so two sleeping bodies (or a sleeping and a
/// static one) never pair.
void findPairs(const Model& model, const State& state, double margin, DetectScratch& s);

/// Narrowphase: the manifolds of every pair at the end of the step.
void findContacts(const Model& model, DetectScratch& s, double margin);

/// s.jointPairs for `state`'s unbroken joints, made again when the number broken changed.
void refreshJointPairs(const Model& model, const State& state, DetectScratch& s);

/// The sorted keys of the pairs with a point deeper than -touchTolerance.
void touchingPairs(const collision::ManifoldList& contacts, double touchTolerance,
                   std::vector<std::uint64_t>& out);

/// Time of impact: for pairs that did not touch at the start of the step (not in
/// `s.touching`), the moment they first come within
/// `tolerance` × the smaller body's size (t0 = time at the start, h = step). A pair that
/// is that near already at the start has its impact at t0. A pair whose points close no
/// faster than `minApproach` there is not an impact: it is left to the contact solver.
/// `sizes`: each body's bounding radius (a mesh's is a pass over its vertices: not per pair).
/// With `thickness` (ImpactTiming::EndOfStep: each body's thickness()) a pair that has
/// contacts at the end of the step (`s.contacts`) is left to the end of the step if its
/// bodies moved less than half the thinner one's thickness (the overlap cannot reach past
/// its middle), and a pair without contacts if they moved less than their thicknesses
/// together (they cannot have passed through): only a fast body meeting a thin one gets a
/// moment of impact. Null: every pair (ImpactTiming::Exact).
void findImpacts(const Model& model, const State& before, const State& after, double t0, double h,
                 double tolerance, double minApproach, const std::vector<double>& sizes,
                 const std::vector<double>* thickness, DetectScratch& s);

}  // namespace tumble
