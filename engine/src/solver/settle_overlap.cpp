#include "solver/settle_overlap.h"

#include "collision/detect.h"
#include "collision/narrowphase.h"
#include "common/pair_key.h"
#include "solver/contact_energy.h"
#include "solver/contact_solver.h"
#include "solver/solver_body.h"

#include <tumble/state.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble {

namespace {

constexpr double kKeep = 0.5;  // × the margin: overlap left to the contact solver's own pass
constexpr int kRounds = 8;     // tests at the poses as they stand, each followed by passes
constexpr int kPasses = 16;    // position passes a round at most
constexpr double kClose =
    0.01;  // × the margin: overlap beyond `keep` by less is left (a push's turn leaves some)
// × the margin: a point the solver had is looked at if its depth, foreseen from its
// features' places in the bodies, comes this near what is allowed (the deepest feature may
// have passed to the next one: a box's corner to its edge).
constexpr double kForesight = 0.1;
constexpr double kMoving = 1e-3;  // × the resting speed: a body slower is at rest here

// How far a surface point of body i can have moved from the free step's end: the frame's
// shift and, turned by θ, at most θ r more (r its bounding radius; 2 sin(θ/2) r exactly).
double moveFromFreeEnd(const collision::Pose& now, const collision::Pose& end, double r) {
    // θ of R Rₑᵀ by atan2 of its sine and cosine (its skew part, its trace: 1 + 2 cos θ):
    // acos of the cosine alone turned rounding of 1e-16 into 1e-8 rad at θ = 0 (sqrt of it),
    // so that a world turned as a whole, whose matrices are not exact, saw bodies move.
    const Mat3 rel = now.R * end.R.transpose();
    const Vec3 skew(rel(2, 1) - rel(1, 2), rel(0, 2) - rel(2, 0), rel(1, 0) - rel(0, 1));
    const double angle = std::atan2(0.5 * skew.norm(), 0.5 * (rel.trace() - 1.0));
    return (now.p - end.p).norm() + angle * r;
}

// Whether a point of body i moves faster than `speed`, by a bound: |v| + |ω| r.
bool movingFaster(const Model& model, const State& state, int i, double r, double speed) {
    const BodyModel& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    return b.invMass * s.P.norm() + angularVelocity(b, s).norm() * r > speed;
}

double motionEnergy(const Model& model, const State& state, int i) {
    const BodyModel& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    BodyVelocity u;
    u.v = b.invMass * s.P;
    u.w = angularVelocity(b, s);
    return kineticOf(b, s.q, u);
}

// Appends the points of `found` (a against b); returns the deepest's overlap beyond what
// is allowed: the margin, and the slop the solver leaves a resting contact.
double addPoints(int a, int b, const BodyState& A, const BodyState& B, const collision::ManifoldList& found,
                 double margin, double slop, double reach, std::vector<SettleScratch::Point>& out) {
    double excess = -std::numeric_limits<double>::infinity();
    const Mat3 RA = A.q.toRotationMatrix(), RB = B.q.toRotationMatrix();
    for (const collision::Manifold& m : found) {
        for (int k = 0; k < m.count; ++k) {
            const collision::ContactPoint& c = m.points[k];
            // Deeper than the smaller body reaches from its centre, its centre is inside the
            // other and the way out is not known: left to the solver and the energy guard (a
            // stiff spring's runaway, not a landing).
            if (c.depth > reach) continue;
            excess = std::max(excess, c.depth - margin - slop);
            // As the contact solver takes them: A's deepest point half the depth below the
            // point, B's half above; the normal points out of B towards A.
            SettleScratch::Point p;
            p.a = a;
            p.b = b;
            p.keep = kKeep * margin + slop;
            p.localA = RA.transpose() * (c.position - 0.5 * c.depth * m.normal - A.x);
            p.localB = RB.transpose() * (c.position + 0.5 * c.depth * m.normal - B.x);
            p.localN = RB.transpose() * m.normal;
            out.push_back(p);
        }
    }
    return excess;
}

// A body about to be pushed for the first time: its place and body-axes spin noted, and
// its own pairs to be tested in the next round.
void firstPush(const Model& model, const State& state, int i, SettleScratch& s) {
    if (s.wasMoved[i]) return;
    s.wasMoved[i] = 1;
    s.moved.push_back(i);
    s.startX.push_back(state.bodies[i].x);
    const BodyModel& body = model.bodies[i];
    const BodyState& st = state.bodies[i];
    s.bodySpin.push_back(body.invInertia * (st.q.conjugate() * st.L));
    if (!s.looked[i] && !s.pending[i]) s.pending[i] = 1, s.toTest.push_back(i);
}

// Each body's level: 0 if it cannot be pushed, else one more than the lowest level among
// the bodies its points touch (a body touching only pushable ones that reach nothing that
// stands: the highest level). The points are then taken level by level, from the ground
// up, and a push between two levels moves the upper body only: one pass sets a stack on
// its support box by box, as shock propagation does for velocities.
void levelPoints(const Model& model, SettleScratch& s) {
    const int n = static_cast<int>(model.bodies.size());
    constexpr int kFloating = std::numeric_limits<int>::max();
    s.level.assign(n, kFloating);
    s.queue.clear();
    for (const SettleScratch::Point& p : s.points)
        for (int i : {p.a, p.b})
            if (!s.movable[i] && s.level[i] != 0) s.level[i] = 0, s.queue.push_back(i);
    // Breadth first over the points' bodies (a point list per body, as offsets).
    s.firstPoint.assign(n + 1, 0);
    for (const SettleScratch::Point& p : s.points) ++s.firstPoint[p.a + 1], ++s.firstPoint[p.b + 1];
    for (int i = 0; i < n; ++i) s.firstPoint[i + 1] += s.firstPoint[i];
    s.pointsOf.resize(2 * s.points.size());
    s.fill.assign(s.firstPoint.begin(), s.firstPoint.end() - 1);
    for (int k = 0; k < static_cast<int>(s.points.size()); ++k)
        for (int i : {s.points[k].a, s.points[k].b}) s.pointsOf[s.fill[i]++] = k;
    for (size_t head = 0; head < s.queue.size(); ++head) {
        const int i = s.queue[head];
        for (int k = s.firstPoint[i]; k < s.firstPoint[i + 1]; ++k) {
            const SettleScratch::Point& p = s.points[s.pointsOf[k]];
            const int j = p.a == i ? p.b : p.a;
            if (s.level[j] == kFloating) s.level[j] = s.level[i] + 1, s.queue.push_back(j);
        }
    }
    std::stable_sort(s.points.begin(), s.points.end(), [&](const auto& x, const auto& y) {
        return std::min(s.level[x.a], s.level[x.b]) < std::min(s.level[y.a], s.level[y.b]);
    });
}

// Position passes over every point found so far, each to its `keep`; velocities untouched.
void pushOut(const Model& model, State& state, double margin, SettleScratch& s) {
    levelPoints(model, s);
    // The bodies' rotation matrices and world inverse inertias, made again after a push.
    for (const SettleScratch::Point& p : s.points)
        for (int i : {p.a, p.b}) s.body[i] = s.movable[i] ? solverBody(model, state, i) : SolverBody{};
    for (const SettleScratch::Point& p : s.points)
        for (int i : {p.a, p.b}) s.rotation[i] = state.bodies[i].q.toRotationMatrix();
    static const SolverBody still;
    for (int pass = 0; pass < kPasses; ++pass) {
        double worst = 0.0;
        for (const SettleScratch::Point& p : s.points) {
            BodyState& a = state.bodies[p.a];
            BodyState& b = state.bodies[p.b];
            const Mat3 &RA = s.rotation[p.a], &RB = s.rotation[p.b];
            const Vec3 sA = a.x + RA * p.localA, sB = b.x + RB * p.localB, nrm = RB * p.localN;
            const double excess = nrm.dot(sB - sA) - p.keep;
            worst = std::max(worst, excess);
            if (excess <= kClose * margin) continue;
            // Between two levels the lower body stands.
            const bool moveA = s.movable[p.a] && s.level[p.a] >= s.level[p.b];
            const bool moveB = s.movable[p.b] && s.level[p.b] >= s.level[p.a];
            const SolverBody& A = moveA ? s.body[p.a] : still;
            const SolverBody& B = moveB ? s.body[p.b] : still;
            const Vec3 rA = sA - a.x, rB = sB - b.x;
            const double k = inverseEffectiveMass(A, rA, B, rB, nrm);
            if (k <= 0.0) continue;
            const Vec3 J = (excess / k) * nrm;
            auto push = [&](int i, const SolverBody& body, BodyState& st, const Vec3& r,
                            const Vec3& impulse) {
                firstPush(model, state, i, s);
                nudge(body, st, r, impulse);
                s.rotation[i] = st.q.toRotationMatrix();
                s.body[i].invI = s.rotation[i] * model.bodies[i].invInertia * s.rotation[i].transpose();
            };
            if (moveA) push(p.a, A, a, rA, J);
            if (moveB) push(p.b, B, b, rB, -J);
        }
        if (worst <= kClose * margin) break;
    }
}

}  // namespace

SettleResult settleOverlap(const Model& model, State& state, const std::vector<collision::Pose>& freeEnd,
                           const collision::ManifoldList& contacts, const std::vector<double>& sizes,
                           const collision::Broadphase& broadphase, double resting,
                           const std::vector<std::uint64_t>& jointPairs, const std::vector<int>& jointed,
                           double margin, SettleScratch& s, EnergyLedger& ledger) {
    SettleResult result;
    const int n = static_cast<int>(model.bodies.size());
    s.pending.assign(n, 0);
    s.toTest.clear();
    auto slopOf = [&](int a, int b) { return kContactSlop * std::min(sizes[a], sizes[b]); };
    // The bodies a push may move: dynamic, awake, without a joint (the joints hold those).
    s.movable.assign(n, 0);
    for (int i = 0; i < n; ++i)
        s.movable[i] = model.bodies[i].motion == Motion::Dynamic && !state.isAsleep(i) ? 1 : 0;
    for (int i : jointed) s.movable[i] = 0;
    auto mark = [&](int i) {
        if (!s.pending[i] && s.movable[i]) {
            s.pending[i] = 1;
            s.toTest.push_back(i);
        }
    };
    s.pose.resize(n);
    for (int i = 0; i < n; ++i) {
        const BodyModel& b = model.bodies[i];
        s.pose[i] = b.standsStill() ? freeEnd[i] : bodyPose(b, state.bodies[i]);  // (nothing moved those)
        if (!s.movable[i]) continue;
        if (moveFromFreeEnd(s.pose[i], freeEnd[i], sizes[i]) > margin) mark(i);
    }
    // And the bodies of a point the solver had that it leaves deeper than is allowed (its
    // depth where the bodies stand, from its features' places in each body at the free
    // step's end), if one of them moves or the point is past what the solver's own pass
    // removes whatever it costs (kFreeOverlap). A body at rest less deep is the solver's to
    // lift as its energy budget allows: lifting it here would make the energy.
    const double moving = kMoving * resting;
    for (const collision::Manifold& m : contacts) {
        const int a = m.bodyA, b = m.bodyB;
        if ((s.pending[a] || !s.movable[a]) && (s.pending[b] || !s.movable[b])) continue;
        const double slop = slopOf(a, b);
        // (A round surface is its core grown by a radius: the core moves with the body, the
        // surface point slides over it as it rolls; as in the solver's gap.)
        const collision::Shape& partA = partShape(model.bodies[a].collider, m.partA);
        const collision::Shape& partB = partShape(model.bodies[b].collider, m.partB);
        const double roundA = roundness(partA), roundB = roundness(partB);
        const Vec3 n = s.pose[b].directionToWorld(freeEnd[b].directionToLocal(m.normal));
        double deepest = 0.0;
        for (int k = 0; k < m.count; ++k) {
            const collision::ContactPoint& c = m.points[k];
            const Vec3 coreA = c.position - (0.5 * c.depth - roundA) * m.normal;
            const Vec3 coreB = c.position + (0.5 * c.depth - roundB) * m.normal;
            const Vec3 sA = s.pose[a].toWorld(freeEnd[a].toLocal(coreA)) - roundA * n;
            const Vec3 sB = s.pose[b].toWorld(freeEnd[b].toLocal(coreB)) + roundB * n;
            deepest = std::max(deepest, n.dot(sB - sA));
        }
        // A capsule's core point slides along its segment as it turns: near the allowance,
        // the pair as it stands.
        const bool capsule = partA.kind == collision::Kind::Capsule || partB.kind == collision::Kind::Capsule;
        if (capsule && deepest > kKeep * margin) {
            s.found.clear();
            collision::collide(model.bodies[a].collider, s.pose[a], model.bodies[b].collider, s.pose[b], 0.0,
                               s.found);
            for (const collision::Manifold& f : s.found) deepest = std::max(deepest, f.maxDepth());
        }
        if (deepest <= (1.0 - kForesight) * margin + slop) continue;
        const bool anyway = deepest > margin + kFreeOverlap * slop;
        for (int i : {a, b})
            if (anyway || movingFaster(model, state, i, sizes[i], moving)) mark(i);
    }
    if (s.toTest.empty()) return result;

    s.looked.assign(n, 0);
    s.moved.clear();
    s.startX.clear();
    s.bodySpin.clear();
    s.points.clear();
    s.wasMoved.assign(n, 0);
    s.body.resize(n);
    s.rotation.resize(n);

    s.tested.clear();
    for (int round = 0; round < kRounds; ++round) {
        // Every body tested so far and the ones pushes reached since, against every body
        // the broadphase holds near them (by the boxes of its last update, swept over the
        // step); each pair once. Tested again each round: a push turns a body about its
        // point, and its other points move as the local points did not foresee.
        for (int i : s.toTest) {
            s.pending[i] = 0;
            s.tested.push_back(i);
            ++result.looked;
        }
        s.toTest.clear();
        s.points.clear();
        for (int i : s.tested) s.looked[i] = 0;
        double worstExcess = -std::numeric_limits<double>::infinity();
        for (int i : s.tested) {
            s.looked[i] = 1;
            const BodyModel& bi = model.bodies[i];
            const collision::Aabb box = bounds(bi.collider, bodyPose(bi, state.bodies[i])).inflated(margin);
            broadphase.query(box, [&](int j) {
                if (j == i || s.looked[j] == 1) return;  // (a body looked at was tested with i)
                const int a = std::min(i, j), b = std::max(i, j);
                if (std::binary_search(jointPairs.begin(), jointPairs.end(), pairKey(a, b))) return;
                if (!model.mayCollide(a, b)) return;
                if (!s.movable[a] && !s.movable[b]) return;
                s.found.clear();
                const BodyModel &A = model.bodies[a], &B = model.bodies[b];
                collision::collide(A.collider, bodyPose(A, state.bodies[a]), B.collider,
                                   bodyPose(B, state.bodies[b]), margin, s.found);
                worstExcess =
                    std::max(worstExcess, addPoints(a, b, state.bodies[a], state.bodies[b], s.found, margin,
                                                    slopOf(a, b), std::min(sizes[a], sizes[b]), s.points));
            });
        }
        if (worstExcess <= 0.0) break;  // (what the solver or the last pushes left is allowed)
        pushOut(model, state, margin, s);
    }
    result.moved = static_cast<int>(s.moved.size());
    if (s.moved.empty()) return result;

    // The spins as they were in body axes; the lifts' potential energy paid from the moved
    // bodies' motion where it can be.
    double lifted = 0.0, kinetic = 0.0;
    for (size_t k = 0; k < s.moved.size(); ++k) {
        const int i = s.moved[k];
        BodyState& st = state.bodies[i];
        st.L = st.q * (model.bodies[i].inertia * s.bodySpin[k]);
        lifted -= model.bodies[i].mass * model.settings.gravity.dot(state.bodies[i].x - s.startX[k]);
        kinetic += motionEnergy(model, state, i);
    }
    ledger.positionCorrection += lifted;
    if (lifted > 0.0 && kinetic > 0.0) {
        const double taken = std::min(lifted, kinetic);
        const double alpha = std::sqrt(std::max(0.0, 1.0 - taken / kinetic));
        for (int i : s.moved) {
            state.bodies[i].P *= alpha;
            state.bodies[i].L *= alpha;
        }
        ledger.lostInContacts += taken;
    }
    return result;
}

}  // namespace tumble
