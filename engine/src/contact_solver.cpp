#include "contact_solver.h"

#include "pair_key.h"

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
constexpr int kShockPasses = 4;         // passes per level of the last sweep (shockPass)
constexpr double kFreeOverlap =
    10.0;  // × the slop: deeper overlap is removed whatever it costs (correctOverlap)

void indexMemory(const State& state, ContactSolverScratch& s) {
    s.memory.clear();
    const auto& mem = state.contacts;
    for (int i = 0; i < static_cast<int>(mem.size());) {
        int j = i;
        while (j < static_cast<int>(mem.size()) && mem[j].bodyA == mem[i].bodyA &&
               mem[j].bodyB == mem[i].bodyB)
            ++j;
        s.memory.emplace(pairKey(mem[i].bodyA, mem[i].bodyB), std::make_pair(i, j));
        i = j;
    }
}

// The remembered point that this point continues, not yet taken by another point of this
// step: each remembered impulse starts one point only (when a manifold gains points, two
// new points near one old one took its impulse twice, and the warm start kicked a box of a
// resting pyramid to 1.2 m/s).
const ContactMemory* remembered(const State& state, ContactSolverScratch& s, const Point& p) {
    const auto it = s.memory.find(pairKey(p.a, p.b));
    if (it == s.memory.end()) return nullptr;
    // The same pair of features if it is still near; else the nearest remembered point
    // (features are renamed when, say, the reference face passes from one box to the other
    // in a stack: the impulses at the same corner still hold).
    int same = -1, nearest = -1;
    double nearestD = kMatch * p.size;
    for (int i = it->second.first; i < it->second.second; ++i) {
        if (s.used[i]) continue;
        const ContactMemory& c = state.contacts[i];
        const double d = (c.position - p.position).norm();
        if (d > kMatch * p.size) continue;
        if (c.feature == p.feature) same = i;
        if (d <= nearestD) nearest = i, nearestD = d;
    }
    const int k = same >= 0 ? same : nearest;
    if (k < 0) return nullptr;
    s.used[k] = 1;
    return &state.contacts[k];
}

void prepareBlock(const SolverBody& A, const SolverBody& B, ContactSolverScratch::Block& block,
                  const ContactSolverScratch& s) {
    const int k = block.count;
    const Point* q = &s.points[block.begin];
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j)
            block.K(i, j) = A.invMass + B.invMass +
                            q[i].n.dot((A.invI * q[j].rA.cross(q[j].n)).cross(q[i].rA)) +
                            q[i].n.dot((B.invI * q[j].rB.cross(q[j].n)).cross(q[i].rB));
    block.Kinv = k > 1 ? leastNormInverse(block.K, k) : Eigen::Matrix4d::Zero();
    if (k == 1) block.Kinv(0, 0) = q[0].kn;
    // Friction at the centroid.
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < k; ++i) c += q[i].position;
    c /= k;
    const Vec3& n = q[0].n;
    block.rA = c - A.x;
    block.rB = c - B.x;
    tangentFrame(n, block.t1, block.t2);
    // K of the two tangents: velocity change along t_i per unit impulse along t_j.
    auto response = [&](const Vec3& ti, const Vec3& tj) {
        return ti.dot(A.invMass * tj + (A.invI * block.rA.cross(tj)).cross(block.rA) + B.invMass * tj +
                      (B.invI * block.rB.cross(tj)).cross(block.rB));
    };
    Eigen::Matrix2d Kt;
    Kt << response(block.t1, block.t1), response(block.t1, block.t2), response(block.t2, block.t1),
        response(block.t2, block.t2);
    block.tangentMass = Kt.inverse();
    const double twist = n.dot(A.invI * n) + n.dot(B.invI * n);
    block.twistMass = twist > 0.0 ? 1.0 / twist : 0.0;
    block.radius = 0.0;
    for (int i = 0; i < k; ++i) block.radius += (q[i].position - c).norm() / k;
}

void prepare(const Model& model, const State& state, const State& before,
             const std::vector<Manifold>& contacts, const std::vector<double>& sizes,
             const ContactSolverSettings& cfg, ContactSolverScratch& s) {
    s.points.clear();
    s.blocks.clear();
    loadSolverBodies(model, before, s.start);
    for (const Manifold& m : contacts) {
        SolverBody& A = s.bodies[m.bodyA];
        SolverBody& B = s.bodies[m.bodyB];
        if (A.invMass == 0.0 && B.invMass == 0.0) continue;  // nothing here can move
        const BodyModel& ma = model.bodies[m.bodyA];
        const BodyModel& mb = model.bodies[m.bodyB];
        const double e = std::max(ma.restitution, mb.restitution);
        const Mat3 RA = state.bodies[m.bodyA].q.toRotationMatrix();
        const Mat3 RB = state.bodies[m.bodyB].q.toRotationMatrix();
        // Each body's turn over the step: its surface points where they were at the start.
        const Mat3 turnA = before.bodies[m.bodyA].q.toRotationMatrix() * RA.transpose();
        const Mat3 turnB = before.bodies[m.bodyB].q.toRotationMatrix() * RB.transpose();
        ContactSolverScratch::Block block;
        block.begin = static_cast<int>(s.points.size());
        block.mu = std::sqrt(ma.friction * mb.friction);
        for (int i = 0; i < m.count; ++i) {
            const collision::ContactPoint& c = m.points[i];
            if (c.depth < -cfg.margin) continue;
            Point p;
            p.a = m.bodyA;
            p.b = m.bodyB;
            p.n = m.normal;
            p.rA = c.position - A.x;
            p.rB = c.position - B.x;
            p.kn = 1.0 / inverseEffectiveMass(A, p.rA, B, p.rB, p.n);
            const double vn = p.n.dot(relativeVelocity(A, p.rA, B, p.rB));
            const double vn0 = p.n.dot(relativeVelocity(s.start[m.bodyA], p.rA, s.start[m.bodyB], p.rB));
            // A's deepest point is half the depth below the midpoint, B's half above.
            const Vec3 sA = p.rA - 0.5 * c.depth * p.n, sB = p.rB + 0.5 * c.depth * p.n;
            p.localA = RA.transpose() * sA;
            p.localB = RB.transpose() * sB;
            // The gap between those two surface points at the start of the step. The bodies
            // are placed again from there with the solved velocities (redoPoses), so the gap
            // at the end is gap0 + h vn: a gap may close within the step and no more, and an
            // overlap is never pushed apart with velocity (the position pass removes it
            // without kinetic energy). A contact is thus the same constraint whatever the
            // step, resting or landing slowly, and never a source of energy.
            const double gap0 =
                p.n.dot((before.bodies[m.bodyA].x + turnA * sA) - (before.bodies[m.bodyB].x + turnB * sB));
            if (vn < -cfg.restingSpeed && vn0 < -cfg.restingSpeed && gap0 <= cfg.touchTolerance)
                p.target = -e * vn;  // touching and approaching fast: a bounce
            else
                p.target = gap0 > 0.0 ? -gap0 / cfg.h : 0.0;
            p.localN = RB.transpose() * p.n;
            p.size = std::min(sizes[m.bodyA], sizes[m.bodyB]);
            p.slop = kSlop * p.size;
            p.feature = c.feature;
            p.position = c.position;
            s.points.push_back(p);
        }
        block.count = static_cast<int>(s.points.size()) - block.begin;
        if (block.count == 0) continue;
        prepareBlock(A, B, block, s);
        s.blocks.push_back(block);
    }
}

void applyFriction(ContactSolverScratch& s, ContactSolverScratch::Block& block, const Eigen::Vector2d& dT,
                   double dTwist) {
    SolverBody& A = s.bodies[s.points[block.begin].a];
    SolverBody& B = s.bodies[s.points[block.begin].b];
    applyPairImpulse(A, block.rA, B, block.rB, dT[0] * block.t1 + dT[1] * block.t2);
    if (dTwist != 0.0) {
        const Vec3& n = s.points[block.begin].n;
        A.w += A.invI * (dTwist * n);
        B.w -= B.invI * (dTwist * n);
        A.touched = A.touched || A.invMass > 0.0;
        B.touched = B.touched || B.invMass > 0.0;
    }
}

// Starts from the remembered impulses, scaled to this step's length (a short step to land
// on a frame needs proportionally less).
void warmStart(const State& state, double h, ContactSolverScratch& s) {
    s.used.assign(state.contacts.size(), 0);
    for (auto& block : s.blocks) {
        Vec3 tangent = Vec3::Zero();
        double twist = 0.0;
        for (int i = 0; i < block.count; ++i) {
            Point& p = s.points[block.begin + i];
            const ContactMemory* c = remembered(state, s, p);
            if (!c) continue;
            const double scale = c->step > 0.0 ? std::min(h / c->step, 100.0) : 1.0;
            p.lambdaN = scale * c->normalImpulse;
            tangent += scale * c->tangentImpulse;
            twist += scale * c->twistImpulse;
            applyPairImpulse(s.bodies[p.a], p.rA, s.bodies[p.b], p.rB, p.lambdaN * p.n);
        }
        block.lambdaT = Eigen::Vector2d(block.t1.dot(tangent), block.t2.dot(tangent));
        block.lambdaTwist = twist;
        applyFriction(s, block, block.lambdaT, twist);
    }
}

void normalPoint(ContactSolverScratch& s, Point& p) {
    SolverBody& A = s.bodies[p.a];
    SolverBody& B = s.bodies[p.b];
    const double vn = p.n.dot(relativeVelocity(A, p.rA, B, p.rB));
    const double old = p.lambdaN;
    p.lambdaN = std::max(0.0, old - p.kn * (vn - p.target));
    const double d = p.lambdaN - old;
    applyImpulse(A, p.rA, d * p.n);
    applyImpulse(B, p.rB, -d * p.n);
}

// The normal impulses of one manifold together: the least-norm impulses that give every
// point its target velocity, none pulling (pushingImpulses).
void normalBlock(ContactSolverScratch& s, const ContactSolverScratch::Block& block) {
    Point* q = &s.points[block.begin];
    const int k = block.count;
    if (k == 1) return normalPoint(s, q[0]);
    SolverBody& A = s.bodies[q[0].a];
    SolverBody& B = s.bodies[q[0].b];
    Eigen::Vector4d lambda = Eigen::Vector4d::Zero(), rhs = Eigen::Vector4d::Zero(),
                    vn = Eigen::Vector4d::Zero();
    for (int i = 0; i < k; ++i) lambda[i] = q[i].lambdaN;
    for (int i = 0; i < k; ++i) {
        // What the impulses must add to the velocity the point would have without them.
        vn[i] = q[i].n.dot(relativeVelocity(A, q[i].rA, B, q[i].rB));
        rhs[i] = q[i].target - (vn[i] - block.K.row(i).dot(lambda));  // zero beyond k
    }
    const Eigen::Vector4d wanted = pushingImpulses(block.K, block.Kinv, rhs, k);
    const Eigen::Vector4d d = wanted - lambda;
    for (int i = 0; i < k; ++i) {
        q[i].lambdaN = wanted[i];
        applyImpulse(A, q[i].rA, d[i] * q[i].n);
        applyImpulse(B, q[i].rB, -d[i] * q[i].n);
    }
}

// Friction of one manifold: stop the sliding and the twisting at the centroid, within
// the Coulomb limits of the current normal impulses.
void frictionBlock(ContactSolverScratch& s, ContactSolverScratch::Block& block) {
    if (block.mu <= 0.0) return;
    double normal = 0.0;
    for (int i = 0; i < block.count; ++i) normal += s.points[block.begin + i].lambdaN;
    const double limit = block.mu * normal;
    const Point& p = s.points[block.begin];
    SolverBody& A = s.bodies[p.a];
    SolverBody& B = s.bodies[p.b];
    const Vec3 v = relativeVelocity(A, block.rA, B, block.rB);
    Eigen::Vector2d l = block.lambdaT - block.tangentMass * Eigen::Vector2d(block.t1.dot(v), block.t2.dot(v));
    if (l.norm() > limit) l *= limit / l.norm();
    // The twist is always clamped: a one-point patch (radius 0) may hold none, whatever
    // was remembered.
    double tw = block.lambdaTwist - block.twistMass * p.n.dot(A.w - B.w);
    tw = std::clamp(tw, -limit * block.radius, limit * block.radius);
    const Eigen::Vector2d dT = l - block.lambdaT;
    const double dTwist = tw - block.lambdaTwist;
    block.lambdaT = l;
    block.lambdaTwist = tw;
    applyFriction(s, block, dT, dTwist);
}

// One pass over the manifolds, forwards on even passes and backwards on odd ones so that
// their order leaves no bias.
void iterate(ContactSolverScratch& s, int pass) {
    const int nb = static_cast<int>(s.blocks.size());
    for (int b = 0; b < nb; ++b) {
        ContactSolverScratch::Block& block = s.blocks[pass % 2 ? nb - 1 - b : b];
        frictionBlock(s, block);
        normalBlock(s, block);
    }
}

// Support levels: 0 for a body that cannot move (static, kinematic, asleep), else the least
// number of contacts between it and such a body (a large number when none is reached).
void supportLevels(ContactSolverScratch& s) {
    constexpr int kUnreached = 1 << 29;
    s.level.assign(s.bodies.size(), kUnreached);
    for (size_t i = 0; i < s.bodies.size(); ++i)
        if (s.bodies[i].invMass == 0.0) s.level[i] = 0;
    // Relaxation over the blocks; a pile is as many rounds deep as it has layers.
    for (bool changed = true; changed;) {
        changed = false;
        for (const auto& block : s.blocks) {
            const Point& p = s.points[block.begin];
            int& la = s.level[p.a];
            int& lb = s.level[p.b];
            if (la + 1 < lb) lb = la + 1, changed = true;
            if (lb + 1 < la) la = lb + 1, changed = true;
        }
    }
}

// The last passes, from the ground up (shock propagation): level by level, the bodies of
// the lower level stand still while the contacts between them and the next level are
// solved (a few passes, so that a body on two supports settles on both), so each body
// ends at rest on what holds it, or moving with it, whatever the iterations left. A tall
// or heavy-on-light stack needs far more Gauss-Seidel passes than a step has to carry its
// weight down to the ground (the error shrinks by a fixed factor per pass, and that factor
// nears 1 as the stack grows); without these passes the stack sinks into itself each step
// until the warm start has caught up. The impulses they add are kept for the next step's
// warm start, where the lower bodies then feel them: at rest they find nothing left to do.
void shockPass(ContactSolverScratch& s, int passes) {
    supportLevels(s);
    const int nb = static_cast<int>(s.blocks.size());
    auto lowerLevel = [&](int b) {
        const Point& p = s.points[s.blocks[b].begin];
        return std::min(s.level[p.a], s.level[p.b]);
    };
    s.order.clear();
    for (int b = 0; b < nb; ++b) {
        const Point& p = s.points[s.blocks[b].begin];
        if (s.level[p.a] != s.level[p.b]) s.order.push_back(b);  // a level's own contacts are done
    }
    std::stable_sort(s.order.begin(), s.order.end(),
                     [&](int x, int y) { return lowerLevel(x) < lowerLevel(y); });
    std::vector<SolverBody> saved;
    std::vector<int> frozenBodies;
    for (size_t g = 0; g < s.order.size();) {
        const int level = lowerLevel(s.order[g]);
        size_t e = g;
        while (e < s.order.size() && lowerLevel(s.order[e]) == level) ++e;
        // The lower level stands still; the blocks are prepared again for that.
        for (size_t k = g; k < e; ++k) {
            const Point& p = s.points[s.blocks[s.order[k]].begin];
            const int lower = s.level[p.a] < s.level[p.b] ? p.a : p.b;
            SolverBody& body = s.bodies[lower];
            if (body.invMass == 0.0) continue;
            frozenBodies.push_back(lower);
            saved.push_back(body);
            body.invMass = 0.0;
            body.invI.setZero();
        }
        s.frozen.clear();
        for (size_t k = g; k < e; ++k) {
            ContactSolverScratch::Block block = s.blocks[s.order[k]];
            Point* q = &s.points[block.begin];
            for (int i = 0; i < block.count; ++i)
                q[i].kn =
                    1.0 / inverseEffectiveMass(s.bodies[q[i].a], q[i].rA, s.bodies[q[i].b], q[i].rB, q[i].n);
            prepareBlock(s.bodies[q[0].a], s.bodies[q[0].b], block, s);
            s.frozen.push_back(block);
        }
        for (int pass = 0; pass < passes; ++pass)
            for (auto& block : s.frozen) {
                frictionBlock(s, block);
                normalBlock(s, block);
            }
        for (size_t k = g; k < e; ++k) {
            ContactSolverScratch::Block& block = s.blocks[s.order[k]];
            block.lambdaT = s.frozen[k - g].lambdaT;
            block.lambdaTwist = s.frozen[k - g].lambdaTwist;
        }
        g = e;
    }
    for (size_t k = 0; k < frozenBodies.size(); ++k) {
        SolverBody& body = s.bodies[frozenBodies[k]];
        body.invMass = saved[k].invMass;
        body.invI = saved[k].invI;
    }
}

// Moves body i by the positional impulse J at offset r (its inverse mass and inertia).
void nudge(const SolverBody& b, BodyState& s, const Vec3& r, const Vec3& J) {
    s.x += b.invMass * J;
    const Vec3 turn = b.invI * r.cross(J);
    const double angle = turn.norm();
    if (angle > 0.0) s.q = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * s.q).normalized();
}

bool correctPositions(State& state, ContactSolverScratch& s, int passes, double slopFactor) {
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
            const double slop = slopFactor * p.slop;
            worst = std::max(worst, depth - slop);
            const double C = std::min(kBaumgarte * (depth - slop), kMaxCorrection * p.size);
            if (C <= 0.0) continue;
            const Vec3 rA = sA - a.x, rB = sB - b.x;
            const double k = inverseEffectiveMass(A, rA, B, rB, n);
            if (k <= 0.0) continue;
            const Vec3 J = (C / k) * n;
            if (A.invMass > 0.0) nudge(A, a, rA, J), s.bodies[p.a].touched = true;
            if (B.invMass > 0.0) nudge(B, b, rB, -J), s.bodies[p.b].touched = true;
            moved = true;
        }
        if (worst <= 0.0) break;
    }
    return moved;
}

void remember(const Model& model, const State& state, double h, ContactSolverScratch& s) {
    s.nextMemory.clear();
    for (const auto& block : s.blocks) {
        const Vec3 tangent = (block.lambdaT[0] * block.t1 + block.lambdaT[1] * block.t2) / block.count;
        for (int i = 0; i < block.count; ++i) {
            const Point& p = s.points[block.begin + i];
            ContactMemory c;
            c.bodyA = p.a;
            c.bodyB = p.b;
            c.feature = p.feature;
            c.position = p.position;
            c.normalImpulse = p.lambdaN;
            c.tangentImpulse = tangent;
            c.twistImpulse = block.lambdaTwist / block.count;
            c.step = h;
            s.nextMemory.push_back(c);
        }
    }
    // Pairs that were not solved because they sleep keep what they had (and tell who
    // rests on whom when something wakes them).
    auto idle = [&](int b) { return state.isAsleep(b) || model.bodies[b].standsStill(); };
    for (const ContactMemory& c : state.contacts)
        if (idle(c.bodyA) && idle(c.bodyB)) s.nextMemory.push_back(c);
}

// The pose of every body the solver pushed, from the start of the step with its new
// velocity (symplectic Euler for the bodies in contact).
void redoPoses(const Model& model, State& state, const State& before, const ContactSolverScratch& s) {
    const double h = state.time - before.time;
    for (int i : model.dynamicBodies) {
        if (!s.bodies[i].touched || state.isAsleep(i)) continue;
        BodyState& b = state.bodies[i];
        b.x = before.bodies[i].x + h * s.bodies[i].v;
        const Vec3 turn = h * s.bodies[i].w;
        const double angle = turn.norm();
        b.q = angle > 0.0 ? (Quat(Eigen::AngleAxisd(angle, turn / angle)) * before.bodies[i].q).normalized()
                          : before.bodies[i].q;
    }
}

// Kinetic energy of body i moving as b, its spin taken in the axes of its orientation q.
double kinetic(const BodyModel& body, const Quat& q, const SolverBody& b) {
    const Vec3 w = q.conjugate() * b.w;
    return 0.5 * body.mass * b.v.squaredNorm() + 0.5 * w.dot(body.inertia * w);
}

// What friction took this step: -Σ λ·(u⁻ + u⁺)/2 over the blocks' tangential and twisting
// rows, with λ the whole impulse of the step (warm start included), u⁻ the relative
// velocity the solver was given and u⁺ the one it left. For impulses that act on both
// bodies of a contact this is exact, row by row, and the rows add up to the change of
// kinetic energy; the normal rows take the rest (the last passes, which hold the lower
// bodies still, included).
double frictionLost(const ContactSolverScratch& s) {
    double lost = 0.0;
    for (const auto& block : s.blocks) {
        const Point& p = s.points[block.begin];
        const SolverBody &A0 = s.entry[p.a], &B0 = s.entry[p.b], &A = s.bodies[p.a], &B = s.bodies[p.b];
        const Vec3 u =
            relativeVelocity(A0, block.rA, B0, block.rB) + relativeVelocity(A, block.rA, B, block.rB);
        const Vec3 J = block.lambdaT[0] * block.t1 + block.lambdaT[1] * block.t2;
        lost -= 0.5 * J.dot(u) + 0.5 * block.lambdaTwist * p.n.dot(A0.w - B0.w + A.w - B.w);
    }
    return lost;
}

// Whether the contacts of this step may only take energy out: none of them is with a
// kinematic body that moves (a conveyor or a paddle does work on what it touches).
bool passive(const Model& model, const std::vector<Manifold>& contacts) {
    for (const Manifold& m : contacts)
        for (int b : {m.bodyA, m.bodyB})
            if (model.bodies[b].motion == Motion::Kinematic && !model.bodies[b].standsStill()) return false;
    return true;
}

// The energy of the bodies the solver moved (s.moving): at the start of the step, as the
// step gave them to the solver (kinetic and gravitational, at the poses the integrator
// reached) and as the solver leaves them (placed again from the start: x = x0 + h v).
EnergyBalance energyBalance(const Model& model, const State& state, const State& before,
                            const ContactSolverScratch& s) {
    EnergyBalance e;
    const Vec3& g = model.settings.gravity;
    const double h = state.time - before.time;
    for (int i : s.moving) {
        const BodyModel& body = model.bodies[i];
        const Quat& q = state.bodies[i].q;
        e.kineticIn += kinetic(body, q, s.entry[i]);
        e.kineticStart += kinetic(body, before.bodies[i].q, s.start[i]);
        e.kineticOut += kinetic(body, q, s.bodies[i]);
        e.potentialIn -= body.mass * g.dot(state.bodies[i].x);
        e.potentialStart -= body.mass * g.dot(before.bodies[i].x);
        e.potentialRate -= body.mass * g.dot(h * s.bodies[i].v);
    }
    return e;
}

// The solver gave the bodies more energy than they brought (Gauss-Seidel stopped before
// it converged, an impulse kept from the last step that no longer fits): their velocities
// are scaled by the largest α ≤ 1 that gives none. Scaling keeps every contact that the
// solver left at rest at rest and every approach as slow, and only ever takes energy out.
void limitEnergy(EnergyBalance& e, ContactSolverScratch& s) {
    // E(α) = α² K + α D + P0 must not exceed E_in; E(0) is every body at rest where it
    // started the step, which is at most its energy there, and so at most E_in.
    const double K = e.kineticOut, D = e.potentialRate, C = e.potentialStart - e.in();
    if (C > 0.0 || K <= 0.0) return;
    const double alpha =
        std::clamp((-D + std::sqrt(std::max(0.0, D * D - 4.0 * K * C))) / (2.0 * K), 0.0, 1.0);
    for (int i : s.moving) {
        s.bodies[i].v *= alpha;
        s.bodies[i].w *= alpha;
    }
    e.kineticOut *= alpha * alpha;
    e.potentialRate *= alpha;
}

// Gravity's potential energy of the bodies s.moving as they stand in `state`.
double potentialOf(const Model& model, const State& state, const std::vector<int>& which) {
    double u = 0.0;
    for (int i : which) u -= model.bodies[i].mass * model.settings.gravity.dot(state.bodies[i].x);
    return u;
}

// Removes overlap left by the step without touching velocities. Overlap deeper than twice
// the slop is always removed (bodies placed inside each other come apart). Between one and
// two slops it is removed only as far as the energy the contacts took this step allows:
// lifting a body adds potential energy, so with nothing taken out a pile that the solver
// holds at rest stays exactly as it is, and a correction never feeds energy in.
void correctOverlap(const Model& model, State& state, ContactSolverScratch& s,
                    const ContactSolverSettings& cfg, const EnergyBalance& e, bool limited) {
    if (!limited) {
        correctPositions(state, s, cfg.positionIterations, 1.0);
        return;
    }
    correctPositions(state, s, cfg.positionIterations, kFreeOverlap);
    const double budget = e.in() - e.kineticOut - potentialOf(model, state, s.moving);
    if (budget <= 0.0) return;
    s.placed.clear();
    for (int i : s.moving) s.placed.push_back({state.bodies[i].x, state.bodies[i].q});
    const double u0 = potentialOf(model, state, s.moving);
    if (!correctPositions(state, s, cfg.positionIterations, 1.0)) return;
    const double added = potentialOf(model, state, s.moving) - u0;
    if (added <= budget) return;
    const double beta = std::max(0.0, budget / added);  // gravity's energy is linear in position
    for (size_t k = 0; k < s.moving.size(); ++k) {
        BodyState& b = state.bodies[s.moving[k]];
        b.x = s.placed[k].first + beta * (b.x - s.placed[k].first);
        b.q = s.placed[k].second.slerp(beta, b.q);
    }
}

}  // namespace

void solveContacts(const Model& model, State& state, const State& before,
                   const std::vector<Manifold>& contacts, const std::vector<double>& sizes,
                   const ContactSolverSettings& cfg, ContactSolverScratch& s, EnergyLedger& ledger) {
    loadSolverBodies(model, state, s.bodies);
    prepare(model, state, before, contacts, sizes, cfg, s);
    indexMemory(state, s);
    s.entry = s.bodies;
    warmStart(state, cfg.h, s);
    for (int k = 0; k < cfg.iterations; ++k) iterate(s, k);
    if (!s.blocks.empty()) shockPass(s, kShockPasses);
    remember(model, state, cfg.h, s);
    state.contacts.swap(s.nextMemory);
    if (s.points.empty()) return;

    // The bodies of the solved points: the solver may have moved them, and the position
    // passes may.
    s.moving.clear();
    for (const Point& p : s.points)
        for (int i : {p.a, p.b})
            if (s.bodies[i].invMass > 0.0) s.moving.push_back(i);
    std::sort(s.moving.begin(), s.moving.end());
    s.moving.erase(std::unique(s.moving.begin(), s.moving.end()), s.moving.end());
    const double frictionLoss = frictionLost(s);
    EnergyBalance e = energyBalance(model, state, before, s);
    const bool limited = passive(model, contacts);
    if (limited && e.excess() > 0.0) limitEnergy(e, s);
    ledger.lostInFriction += frictionLoss;
    ledger.lostInContacts += e.kineticIn - e.kineticOut - frictionLoss;

    storeSolverBodies(model, s.bodies, state);
    // Re-placing turns bodies. Their spin is carried along in body axes (ω_body fixed), so
    // ½ ω_bodyᵀ I_body ω_body, the kinetic energy, is exactly what the solver left; L is set
    // again at the new orientation.
    s.bodySpin.resize(model.bodies.size());
    for (int i : model.dynamicBodies) s.bodySpin[i] = state.bodies[i].q.conjugate() * s.bodies[i].w;
    const double potential = energy(model, state).potential;
    redoPoses(model, state, before, s);
    correctOverlap(model, state, s, cfg, e, limited);
    ledger.positionCorrection += energy(model, state).potential - potential;
    for (int i : model.dynamicBodies) {
        if (!s.bodies[i].touched || state.isAsleep(i)) continue;
        BodyState& b = state.bodies[i];
        b.L = b.q * (model.bodies[i].inertia * s.bodySpin[i]);
    }
}

}  // namespace tumble
