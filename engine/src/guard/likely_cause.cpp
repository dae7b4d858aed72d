// Stability limits on the harmonic oscillator x'' = -ω² x, per step h (z = ωh on the
// imaginary axis): explicit Euler multiplies the energy by 1 + z² every step, so it never
// holds an undamped spring; symplectic Euler and velocity Verlet (the splitting's
// translation) hold it for z < 2; classical RK4 for z < 2√2. A spring at an arm r from the
// centre of mass also swings the body about it: its effective inverse mass is at most
// 1/m + |r|²/I_min, which gives an upper bound of ω, so the step said to be needed is safe.
// Damping at rate λ (1/s) is stable for λh below 2 (2.78 for RK4); explicit Euler on a
// damped spring holds it only for h < c/k (the damping must beat its 1 + z² gain).
#include "guard/likely_cause.h"

#include "common/number_text.h"

#include "collision/detect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tumble {

namespace {

std::string bodyRef(const Model& m, int i) {
    return "body '" + m.bodies[i].name + "'";
}

double dampingLimit(Integrator id) {
    return id == Integrator::Rk4 ? 2.78 : 2.0;
}

// The springs of one body seen as one oscillator: Σ k/m_eff, the stiffest spring, damping.
struct Springs {
    double omega2 = 0.0;  // Σ k_j / m_eff,j (1/s²)
    double rate = 0.0;    // Σ c_j / m_eff,j (1/s)
    int stiffest = -1;    // index into the body's forces
    const ForceTerm* term = nullptr;
    double termInvMass = 0.0;
};

Springs springsOf(const Model& m, int body) {
    Springs s;
    const BodyModel& b = m.bodies[body];
    const double iMin = b.principalMoments.minCoeff();
    int index = 0;
    double worst = 0.0;
    for (const ForceTerm& f : m.forces) {
        if (f.body != body) continue;
        if (f.type == ForceType::Spring) {
            const double invM = b.invMass + (iMin > 0.0 ? f.arm.squaredNorm() / iMin : 0.0);
            s.omega2 += f.stiffness * invM;
            s.rate += f.damping * invM;
            if (f.stiffness * invM > worst || !s.term) {
                worst = f.stiffness * invM;
                s.stiffest = index;
                s.term = &f;
                s.termInvMass = invM;
            }
        }
        ++index;
    }
    return s;
}

std::string springName(const Model& m, int body, const Springs& s) {
    const BodyModel& b = m.bodies[body];
    std::string mass = "m = " + numberText(b.mass, 3) + " kg";
    if (s.term->arm.squaredNorm() > 0.0)
        mass += ", " + numberText(1.0 / s.termInvMass, 3) + " kg at its point";
    return "spring forces[" + std::to_string(s.stiffest) + "] of " + bodyRef(m, body) +
           " (k = " + numberText(s.term->stiffness, 3) + " N/m, " + mass;
}

// A spring or damper of `body` that the step cannot hold, or "".
std::string stiffness(const Model& m, int body) {
    const double dt = m.settings.dt;
    const Integrator id = m.integrator->id;
    const char* name = m.integrator->name;
    const BodyModel& b = m.bodies[body];
    const Springs s = springsOf(m, body);
    if (s.term && s.omega2 > 0.0) {
        const double omega = std::sqrt(s.omega2);
        if (id == Integrator::Euler) {
            const double needs = s.rate / s.omega2;  // stable for dt < c/k
            if (dt >= needs) {
                return "explicit euler gains energy on " + springName(m, body, s) +
                       (needs > 0.0 ? ": it would need dt < " + numberText(needs, 3) + " s"
                                    : ": undamped, at any step") +
                       "); use rk4 (stable for dt < " +
                       numberText(oscillatorLimit(Integrator::Rk4) / omega, 3) +
                       " s) or symplectic-euler (dt < " +
                       numberText(oscillatorLimit(Integrator::SymplecticEuler) / omega, 3) + " s)";
            }
        } else if (dt * omega >= oscillatorLimit(id)) {
            return "dt = " + numberText(dt, 3) + " s is too large for " + springName(m, body, s) +
                   ": needs dt < " + numberText(oscillatorLimit(id) / omega, 3) + " s with " + name + ")";
        }
    }
    const double rates[3] = {s.rate, b.linearDamping, b.angularDamping};
    const char* what[3] = {"the damping of its springs", "its linear_damping", "its angular_damping"};
    for (int k = 0; k < 3; ++k) {
        if (rates[k] > 0.0 && dt * rates[k] >= dampingLimit(id))
            return "dt = " + numberText(dt, 3) + " s is too large for " + what[k] + " of " +
                   bodyRef(m, body) + " (" + numberText(rates[k], 3) + " 1/s: needs dt < " +
                   numberText(dampingLimit(id) / rates[k], 3) + " s with " + name + ")";
    }
    return {};
}

double sizeOf(const Model& m, int i) {
    return boundingRadius(m.bodies[i].collider);
}

}  // namespace

double oscillatorLimit(Integrator id) {
    switch (id) {
        case Integrator::Euler: return 0.0;
        case Integrator::SymplecticEuler: return 2.0;
        case Integrator::Splitting:
        case Integrator::Splitting4: return 2.0;
        case Integrator::Rk4: return 2.0 * std::sqrt(2.0);
    }
    return 0.0;
}

std::string likelyCause(const Model& m, const State& state, int body) {
    const double dt = m.settings.dt;
    if (std::string s = stiffness(m, body); !s.empty()) return s;
    for (int i : m.dynamicBodies) {
        if (i == body) continue;
        if (std::string s = stiffness(m, i); !s.empty()) return s;
    }
    // A kinematic body that moves a good part of a body's size in one step drives deep
    // overlaps that the contact solver answers with large impulses.
    const double own = sizeOf(m, body);
    for (int k : m.kinematicBodies) {
        const BodyModel& b = m.bodies[k];
        if (b.standsStill()) continue;
        const double reach = std::isfinite(sizeOf(m, k)) ? sizeOf(m, k) : 0.0;
        const double speed = b.topSpeed(reach);
        const double smaller = std::min(own, reach > 0.0 ? reach : own);
        if (speed * dt > 0.1 * smaller)
            return std::string(b.path ? "animated " : "kinematic ") + bodyRef(m, k) + " moves " +
                   numberText(speed * dt, 3) + " m per step (" + numberText(speed, 3) +
                   " m/s), more than a tenth of " +
                   (smaller == own ? "the size of " + bodyRef(m, body) : "its own size") + " (" +
                   numberText(smaller, 3) + " m): use a smaller step";
    }
    if (m.bodies[body].motion == Motion::Dynamic) {
        const Vec3 omega = derive(m.bodies[body], state.bodies[body]).omega;
        const double turn = omega.norm() * dt;
        if (std::isfinite(turn) && turn > 0.5) {
            return bodyRef(m, body) + " spins at " + numberText(omega.norm(), 3) + " rad/s, " +
                   numberText(turn, 3) + " rad per step" +
                   (m.integrator->id == Integrator::Euler
                        ? ", too fast for explicit euler: use splitting (exact rotations) or a smaller step"
                        : ": use a smaller step");
        }
    }
    if (needsContacts(m))
        return "the contact solver (the contacts put energy in): try half the step (dt = " +
               numberText(dt, 3) + " s -> " + numberText(0.5 * dt, 3) +
               " s) or twice the solver iterations (solver_iterations = " +
               std::to_string(m.settings.solverIterations) + " -> " +
               std::to_string(2 * m.settings.solverIterations) + ")";
    return "a step too large for the forces acting on it: try a smaller step (dt = " + numberText(dt, 3) +
           " s)";
}

}  // namespace tumble
