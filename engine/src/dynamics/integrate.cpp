// The integrators. Every one advances (x, q, P, L) of the dynamic bodies; kinematic
// bodies move exactly with their constant velocities whatever the integrator.
//
// euler, rk4: the paper's two methods on the state derivative (18), with the
//   orientation kept as a quaternion (q' = ½ ω ⊗ q) and renormalised after the step.
// symplectic-euler: kick the momenta with the forces at the start, then move the pose
//   with the new velocities; the rotation is applied exactly (exponential map).
// splitting: Strang splitting of kick (forces) and drift (free motion). The free
//   rotation is itself split into exact rotations about the three principal axes
//   (h/2, h/2, h, h/2, h/2). L is untouched by the drift, so |L| is kept to rounding,
//   and the scheme is symplectic, so the energy of a free body oscillates instead of
//   drifting. Second order, two force evaluations per step. See freeRotation for the
//   sub-steps of a fast spin and the energy kept to rounding.
// splitting-4: the same with a fourth-order free rotation (a composition of three).
#include "dynamics/integrate.h"
#include "common/stage_clock.h"
#include "common/workers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace tumble {

namespace {

constexpr int kBodyGrain = 256;  // bodies per chunk on the worker threads

// The forces on `bodies` as they stand, with the forces that act during the step: those
// active at its middle `during` (World::step cuts a step where a force switches, so one set
// acts over each piece; read at the piece's ends, a force starting at the end of a piece
// gave it half a kick of F h too many, and one ending there half a kick too few).
const std::vector<Wrench>& evaluateForces(const Model& model, const std::vector<BodyState>& bodies,
                                          double during, IntegrateScratch& scratch, Profile& profile) {
    const std::uint64_t t0 = stage_clock::now();
    accumulateForces(model, bodies, during, scratch.wrench);
    profile.forces += stage_clock::since(t0);  // ticks (stage_clock.h)
    ++profile.forceEvaluations;
    return scratch.wrench;
}

// The dynamic bodies to advance: all of them, or the awake ones when some sleep.
const std::vector<int>& awake(const Model& model, const IntegrateScratch& scr) {
    return scr.awake ? *scr.awake : model.dynamicBodies;
}

Eigen::Vector4d quatRate(const Quat& q, const Vec3& omega) {
    const Quat dq = Quat(0.0, omega.x(), omega.y(), omega.z()) * q;
    return 0.5 * Eigen::Vector4d(dq.w(), dq.x(), dq.y(), dq.z());
}

Quat addToQuat(const Quat& q, const Eigen::Vector4d& d, double h) {
    return Quat(q.w() + h * d[0], q.x() + h * d[1], q.y() + h * d[2], q.z() + h * d[3]);
}

// The state derivative (18) of every dynamic body at `bodies`, with the forces of the step
// whose middle is `during`.
void rates(const Model& model, const std::vector<BodyState>& bodies, double during,
           std::vector<IntegrateScratch::Rate>& out, IntegrateScratch& scratch, Profile& profile) {
    const std::vector<Wrench>& w = evaluateForces(model, bodies, during, scratch, profile);
    out.resize(bodies.size());
    for (int i : awake(model, scratch)) {
        const BodyModel& b = model.bodies[i];
        const BodyState& s = bodies[i];
        const Mat3 R = s.q.normalized().toRotationMatrix();
        const Vec3 omega = R * (b.invInertia * (R.transpose() * s.L));
        out[i] = {b.invMass * s.P, w[i].force, w[i].torque, quatRate(s.q, omega)};
    }
}

void euler(const Model& model, State& state, double h, IntegrateScratch& scr, Profile& prof) {
    auto& k = scr.rates[0];
    rates(model, state.bodies, state.time + 0.5 * h, k, scr, prof);
    for (int i : awake(model, scr)) {
        BodyState& s = state.bodies[i];
        s.x += h * k[i].x;
        s.q = addToQuat(s.q, k[i].q, h).normalized();
        s.P += h * k[i].P;
        s.L += h * k[i].L;
    }
}

void rk4(const Model& model, State& state, double h, IntegrateScratch& scr, Profile& prof) {
    const double t = state.time;
    scr.stage = state.bodies;
    const double stageStep[3] = {0.5 * h, 0.5 * h, h};
    for (int n = 0; n < 4; ++n) {
        rates(model, scr.stage, t + 0.5 * h, scr.rates[n], scr, prof);
        if (n == 3) break;
        for (int i : awake(model, scr)) {
            const BodyState& s = state.bodies[i];
            const auto& k = scr.rates[n][i];
            BodyState& y = scr.stage[i];
            y.x = s.x + stageStep[n] * k.x;
            // Unit, as every stage that reads it (a force at a point, a spring) turns vectors
            // with it: a quaternion off unit length turns them by a rotation that depends on
            // the pose (a spring pendulum turned as a whole ran 0.14 rad from the original).
            y.q = addToQuat(s.q, k.q, stageStep[n]).normalized();
            y.P = s.P + stageStep[n] * k.P;
            y.L = s.L + stageStep[n] * k.L;
        }
    }
    const double w = h / 6.0;
    for (int i : awake(model, scr)) {
        BodyState& s = state.bodies[i];
        const auto& k1 = scr.rates[0][i];
        const auto& k2 = scr.rates[1][i];
        const auto& k3 = scr.rates[2][i];
        const auto& k4 = scr.rates[3][i];
        s.x += w * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x);
        s.q = addToQuat(s.q, k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q, w).normalized();
        s.P += w * (k1.P + 2.0 * k2.P + 2.0 * k3.P + k4.P);
        s.L += w * (k1.L + 2.0 * k2.L + 2.0 * k3.L + k4.L);
    }
}

void symplecticEuler(const Model& model, State& state, double h, IntegrateScratch& scr, Profile& prof) {
    const std::vector<Wrench>& w = evaluateForces(model, state.bodies, state.time + 0.5 * h, scr, prof);
    for (int i : awake(model, scr)) {
        const BodyModel& b = model.bodies[i];
        BodyState& s = state.bodies[i];
        s.P += h * w[i].force;
        s.L += h * w[i].torque;
        const Mat3 R = s.q.toRotationMatrix();
        const Vec3 omega = R * (b.invInertia * (R.transpose() * s.L));
        s.x += h * b.invMass * s.P;
        s.q = (expMap(h * omega) * s.q).normalized();
    }
}

// Torque-free rotation for time h: the body's L in world axes stays fixed, and so do its
// two invariants in body axes, |Π|² and the kinetic energy Π·I⁻¹Π, where Π = Rᵀ L. Three
// parts:
// 1. Exact rotations about the principal axes in turn (h/2, h/2, h, h/2, h/2): sub-step
//    a turns the body about principal axis a by the angle h (a · Π) / I_a. Each keeps L
//    and |Π| exactly; together they are symplectic and second order.
// 2. Sub-steps, so that no sub-step turns the body by more than kMaxTurn radians: the
//    splitting's error grows with the turn per step (a box at 1 000 rad/s and 1/240 s
//    turns 4 rad a step, and the splitting alone let it flip to another axis, its energy
//    ×5.8). A body turning slower costs nothing more.
// 3. Π is put back on the curve where both invariants have their values from before (the
//    exact motion never leaves it) by turning it on the sphere |Π| = const along the
//    energy's gradient, and the body is turned by the same tiny amount so that R Π = L
//    still holds. The energy is then kept to rounding at any speed, and Π cannot wander
//    to another axis: the curve near one axis never reaches another.
constexpr double kMaxTurn = 0.5;  // rad per sub-step of the splitting
constexpr int kMaxSubsteps = 1000;

// Π (body axes) moved on its sphere to the energy level 2T = e0: Newton along the energy's
// gradient on the sphere, each step accepted only where it brings the energy nearer the
// level (halved until it does; none that does: stop where it is). Unchanged when the
// level is met to rounding already.
// Why the safeguard: the gradient vanishes on a principal axis, so a body spinning about
// one (whatever its pose) had a rounding-level energy error divided by a near-zero
// gradient: the step threw Π across the sphere, the error grew, the loop stopped there,
// and the body was turned with it (a box turned at random and spun about a principal axis
// changed its energy by 1 % to 110 % in 3 s; issue 44). Near an axis the level is a small
// ellipse around it, or beyond reach when rounding put e0 past the extreme value: the
// halved steps then only ever go as far as the energy needs, and Π stays on the axis.
// Near the middle axis the gradient along the sphere is small and Newton slow (a box spun
// at 1 000 rad/s about its middle axis kept 1.6e-7 of energy error after four iterations a
// step); it stops as soon as the level is reached, so the cap is rarely met.
Vec3 ontoEnergy(const BodyModel& b, const Vec3& bodyL, double e0) {
    const Mat3& A = b.principalAxes;
    Vec3 p = A.transpose() * bodyL;
    const double g0 = p.squaredNorm(), radius = std::sqrt(g0);
    const Vec3 invI = b.principalMoments.cwiseInverse();
    auto offLevel = [&](const Vec3& x) { return x.dot(invI.cwiseProduct(x)) - e0; };
    // The energy as read from Π carries a few roundings of e0 (Π = q* L q, then the sum).
    // An error within them is corrected only where that costs a turn of rounding size: near
    // an axis, where the gradient vanishes, it would turn the body by far more.
    const double rounding = 16.0 * std::numeric_limits<double>::epsilon() * e0;
    double e = offLevel(p);
    bool moved = false;
    for (int it = 0; it < 50 && std::abs(e) > 4e-16 * e0; ++it) {
        const Vec3 Jp = invI.cwiseProduct(p);
        const Vec3 d = Jp - (Jp.dot(p) / g0) * p;  // the energy's gradient along the sphere, /2
        const double dd = d.squaredNorm();
        if (!(dd > 0.0)) break;
        Vec3 step = -(0.5 * e / dd) * d;
        if (!(std::abs(e) > rounding) && step.squaredNorm() > 1e-24 * g0) break;
        bool better = false;
        for (int halve = 0; halve < 64 && !better; ++halve, step *= 0.5) {
            Vec3 trial = p + step;
            trial *= radius / trial.norm();
            const double et = offLevel(trial);
            if (std::abs(et) < std::abs(e)) p = trial, e = et, better = true;
        }
        if (!better) break;
        moved = true;
    }
    return moved ? Vec3(A * p) : bodyL;
}

// The rotation that takes a to b, two vectors of the same length (Π before and after the
// projection, both on |Π| = |L|): the quaternion (|a|² + a·b, a × b), normalised, which is
// exact for any angle short of a half turn.
Quat turnBetween(const Vec3& a, const Vec3& b) {
    const Vec3 c = a.cross(b);
    return Quat(a.squaredNorm() + a.dot(b), c.x(), c.y(), c.z()).normalized();
}

void freeRotation(const BodyModel& b, BodyState& s, double h, bool fourthOrder) {
    // No spin, no turn (a body at rest on others: the solver leaves it so to the bit).
    if (s.L.isZero(0.0)) return;
    // A body whose three moments are equal (a sphere, a cube) spins at ω = L / I, constant:
    // one exact turn about L, whatever the step.
    const Vec3& I = b.principalMoments;
    if (I.maxCoeff() - I.minCoeff() <= 1e-12 * I.maxCoeff()) {
        s.q = (expMap(h * s.L / I[0]) * s.q).normalized();
        return;
    }
    static constexpr int axis[5] = {0, 1, 2, 1, 0};
    static constexpr double part[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
    const Vec3 bodyL0 = s.q.conjugate() * s.L;
    const Vec3 spin = b.principalAxes.transpose() * bodyL0;
    const Vec3 omega = spin.cwiseQuotient(b.principalMoments);  // principal axes
    // At most kMaxSubsteps (a body past 500 rad a step keeps its energy and axis but not
    // its phase); a non-finite spin is left to the finite-state check.
    const double turns = h * omega.norm() / kMaxTurn;
    const int n = turns > 1.0 ? static_cast<int>(std::ceil(std::min(turns, double(kMaxSubsteps)))) : 1;
    const double hs = h / n;
    // splitting-4: Yoshida's triple jump, three symmetric second-order steps of weights
    // g1, g0, g1 (g0 < 0), is fourth order; the projection below changes it by what the
    // energy error is, O(h⁵) a step, so it stays fourth order.
    const double c = std::cbrt(2.0), g1 = 1.0 / (2.0 - c), g0 = -c / (2.0 - c);
    const double single[1] = {1.0}, triple[3] = {g1, g0, g1};
    const std::span<const double> weights = fourthOrder ? std::span<const double>(triple) : single;
    // Π in principal axes is carried along: a turn by θ about principal axis k turns Π's
    // other two components by -θ (the body turns, L stays), so L need not be read again
    // through the quaternion at each of the five turns.
    Vec3 p = spin;
    for (int k = 0; k < n; ++k) {
        for (const double w : weights) {
            for (int i = 0; i < 5; ++i) {
                const int ax = axis[i], u = (ax + 1) % 3, v = (ax + 2) % 3;
                const double half = 0.5 * part[i] * w * hs * p[ax] / b.principalMoments[ax];
                const double sh = std::sin(half), ch = std::cos(half);
                const Vec3 a = b.principalAxes.col(ax) * sh;
                s.q = s.q * Quat(ch, a.x(), a.y(), a.z());
                const double cs = ch * ch - sh * sh, sn = 2.0 * sh * ch;  // cos θ, sin θ
                const double pu = p[u], pv = p[v];
                p[u] = cs * pu + sn * pv;
                p[v] = cs * pv - sn * pu;
            }
        }
    }
    s.q.normalize();
    // The body is put back on its energy level every step, not only after sub-steps: the
    // splitting's own energy error, a bounded oscillation of O(h²), reached 0.76 % on a box
    // tumbling about its long axis at 0.5 rad a step (splitting-4: O(h⁴), 3e-3). Projected,
    // both keep it to rounding at any turn and keep their order (2.03 and 4.01 measured);
    // the Dzhanibekov top at dt 1e-3 is 8.1e-8 rad (splitting; 5.8e-7 unprojected) and
    // 3.5e-10 rad (splitting-4; 2.2e-11 unprojected) off RK4 at a 64 times smaller step.
    // Projecting only past a threshold was tried for splitting-4 and made its error erratic
    // (a kick now and then near the middle axis, where the way back to the level is long):
    // 1e-8 gave 0.032 rad on the 10 s tumbling box at 1/60 s, where it is 2.2e-5 now.
    const double e0 = spin.dot(omega);
    if (!(e0 > 0.0)) return;
    const Vec3 bodyL = s.q.conjugate() * s.L;
    const Vec3 onCurve = ontoEnergy(b, bodyL, e0);
    if (onCurve == bodyL) return;
    // Turn the body so that the new Π is what L reads in its axes: q' Π' q'* = q Π q* = L.
    s.q = (s.q * turnBetween(onCurve, bodyL)).normalized();
}

void splitting(const Model& model, State& state, double h, IntegrateScratch& scr, Profile& prof,
               bool fourthOrderRotation) {
    const std::vector<Wrench>& w0 = evaluateForces(model, state.bodies, state.time + 0.5 * h, scr, prof);
    // Each body's kick and drift is its own: spread over the worker threads.
    const std::vector<int>& bodies = awake(model, scr);
    forEachChunk(
        scr.pool, static_cast<int>(bodies.size()), kBodyGrain, [&](int begin, int end) {
        for (int k = begin; k < end; ++k) {
            const int i = bodies[k];
            const BodyModel& b = model.bodies[i];
            BodyState& s = state.bodies[i];
            s.P += 0.5 * h * w0[i].force;
            s.L += 0.5 * h * w0[i].torque;
            s.x += h * b.invMass * s.P;
            freeRotation(b, s, h, fourthOrderRotation);
        }
    }, &scr.drift);
    const std::vector<Wrench>& w1 = evaluateForces(model, state.bodies, state.time + 0.5 * h, scr, prof);
    for (int i : awake(model, scr)) {
        BodyState& s = state.bodies[i];
        s.P += 0.5 * h * w1[i].force;
        s.L += 0.5 * h * w1[i].torque;
    }
}

}  // namespace

void integrate(const Model& model, State& state, double h, IntegrateScratch& scratch, Profile& profile) {
    switch (model.integrator->id) {
        case Integrator::Euler: euler(model, state, h, scratch, profile); break;
        case Integrator::SymplecticEuler: symplecticEuler(model, state, h, scratch, profile); break;
        case Integrator::Rk4: rk4(model, state, h, scratch, profile); break;
        case Integrator::Splitting: splitting(model, state, h, scratch, profile, false); break;
        case Integrator::Splitting4: splitting(model, state, h, scratch, profile, true); break;
    }
    for (int i : model.kinematicBodies) {
        const BodyModel& b = model.bodies[i];
        BodyState& s = state.bodies[i];
        if (b.path) {
            placeOnPath(b, state.time + h, s);
            continue;
        }
        s.x += h * b.kinematicVelocity;
        s.q = (expMap(h * b.kinematicAngularVelocity) * s.q).normalized();
    }
}

}  // namespace tumble
