#include "solver/contact_solver.h"

#include "common/make_room.h"
#include "common/pair_key.h"
#include "islands/islands.h"
#include "solver/block_regions.h"
#include "solver/contact_energy.h"
#include "solver/contact_islands.h"
#include "solver/contact_prepare.h"
#include "solver/contact_rows.h"
#include "solver/joint_general.h"
#include "solver/joint_math.h"
#include "solver/joints.h"
#include "solver/place_bodies.h"
#include "solver/shock_propagation.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tumble {

using collision::Manifold;
using collision::ManifoldList;
using Point = ContactSolverScratch::Point;

namespace {

constexpr double kMatch = 0.1;   // a remembered point is the same within this × size
constexpr int kShockPasses = 4;  // passes per level of the last sweep (shock_propagation.cpp)
constexpr double kStillSpeed =
    1e-8;  // × the resting speed: slower is the passes' rounding (stopRoundingMotion)

template <class T>
bool sameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

void indexMemory(const State& state, ContactSolverScratch& s) {
    s.memory.clear();
    const auto& mem = state.contacts;
    for (int i = 0; i < static_cast<int>(mem.size());) {
        int j = i;
        while (j < static_cast<int>(mem.size()) && mem[j].bodyA == mem[i].bodyA &&
               mem[j].bodyB == mem[i].bodyB)
            ++j;
        s.memory.push_back({pairKey(mem[i].bodyA, mem[i].bodyB), i, j});
        i = j;
    }
    // By pair, the first run of a pair first (the lookup takes it, as a map's first insert).
    std::sort(s.memory.begin(), s.memory.end(), [](const auto& x, const auto& y) {
        return x.key < y.key || (x.key == y.key && x.begin < y.begin);  // stable, without a buffer
    });
}

// The remembered point that this point continues, not yet taken by another point of this
// step: each remembered impulse starts one point only (when a manifold gains points, two
// new points near one old one took its impulse twice, and the warm start kicked a box of a
// resting pyramid to 1.2 m/s).
const ContactMemory* remembered(const State& state, ContactSolverScratch& s, const Point& p,
                                const ContactSolverScratch::PointGeometry& g) {
    const std::uint64_t key = pairKey(p.a, p.b);
    const auto it = std::lower_bound(s.memory.begin(), s.memory.end(), key,
                                     [](const auto& x, std::uint64_t k) { return x.key < k; });
    if (it == s.memory.end() || it->key != key) return nullptr;
    // The same pair of features if it is still near; else the nearest remembered point
    // (features are renamed when, say, the reference face passes from one box to the other
    // in a stack: the impulses at the same corner still hold).
    int same = -1, nearest = -1;
    double nearestD = kMatch * g.size;
    for (int i = it->begin; i < it->end; ++i) {
        if (s.used[i]) continue;
        const ContactMemory& c = state.contacts[i];
        const double d = (c.position - g.position).norm();
        if (d > kMatch * g.size) continue;
        if (c.feature == g.feature) same = i;
        if (d <= nearestD) nearest = i, nearestD = d;
    }
    const int k = same >= 0 ? same : nearest;
    if (k < 0) return nullptr;
    s.used[k] = 1;
    return &state.contacts[k];
}

// Starts blocks [begin, end) from the remembered impulses, scaled to this step's length (a
// short step to land on a frame needs proportionally less), at most `growth` times
// (warmScale). Whether any was scaled up.
bool warmStartBlocks(const State& state, double h, double growth, ContactSolverScratch& s, int begin, int end) {
    bool grew = false;
    for (int k = begin; k < end; ++k) {
        ContactSolverScratch::Block& block = s.blocks[k];
        Vec3 tangent = Vec3::Zero();
        double twist = 0.0;
        block.warmWhole = true;
        for (int i = 0; i < block.count; ++i) {
            Point& p = s.points[block.begin + i];
            const ContactMemory* c = remembered(state, s, p, s.geometry[block.begin + i]);
            ContactSolverScratch::PointGeometry& g = s.geometry[block.begin + i];
            g.memory = c ? static_cast<int>(c - state.contacts.data()) : -1;
            if (!c) {
                block.warmWhole = false;
                continue;
            }
            const double scale = warmScale(h, c->step, growth);
            block.warmWhole = block.warmWhole && scale == 1.0;
            g.warmNormal = c->normalImpulse;
            g.warmTangent = c->tangentImpulse;
            g.warmTwist = c->twistImpulse;
            grew = grew || scale > 1.0;
            p.lambdaN = scale * c->normalImpulse;
            tangent += scale * c->tangentImpulse;
            twist += scale * c->twistImpulse;
            const Vec3 J = p.lambdaN * p.n;  // (applyPairImpulse without the energy it would return)
            const Vec3& at = s.geometry[block.begin + i].position;
            // (A body that cannot move is not written: two regions start side by side.)
            if (s.bodies[p.a].invMass > 0.0) applyImpulse(s.bodies[p.a], at - s.bodies[p.a].x, J);
            if (s.bodies[p.b].invMass > 0.0) applyImpulse(s.bodies[p.b], at - s.bodies[p.b].x, -J);
        }
        block.lambdaT = Eigen::Vector2d(block.t1.dot(tangent), block.t2.dot(tangent));
        block.lambdaTwist = twist;
        block.warmT = block.lambdaT;
        block.warmTwist = twist;
        applyFriction(s, block, block.lambdaT, twist);
    }
    return grew;
}

// All the blocks; a split island's two regions side by side, then the boundary: the same as
// one run over the blocks in their order, since the regions share no movable body and no
// pair (remembered() takes points of the block's own pair only). Whether any was scaled up.
bool warmStart(const State& state, double h, double growth, ContactSolverScratch& s) {
    const int nb = static_cast<int>(s.blocks.size());
    if (!s.split) return warmStartBlocks(state, h, growth, s, 0, nb);
    const auto& at = s.regionBegin;
    bool grew[2] = {false, false};
    onRegions(s, [&](int r) { grew[r] = warmStartBlocks(state, h, growth, s, at[r], at[r + 1]); });
    return warmStartBlocks(state, h, growth, s, at[2], at[3]) || grew[0] || grew[1];
}

// One pass over the blocks, forwards on even passes and backwards on odd ones so that
// their order leaves no bias. Returns whether any block changed: a pass that changed none
// leaves every block's input as it found it, so every later pass would change none either
// (a ball rolling on the ground is there after two passes of twenty).
//
// The same holds block by block: a block's update reads only its own impulses and its two
// bodies' velocities, so a block whose last update changed nothing is skipped until another
// block changes one of its bodies (a hull at rest on the ground is left alone while the
// ones still landing iterate). "Nothing" is up to `quietSpeed` (an impulse change of at
// most that speed times the block's first normal mass, 1e-10 of the resting speed from
// World): the blocks of a resting pile otherwise hover in their last bits for all twenty
// passes (piles-sleep-off: 6.0 M block updates in 600 steps, 0.52 M with the tolerance).
// Between moving bodies "nothing" is also up to 1e-4 of how fast they move (updateBlock).
// Stamps count block updates within the step; a body that cannot move (static, kinematic)
// is never stamped, since no impulse changes it.
bool iterate(ContactSolverScratch& s, int pass, double quietSpeed) {
    const int nb = static_cast<int>(s.blocks.size());
    bool changed = false;
    for (int b = 0; b < nb; ++b) changed |= updateBlock(s, pass % 2 ? nb - 1 - b : b, quietSpeed);
    // The joints in the same pass, on the same bodies (joints.h).
    const int nj = static_cast<int>(s.jointRows.size());
    for (int j = 0; j < nj; ++j) changed |= updateJoint(s, pass % 2 ? nj - 1 - j : j, quietSpeed);
    return changed;
}

// solvedKinetic(s.bodies) right after the warm start, each solved body's term kept and
// each still body's taken as kept (its warm start is not made, and would give the same).
double kineticAfterWarmStart(const Model& model, const State& state, ContactSolverScratch& s) {
    if (!s.memoryChanged) return solvedKinetic(model, state, s, s.bodies);
    double e = 0.0;
    for (int i : s.involved) {
        if (!(s.bodies[i].invMass > 0.0)) continue;
        if (!isStill(s, i)) s.warmKinetic[i] = kineticOf(model.bodies[i], state.bodies[i].q, s.bodies[i]);
        e += s.warmKinetic[i];
    }
    return e;
}

// The warm start of the contacts and joints. Remembered impulses are scaled to this step's
// length, up to kWarmGrowth times after a shorter solve (the last part of a step after a
// cut, a short step to land on a frame). What such a short solve did was not all weight
// and tension: it also stopped motion, which does not grow with the step, and scaled up it
// threw bodies apart (a pile of 20 ragdolls at 1/60 s went from 321 J of kinetic energy to
// 3.4e8 J in one warm start; drop-3000 kept 2 899 of its 3 008 boxes moving after 3 s). A
// start that raises the kinetic energy by more than a tenth is taken back and made again
// with the impulses as they were (no growth).
void warmStartChecked(const Model& model, const State& state, double h, ContactSolverScratch& s) {
    constexpr double kWarmGrowth = 100.0;
    const bool contactsGrew = warmStart(state, h, kWarmGrowth, s);
    const bool grew = prepareJoints(model, state, h, s, false, nullptr, kWarmGrowth) || contactsGrew;
    // (Kept for every body whenever the still islands are followed, grown or not: a body
    // still next step takes its term from here.)
    const bool keep = s.memoryChanged != nullptr;
    const double after = grew || keep ? kineticAfterWarmStart(model, state, s) : 0.0;
    if (grew && after > 1.1 * solvedKinetic(model, state, s, s.entry)) {
        for (int i : s.involved) static_cast<BodyVelocity&>(s.bodies[i]) = s.entry[i];
        for (const ContactSolverScratch::PointGeometry& g : s.geometry)
            if (g.memory >= 0) s.used[g.memory] = 0;  // (this solve's points took them)
        warmStart(state, h, 1.0, s);                  // (sets again every remembered point's impulse)
        prepareJoints(model, state, h, s);
    }
    // The still bodies end the solve at rest, as they started it (still_islands.h).
    if (s.still)
        for (int i : s.involved)
            if (isStill(s, i)) s.bodies[i].v.setZero(), s.bodies[i].w.setZero();
}

// Whether a block is remembered as it was: its points all started from remembered points,
// unscaled, its bodies end the solve at rest (stopRoundingMotion) and its impulses moved
// by no more than the passes' quiet tolerance (`quietSpeed` times its normal mass). The
// passes' last updates move a resting block's impulses by rounding, differently every
// step: remembered as they came out, a pile at rest would never come to a fixed point
// (hull-rain: the impulses of nine resting points in ten differed in their last bits from
// step to step while their rocks stood still to the bit; still_islands.h). Friction is
// remembered as each point's share of its block's, which the warm start adds up again:
// made again from the sum, the shares would differ by rounding too.
bool keepsMemory(const ContactSolverScratch& s, const ContactSolverScratch::Block& block, double quietSpeed) {
    if (!block.warmWhole) return false;
    const Point& p = s.points[block.begin];
    if (!atRest(s.bodies[p.a]) || !atRest(s.bodies[p.b])) return false;
    const double tol = quietSpeed * p.kn;
    for (int i = 0; i < block.count; ++i)
        if (!(std::abs(s.points[block.begin + i].lambdaN - s.geometry[block.begin + i].warmNormal) <= tol))
            return false;
    return (block.lambdaT - block.warmT).cwiseAbs().maxCoeff() <= tol &&
           std::abs(block.lambdaTwist - block.warmTwist) <= tol * block.radius;
}

// The memory of the block's point i after a solve over h (`kept`: keepsMemory).
ContactMemory memoryOf(const ContactSolverScratch& s, const ContactSolverScratch::Block& block, int i,
                       double h, bool kept) {
    const Point& p = s.points[block.begin + i];
    const ContactSolverScratch::PointGeometry& g = s.geometry[block.begin + i];
    ContactMemory c;
    c.bodyA = p.a;
    c.bodyB = p.b;
    c.feature = g.feature;
    c.position = g.position;
    if (kept) {
        c.normalImpulse = g.warmNormal;
        c.tangentImpulse = g.warmTangent;
        c.twistImpulse = g.warmTwist;
    } else {
        c.normalImpulse = p.lambdaN;
        c.tangentImpulse = (block.lambdaT[0] * block.t1 + block.lambdaT[1] * block.t2) / block.count;
        c.twistImpulse = block.lambdaTwist / block.count;
    }
    c.step = h;
    return c;
}

// The remembered points that go: those of solved pairs that no point took.
template <class Idle>
void markDroppedMemory(const State& state, ContactSolverScratch& s, bool warmStarted, const Idle& idle,
                       size_t fresh) {
    std::vector<std::uint8_t>& changed = *s.memoryChanged;
    const std::vector<ContactMemory>& memory = state.contacts;
    for (size_t k = 0; k < fresh; ++k) {
        const ContactMemory& c = memory[k];
        if (idle(c.bodyA) && idle(c.bodyB)) continue;  // kept as it is
        if (!warmStarted || k >= s.used.size() || !s.used[k]) changed[c.bodyA] = changed[c.bodyB] = 1;
    }
}

// What rememberIsland is about to write, against what the points started from: the points
// of this island's blocks whose memory is not what they started from.
void markChangedMemory(const State& state, double h, ContactSolverScratch& s) {
    std::vector<std::uint8_t>& changed = *s.memoryChanged;
    const std::vector<ContactMemory>& memory = state.contacts;
    for (size_t b = 0; b < s.blocks.size(); ++b) {
        const auto& block = s.blocks[b];
        // Every block, moving bodies' too: the energy limit, after this, can stop a body
        // that moves here (all of a step's motion scaled by 0), which then ends at rest.
        for (int i = 0; i < block.count; ++i) {
            const ContactMemory m = memoryOf(s, block, i, h, s.kept[b]);
            const int k = s.geometry[block.begin + i].memory;
            const ContactMemory* c = k >= 0 ? &memory[k] : nullptr;
            const bool same = c && c->feature == m.feature && sameBits(c->position, m.position) &&
                              sameBits(c->normalImpulse, m.normalImpulse) &&
                              sameBits(c->tangentImpulse, m.tangentImpulse) &&
                              sameBits(c->twistImpulse, m.twistImpulse) && sameBits(c->step, h);
            if (!same) changed[m.bodyA] = changed[m.bodyB] = 1;
        }
    }
}

// State::contacts made the memory of this solve, in place: the pairs not solved because
// they sleep (or stand still) keep what they had (and tell who rests on whom when
// something wakes them), the solved points are added after them. (A second list traded
// with this one every solve held as much again: a third of a megabyte of hull-rain's
// peak, with its ~1 100 points of sleeping rocks.) First the memory of the pairs solved
// goes, of the points before `fresh` (those from `fresh` on are this solve's, added island
// by island: they stay, after the others); with s.memoryChanged, the bodies of every
// remembered point of a solved pair that no point took (`warmStarted`: the points' sources
// are known) are marked there.
void dropSolvedMemory(const Model& model, State& state, ContactSolverScratch& s, bool warmStarted,
                      size_t fresh) {
    auto idle = [&](int b) { return state.isAsleep(b) || model.bodies[b].standsStill() || isStill(s, b); };
    if (s.memoryChanged) markDroppedMemory(state, s, warmStarted, idle, fresh);
    std::vector<ContactMemory>& m = state.contacts;
    const auto fromFresh = m.begin() + static_cast<std::ptrdiff_t>(fresh);
    m.erase(std::remove_if(m.begin(), fromFresh,
                           [&](const ContactMemory& c) { return !(idle(c.bodyA) && idle(c.bodyB)); }),
            fromFresh);
}

// ... then this island's points are added: when it is the only island, once the memory
// of its pairs is dropped; else after the memory as it was (the islands after this one
// take their warm starts from that part only, as solveContacts indexed it), or to s.fresh
// when solveContacts found no room there (s.toFresh). With s.memoryChanged, the bodies of
// every point whose memory is not the one it started from, bit for bit, are marked there.
void rememberIsland(const Model& model, State& state, double h, double quietSpeed, ContactSolverScratch& s,
                    bool onlyIsland) {
    s.kept.resize(s.blocks.size());
    for (size_t b = 0; b < s.blocks.size(); ++b) s.kept[b] = keepsMemory(s, s.blocks[b], quietSpeed);
    if (s.memoryChanged) markChangedMemory(state, h, s);
    if (onlyIsland) dropSolvedMemory(model, state, s, true, state.contacts.size());
    std::vector<ContactMemory>& out = !onlyIsland && s.toFresh ? s.fresh : state.contacts;
    makeRoom(out, out.size() + s.points.size());
    for (size_t b = 0; b < s.blocks.size(); ++b)
        for (int i = 0; i < s.blocks[b].count; ++i) out.push_back(memoryOf(s, s.blocks[b], i, h, s.kept[b]));
}

// A body the contacts hold whose velocity the solve left below `still` (and whose spin
// moves its far side slower than that) is at rest: what is left is the passes' rounding,
// not motion. (A resting rock on three triangles kept 1e-15 to 1e-10 m/s from its blocks'
// last passes, so it never stood still to the bit and the narrowphase could not take its
// pairs as last found: hull-rain with sleeping off looked at 230 of its 302 pairs again
// every step.) Only ever takes energy away.
void stopRoundingMotion(const std::vector<double>& sizes, double still, ContactSolverScratch& s) {
    if (!(still > 0.0)) return;
    for (int i : s.involved) {
        SolverBody& b = s.bodies[i];
        if (b.invMass == 0.0 || !b.touched) continue;
        if (b.v.squaredNorm() < still * still && b.w.squaredNorm() * sizes[i] * sizes[i] < still * still) {
            b.v.setZero();
            b.w.setZero();
        }
    }
}

// The potential energy of the solve's bodies (gravity and their springs): what the position
// passes can change. (The springs are listed once, in sizeContactSolver: a solve per island
// went over every force of the model each time.)
double potentialOf(const Model& model, const State& state, const ContactSolverScratch& s) {
    const std::vector<int>& only = s.involved;
    double e = gravityPotential(model, state, only);
    for (int k : s.springs) {
        const ForceTerm& f = model.forces[k];
        if (!f.activeAt(state.time) || !std::binary_search(only.begin(), only.end(), f.body)) continue;
        const BodyState& s = state.bodies[f.body];
        const double stretch = (s.x + s.q * f.arm - f.anchor).norm() - f.restLength;
        e += 0.5 * f.stiffness * stretch * stretch;
    }
    return e;
}

// The poses of the solve's bodies now (s.poses, by body), for potentialChange.
void keepPoses(const State& state, ContactSolverScratch& s) {
    s.poses.resize(state.bodies.size());
    for (int i : s.involved) s.poses[i] = {state.bodies[i].x, state.bodies[i].q};
}

// How much the potential energy of the solve's bodies changed from s.poses to `state`,
// summed from each body's own move and each spring's own stretch, not as the difference of
// two totals: a resting pyramid's totals of 1e4 J lost 1.4e-11 J a step to their rounding,
// which the ledger then booked as energy the contacts made.
double potentialChange(const Model& model, const State& state, const ContactSolverScratch& s) {
    const Vec3& g = model.settings.gravity;
    double change = 0.0;
    for (int i : s.involved)
        if (model.bodies[i].motion == Motion::Dynamic)
            change -= model.bodies[i].mass * g.dot(state.bodies[i].x - s.poses[i].x);
    const std::vector<int>& only = s.involved;
    for (int k : s.springs) {
        const ForceTerm& f = model.forces[k];
        if (!f.activeAt(state.time) || !std::binary_search(only.begin(), only.end(), f.body)) continue;
        const BodyState& now = state.bodies[f.body];
        const ContactSolverScratch::Pose& was = s.poses[f.body];
        const double a = (now.x + now.q * f.arm - f.anchor).norm() - f.restLength;
        const double b = (was.x + was.q * f.arm - f.anchor).norm() - f.restLength;
        change += 0.5 * f.stiffness * (a - b) * (a + b);
    }
    return change;
}

// The kinetic energy of the solve's bodies as s.bodies has them, and their potential
// energy in `state` (the joints' first projection changes both).
double solvedEnergy(const Model& model, const State& state, const ContactSolverScratch& s) {
    return solvedKinetic(model, state, s, s.bodies) + potentialOf(model, state, s);
}

}  // namespace

// The solve of one island (contactIslands): of all the contacts and joints when the model
// has joints.
void solveIsland(const Model& model, State& state, const State& before, const ManifoldList& contacts,
                 const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s,
                 EnergyLedger& ledger, bool onlyIsland) {
    s.stepStart = &before;
    bodiesOf(contacts, s.seen, s.involved);
    addJointBodies(model, state, s.involved, s.seen);
    loadSolverBodies(model, state, s.bodies, s.involved);
    chordVelocities(model, state, before, s.bodies, s.involved);
    if (s.still)
        s.stillBodies += static_cast<int>(
            std::count_if(s.involved.begin(), s.involved.end(), [&](int i) { return isStill(s, i); }));
    // The jointed bodies' free step put them off their joints: placed back now, with the
    // velocity that move implies; the velocity rows below then act at the joints' new
    // places (RATTLE's two halves), and these bodies keep these poses (redoPoses).
    if (!model.joints.empty()) {
        const double energy = solvedEnergy(model, state, s);
        projectJoints(model, state, s, cfg.h, &before);
        ledger.lostInJoints += energy - solvedEnergy(model, state, s);
    }
    prepareContacts(model, state, before, contacts, sizes, cfg, s);
    s.entry.resize(s.bodies.size());  // only the solved bodies' entries are read
    for (int i : s.involved) s.entry[i] = s.bodies[i];
    warmStartChecked(model, state, cfg.h, s);  // and the joints' rows
    s.quietSince.assign(s.blocks.size(), -1);
    s.tick = 0;
    s.changedAt.resize(s.bodies.size());
    for (int i : s.involved) s.changedAt[i] = 0;
    bool converged = false;
    // A large island's two regions side by side (block_regions.h).
    for (int k = 0; k < cfg.iterations && !converged; ++k)
        converged = !(s.split ? iterateRegions(s, k, cfg.quietSpeed) : iterate(s, k, cfg.quietSpeed));
    // (Not with joints yet: the shock pass holds bodies still that a joint may have to move.)
    if (!s.blocks.empty() && s.jointRows.empty())
        shockPass(s, kShockPasses, converged, cfg.quietSpeed, kStillSpeed * cfg.restingSpeed);
    stopRoundingMotion(sizes, kStillSpeed * cfg.restingSpeed, s);
    rememberIsland(model, state, cfg.h, cfg.quietSpeed, s, onlyIsland);
    rememberJoints(model, s, cfg.h, state);
    if (s.points.empty() && s.jointRows.empty() && s.stillMoving.empty()) return;

    // The bodies of the solved points and joints: the solver may have moved them, and the
    // position passes may.
    s.moving.clear();
    for (const Point& p : s.points)
        for (int i : {p.a, p.b})
            if (s.bodies[i].invMass > 0.0) s.moving.push_back(i);
    for (const ContactSolverScratch::JointRow& r : s.jointRows)
        for (int i : {r.a, r.b})
            if (i >= 0 && s.bodies[i].invMass > 0.0) s.moving.push_back(i);
    s.moving.insert(s.moving.end(), s.stillMoving.begin(), s.stillMoving.end());
    uniqueBodies(s.moving, s.seen);
    EnergyBalance e = energyBalance(model, state, before, s);
    // The energy limit is the contacts' (they must never add energy); with joints in the
    // same solve, scaling the velocities would break the joints, so it is left out there.
    const bool limited = passive(model, contacts, s) && s.jointRows.empty();
    if (limited && e.excess() > 0.0) limitEnergy(model, state, e, s, state.time - before.time);
    // Friction's work with the velocities the bodies leave with (after the limit, which
    // stopped a resting pyramid's last rounding: taken before it, friction booked −0.012 J).
    const double frictionLoss = frictionLost(s);
    // The joints' rows took what their impulses took (jointWork, exact per row); the
    // contacts the rest of what the solve took beyond friction.
    ledger.lostInFriction += frictionLoss;
    ledger.lostInJoints -= s.jointWork;
    const double driven = limited ? 0.0 : kinematicWork(s);
    ledger.doneByKinematic += driven;
    ledger.lostInContacts += e.kineticIn - e.kineticOut - frictionLoss + s.jointWork + driven;

    storeSolverBodies(model, s.bodies, state, s.involved);
    // Re-placing turns bodies. Their spin is carried along in body axes (ω_body fixed), so
    // ½ ω_bodyᵀ I_body ω_body, the kinetic energy, is exactly what the solver left; L is set
    // again at the new orientation.
    s.bodySpin.resize(model.bodies.size());
    for (int i : s.involved) s.bodySpin[i] = state.bodies[i].q.conjugate() * s.bodies[i].w;
    // Re-placing the bodies from the step's start is the contacts' doing (what they stopped
    // does not fall, so a resting body books nothing: the free step's ½ m g² h² of speed and
    // its fall of as much potential energy cancel); removing overlap is a correction.
    keepPoses(state, s);
    redoPoses(model, state, before, 0.01 * cfg.restingSpeed, s);
    ledger.lostInContacts -= potentialChange(model, state, s);
    keepPoses(state, s);
    correctOverlap(model, state, s, cfg, e, limited);
    ledger.positionCorrection += potentialChange(model, state, s);
    if (!s.jointRows.empty()) {
        keepPoses(state, s);
        nudgeDrives(model, state, s, cfg.h);
        projectJoints(model, state, s, 0.0);
        ledger.lostInJoints -= potentialChange(model, state, s);
        // The springs' energy: what their rows gave the bodies is in jointWork; what the
        // step's moves stored in them is theirs too, not lost.
        ledger.lostInJoints -= joint::jointSpringEnergy(model, state) - joint::jointSpringEnergy(model, before);
    }
    for (int i : s.involved) {
        if (model.bodies[i].motion != Motion::Dynamic || !s.bodies[i].touched || state.isAsleep(i)) continue;
        BodyState& b = state.bodies[i];
        b.L = b.q * (model.bodies[i].inertia * s.bodySpin[i]);
    }
}

void solveContacts(const Model& model, State& state, const State& before, const ManifoldList& contacts,
                   const std::vector<double>& sizes, const ContactSolverSettings& cfg,
                   ContactSolverScratch& s, EnergyLedger& ledger) {
    s.jointsOpen = s.jointsOpenAll = 0.0;  // (projectJoints sets them, the last call's standing)
    s.stillBodies = 0;
    if (contacts.empty() &&
        model.joints.empty()) {  // nothing to solve: only the memory of sleeping pairs is kept
        s.points.clear();
        s.geometry.clear();
        s.blocks.clear();
        s.jointRows.clear();
        dropSolvedMemory(model, state, s, false, state.contacts.size());
        return;
    }
    indexMemory(state, s);
    s.used.assign(state.contacts.size(), 0);
    const int islands = model.joints.empty() ? contactIslands(model, state, contacts, s) : 1;
    if (islands <= 1) {
        solveIsland(model, state, before, contacts, sizes, cfg, s, ledger, true);
        return;
    }
    // The islands' points (each manifold's at most) go after the memory as it is, which the
    // islands' warm starts read, when the memory has room for them: a heap mostly at rest,
    // few points solved against many remembered (a second list for them was 56 KB of
    // hull-rain's peak). Else to a list of their own: with every pair solved there are as
    // many points as remembered, and room for twice the memory (grown by half again, the
    // old room still held while it is copied) was more than the second list.
    const size_t remembered = state.contacts.size();
    size_t points = 0;
    for (const Manifold& m : contacts) points += static_cast<size_t>(m.count);
    s.toFresh = state.contacts.capacity() < remembered + points;
    s.fresh.clear();
    solveIslands(model, state, before, contacts, sizes, cfg, s, ledger, islands, points);
    dropSolvedMemory(model, state, s, true, remembered);
    if (s.toFresh) {
        makeRoom(state.contacts, state.contacts.size() + s.fresh.size());
        state.contacts.insert(state.contacts.end(), s.fresh.begin(), s.fresh.end());
        s.fresh.clear();
    }
}

void sizeContactSolver(const Model& model, ContactSolverScratch& s) {
    const size_t n = model.bodies.size();
    s.lanes.clear();  // (sized for this model when first used)
    sizeSolverBodies(model, s.bodies);
    s.start.assign(n, BodyVelocity{});
    s.entry.assign(n, BodyVelocity{});
    s.warmKinetic.assign(n, 0.0);
    s.frictionShare.assign(n, 0.0);
    s.slideCount.assign(n, 0);
    s.slideBlock.assign(n, -1);
    s.slideNormals.resize(n);
    s.bodySpin.assign(n, Vec3::Zero());
    s.rotation.assign(n, Mat3::Identity());
    s.nudgedAt.assign(n, 0);
    s.level.assign(n, 0);
    s.seen.assign(n, 0);
    s.springs.clear();
    for (size_t k = 0; k < model.forces.size(); ++k)
        if (model.forces[k].type == ForceType::Spring) s.springs.push_back(static_cast<int>(k));
}

}  // namespace tumble
