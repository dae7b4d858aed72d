#include "contact_solver.h"

#include <algorithm>
#include <cmath>

namespace tumble {

using collision::Manifold;
using Point = ContactSolverScratch::Point;

namespace {

constexpr double kSlop = 0.005;         // overlap left alone, × the smaller body's size
constexpr double kBaumgarte = 0.2;      // share of the overlap beyond the slop removed per pass
constexpr double kMaxCorrection = 0.1;  // largest move per pass, × size
constexpr double kMatch = 0.1;          // a remembered point is the same within this × size

std::uint64_t pairKey(int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

void indexMemory(const State& state, ContactSolverScratch& s) {
    s.memory.clear();
    const auto& mem = state.contacts;
    for (int i = 0; i < static_cast<int>(mem.size());) {
        int j = i;
        while (j < static_cast<int>(mem.size()) && mem[j].bodyA == mem[i].bodyA && mem[j].bodyB == mem[i].bodyB) ++j;
        s.memory.emplace(pairKey(mem[i].bodyA, mem[i].bodyB), std::make_pair(i, j));
        i = j;
    }
}

const ContactMemory* remembered(const State& state, const ContactSolverScratch& s, const Point& p) {
    const auto it = s.memory.find(pairKey(p.a, p.b));
    if (it == s.memory.end()) return nullptr;
    const ContactMemory* best = nullptr;
    double bestD = kMatch * p.size;
    for (int i = it->second.first; i < it->second.second; ++i) {
        const ContactMemory& c = state.contacts[i];
        const double d = (c.position - p.position).norm();
        if (c.feature == p.feature && d <= bestD) best = &c, bestD = d;
    }
    return best;
}

void prepare(const Model& model, const State& state, const std::vector<Manifold>& contacts,
             const std::vector<double>& sizes, const ContactSolverSettings& cfg, ContactSolverScratch& s) {
    s.points.clear();
    for (const Manifold& m : contacts) {
        SolverBody& A = s.bodies[m.bodyA];
        SolverBody& B = s.bodies[m.bodyB];
        if (A.invMass == 0.0 && B.invMass == 0.0) continue;  // nothing here can move
        const BodyModel& ma = model.bodies[m.bodyA];
        const BodyModel& mb = model.bodies[m.bodyB];
        const double e = std::max(ma.restitution, mb.restitution);
        const double mu = std::sqrt(ma.friction * mb.friction);
        const Mat3 RA = state.bodies[m.bodyA].q.toRotationMatrix();
        const Mat3 RB = state.bodies[m.bodyB].q.toRotationMatrix();
        for (int i = 0; i < m.count; ++i) {
            const collision::ContactPoint& c = m.points[i];
            if (c.depth < -cfg.touchTolerance) continue;
            Point p;
            p.a = m.bodyA;
            p.b = m.bodyB;
            p.n = m.normal;
            tangentFrame(p.n, p.t1, p.t2);
            p.rA = c.position - A.x;
            p.rB = c.position - B.x;
            p.kn = 1.0 / inverseEffectiveMass(A, p.rA, B, p.rB, p.n);
            p.kt1 = 1.0 / inverseEffectiveMass(A, p.rA, B, p.rB, p.t1);
            p.kt2 = 1.0 / inverseEffectiveMass(A, p.rA, B, p.rB, p.t2);
            p.mu = mu;
            const double vn = p.n.dot(relativeVelocity(A, p.rA, B, p.rB));
            if (c.depth < 0.0)
                p.target = c.depth / cfg.h;  // apart: may close the gap within a step, no more
            else
                p.target = vn < -cfg.restingSpeed ? -e * vn : 0.0;
            // A's deepest point is half the depth below the midpoint, B's half above.
            p.localA = RA.transpose() * (p.rA - 0.5 * c.depth * p.n);
            p.localB = RB.transpose() * (p.rB + 0.5 * c.depth * p.n);
            p.localN = RB.transpose() * p.n;
            p.size = std::min(sizes[m.bodyA], sizes[m.bodyB]);
            p.slop = kSlop * p.size;
            p.feature = c.feature;
            p.position = c.position;
            s.points.push_back(p);
        }
    }
}

void warmStart(const State& state, ContactSolverScratch& s, EnergyLedger& ledger) {
    for (Point& p : s.points) {
        const ContactMemory* c = remembered(state, s, p);
        if (!c) continue;
        p.lambdaN = c->normalImpulse;
        p.lambdaT1 = p.t1.dot(c->tangentImpulse);
        p.lambdaT2 = p.t2.dot(c->tangentImpulse);
        SolverBody& A = s.bodies[p.a];
        SolverBody& B = s.bodies[p.b];
        ledger.lostInContacts += applyPairImpulse(A, p.rA, B, p.rB, p.lambdaN * p.n);
        ledger.lostInFriction += applyPairImpulse(A, p.rA, B, p.rB, p.lambdaT1 * p.t1 + p.lambdaT2 * p.t2);
    }
}

void iterate(ContactSolverScratch& s, EnergyLedger& ledger) {
    for (Point& p : s.points) {
        SolverBody& A = s.bodies[p.a];
        SolverBody& B = s.bodies[p.b];
        // Friction first, inside the cone of the current normal impulse.
        if (p.mu > 0.0) {
            const Vec3 v = relativeVelocity(A, p.rA, B, p.rB);
            const double old1 = p.lambdaT1, old2 = p.lambdaT2;
            double l1 = old1 - p.kt1 * p.t1.dot(v), l2 = old2 - p.kt2 * p.t2.dot(v);
            const double limit = p.mu * p.lambdaN, len = std::hypot(l1, l2);
            if (len > limit) l1 *= limit / len, l2 *= limit / len;
            p.lambdaT1 = l1;
            p.lambdaT2 = l2;
            ledger.lostInFriction += applyPairImpulse(A, p.rA, B, p.rB, (l1 - old1) * p.t1 + (l2 - old2) * p.t2);
        }
        const double vn = p.n.dot(relativeVelocity(A, p.rA, B, p.rB));
        const double old = p.lambdaN;
        p.lambdaN = std::max(0.0, old - p.kn * (vn - p.target));
        ledger.lostInContacts += applyPairImpulse(A, p.rA, B, p.rB, (p.lambdaN - old) * p.n);
    }
}

// Moves body i by the positional impulse J at offset r (its inverse mass and inertia).
void nudge(const SolverBody& b, BodyState& s, const Vec3& r, const Vec3& J) {
    s.x += b.invMass * J;
    const Vec3 turn = b.invI * r.cross(J);
    const double angle = turn.norm();
    if (angle > 0.0) s.q = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * s.q).normalized();
}

bool correctPositions(State& state, ContactSolverScratch& s, int passes) {
    bool moved = false;
    for (int pass = 0; pass < passes; ++pass) {
        double worst = 0.0;
        for (const Point& p : s.points) {
            BodyState& a = state.bodies[p.a];
            BodyState& b = state.bodies[p.b];
            const SolverBody& A = s.bodies[p.a];
            const SolverBody& B = s.bodies[p.b];
            const Mat3 RA = a.q.toRotationMatrix(), RB = b.q.toRotationMatrix();
            const Vec3 sA = a.x + RA * p.localA, sB = b.x + RB * p.localB, n = RB * p.localN;
            const double depth = n.dot(sB - sA);
            worst = std::max(worst, depth - p.slop);
            const double C = std::min(kBaumgarte * (depth - p.slop), kMaxCorrection * p.size);
            if (C <= 0.0) continue;
            const Vec3 rA = sA - a.x, rB = sB - b.x;
            const double k = inverseEffectiveMass(A, rA, B, rB, n);
            if (k <= 0.0) continue;
            const Vec3 J = (C / k) * n;
            if (A.invMass > 0.0) nudge(A, a, rA, J);
            if (B.invMass > 0.0) nudge(B, b, rB, -J);
            moved = true;
        }
        if (worst <= 0.0) break;
    }
    return moved;
}

void remember(const Model& model, const State& state, ContactSolverScratch& s) {
    s.nextMemory.clear();
    for (const Point& p : s.points) {
        ContactMemory c;
        c.bodyA = p.a;
        c.bodyB = p.b;
        c.feature = p.feature;
        c.position = p.position;
        c.normalImpulse = p.lambdaN;
        c.tangentImpulse = p.lambdaT1 * p.t1 + p.lambdaT2 * p.t2;
        s.nextMemory.push_back(c);
    }
    // Pairs that were not solved because they sleep keep what they had (and tell who
    // rests on whom when something wakes them).
    auto idle = [&](int b) { return state.isAsleep(b) || model.bodies[b].motion == Motion::Static; };
    for (const ContactMemory& c : state.contacts)
        if (idle(c.bodyA) && idle(c.bodyB)) s.nextMemory.push_back(c);
}

}  // namespace

void solveContacts(const Model& model, State& state, const std::vector<Manifold>& contacts,
                   const std::vector<double>& sizes, const ContactSolverSettings& cfg,
                   ContactSolverScratch& s, EnergyLedger& ledger) {
    loadSolverBodies(model, state, s.bodies);
    prepare(model, state, contacts, sizes, cfg, s);
    indexMemory(state, s);
    warmStart(state, s, ledger);
    for (int k = 0; k < cfg.iterations; ++k) iterate(s, ledger);
    storeSolverBodies(model, s.bodies, state);
    remember(model, state, s);
    state.contacts.swap(s.nextMemory);
    if (s.points.empty()) return;
    const double before = energy(model, state).potential;
    if (correctPositions(state, s, cfg.positionIterations))
        ledger.positionCorrection += energy(model, state).potential - before;
}

}  // namespace tumble
