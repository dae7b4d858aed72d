#include "solver/contact_energy.h"

#include <algorithm>
#include <cmath>

namespace tumble {

using collision::Manifold;
using collision::ManifoldList;
using Point = ContactSolverScratch::Point;

namespace {

constexpr double kBaumgarte = 0.2;      // share of the overlap beyond the slop removed per pass
constexpr double kMaxCorrection = 0.1;  // largest move per pass, × size
// × the slop: overlap beyond the slop by less is left as it is. The passes remove a fixed
// share of the excess, so without this an excess never reaches zero: it shrinks by 0.8 a
// pass for ever and ends as rounding (hull-rain at rest: a quarter of the last steps'
// nudges moved rocks by 1e-14 of the slop, and kept them from standing still to the bit).
constexpr double kSettled = 1e-3;

}  // namespace

double kineticOf(const BodyModel& body, const Quat& q, const BodyVelocity& b) {
    // Three equal moments (a ball, a cube): the same in every frame, no turn needed.
    const Vec3 w = body.sphericalInertia ? b.w : Vec3(q.conjugate() * b.w);
    return 0.5 * body.mass * b.v.squaredNorm() + 0.5 * w.dot(body.inertia * w);
}

void nudge(const SolverBody& b, BodyState& s, const Vec3& r, const Vec3& J) {
    s.x += b.invMass * J;
    const Vec3 turn = b.invI * r.cross(J);
    const double angle = turn.norm();
    if (angle > 0.0) s.q = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * s.q).normalized();
}

namespace {

bool correctPositions(State& state, ContactSolverScratch& s, int passes, double slopFactor) {
    bool moved = false;
    // Each body's rotation matrix, made once and again only when a nudge turns the body
    // (the same matrices as made point by point, two a point and pass before).
    s.rotation.resize(state.bodies.size());
    for (int i : s.involved) s.rotation[i] = state.bodies[i].q.toRotationMatrix();
    // A point found within its slop is passed over until a nudge moves one of its bodies:
    // it would be found there again (its bodies' poses are what they were), and it adds
    // nothing to `worst` either. Counted in nudges within this call; a body that cannot move
    // is never nudged. (hull-rain: 87 % of the points' visits found nothing to do.)
    s.nudgedAt.resize(state.bodies.size());
    for (int i : s.involved) s.nudgedAt[i] = 0;
    s.settledAt.assign(s.points.size(), -1);
    long nudges = 0;
    for (int pass = 0; pass < passes; ++pass) {
        double worst = 0.0;
        for (size_t i = 0; i < s.points.size(); ++i) {
            const Point& p = s.points[i];
            const long settled = s.settledAt[i];
            if (settled >= 0 && s.nudgedAt[p.a] <= settled && s.nudgedAt[p.b] <= settled) continue;
            const ContactSolverScratch::PointGeometry& g = s.geometry[i];
            BodyState& a = state.bodies[p.a];
            BodyState& b = state.bodies[p.b];
            const SolverBody& A = s.bodies[p.a];
            const SolverBody& B = s.bodies[p.b];
            const Mat3& RA = s.rotation[p.a];
            const Mat3& RB = s.rotation[p.b];
            const Vec3 sA = a.x + RA * g.localA, sB = b.x + RB * g.localB, n = RB * g.localN;
            const double depth = n.dot(sB - sA);
            const double slop = slopFactor * g.slop;
            const double excess = depth - slop - kSettled * g.slop;
            worst = std::max(worst, excess);
            if (excess <= 0.0) {
                s.settledAt[i] = nudges;
                continue;
            }
            const double C = std::min(kBaumgarte * (depth - slop), kMaxCorrection * g.size);
            if (C <= 0.0) continue;
            const Vec3 rA = sA - a.x, rB = sB - b.x;
            const double k = inverseEffectiveMass(A, rA, B, rB, n);
            if (k <= 0.0) continue;
            const Vec3 J = (C / k) * n;
            ++nudges;
            if (A.invMass > 0.0) {
                nudge(A, a, rA, J);
                s.bodies[p.a].touched = true;
                s.rotation[p.a] = a.q.toRotationMatrix();
                s.nudgedAt[p.a] = nudges;
            }
            if (B.invMass > 0.0) {
                nudge(B, b, rB, -J);
                s.bodies[p.b].touched = true;
                s.rotation[p.b] = b.q.toRotationMatrix();
                s.nudgedAt[p.b] = nudges;
            }
            moved = true;
        }
        if (worst <= 0.0) break;
    }
    return moved;
}

}  // namespace

namespace {

// (The inverse masses are s.bodies': no stage between the solver's entry and its end
// changes one.)
template <class Body>
double solvedKineticOf(const Model& model, const State& state, const ContactSolverScratch& s,
                       const std::vector<Body>& bodies) {
    double e = 0.0;
    for (int i : s.involved)
        if (s.bodies[i].invMass > 0.0) e += kineticOf(model.bodies[i], state.bodies[i].q, bodies[i]);
    return e;
}

}  // namespace

double solvedKinetic(const Model& model, const State& state, const ContactSolverScratch& s,
                     const std::vector<SolverBody>& bodies) {
    return solvedKineticOf(model, state, s, bodies);
}

double solvedKinetic(const Model& model, const State& state, const ContactSolverScratch& s,
                     const std::vector<BodyVelocity>& bodies) {
    return solvedKineticOf(model, state, s, bodies);
}

double gravityPotential(const Model& model, const State& state, const std::vector<int>& which) {
    double u = 0.0;
    for (int i : which)
        if (model.bodies[i].motion == Motion::Dynamic)
            u -= model.bodies[i].mass * model.settings.gravity.dot(state.bodies[i].x);
    return u;
}

// What friction took this step: -Σ λ·(u₀ + u⁺)/2 over the blocks' tangential and twisting
// rows, with λ the whole impulse of the step (warm start included), u₀ the relative
// velocity at the start of the step and u⁺ the one the solver left: the work of a constant
// friction force over the path the bodies are placed on, h (u₀ + u⁺)/2 (redoPoses), exact
// for bodies sliding under constant forces. A body held at rest books nothing (u₀ = u⁺ = 0),
// where u⁻, the velocity after the free step, made a box held on a slope "lose" λ g h / 2 a
// step and a resting pyramid's passes book friction both ways (issue 44: −0.05 J over 60 s).
// The normal rows take the rest (the last passes, which hold the lower bodies still,
// included).
//
// With still islands followed (s.memoryChanged), each block's loss is also kept with one of
// its bodies (frictionShare), and a still body's kept losses are added for its blocks,
// which are not solved: the same total as solving them, up to the order of the sum.
double frictionLost(ContactSolverScratch& s) {
    const bool keep = s.memoryChanged != nullptr;
    auto still = [&](int i) { return s.still && (*s.still)[i]; };
    if (keep)
        for (int i : s.involved)
            if (!still(i)) s.frictionShare[i] = 0.0;
    double lost = 0.0;
    for (const auto& block : s.blocks) {
        const Point& p = s.points[block.begin];
        const BodyVelocity &A0 = s.start[p.a], &B0 = s.start[p.b];
        const SolverBody &A = s.bodies[p.a], &B = s.bodies[p.b];
        const Vec3 u =
            relativeVelocity(A0, block.rA, B0, block.rB) + relativeVelocity(A, block.rA, B, block.rB);
        const Eigen::Vector2d T = block.frictionApplied();
        const Vec3 J = T[0] * block.t1 + T[1] * block.t2;
        const double twist = block.twistApplied();
        const double l = -(0.5 * J.dot(u) + 0.5 * twist * p.n.dot(A0.w - B0.w + A.w - B.w));
        lost += l;
        if (keep) s.frictionShare[A.invMass > 0.0 ? p.a : p.b] += l;
    }
    if (s.still)
        for (int i : s.involved)
            if (still(i)) lost += s.frictionShare[i];
    return lost;
}

double kinematicWork(const ContactSolverScratch& s) {
    double work = 0.0;
    for (const auto& block : s.blocks) {
        const Point& p = s.points[block.begin];
        const SolverBody &A = s.bodies[p.a], &B = s.bodies[p.b];
        if (A.invMass > 0.0 && B.invMass > 0.0) continue;
        for (int k = block.begin; k < block.begin + block.count; ++k) {
            const Vec3& at = s.geometry[k].position;
            work += drivenWork(A, at - A.x, B, at - B.x, s.points[k].lambdaN * s.points[k].n);
        }
        const Eigen::Vector2d T = block.frictionApplied();
        work += drivenWork(A, block.rA, B, block.rB, T[0] * block.t1 + T[1] * block.t2);
        // The twist about n: a couple, whose work is its moment times the giver's spin.
        const double twist = block.twistApplied();
        if (A.invMass == 0.0) work -= twist * p.n.dot(A.w);
        if (B.invMass == 0.0) work += twist * p.n.dot(B.w);
    }
    return work;
}

// Whether the contacts of this step may only take energy out: none of them is with a
// kinematic body that moves in this solve (a conveyor or a paddle does work on what it
// touches; an animated body holding still between its keys does none).
bool passive(const Model& model, const ManifoldList& contacts, const ContactSolverScratch& s) {
    for (const Manifold& m : contacts)
        for (int b : {m.bodyA, m.bodyB})
            if (model.bodies[b].motion == Motion::Kinematic && !model.bodies[b].standsStill() &&
                !(s.bodies[b].v.isZero(0.0) && s.bodies[b].w.isZero(0.0)))
                return false;
    return true;
}

namespace {

// The power of the applied forces, torques and springs' elastic pull on the solver's bodies
// `moving` at the velocities s.bodies has: the work they do over the step, h times this, is
// energy the solve may hand on (a push beyond friction) and not energy it made.
double appliedPower(const Model& model, const State& state, double during, const ContactSolverScratch& s) {
    double power = 0.0;
    for (const ForceTerm& f : model.forces) {
        if (!f.activeAt(during) || !std::binary_search(s.moving.begin(), s.moving.end(), f.body)) continue;
        const BodyState& b = state.bodies[f.body];
        const SolverBody& v = s.bodies[f.body];
        const Vec3 r = b.q * f.arm;
        switch (f.type) {
            case ForceType::Force: {
                const Vec3 F = f.frame == Frame::Body ? Vec3(b.q * f.vector) : f.vector;
                power += F.dot(v.v + v.w.cross(r));
                break;
            }
            case ForceType::Torque:
                power += (f.frame == Frame::Body ? Vec3(b.q * f.vector) : f.vector).dot(v.w);
                break;
            case ForceType::Spring: {
                const Vec3 d = b.x + r - f.anchor;
                const double length = d.norm();
                if (length > 1e-12)
                    power -= f.stiffness * (length - f.restLength) * (d / length).dot(v.v + v.w.cross(r));
                break;
            }
        }
    }
    return power;
}

}  // namespace

// The energy of the bodies the solver moved (s.moving): at the start of the step, as the
// step gave them to the solver (kinetic and gravitational, at the poses the integrator
// reached) and as the solver leaves them (placed again from the start: x = x0 + h v, where
// gravity and the applied forces do their work, linear in the velocities as the potential
// "rate"). Without the applied forces' work, a box pushed beyond friction with the
// symplectic Euler integrator (whose free step lowers the box by g h², not g h² / 2) seemed
// to gain what the push gave it, and the limit stopped it dead.
EnergyBalance energyBalance(const Model& model, const State& state, const State& before,
                            const ContactSolverScratch& s) {
    EnergyBalance e;
    const Vec3& g = model.settings.gravity;
    const double h = state.time - before.time;
    for (int i : s.moving) {
        const BodyModel& body = model.bodies[i];
        const Quat& q = state.bodies[i].q;
        e.kineticIn += kineticOf(body, q, s.entry[i]);
        e.kineticStart += kineticOf(body, before.bodies[i].q, s.start[i]);
        e.kineticOut += kineticOf(body, q, s.bodies[i]);
        e.potentialIn -= body.mass * g.dot(state.bodies[i].x);
        e.potentialStart -= body.mass * g.dot(before.bodies[i].x);
        e.potentialRate -= body.mass * g.dot(h * s.bodies[i].v);
    }
    if (!model.forces.empty()) e.potentialRate -= h * appliedPower(model, state, before.time + 0.5 * h, s);
    return e;
}

// The solver gave the bodies more energy than they brought (Gauss-Seidel stopped before
// it converged, an impulse kept from the last step that no longer fits): their velocities
// are scaled by the largest α ≤ 1 that gives none. Scaling keeps every contact that the
// solver left at rest at rest and every approach as slow, and only ever takes energy out.
// A body at a point that no impulse reached (a pair moving apart) keeps its velocity: it is
// not stored (storeSolverBodies keeps the pushed ones only), so the balance counts it as it
// leaves. (Booked as scaled, the ledger took from the contacts what such bodies kept:
// 13.8 J in one step of 200 chairs piling up. α is still found with them in the sum: found
// without them it slowed the pushed bodies more, and a capsule then went through the floor
// of a bin of 50 landing bodies at 1/30 s, a moment of impact past the eight a step.)
void limitEnergy(const Model& model, const State& state, EnergyBalance& e, ContactSolverScratch& s,
                 double h) {
    // E(α) = α² K + α D + P0 must not exceed E_in; E(0) is every body at rest where it
    // started the step, which is at most its energy there, and so at most E_in.
    const double K = e.kineticOut, D = e.potentialRate, C = e.potentialStart - e.in();
    if (C > 0.0 || K <= 0.0) return;
    const double alpha =
        std::clamp((-D + std::sqrt(std::max(0.0, D * D - 4.0 * K * C))) / (2.0 * K), 0.0, 1.0);
    const Vec3& g = model.settings.gravity;
    double keptKinetic = 0.0, keptRate = 0.0;
    for (int i : s.moving) {
        if (!s.bodies[i].touched) {
            keptKinetic += kineticOf(model.bodies[i], state.bodies[i].q, s.bodies[i]);
            keptRate -= model.bodies[i].mass * g.dot(h * s.bodies[i].v);
            continue;
        }
        s.bodies[i].v *= alpha;
        s.bodies[i].w *= alpha;
    }
    e.kineticOut = alpha * alpha * (K - keptKinetic) + keptKinetic;
    e.potentialRate = alpha * (D - keptRate) + keptRate;
}

// Overlap beyond one slop that no pass removed because the step's energy budget, which all
// the solve's islands share, was spent: its bodies at rest are not at a fixed point of
// their own (a budget from another island would move them), so s.memoryChanged marks them
// (still_islands.h). Where the budget allows the pass, such a point is moved, and its
// bodies with it.
namespace {

void markWaitingOverlap(const State& state, ContactSolverScratch& s) {
    if (!s.memoryChanged) return;
    std::vector<std::uint8_t>& changed = *s.memoryChanged;
    for (size_t i = 0; i < s.points.size(); ++i) {
        const Point& p = s.points[i];
        if (!atRest(s.bodies[p.a]) || !atRest(s.bodies[p.b])) continue;
        const ContactSolverScratch::PointGeometry& g = s.geometry[i];
        const BodyState& a = state.bodies[p.a];
        const BodyState& b = state.bodies[p.b];
        const Mat3& RA = s.rotation[p.a];
        const Mat3& RB = s.rotation[p.b];
        const double depth = (RB * g.localN).dot((b.x + RB * g.localB) - (a.x + RA * g.localA));
        if (depth - (1.0 + kSettled) * g.slop > 0.0) changed[p.a] = changed[p.b] = 1;
    }
}

}  // namespace

// Removes overlap left by the step without touching velocities. Overlap deeper than ten
// slops is always removed (bodies placed inside each other come apart). Between one and
// ten slops it is removed only as far as the energy the contacts took this step allows:
// lifting a body adds potential energy, so with nothing taken out a pile that the solver
// holds at rest stays exactly as it is, and a correction never feeds energy in.
void correctOverlap(const Model& model, State& state, ContactSolverScratch& s,
                    const ContactSolverSettings& cfg, const EnergyBalance& e, bool limited) {
    if (!limited) {
        correctPositions(state, s, cfg.positionIterations, 1.0);
        return;
    }
    correctPositions(state, s, cfg.positionIterations, kFreeOverlap);
    const double budget = e.in() - e.kineticOut - gravityPotential(model, state, s.moving);
    if (budget <= 0.0) {
        markWaitingOverlap(state, s);
        return;
    }
    s.placed.clear();
    for (int i : s.moving) s.placed.push_back({state.bodies[i].x, state.bodies[i].q});
    const double u0 = gravityPotential(model, state, s.moving);
    if (!correctPositions(state, s, cfg.positionIterations, 1.0)) return;
    const double added = gravityPotential(model, state, s.moving) - u0;
    if (added <= budget) return;
    const double beta = std::max(0.0, budget / added);  // gravity's energy is linear in position
    for (size_t k = 0; k < s.moving.size(); ++k) {
        BodyState& b = state.bodies[s.moving[k]];
        b.x = s.placed[k].first + beta * (b.x - s.placed[k].first);
        b.q = s.placed[k].second.slerp(beta, b.q);
    }
}

}  // namespace tumble
