// Stage: the contact solver, for contacts that persist (resting, sliding, rolling). It runs
// at the end of every step on the contacts found there, after any moments of impact were
// handled (impact.h).
//
// Velocities: sequential impulses with accumulated, clamped impulses per point (the
// normal impulse never pulls; the friction impulse stays inside the Coulomb cone
// |λt| ≤ μ λn), started from the impulses of the same points in the last step (warm
// starting: a stack needs few iterations because each step starts from the answer of the
// one before). A point approaching faster than the resting speed, both now and with the
// velocities at the start of the step, bounces with restitution ε (target -ε v⁻); else it
// is resting contact (target 0): a body pressed onto its support by a force does not
// bounce on it. Friction acts per manifold
// at the centroid of its points (see Block below).
//
// Positions: the overlap left by the step is removed by moving the bodies apart along
// the normal (a few Gauss-Seidel passes, a fraction of the overlap beyond a small slop
// each step) without touching the momenta, so the correction adds no kinetic energy. The
// potential energy it adds is counted in the ledger.
#pragma once

#include "common/make_room.h"
#include "common/pool_gate.h"
#include "solver/solver_body.h"

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/profile.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace tumble {

class Workers;

/// Overlap the contact solver leaves alone at a point, × the smaller body's size (its
/// bounding radius).
inline constexpr double kContactSlop = 0.005;
/// × the slop: deeper overlap is removed whatever it costs in energy (contact_energy.cpp).
inline constexpr double kFreeOverlap = 10.0;

using collision::roundness;  // (tumble/collision.h)

struct ContactSolverScratch {
    /// What the iterations read and write of a point; the rest is in PointGeometry, so that
    /// the passes over the rows stream as little memory as they can (the iterations of a
    /// 1 240-box pyramid went over 13 MB twenty times a step).
    struct Point {
        int a = 0, b = 0;
        Vec3 n;  // (the arms r are PointGeometry::position less each body's centre)
        // The angular parts of the normal row, set by preparePoint: rA × n and rB × n (a
        // body's spin changes the normal velocity by ω·(r × n)), and what a unit impulse
        // along n does to each spin, I⁻¹(r × n). The iterations need no matrix product.
        Vec3 armA, armB, spinA, spinB;
        double kn = 0;         // effective mass along the normal
        double target = 0.0;   // wanted normal velocity after the solve
        double lambdaN = 0.0;  // accumulated normal impulse
    };
    /// The rest of point k: for the position passes, the warm start and the memory.
    struct PointGeometry {
        Vec3 localA, localB, localN;  // A's and B's surface points, n in B
        double slop = 0.0, size = 0.0;
        double depth = 0.0;  // as found: the surface points are half of it either side of `position`
        std::uint32_t feature = 0;
        bool roundA = false, roundB = false;  // a sphere's or capsule's surface (prepareBlock)
        int memory = -1;  // the remembered point its warm start took (index in State::contacts), or -1
        // That point's impulses, when it was taken unscaled (remember).
        double warmNormal = 0.0;
        Vec3 warmTangent = Vec3::Zero();
        double warmTwist = 0.0;
        Vec3 position;
    };
    /// One manifold. Its points are solved together along the normal (K: normal velocity
    /// change at i per unit impulse at j, and its least-norm inverse). Friction acts on the
    /// manifold as a whole, at the centroid of its points: a tangential impulse inside the
    /// disc μ Σλn and a twisting impulse about the normal inside μ Σλn × the patch radius.
    /// Solved per patch, friction has no order among the points to favour, so a symmetric
    /// stack stays symmetric.
    struct Block {
        int begin = 0, count = 0;
        Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
        Eigen::Matrix4d Kinv = Eigen::Matrix4d::Zero();
        double mu = 0.0;
        Vec3 rA, rB, t1, t2;  // centroid offsets, tangents
        // As Point's for the rows t1, t2 at the centroid and the twist about n:
        // r × t and I⁻¹(r × t) per body and tangent, I⁻¹ n per body.
        Vec3 armA[2], armB[2], spinA[2], spinB[2], twistA, twistB;
        Eigen::Matrix2d tangentMass;  // inverse of the 2x2 tangential K at the centroid
        double twistMass = 0.0, radius = 0.0;
        Eigen::Vector2d lambdaT = Eigen::Vector2d::Zero();
        double lambdaTwist = 0.0;
        // What the shock pass added to the friction (shock_propagation.cpp): applied to the
        // bodies and counted in the ledger, but not remembered for the next warm start.
        Eigen::Vector2d shockT = Eigen::Vector2d::Zero();
        double shockTwist = 0.0;
        /// All the friction this solve applied (the ledger, sliding friction's re-posing).
        Eigen::Vector2d frictionApplied() const { return lambdaT + shockT; }
        double twistApplied() const { return lambdaTwist + shockTwist; }
        // The friction impulses the warm start gave: a block at rest that ends with about
        // them is remembered as it was (remember).
        Eigen::Vector2d warmT = Eigen::Vector2d::Zero();
        double warmTwist = 0.0;
        bool warmWhole = false;  // every point started from a remembered point, unscaled
        int subsets = -1;        ///< its entry in the pool of sub-inverses once it needs one (-1: none yet)
        bool arriving = false;   ///< a point apart at the step's start, or meeting fast (redoPoses)
    };
    /// A joint's rows in this solve (joints.cpp): a ball's three, through the 3 × 3 inverse
    /// of its effective mass; a distance's or rope's one, along the anchors' line.
    struct JointRow {
        int joint = 0, a = 0, b = 0;       // b: a body index (the world's row has an immovable body)
        Vec3 rA, rB;                       // world arms from the centres of mass to the anchors
        Mat3 Kinv = Mat3::Zero();          // ball
        Vec3 n, armA, armB, spinA, spinB;  // distance and rope: as a contact point's normal row
        double k = 0.0, target = 0.0;
        bool ball = false;           // three rows (else one along n)
        bool pullsOnly = false;      // rope
        Vec3 lambda = Vec3::Zero();  // accumulated impulse (x alone for a single row)
        int general = -1;            // hinge, slider, fixed: its entry in generalRows
        // A ball joint's cone and twist limits (joint_cone.h): one-sided angular rows keeping
        // the rate (ωA − ωB)·axis on its side of `target`, λ ≥ 0 (sign +1) or ≤ 0 (−1); kept
        // in angularRows[angularBegin ..] (a row here for every joint slowed ragdoll piles).
        struct Angular {
            Vec3 axis = Vec3::Zero();
            double k = 0.0, target = 0.0, lambda = 0.0;
            int sign = 0;
        };
        int angularBegin = 0, angulars = 0;
    };
    /// A hinge's, slider's, fixed or six-axis joint's locked rows (joint_general.h): up to
    /// six, solved together through the inverse of their effective mass.
    struct GeneralRow {
        int m = 0;  // rows
        // Per row (a column): the impulse's effect on A's and B's (v, ω) per unit, i.e. the
        // rows of the Jacobian; and M⁻¹ times them.
        Eigen::Matrix<double, 6, 6> JA = Eigen::Matrix<double, 6, 6>::Zero(),
                                    JB = Eigen::Matrix<double, 6, 6>::Zero();
        Eigen::Matrix<double, 6, 6> Kinv = Eigen::Matrix<double, 6, 6>::Zero();
        Eigen::Matrix<double, 6, 1> lambda = Eigen::Matrix<double, 6, 1>::Zero();
        Mat3 lin = Mat3::Zero(), ang = Mat3::Zero();  // the rows' directions (columns)
        int nl = 0, na = 0;
        // Its free axes that something acts on (a hinge's or slider's, a six-axis joint's
        // not locked), in axisRows.
        int axisBegin = 0, axes = 0;
        // Its spring and servo (joint_drive.h): the rate after is κ v* + target, solved as
        // the soft row (1 − κ) v + (κ / mass) λ = target, `mass` the axis's with the joint's
        // other rows held, λ within ±most.
        // `hard`: a rate row instead (a servo by its time constant), `target` its rate.
        struct Drive {
            double kappa = 1.0, target = 0.0, mass = 0.0, gain = 0.0, lambda = 0.0, most = HUGE_VAL;
            bool hard = false;
        };
    };
    // A free axis's row (its Jacobian columns, the coordinate along it: angle or offset) and
    // the scalar rows of its motor, limits, spring and servo.
    struct AxisRow {
        const JointAxis* settings = nullptr;
        Eigen::Matrix<double, 6, 1> JAx, JBx;  // (set with the axis: generalRows)
        double coord = 0.0, kAxis = 0.0;
        bool motor = false, lowerOn = false, upperOn = false;
        double motorSpeed = 0.0, motorMax = 0.0, motorLambda = 0.0;
        double lowerTarget = 0.0, lowerLambda = 0.0, upperTarget = 0.0, upperLambda = 0.0;
        int driveBegin = 0, drives = 0;            // in driveRows
        double startRate = 0.0, startCoord = 0.0;  // the coordinate's at the step's start
    };
    std::vector<GeneralRow> generalRows;
    std::vector<JointRow::Angular> angularRows;  // the balls' cone and twist rows
    std::vector<AxisRow> axisRows;               // the free axes acted on
    std::vector<GeneralRow::Drive> driveRows;    // the free axes' springs and servos
    /// The state at the start of the interval the solve covers (solveIsland sets it; the
    /// joints' springs and servos read their coordinate there).
    const State* stepStart = nullptr;
    /// The kinetic energy the joints' rows gave their bodies since prepareJoints (negative:
    /// took), each impulse's λ·(u⁻ + u⁺)/2 with u the row's velocity before and after it.
    double jointWork = 0.0;
    /// Per joint: the impulse on A the step's first projection gave the velocities (RATTLE's
    /// half of the joint's force; the rows give the rest), for breaking.
    std::vector<Vec3> projectedImpulse;
    /// Per joint: the couple on A the same projection gave (hinge, slider, fixed), for the
    /// joint's reaction (State::jointCouples).
    std::vector<Vec3> projectedCouple;
    /// Per joint, in the joints' position passes: whether it was last found holding, with
    /// its error then and its bodies' poses (joints.cpp projectionPass).
    struct JointCheck {
        struct Place {
            Vec3 x = Vec3::Zero();
            Quat q = Quat::Identity();
        } a, b;
        double error = 0.0;
        bool held = false;
    };
    std::vector<JointCheck> jointChecks;
    PageVector<Point> points;            // (make_room.h: their old room is given back when they grow)
    PageVector<PointGeometry> geometry;  // per point
    PageVector<Block> blocks;
    std::vector<JointRow> jointRows;
    /// The largest joint error (m or rad) the solve's last projection left (projectJoints) in
    /// groups of at most 64 joints, and the largest of those over the step's end-of-step
    /// solves (World::finishStep); the same over every joint (`All`), and over the pieces of
    /// a composed step (World::stepComposed).
    double jointsOpen = 0.0, stepJointsOpen = 0.0;
    double jointsOpenAll = 0.0, stepJointsOpenAll = 0.0, composedJointsOpenAll = 0.0;
    // K's sub-inverses (pushingImpulses), for the blocks that have needed one (Block::subsets):
    // most blocks never let a point go, and an entry for every block was 288 bytes each.
    std::vector<SubsetInverses> subsets;
    std::vector<SubsetInverses> frozenSubsets;  // the same for the frozen blocks (shockPass)
    std::vector<SolverBody> bodies;
    std::vector<BodyVelocity> start;      // velocities at the start of the step
    std::vector<Vec3> bodySpin;           // ω in body axes, kept while bodies are re-placed
    std::vector<int> level;               // contacts between a body and one that cannot move (shockPass)
    std::vector<int> order;               // blocks from the bottom up
    PageVector<Block> frozen;             // the blocks of one level with its lower bodies standing still
    std::vector<int> frozenBodies;        // the lower bodies held still, all levels so far
    std::vector<SolverBody> savedBodies;  // their entries before (the same order)
    std::vector<int> moving;              // the dynamic bodies the solver moved
    std::vector<int> involved;            // the bodies of the contacts, ascending (all the solve touches)
    std::vector<BodyVelocity> entry;      // the velocities the solver was given
    std::vector<std::pair<Vec3, Quat>> placed;  // poses before the energy-limited correction
    std::vector<Mat3> rotation;                 // per body: its rotation matrix in the position passes
    // The position passes' skipping (correctPositions): per body, the nudge that last moved
    // it; per point, the nudge count when it was last found within its slop (-1: not).
    std::vector<long> nudgedAt;
    std::vector<long> settledAt;
    struct MemoryRun {
        std::uint64_t key;  // pairKey
        int begin, end;     // the pair's range in State::contacts
    };
    std::vector<MemoryRun> memory;   // sorted by key (a map's nodes were an allocation per pair and step)
    std::vector<std::uint8_t> used;  // remembered points already taken this step (warmStart)
    // The islands' new memory when State::contacts has no room for it after the old
    // (solveContacts, rememberIsland).
    std::vector<ContactMemory> fresh;
    bool toFresh = false;
    std::vector<std::uint8_t> seen;  // bodiesOf's flags
    // The passes' skipping (iterate): per block, the update after which it was quiet (-1: it
    // changed something); per body, the update that last changed its velocity.
    std::vector<long> quietSince;
    std::vector<long> changedAt;
    long tick = 0;
    // A large island's blocks in two regions and their boundary (block_regions.h): region r's
    // are blocks[regionBegin[r] .. regionBegin[r + 1]), the boundary's from regionBegin[2];
    // `split` false: not split. While they are made: the movable bodies in order along the
    // cut, each body's blocks, each body's region, each block's group, and the blocks in group order
    // (by their index in blockManifold as chosen); per region on the pool, the blocks that
    // want an entry in `subsets`.
    bool split = false;
    std::array<int, 4> regionBegin{};
    std::vector<int> cut, regionBlocks, bodyBlocks;
    std::vector<std::int8_t> bodyRegion, blockRegion;
    std::array<std::vector<int>, 2> wants;
    long pooledRegions = 0;  // passes whose regions went to the pool (Profile)
    // Per block, its manifold in the island's list, which of its points are solved (bits) and
    // where its points begin; whether making the blocks pays on the pool (contact_prepare.h).
    std::vector<int> blockManifold, spareManifold, blockFirst;
    std::vector<std::uint8_t> blockPoints, sparePoints;
    PoolGate prepareGate;
    // Per body: how many directions it slides across (-1: held), and those normals (redoPoses).
    std::vector<int> slideCount;
    std::vector<std::array<Vec3, 3>> slideNormals;
    std::vector<int> slideBlock;  // per body: its only block this solve, -1 none, -2 several
    struct Pose {
        Vec3 x;
        Quat q;
    };
    std::vector<Pose> poses;  // per body: the poses the ledger measures a move from (keepPoses)
    // Islands at their fixed point (still_islands.h): per body, 1 for the bodies whose
    // contacts are taken as last solved (null: none); set by World around one solve.
    const std::vector<std::uint8_t>* still = nullptr;
    std::vector<int> stillMoving;    // the still bodies the solve would have moved (s.moving's share)
    int stillBodies = 0;             // of the last solve's bodies, how many were still
    std::vector<std::uint8_t> kept;  // per block: remembered as it was (keepsMemory)
    // Per body, what a still body adds to the sums over all bodies, as its last solve found
    // it: its kinetic energy after the warm start, the friction losses of its blocks.
    std::vector<double> warmKinetic;
    std::vector<double> frictionShare;
    // Per body (World's StillScratch::changed): set when a remembered impulse of its
    // contacts changed or went (remember), or one of its points overlaps by more than the
    // slop after the solve (correctPositions); null: not kept.
    std::vector<std::uint8_t>* memoryChanged = nullptr;
    // The islands (contactIslands): union-find per body, each manifold's island, the
    // manifolds island by island, and the one island being solved.
    std::vector<int> parent, islandOfRoot, roots, islandOf, islandBegin, islandFill, islandManifolds;
    collision::ManifoldList islandContacts;
    std::vector<int> springs;  // Model::forces' springs, by index (sizeContactSolver)
    // Islands solved on the worker threads (solveContacts, issue 53): the pool (World sets it;
    // null: one thread), whether a solve's islands are worth it (timed by their points), and a
    // scratch of its own for each thread (a lane: each island's solve reads nothing a lane
    // kept from an earlier one but the memory index, copied in, so any lane gives the same
    // answer). Per island, in island order: where its memory went in its lane's `fresh`, and
    // what it booked in the ledger (added up in island order on any number of threads).
    Workers* pool = nullptr;
    PoolGate islandsGate;
    std::vector<std::unique_ptr<ContactSolverScratch>> lanes;
    struct IslandOut {
        int lane = 0;
        size_t begin = 0, end = 0;
        EnergyLedger ledger;
    };
    std::vector<IslandOut> islandOut;
    std::vector<int> islandOrder;  // the islands largest first, as the lanes take them
    std::vector<std::uint8_t> laneChanged;  // a lane's own memoryChanged flags (merged after)
    long pooledSolves = 0;                  // solves whose islands went to the pool (Profile)
};

/// A body whose contacts this solve takes as last solved (still_islands.h).
inline bool isStill(const ContactSolverScratch& s, int i) {
    return s.still && (*s.still)[i];
}

struct ContactSolverSettings {
    int iterations = 20;  ///< velocity iterations
    int positionIterations = 4;
    double quietSpeed = 0.0;      ///< a block whose update changes its velocity less is left alone (iterate)
    double h = 1.0 / 240.0;       ///< the (last part of the) step, for speculative points and warm starting
    double restingSpeed = 0.0;    ///< below this approach speed, no bounce
    double touchTolerance = 0.0;  ///< points deeper than minus this touch
    double margin = 0.0;          ///< points deeper than minus this are solved (their gap may close)
};

/// How much a remembered impulse from a solve over `before` seconds is scaled for one over
/// `h`: h / before (a resting contact's impulse, a joint's tension, grow with the step), at
/// most `most`; 1 when `before` is unknown (0). solveContacts first tries the bound of 100
/// and falls back to 1 when that start adds kinetic energy (see there).
inline double warmScale(double h, double before, double most) {
    return before > 0.0 ? std::min(h / before, most) : 1.0;
}

/// Sizes the scratch's per-body arrays for `model` (World's constructor: at loading, not in
/// the first step; see sizeSolverBodies).
void sizeContactSolver(const Model& model, ContactSolverScratch& scratch);

/// Solves the velocities of the contacts and removes their overlap; writes the momenta
/// and poses of the dynamic bodies, the impulses to remember (State::contacts, keeping
/// those of sleeping pairs) and the ledger. `sizes`: per body, the bounding radius.
/// `before`: the state at the start of the (last part of the) step: a body the solver
/// pushed is moved again from there with its new velocity (x = x0 + h v, q turned by h ω),
/// so that the motion the contact forbids (sinking, creeping down a slope) never happens.
void solveContacts(const Model& model, State& state, const State& before,
                   const collision::ManifoldList& contacts, const std::vector<double>& sizes,
                   const ContactSolverSettings& settings, ContactSolverScratch& scratch,
                   EnergyLedger& ledger);

}  // namespace tumble
