#include "impacts/impact.h"

#include "common/resting.h"
#include "solver/joints.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace tumble {

using collision::Manifold;
using collision::ManifoldList;

namespace {

constexpr int kMaxSweeps = 200;

double restitution(const Model& model, const Manifold& m) {
    return std::max(model.bodies[m.bodyA].restitutionOf(m.partA),
                    model.bodies[m.bodyB].restitutionOf(m.partB));
}

double friction(const Model& model, const Manifold& m) {
    return std::sqrt(model.bodies[m.bodyA].frictionOf(m.partA) * model.bodies[m.bodyB].frictionOf(m.partB));
}

bool touches(const Manifold& m, double tol) {
    for (int i = 0; i < m.count; ++i)
        if (m.points[i].depth >= -tol) return true;
    return false;
}

// The manifolds reached from the seed bodies through touching manifolds; dynamic bodies
// carry the reach on, static and kinematic ones do not. A breadth-first search over each
// body's touching manifolds: linear in the contacts (sweeping the whole list until nothing
// grew took a pass per link of the longest chain, quadratic for a long row or a tall pile).
void collectIsland(const Model& model, const State& state, const ManifoldList& contacts,
                   const std::vector<int>& seeds, double tol, ImpactScratch& s) {
    const size_t n = model.bodies.size();
    s.inIsland.assign(n, 0);
    s.manifolds.clear();
    auto carries = [&](int b) { return model.bodies[b].motion == Motion::Dynamic && !state.isAsleep(b); };
    // Each body's touching manifolds, as ranges of one array (counting sort by body).
    s.first.assign(n + 1, 0);
    for (const Manifold& m : contacts)
        if (touches(m, tol)) ++s.first[m.bodyA + 1], ++s.first[m.bodyB + 1];
    for (size_t i = 0; i < n; ++i) s.first[i + 1] += s.first[i];
    s.byBody.resize(s.first[n]);
    s.fill.assign(s.first.begin(), s.first.end() - 1);
    for (size_t k = 0; k < contacts.size(); ++k) {
        const Manifold& m = contacts[k];
        if (!touches(m, tol)) continue;
        s.byBody[s.fill[m.bodyA]++] = static_cast<int>(k);
        s.byBody[s.fill[m.bodyB]++] = static_cast<int>(k);
    }
    // Joints carry an impact as contacts do: a body's joint partners are in its island.
    s.jointFirst.assign(n + 1, 0);
    for (const JointModel& j : model.joints)
        if (j.b >= 0) ++s.jointFirst[j.a + 1], ++s.jointFirst[j.b + 1];
    for (size_t i = 0; i < n; ++i) s.jointFirst[i + 1] += s.jointFirst[i];
    s.partners.resize(s.jointFirst[n]);
    s.jointFill.assign(s.jointFirst.begin(), s.jointFirst.end() - 1);
    for (const JointModel& j : model.joints) {
        if (j.b < 0) continue;
        s.partners[s.jointFill[j.a]++] = j.b;
        s.partners[s.jointFill[j.b]++] = j.a;
    }
    s.taken.assign(contacts.size(), 0);
    s.queue.clear();
    for (int b : seeds)
        if (carries(b) && !s.inIsland[b]) s.inIsland[b] = 1, s.queue.push_back(b);
    for (size_t q = 0; q < s.queue.size(); ++q) {
        const int body = s.queue[q];
        for (int j = s.first[body]; j < s.first[body + 1]; ++j) {
            const int k = s.byBody[j];
            if (s.taken[k]) continue;
            s.taken[k] = 1;
            for (int b : {contacts[k].bodyA, contacts[k].bodyB})
                if (carries(b) && !s.inIsland[b]) s.inIsland[b] = 1, s.queue.push_back(b);
        }
        for (int j = s.jointFirst[body]; j < s.jointFirst[body + 1]; ++j) {
            const int b = s.partners[j];
            if (carries(b) && !s.inIsland[b]) s.inIsland[b] = 1, s.queue.push_back(b);
        }
    }
    for (size_t k = 0; k < contacts.size(); ++k)
        if (s.taken[k]) s.manifolds.push_back(static_cast<int>(k));
}

// Applies the impulse J at a pair's points, booking what it dissipated in `lost` and what a
// moving kinematic or animated body gave in `driven` (drivenWork, taken at the velocities
// before: a body that no impulse moves keeps them).
void book(double& lost, double& driven, SolverBody& A, const Vec3& rA, SolverBody& B, const Vec3& rB,
          const Vec3& J) {
    driven += drivenWork(A, rA, B, rB, J);
    lost += applyPairImpulse(A, rA, B, rB, J);
}

constexpr int kJointRounds = 100;   // a manifold's rounds with the joints (below)
constexpr double kMostRound = 4.0;  // a round adds at most this many times the impact's impulse

// One manifold: the approaching touching points solved together. Returns whether any
// point was approaching.
// With `joints` (one sweep of the island's joint rows, given the round; whether it moved a
// body), the joints act at once with the impact, as parts of one rigid body: the points keep
// the velocity restitution gave them as their target, and rounds of the joints' sweep and of
// the impulse the points still lack (never a pull) follow until both hold. (A ball hitting a
// dumbbell along its rod meets both of its balls, as it would meet one body of their mass;
// later manifolds still take their turn after, which is how a row of balls passes an impact
// on.)
bool solveManifold(const Model& model, const Manifold& m, std::vector<SolverBody>& bodies, double tol,
                   double approachTol, double restingSpeed, EnergyLedger& ledger,
                   const std::function<bool(int, int, int)>* joints = nullptr) {
    SolverBody& A = bodies[m.bodyA];
    SolverBody& B = bodies[m.bodyB];
    const Vec3& n = m.normal;
    const double e = restitution(model, m);
    // How gravity closes the pair along n: negative when it presses them together.
    const Vec3& grav = model.settings.gravity;
    const double closing =
        n.dot((A.invMass > 0.0 ? grav : Vec3::Zero()) - (B.invMass > 0.0 ? grav : Vec3::Zero()));
    const double settling = std::max(approachTol, restingSpeed * restingShare(grav, n));
    Vec3 rA[Manifold::kMaxPoints], rB[Manifold::kMaxPoints];
    double gain[Manifold::kMaxPoints];  // wanted change of the normal velocity
    int k = 0;
    for (int i = 0; i < m.count; ++i) {
        if (m.points[i].depth < -tol) continue;
        const Vec3 a = m.points[i].position - A.x, b = m.points[i].position - B.x;
        const double vn = n.dot(relativeVelocity(A, a, B, b));
        // Slower than the resting speed is settling, left to the contact solver (which
        // converges on it far faster than this loop, warm started).
        if (vn >= -settling) continue;
        rA[k] = a;
        rB[k] = b;
        // Restitution of the speed at the touch: a point found overlapping by d (at the end of
        // a step, not at its moment of impact) has fallen d under gravity since, and energy
        // gives v_touch² = vn² + 2 a d. From vn itself the bounce would also return that fall
        // once the position pass lifts the bodies out: an elastic ball gained m g d a bounce.
        const double d = std::max(m.points[i].depth, 0.0);
        const double touch = std::sqrt(std::max(vn * vn + 2.0 * closing * d, 0.0));
        gain[k] = -vn + e * touch;
        ++k;
    }
    if (k == 0) return false;

    // K(i, j): normal velocity change at point i per unit normal impulse at point j.
    Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
    Eigen::Vector4d g = Eigen::Vector4d::Zero();
    for (int i = 0; i < k; ++i) {
        g[i] = gain[i];
        for (int j = 0; j < k; ++j)
            K(i, j) = A.invMass + B.invMass + n.dot((A.invI * rA[j].cross(n)).cross(rA[i])) +
                      n.dot((B.invI * rB[j].cross(n)).cross(rB[i]));
    }
    const Eigen::Matrix4d Kinv = leastNormInverse(K, k);
    Eigen::Vector4d lambda = pushingImpulses(K, Kinv, g, k);
    Eigen::Vector4d target = Eigen::Vector4d::Zero();  // the normal velocities restitution asks
    for (int i = 0; i < k; ++i) target[i] = n.dot(relativeVelocity(A, rA[i], B, rB[i])) + gain[i];
    for (int i = 0; i < k; ++i)
        if (lambda[i] > 0.0)
            book(ledger.lostInContacts, ledger.doneByKinematic, A, rA[i], B, rB[i], lambda[i] * n);
    const double first = lambda.head(k).sum();  // the impact's own impulse
    double before = HUGE_VAL;
    Eigen::Vector4d last = Eigen::Vector4d::Zero();  // the need a round ago
    for (int round = 0; joints && round < kJointRounds; ++round) {
        const bool moved = (*joints)(m.bodyA, m.bodyB, round);
        Eigen::Vector4d need = Eigen::Vector4d::Zero();
        double worst = 0.0;
        for (int i = 0; i < k; ++i) {
            need[i] = target[i] - n.dot(relativeVelocity(A, rA[i], B, rB[i]));
            if (need[i] > 0.0 || lambda[i] > 0.0) worst = std::max(worst, std::abs(need[i]));
        }
        if (!moved && worst <= approachTol) break;
        // Rounds that no longer bring the points nearer their target (the joints do not let
        // the bodies part that way: a link hitting the next but one of its chain) stop: more
        // impulse there would only spin the bodies up.
        if (round >= 2 && worst > 0.9 * before) break;
        before = worst;
        Eigen::Vector4d more = Kinv * need;
        // Where the need is the last round's shrunk by a ratio ρ (the same direction to 5 %),
        // the rounds ahead would add its impulse again times ρ, ρ², ...: given at once, as
        // 1 / (1 − ρ) of it (Aitken's extrapolation of a geometric sequence; ρ < 0.9, and
        // within kMostRound). The rounds stop as before (both hold, no progress, too much),
        // so where they converge it is to the same impulse, sooner: ragdoll-pile's manifolds
        // that took 30-100 rounds, 2 741 in 300 steps -> 171; its impacts 1.47 -> 1.19 ms.
        if (round >= 1) {
            const double ll = last.head(k).squaredNorm();
            const double rho = ll > 0.0 ? need.head(k).dot(last.head(k)) / ll : 0.0;
            const bool along = (need.head(k) - rho * last.head(k)).norm() < 0.05 * need.head(k).norm();
            if (rho > 0.0 && rho < 0.9 && along) {
                const Eigen::Vector4d boosted = more / (1.0 - rho);
                if (boosted.head(k).cwiseMax(0.0).sum() <= kMostRound * std::max(first, 0.0)) more = boosted;
            }
        }
        last = need;
        for (int i = 0; i < k; ++i)
            more[i] = std::max(more[i], -lambda[i]);  // what was pushed may be taken back, no more
        // A round that would add several times the impact's own impulse is not taken, and the
        // rounds stop: where the joints hold the bodies the pair's own response can ask for
        // that (two points of a nearly singular K, a torso struck beside a shoulder joint:
        // 0.95 m/s wanted at the points, 60 N s pushed at one of them where the impact gave
        // 1.5, and 228 m/s reached; a pile of ragdolls gained 2.7e4 J in one impact).
        if (more.head(k).cwiseMax(0.0).sum() > kMostRound * std::max(first, 0.0)) break;
        for (int i = 0; i < k; ++i) {
            if (more[i] == 0.0) continue;
            lambda[i] += more[i];
            book(ledger.lostInContacts, ledger.doneByKinematic, A, rA[i], B, rB[i], more[i] * n);
        }
    }

    // Coulomb friction at each point that was pushed: stop the sliding, within μ j.
    const double mu = friction(model, m);
    if (mu > 0.0) {
        for (int i = 0; i < k; ++i) {
            if (lambda[i] <= 0.0) continue;
            const Vec3 v = relativeVelocity(A, rA[i], B, rB[i]);
            const Vec3 vt = v - n.dot(v) * n;
            const double speed = vt.norm();
            if (speed <= approachTol) continue;
            const Vec3 t = -vt / speed;
            const double jt = std::min(speed / inverseEffectiveMass(A, rA[i], B, rB[i], t), mu * lambda[i]);
            book(ledger.lostInFriction, ledger.doneByKinematic, A, rA[i], B, rB[i], jt * t);
        }
    }
    return true;
}

}  // namespace

void approachingBodies(const Model& model, const State& before, const State& state,
                       const ManifoldList& contacts, double tol, double speed, std::vector<int>& seeds) {
    seeds.clear();
    // Each manifold's bodies are loaded when one of its points touches, and their velocities
    // at the start only when a point approaches now (most resting contacts do not).
    for (const Manifold& m : contacts) {
        bool loaded = false, loadedStart = false;
        SolverBody A, B, A0, B0;
        for (int i = 0; i < m.count; ++i) {
            if (m.points[i].depth < -tol) continue;
            // An animated body moves as the step's solve has it: its chord over the step (its
            // instant velocity, a lift speeding up, would approach what rides it by a h / 2).
            if (!loaded) {
                A = solverBody(model, state, m.bodyA), B = solverBody(model, state, m.bodyB), loaded = true;
                chordVelocity(model, state, before, m.bodyA, A);
                chordVelocity(model, state, before, m.bodyB, B);
            }
            const Vec3& p = m.points[i].position;
            if (m.normal.dot(relativeVelocity(A, p - A.x, B, p - B.x)) >= -speed) continue;
            if (!loadedStart) {
                A0 = solverBody(model, before, m.bodyA), B0 = solverBody(model, before, m.bodyB),
                loadedStart = true;
                chordVelocity(model, state, before, m.bodyA, A0);
                chordVelocity(model, state, before, m.bodyB, B0);
            }
            if (m.normal.dot(relativeVelocity(A0, p - A.x, B0, p - B.x)) >= -speed) continue;
            seeds.push_back(m.bodyA);
            seeds.push_back(m.bodyB);
            break;
        }
    }
}

namespace {

ImpactResult resolve(const Model& model, State& state, const ManifoldList& contacts,
                     const std::vector<int>& seeds, double touchTolerance, double restingSpeed,
                     ImpactScratch& s, EnergyLedger& ledger, ContactSolverScratch* joints,
                     const State* chordFrom) {
    ImpactResult result;
    collectIsland(model, state, contacts, seeds, touchTolerance, s);
    if (s.manifolds.empty()) return result;
    s.involved.clear();
    for (int k : s.manifolds)
        s.involved.push_back(contacts[k].bodyA), s.involved.push_back(contacts[k].bodyB);
    bool jointed = joints && !model.joints.empty();
    if (jointed) {  // the bodies reached through joints, and the joints' other bodies
        s.involved.insert(s.involved.end(), s.queue.begin(), s.queue.end());
        for (const JointModel& j : model.joints)
            if (j.b >= 0 && (s.inIsland[j.a] || s.inIsland[j.b]))
                s.involved.push_back(j.a), s.involved.push_back(j.b);
    }
    uniqueBodies(s.involved, s.seen);
    loadSolverBodies(model, state, s.bodies, s.involved);
    if (chordFrom) chordVelocities(model, state, *chordFrom, s.bodies, s.involved);
    // The joints' rows work on the contact solver's scratch: its bodies are these while the
    // impact lasts (swapped in and out, no copy).
    if (jointed) {
        std::swap(joints->bodies, s.bodies);
        joints->changedAt.resize(joints->bodies.size());
        prepareJoints(model, state, 0.0, *joints, true, &s.inIsland);
        std::swap(joints->bodies, s.bodies);
        if (joints->jointRows.empty()) jointed = false;
    }

    // "Still approaching" relative to the fastest approach at the start.
    double scale = 0.0;
    for (int k : s.manifolds) {
        const Manifold& m = contacts[k];
        for (int i = 0; i < m.count; ++i) {
            const Vec3& p = m.points[i].position;
            const Vec3 v = relativeVelocity(s.bodies[m.bodyA], p - s.bodies[m.bodyA].x, s.bodies[m.bodyB],
                                            p - s.bodies[m.bodyB].x);
            scale = std::max(scale, std::abs(m.normal.dot(v)));
        }
    }
    const double approachTol = 1e-9 * scale + 1e-15;

    // A manifold found with nothing approaching is looked at again only once an impulse
    // has changed one of its bodies: the sweeps then give bit for bit what sweeping every
    // manifold gives, at the cost of the manifolds the impact actually reaches (an impact
    // on a pile of thousands travels down one column of it).
    s.changedAt.assign(model.bodies.size(), -1);
    s.checkedAt.assign(s.manifolds.size(), 0);
    s.approached.assign(s.manifolds.size(), 1);
    long clock = 0;
    // One sweep of the joints' rows (their solver bodies are these, swapped in); the
    // manifolds of the bodies they move are looked at again.
    // A row whose bodies took no impulse since its last update is left alone (as the
    // manifolds are): in a pile of ragdolls each manifold's rounds swept all 180 joints of
    // the island, most of them far from the impact. `a`, `b`: the bodies the caller has just
    // pushed (-1: none).
    s.jointCheckedAt.assign(joints ? joints->jointRows.size() : 0,
                            -2);  // before every body's -1: all looked at once
    // The joints' work is bounded as one manifold's is: kMaxSweeps sweeps of kJointRounds
    // rounds, each updating every row once (20 000 updates a row). The worst impact of a
    // pile of ragdolls took 12 800 a row (ragdoll-pile, end-of-step impacts), the sample
    // ragdoll 8 500; a fuzzed chain whose link was a ball of 5 m among the others (its
    // energy running away) took 77 000, 1.5 million row updates in one impact, and the
    // sanitized build 18 s for its first three steps. Past the bound the impact stops as at
    // kMaxSweeps (`limited`) and the contact solver takes what is left.
    const long rows = jointed ? static_cast<long>(joints->jointRows.size()) : 0;
    const long jointBudget = static_cast<long>(kMaxSweeps) * kJointRounds * rows;
    long jointUpdates = 0;
    const std::function<bool(int, int, int)> sweepJoints = [&](int a, int b, int round) {
        if (a >= 0) s.changedAt[a] = s.changedAt[b] = ++clock;
        if (jointUpdates >= jointBudget) return false;
        std::swap(joints->bodies, s.bodies);
        bool moved = false;
        const int nj = static_cast<int>(joints->jointRows.size());
        // Forwards and backwards by turns (`round`: the caller's count), as the contact
        // solver's passes go: an impulse reaches through a ragdoll's joints against their
        // order only one joint a sweep in one direction. (ragdoll-pile: 65 % of manifolds'
        // rounds ran 30-100 sweeps, 11.6 million row updates in 300 steps, 2.4 ms a step;
        // by turns most take 3-9, 8.1 million updates, 1.65 ms. Both directions in every
        // sweep took more sweeps.) The turn is the caller's round, not a count of all
        // sweeps: a tolerance met one round sooner in a turned world would otherwise turn
        // every later sweep of the impact around (the suspension cart 4e-7 m apart in 1 s).
        const bool backwards = round % 2 == 1;
        for (int at = 0; at < nj; ++at) {
            const int k = backwards ? nj - 1 - at : at;
            const auto& row = joints->jointRows[k];
            if (s.jointCheckedAt[k] > s.changedAt[row.a] &&
                (row.b < 0 || s.jointCheckedAt[k] > s.changedAt[row.b]))
                continue;
            s.jointCheckedAt[k] = ++clock;
            ++jointUpdates;
            if (!updateJoint(*joints, k, approachTol)) continue;
            const auto& r = joints->jointRows[k];
            s.changedAt[r.a] = ++clock;
            if (r.b >= 0) s.changedAt[r.b] = clock;
            moved = true;
        }
        std::swap(joints->bodies, s.bodies);
        return moved;
    };
    auto touchesJoints = [&](const Manifold& m) {
        return (!model.jointed.empty()) && (model.jointed[m.bodyA] || model.jointed[m.bodyB]);
    };
    for (;;) {
        bool any = false;
        for (size_t i = 0; i < s.manifolds.size(); ++i) {
            const Manifold& m = contacts[s.manifolds[i]];
            if (!s.approached[i] && s.checkedAt[i] > s.changedAt[m.bodyA] &&
                s.checkedAt[i] > s.changedAt[m.bodyB])
                continue;
            s.checkedAt[i] = ++clock;
            s.approached[i] = solveManifold(model, m, s.bodies, touchTolerance, approachTol, restingSpeed,
                                            ledger, jointed && touchesJoints(m) ? &sweepJoints : nullptr);
            if (s.approached[i]) s.changedAt[m.bodyA] = s.changedAt[m.bodyB] = clock;
            any |= s.approached[i] != 0;
        }
        if (jointed) any |= sweepJoints(-1, -1, result.sweeps);
        if (!any) break;
        if (++result.sweeps == kMaxSweeps || (jointed && jointUpdates >= jointBudget)) {
            result.limited = true;
            break;
        }
    }
    if (jointed) ledger.lostInJoints -= joints->jointWork;  // (the contacts' impulses are booked as applied)
    storeSolverBodies(model, s.bodies, state, s.involved);
    return result;
}

}  // namespace

ImpactResult resolveImpacts(const Model& model, State& state, const ManifoldList& contacts,
                            const std::vector<int>& seeds, double touchTolerance, double restingSpeed,
                            ImpactScratch& s, EnergyLedger& ledger, ContactSolverScratch* joints,
                            const State* chordFrom) {
    // With the contact solver's scratch, the impact borrows its per-body array (each loads
    // the entries of the bodies it indexes before reading them): one array of solver bodies
    // a world, not two (48 KB of hull-rain's 300 rocks).
    if (joints) std::swap(joints->bodies, s.bodies);
    const ImpactResult result =
        resolve(model, state, contacts, seeds, touchTolerance, restingSpeed, s, ledger, joints, chordFrom);
    if (joints) std::swap(joints->bodies, s.bodies);
    return result;
}

void sizeImpacts(const Model& model, ImpactScratch& s) {
    const size_t n = model.bodies.size();
    s.inIsland.assign(n, 0);
    s.seen.assign(n, 0);
    s.first.assign(n + 1, 0);
    s.fill.assign(n, 0);
    s.changedAt.assign(n, -1);
}

}  // namespace tumble
