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
//   drifting. Second order, two force evaluations per step.
#include "integrate.h"

#include <chrono>

namespace tumble {

namespace {

using Clock = std::chrono::steady_clock;

const std::vector<Wrench>& evaluateForces(const Model& model, const std::vector<BodyState>& bodies,
                                          double t, IntegrateScratch& scratch, Profile& profile) {
    const auto t0 = Clock::now();
    accumulateForces(model, bodies, t, scratch.wrench);
    profile.forces += std::chrono::duration<double>(Clock::now() - t0).count();
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

// The state derivative (18) of every dynamic body at (t, bodies).
void rates(const Model& model, const std::vector<BodyState>& bodies, double t,
           std::vector<IntegrateScratch::Rate>& out, IntegrateScratch& scratch, Profile& profile) {
    const std::vector<Wrench>& w = evaluateForces(model, bodies, t, scratch, profile);
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
    rates(model, state.bodies, state.time, k, scr, prof);
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
        rates(model, scr.stage, n == 0 ? t : t + stageStep[n - 1], scr.rates[n], scr, prof);
        if (n == 3) break;
        for (int i : awake(model, scr)) {
            const BodyState& s = state.bodies[i];
            const auto& k = scr.rates[n][i];
            BodyState& y = scr.stage[i];
            y.x = s.x + stageStep[n] * k.x;
            y.q = addToQuat(s.q, k.q, stageStep[n]);
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

void symplecticEuler(const Model& model, State& state, double h, IntegrateScratch& scr,
                     Profile& prof) {
    const std::vector<Wrench>& w = evaluateForces(model, state.bodies, state.time, scr, prof);
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

// Exact torque-free rotation for time h, split about the principal axes. In the world
// frame L stays fixed; each sub-step turns the body about one principal axis a by the
// angle h (a · Π) / I_a, where Π = Rᵀ L is L in body axes.
void freeRotation(const BodyModel& b, BodyState& s, double h) {
    static constexpr int axis[5] = {0, 1, 2, 1, 0};
    static constexpr double part[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
    for (int n = 0; n < 5; ++n) {
        const Vec3 a = b.principalAxes.col(axis[n]);
        const Vec3 bodyL = s.q.conjugate() * s.L;
        const double angle = part[n] * h * a.dot(bodyL) / b.principalMoments[axis[n]];
        s.q = s.q * expMap(angle * a);
    }
    s.q.normalize();
}

void splitting(const Model& model, State& state, double h, IntegrateScratch& scr, Profile& prof) {
    const std::vector<Wrench>& w0 = evaluateForces(model, state.bodies, state.time, scr, prof);
    for (int i : awake(model, scr)) {
        const BodyModel& b = model.bodies[i];
        BodyState& s = state.bodies[i];
        s.P += 0.5 * h * w0[i].force;
        s.L += 0.5 * h * w0[i].torque;
        s.x += h * b.invMass * s.P;
        freeRotation(b, s, h);
    }
    const std::vector<Wrench>& w1 = evaluateForces(model, state.bodies, state.time + h, scr, prof);
    for (int i : awake(model, scr)) {
        BodyState& s = state.bodies[i];
        s.P += 0.5 * h * w1[i].force;
        s.L += 0.5 * h * w1[i].torque;
    }
}

}  // namespace

void integrate(const Model& model, State& state, double h, IntegrateScratch& scratch,
               Profile& profile) {
    switch (model.integrator->id) {
    case Integrator::Euler: euler(model, state, h, scratch, profile); break;
    case Integrator::SymplecticEuler: symplecticEuler(model, state, h, scratch, profile); break;
    case Integrator::Rk4: rk4(model, state, h, scratch, profile); break;
    case Integrator::Splitting: splitting(model, state, h, scratch, profile); break;
    }
    for (int i : model.kinematicBodies) {
        const BodyModel& b = model.bodies[i];
        BodyState& s = state.bodies[i];
        s.x += h * b.kinematicVelocity;
        s.q = (expMap(h * b.kinematicAngularVelocity) * s.q).normalized();
    }
}

}  // namespace tumble
