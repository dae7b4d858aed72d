// What the step keeps account of as it runs: the time each stage took (Profile) and where
// the energy went (EnergyLedger). Each stage adds to them; World owns the totals and hands
// them out (World::profile, World::ledger). A header of its own so that the stages need not
// include the World that calls them.
#pragma once

namespace tumble {

/// Wall-clock time spent in each stage, accumulated over steps (seconds; the World counts
/// in ticks of a cheaper clock and converts them when asked).
struct Profile {
    double forces = 0.0;
    double integrate = 0.0;
    double broadphase = 0.0;
    double narrowphase = 0.0;
    double timeOfImpact = 0.0;
    double impactSolve = 0.0;  ///< re-stepping to the moments of impact and the impulses there
    double solve = 0.0;        ///< the contact solver at the end of each step
    double sleep = 0.0;        ///< islands and sleeping
    long steps = 0;
    long forceEvaluations = 0;
    long pairs = 0;          ///< broadphase pairs, summed over steps
    long pairsReused = 0;    ///< narrowphase pairs taken as last found (both bodies exactly where they were)
    long pairsApart = 0;     ///< convex pairs shown apart by their last direction apart, without GJK
    long contactPoints = 0;  ///< narrowphase contact points, summed over steps
    long impacts = 0;        ///< pairs that came into contact within a step
    long impactSearches = 0;  ///< pairs searched for a moment of impact (collision::timeOfImpact), summed
    /// ... and pairs whose search was not needed: found without an impact earlier in the same
    /// step, neither body's path changed by a cut since (findImpacts)
    long impactSearchesKept = 0;
    long impactMoments = 0;  ///< moments of impact the step was cut at
    long impactSweepLimits = 0;  ///< impact loops stopped by their bound (see docs/architecture.md)
    long awakeBodySteps = 0;     ///< dynamic bodies integrated, summed over steps (sleeping ones are not)
    long parkedBodySteps = 0;    ///< bodies of islands without an impact kept out of the cuts, summed
    long islandRestarts = 0;     ///< steps taken again with every body cut (a cut body met a parked one)
    long stillBodySteps =
        0;  ///< bodies whose contacts were taken as last solved (at their fixed point), summed
    long settledBodies =
        0;  ///< bodies pushed out of overlap deeper than the margin after the solve (settle_overlap.h)
    long jointSplits = 0;  ///< steps taken again in two halves: their joints did not hold (World::step)
    /// Stages handed to the worker threads (World::setThreads): a stage goes to them only when
    /// its items are worth it (common/pool_gate.h); 0 on one thread.
    long pooledRuns = 0;
    /// Contact solves whose islands went to the worker threads, one island per thread at a
    /// time (solver/contact_islands.h); 0 on one thread.
    long pooledIslandSolves = 0;
    /// Velocity passes of a large island whose two regions went to the worker threads
    /// (solver/block_regions.h); 0 on one thread.
    long pooledRegions = 0;
};

/// Where kinetic and potential energy went, accumulated over steps (J). In a scene with no
/// driving force, energy(end) = energy(start) - lostInContacts - lostInFriction
/// + positionCorrection, up to the integrator's own error.
struct EnergyLedger {
    double lostInContacts = 0.0;  ///< kinetic energy taken by normal impulses (restitution < 1)
    double lostInFriction = 0.0;  ///< kinetic energy taken by friction impulses
    double positionCorrection =
        0.0;  ///< potential energy of placing pushed bodies (contact positions, overlap removal)
    /// Kinetic and potential energy taken by joints: their impulses (exact per row) and the
    /// projections that put the bodies back on them. Negative when a joint gave energy: a
    /// motor driving its bodies, a joint to a moving kinematic body.
    double lostInJoints = 0.0;
    /// Work moving kinematic and animated bodies did on the others through contacts and
    /// impacts (J): each impulse they gave times the velocity of their point it acted at. A
    /// paddle that throws a ball did positive work; a lift letting a box down, negative. The
    /// contact and friction losses above are net of it (what the contacts dissipated).
    double doneByKinematic = 0.0;
};

}  // namespace tumble
