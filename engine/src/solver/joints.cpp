#include "solver/joints.h"

#include "solver/contact_energy.h"
#include "solver/joint_cone.h"
#include "solver/joint_drive.h"
#include "solver/joint_general.h"
#include "solver/joint_math.h"
#include "solver/joint_projection.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace tumble {

using JointRow = ContactSolverScratch::JointRow;
using namespace joint;

namespace {

constexpr int kNewtonSteps = 12;  // per group (joint_projection.cpp)
constexpr int kRattlePasses = 6;
constexpr int kProjectionPasses = 100;

// The effective mass matrix of a point held on two bodies (velocity change of the relative
// point velocity per unit impulse): Σ m⁻¹ 1 - [r]× I⁻¹ [r]×.
Mat3 pointMass(const SolverBody& A, const Vec3& rA, const SolverBody* B, const Vec3& rB) {
    Mat3 K = moveFor(A, rA, rA);
    if (B) K += moveFor(*B, rB, rB);
    return K;
}

// A distance row's effective mass along n, and its arms and spins.
void lineRow(const SolverBody& A, const SolverBody* B, JointRow& r) {
    r.armA = r.rA.cross(r.n);
    r.armB = r.rB.cross(r.n);
    r.spinA = A.invI * r.armA;
    r.spinB = B ? Vec3(B->invI * r.armB) : Vec3::Zero();
    const double inv = A.invMass + (B ? B->invMass : 0.0) + r.armA.dot(r.spinA) + r.armB.dot(r.spinB);
    r.k = inv > 0.0 ? 1.0 / inv : 0.0;
}

void applyLine(SolverBody& A, SolverBody* B, const JointRow& r, double d) {
    A.v += (A.invMass * d) * r.n;
    A.w += d * r.spinA;
    A.touched = true;
    if (!B) return;
    B->v -= (B->invMass * d) * r.n;
    B->w -= d * r.spinB;
    B->touched = true;
}

SolverBody* other(ContactSolverScratch& s, const JointRow& r) {
    return r.b >= 0 ? &s.bodies[r.b] : nullptr;
}

// A's anchor's velocity relative to B's (B null: the world's, at rest).
Vec3 relativeTo(const SolverBody& A, const Vec3& rA, const SolverBody* B, const Vec3& rB) {
    return pointVelocity(A, rA) - (B ? pointVelocity(*B, rB) : Vec3::Zero());
}

// The velocity of a distance or rope row: the anchors' separating speed along r.n.
double lineVelocity(const SolverBody& A, const SolverBody* B, const JointRow& r) {
    return r.n.dot(A.v - (B ? B->v : Vec3::Zero())) + r.armA.dot(A.w) - (B ? r.armB.dot(B->w) : 0.0);
}

const SolverBody kStill;           // the world: nothing moves it
constexpr double kReached = 1e-9;  // m or rad: a limit or a rope this near is taut in an impact

// The length of joint k's last solve (0: unknown).
double lastStep(const State& state, int k) {
    return k < static_cast<int>(state.jointSteps.size()) ? state.jointSteps[k] : 0.0;
}

// The time over which joint k's remembered force acts in the warm start of a solve over h:
// h, but at most `most` times its last solve's length (as warmScale bounds the contacts').
double warmSpan(const State& state, int k, double h, double most) {
    const double last = lastStep(state, k);
    return last > 0.0 ? std::min(h, most * last) : h;
}

// A ball joint's cone and twist rows (joint_cone.h) at the poses now; in an impact only a
// bound reached, holding.
void ballLimitRows(const JointModel& j, const State& state, double h, bool impulsive, const SolverBody& A,
                   const SolverBody* B, JointRow& r, std::vector<JointRow::Angular>& rows) {
    r.angularBegin = static_cast<int>(rows.size());
    const BallAngles g = ballAngles(j, state.bodies[j.a], j.b >= 0 ? &state.bodies[j.b] : nullptr);
    // `room`: how far the angle may still go towards the bound (negative: past it).
    auto add = [&](const Vec3& axis, double room, int sign) {
        if (impulsive && room > kReached) return;
        const double inv = axis.dot(A.invI * axis) + (B ? axis.dot(B->invI * axis) : 0.0);
        if (!(inv > 0.0)) return;
        JointRow::Angular& row = rows.emplace_back();
        ++r.angulars;
        row.axis = axis;
        row.k = 1.0 / inv;
        row.sign = sign;
        row.target = impulsive ? 0.0 : -sign * std::max(room, 0.0) / h;
    };
    if (j.swingLimited && g.swingKnown) add(g.swingAxis, g.swingBound - g.swing, -1);
    if (j.twistLimited) {
        add(g.twistAxis, g.twist - j.twistLower, +1);
        add(g.twistAxis, j.twistUpper - g.twist, -1);
    }
}

// The mass along a hinge's or slider's free axis with its other rows held: the inverse of
// Jx M⁻¹ Jxᵀ − aᵀ K⁻¹ a, a = J M⁻¹ Jxᵀ (0: nothing can move along it); with `held`, the
// impulse on the other rows, −K⁻¹ a, that goes with a unit impulse along the axis.
double heldAxisMass(const ContactSolverScratch::GeneralRow& g, const AxisRow& x, const SolverBody& A,
                    const SolverBody& B, Vector6* held = nullptr) {
    auto moved = [](const SolverBody& body, const Vector6& J) {
        Vector6 out;
        out << body.invMass * J.head<3>(), body.invI * J.tail<3>();
        return out;
    };
    const Vector6 mA = moved(A, x.JAx), mB = moved(B, x.JBx);
    Vector6 a = g.JA.transpose() * mA + g.JB.transpose() * mB;
    a.tail(6 - g.m).setZero();
    const Vector6 Ka = g.Kinv * a;
    if (held) *held = -Ka;
    const double inv = x.JAx.dot(mA) + x.JBx.dot(mB) - a.dot(Ka);
    return inv > 1e-12 * (x.JAx.dot(mA) + x.JBx.dot(mB)) ? 1.0 / inv : 0.0;
}

// A difference of free axis x's coordinates: a six-axis joint's angle (a rotation vector's
// component, within ±π) jumps by 2π as it passes ±π, so its differences are taken the
// short way round (a hinge's angle is counted on past a turn: as it is).
double gap(const JointAxis& x, double d) {
    return x.axis >= 3 ? std::remainder(d, 2.0 * M_PI) : d;
}

// The coordinate of joint j's free axis x at the poses of `at` (a hinge's angle near the
// last step's, as `state` tracks it).
double coordinateAt(const JointModel& j, const JointAxis& x, const State& at, const State& state) {
    return axisCoordinate(j, x, at.bodies[j.a], j.b >= 0 ? &at.bodies[j.b] : nullptr, state);
}

// A hinge's or slider's spring and servo as rows along its free axis (joint_drive.h): a
// spring, and a servo by gains, as soft rows; a servo by its time constant as a rate row
// whose target is the critically damped path's from the step's start (rate v₀, coordinate
// c₀): (b/h)(c₀ − target) + (α + b) v₀, held against any load up to its force.
void prepareDrives(const JointModel& jm, double h, const State& state, ContactSolverScratch& s,
                   const SolverBody& A, const SolverBody& B, const ContactSolverScratch::GeneralRow& g,
                   AxisRow& x) {
    const JointAxis& j = *x.settings;
    x.drives = 0;
    x.driveBegin = static_cast<int>(s.driveRows.size());
    if (!(j.spring || j.servo) || !(h > 0.0)) return;
    const double mass = heldAxisMass(g, x, A, B);
    if (!(mass > 0.0)) return;
    {
        SolverBody A0, B0;  // the bodies' velocities at the step's start
        static_cast<BodyVelocity&>(A0) = s.start[jm.a];
        if (jm.b >= 0) static_cast<BodyVelocity&>(B0) = s.start[jm.b];
        x.startRate = axisVelocity(x, A0, B0);
    }
    x.startCoord = s.stepStart ? coordinateAt(jm, j, *s.stepStart, state) : x.coord - h * x.startRate;
    auto add = [&](double p, double q, double error, double most) {
        const DriveStep step = driveStep(p, q, h);
        ContactSolverScratch::GeneralRow::Drive& d = s.driveRows.emplace_back();
        ++x.drives;
        d.kappa = step.kappa;
        d.target = step.b / h * error + (step.alpha - step.kappa) * x.startRate;
        d.mass = mass;
        d.gain = 1.0 / ((1.0 - step.kappa) / x.kAxis + step.kappa / mass);
        d.most = most;
    };
    if (j.spring) add(j.springDamping / mass, j.springStiffness / mass, gap(j, x.coord - j.springRest), HUGE_VAL);
    if (!j.servo) return;
    const double tau = j.servoTimeConstant;
    // The target at the step's end (a keyed one moves: each step chases it).
    const double target = j.servoTargetAt(s.stepStart ? s.stepStart->time + h : state.time);
    if (!(tau > 0.0)) {
        add(j.servoDamping / mass, j.servoStiffness / mass, gap(j, x.coord - target), j.servoMax * h);
        return;
    }
    const DriveStep step = driveStep(2.0 / tau, 1.0 / (tau * tau), h);
    ContactSolverScratch::GeneralRow::Drive& d = s.driveRows.emplace_back();
    ++x.drives;
    d.hard = true;
    d.target = step.b / h * gap(j, x.startCoord - target) + (step.alpha + step.b) * x.startRate;
    d.most = j.servoMax * h;
}

// A hinge's, slider's or fixed joint's rows at the bodies' poses now, warm-started; false
// when nothing here can move.
bool prepareGeneral(const JointModel& j, int k, const State& state, double h, double span, bool remembered,
                    bool impulsive, SolverBody& A, SolverBody* B, ContactSolverScratch& s, JointRow& r) {
    ContactSolverScratch::GeneralRow g;
    const int free = freeAxes(j);
    bool acted = false;
    for (int k = 0; k < free && !acted; ++k) acted = freeAxis(j, k).acted();
    std::array<AxisRow, 6> axes;
    generalRows(j, state.bodies[j.a], j.b >= 0 ? &state.bodies[j.b] : nullptr, g, nullptr,
                hingeNear(state, j), acted ? axes.data() : nullptr);
    const Matrix6 K = generalMass(g, g, A, B ? *B : kStill);
    const Eigen::LDLT<Matrix6> ldlt(K);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0)) return false;
    g.Kinv = ldlt.solve(Matrix6::Identity());
    if (!g.Kinv.allFinite()) return false;
    if (remembered && state.jointTorques.size() == state.jointImpulses.size()) {
        g.lambda.head(g.nl) = g.lin.leftCols(g.nl).transpose() * (span * state.jointImpulses[k]);
        // (The rows' directions are square to each other but a six-axis joint's angular ones,
        // the torque's least-squares split over them: the impulses that give it again.)
        if (j.type == JointType::SixAxis && g.na > 0)
            g.lambda.segment(g.nl, g.na) =
                g.ang.leftCols(g.na).colPivHouseholderQr().solve(span * state.jointTorques[k]);
        else
            g.lambda.segment(g.nl, g.na) = g.ang.leftCols(g.na).transpose() * (span * state.jointTorques[k]);
        // Its work: λ·u⁻ + λᵀKλ/2 (the rows' velocity after is u⁻ + Kλ).
        s.jointWork +=
            g.lambda.dot(generalVelocity(g, A, B ? *B : kStill)) + 0.5 * g.lambda.dot(K * g.lambda);
        applyGeneral(g, A, B, g.lambda);
    }
    g.axisBegin = static_cast<int>(s.axisRows.size());
    for (int k = 0; acted && k < free; ++k) {
        AxisRow& x = axes[k];
        const JointAxis& a = *x.settings;
        if (!a.acted()) continue;
        x.kAxis = axisMass(x, A, B ? *B : kStill);
        if (!(x.kAxis > 0.0)) continue;
        if (!impulsive && (a.spring || a.servo)) prepareDrives(j, h, state, s, A, B ? *B : kStill, g, x);
        if (!impulsive) {
            x.motor = a.motor;
            x.motorSpeed = a.motorSpeed;
            x.motorMax = a.motorMax * h;
            x.lowerOn = x.upperOn = a.limited;
            x.lowerTarget = -std::max(x.coord - a.lower, 0.0) / h;  // reach the limit, no further
            x.upperTarget = std::max(a.upper - x.coord, 0.0) / h;
        } else if (a.limited) {  // an impact: a limit reached holds
            x.lowerOn = x.coord - a.lower <= kReached;
            x.upperOn = a.upper - x.coord <= kReached;
        }
        s.axisRows.push_back(x);
        ++g.axes;
    }
    r.general = static_cast<int>(s.generalRows.size());
    s.generalRows.push_back(g);
    return true;
}

}  // namespace

void addJointBodies(const Model& model, const State& state, std::vector<int>& involved,
                    std::vector<std::uint8_t>& seen) {
    const std::size_t before = involved.size();
    for (const JointModel& j : model.joints) {
        if (!active(model, state, j)) continue;
        involved.push_back(j.a);
        if (j.b >= 0) involved.push_back(j.b);
    }
    if (involved.size() != before) uniqueBodies(involved, seen);
}

bool prepareJoints(const Model& model, const State& state, double h, ContactSolverScratch& s, bool impulsive,
                   const std::vector<std::uint8_t>* only, double warmGrowth) {
    s.jointRows.clear();
    s.generalRows.clear();
    s.angularRows.clear();
    s.axisRows.clear();
    s.driveRows.clear();
    s.jointWork = 0.0;
    const bool remembered = !impulsive && state.jointImpulses.size() == model.joints.size();
    bool grew = false;
    for (int k = 0; k < static_cast<int>(model.joints.size()); ++k) {
        const JointModel& j = model.joints[k];
        if (!active(model, state, j)) continue;
        if (only && !(*only)[j.a] && (j.b < 0 || !(*only)[j.b])) continue;
        const double span = warmSpan(state, k, h, warmGrowth);
        grew = grew || (remembered && span > lastStep(state, k) && lastStep(state, k) > 0.0);
        JointRow r;
        r.joint = k;
        r.a = j.a;
        r.b = j.b;
        SolverBody& A = s.bodies[j.a];
        SolverBody* B = j.b >= 0 ? &s.bodies[j.b] : nullptr;
        r.rA = state.bodies[j.a].q * j.anchorA;
        const Vec3 pA = state.bodies[j.a].x + r.rA;
        r.rB = j.b >= 0 ? Vec3(state.bodies[j.b].q * j.anchorB) : Vec3::Zero();
        const Vec3 pB = j.b >= 0 ? Vec3(state.bodies[j.b].x + r.rB) : j.anchorB;
        if (isGeneral(j.type)) {
            if (prepareGeneral(j, k, state, h, span, remembered, impulsive, A, B, s, r))
                s.jointRows.push_back(r);
            continue;
        }
        if (j.type == JointType::Ball) {
            const Mat3 K = pointMass(A, r.rA, B, r.rB);
            if (!(K.determinant() > 0.0)) continue;  // nothing here can move
            r.Kinv = K.inverse();
            r.ball = true;
            if (j.swingLimited || j.twistLimited) ballLimitRows(j, state, h, impulsive, A, B, r, s.angularRows);
        } else {
            const Vec3 d = pA - pB;
            const double length = d.norm();
            if (!(length > kDegenerate)) continue;  // no line yet: held next step, projected now
            r.n = d / length;
            lineRow(A, B, r);
            if (!(r.k > 0.0)) continue;
            r.pullsOnly = j.type == JointType::Rope;
            // A rope lets its slack close within the step, no more (a contact's speculative
            // target); a rod keeps its length (the drift is projected away afterwards). In
            // an impact a slack rope does nothing and a taut one holds.
            if (impulsive && r.pullsOnly && j.length - length > kReached) continue;
            r.target = r.pullsOnly && !impulsive ? std::max(0.0, (j.length - length) / h) : 0.0;
        }
        // The warm start: the last step's force over this step (warmSpan).
        if (remembered) {
            r.lambda = span * state.jointImpulses[k];
            if (j.type != JointType::Ball) r.lambda.y() = r.lambda.z() = 0.0;
            if (r.pullsOnly) r.lambda.x() = std::min(r.lambda.x(), 0.0);
            if (j.type == JointType::Ball) {
                const Vec3 before = relativeTo(A, r.rA, B, r.rB);
                applyImpulse(A, r.rA, r.lambda);
                if (B) applyImpulse(*B, r.rB, -r.lambda);
                s.jointWork += 0.5 * r.lambda.dot(before + relativeTo(A, r.rA, B, r.rB));
            } else if (r.lambda.x() != 0.0) {
                s.jointWork += r.lambda.x() * (lineVelocity(A, B, r) + 0.5 * r.lambda.x() / r.k);
                applyLine(A, B, r, r.lambda.x());
            }
        }
        s.jointRows.push_back(r);
    }
    return grew;
}

bool updateJoint(ContactSolverScratch& s, int k, double quietSpeed) {
    JointRow& r = s.jointRows[k];
    SolverBody& A = s.bodies[r.a];
    SolverBody* B = other(s, r);
    double change = 0.0;
    if (r.general >= 0) {  // hinge, slider, fixed: all rows at once
        ContactSolverScratch::GeneralRow& g = s.generalRows[r.general];
        const Vector6 v = generalVelocity(g, A, B ? *B : kStill);
        const Vector6 d = -(g.Kinv * v);
        g.lambda += d;
        applyGeneral(g, A, B, d);
        s.jointWork += 0.5 * d.dot(v);         // (the rows' velocity after is v + Kd = 0)
        change = v.lpNorm<Eigen::Infinity>();  // (the rows past m are zero)
        // The motors', limits', springs' and servos' rows along the free axes.
        for (int k = 0; k < g.axes; ++k) {
            AxisRow& x = s.axisRows[g.axisBegin + k];
            auto take = [&](double& lambda, double next, double vx) {
                if (next == lambda) return;
                s.jointWork += (next - lambda) * (vx + 0.5 * (next - lambda) / x.kAxis);
                applyAxis(x, A, B, next - lambda);
                change = std::max(change, std::abs(next - lambda) / x.kAxis);
                lambda = next;
            };
            auto row = [&](double& lambda, double target, double low, double high) {
                const double vx = axisVelocity(x, A, B ? *B : kStill);
                take(lambda, std::clamp(lambda - x.kAxis * (vx - target), low, high), vx);
            };
            for (int i = 0; i < x.drives; ++i) {  // spring, servo: soft rows, or a servo's rate
                ContactSolverScratch::GeneralRow::Drive& d = s.driveRows[x.driveBegin + i];
                if (d.hard) {
                    row(d.lambda, d.target, -d.most, d.most);
                    continue;
                }
                const double vx = axisVelocity(x, A, B ? *B : kStill);
                const double residual = (1.0 - d.kappa) * vx + d.kappa / d.mass * d.lambda - d.target;
                take(d.lambda, std::clamp(d.lambda - d.gain * residual, -d.most, d.most), vx);
            }
            if (x.motor) row(x.motorLambda, x.motorSpeed, -x.motorMax, x.motorMax);
            if (x.lowerOn) row(x.lowerLambda, x.lowerTarget, 0.0, HUGE_VAL);
            if (x.upperOn) row(x.upperLambda, x.upperTarget, -HUGE_VAL, 0.0);
        }
    } else if (!r.ball) {  // one row along the line
        const double vn = lineVelocity(A, B, r);
        const double old = r.lambda.x();
        double next = old - r.k * (vn - r.target);
        if (r.pullsOnly) next = std::min(next, 0.0);
        const double d = next - old;
        r.lambda.x() = next;
        if (d != 0.0) applyLine(A, B, r, d);
        s.jointWork += d * (vn + 0.5 * d / r.k);
        change = std::abs(d) / r.k;  // the speed it changed
    } else {
        const Vec3 dv = relativeTo(A, r.rA, B, r.rB);
        const Vec3 d = -(r.Kinv * dv);
        r.lambda += d;
        applyImpulse(A, r.rA, d);
        if (B) applyImpulse(*B, r.rB, -d);
        s.jointWork += 0.5 * d.dot(dv);  // (the anchors' relative velocity after is dv + Kd = 0)
        change = dv.lpNorm<Eigen::Infinity>();
        for (int i = 0; i < r.angulars; ++i) {  // its cone and twist limits
            JointRow::Angular& q = s.angularRows[r.angularBegin + i];
            const double rate = q.axis.dot(A.w - (B ? B->w : Vec3::Zero()));
            double next = q.lambda - q.k * (rate - q.target);
            next = q.sign > 0 ? std::max(next, 0.0) : std::min(next, 0.0);
            const double step = next - q.lambda;
            if (step == 0.0) continue;
            A.w += A.invI * (step * q.axis);
            A.touched = true;
            if (B) {
                B->w -= B->invI * (step * q.axis);
                B->touched = true;
            }
            s.jointWork += step * (rate + 0.5 * step / q.k);
            change = std::max(change, std::abs(step) / q.k);
            q.lambda = next;
        }
    }
    if (!(change > quietSpeed)) return false;
    const long tick = ++s.tick;  // the contact blocks of these bodies look again
    if (A.invMass > 0.0) s.changedAt[r.a] = tick;
    if (B && B->invMass > 0.0) s.changedAt[r.b] = tick;
    return true;
}

void nudgeDrives(const Model& model, State& state, const ContactSolverScratch& s, double h) {
    if (!s.stepStart) return;
    // Over the step each coordinate moves by the mean of its start and end rates: what is
    // missing is moved along its free axis with the joint's other rows held (a hinge's body
    // turned about the hinge, not its centre). A joint's move turns its base, which may be
    // another's part (an arm's elbow turns its upper link): Gauss-Seidel passes until none
    // is missing more than kHeld.
    constexpr int kPasses = 20;
    for (int pass = 0; pass < kPasses; ++pass) {
        double worst = 0.0;
        for (const JointRow& r : s.jointRows) {
            if (r.general < 0) continue;
            const ContactSolverScratch::GeneralRow& g = s.generalRows[r.general];
            for (int k = 0; k < g.axes; ++k) {
                const AxisRow& x = s.axisRows[g.axisBegin + k];
                if (x.drives == 0) continue;
                const JointModel& j = model.joints[r.joint];
                const bool moveA = movable(model, state, j.a), moveB = movable(model, state, j.b);
                const SolverBody& A = moveA ? s.bodies[j.a] : kStill;
                const SolverBody& B = moveB ? s.bodies[j.b] : kStill;
                const double missing =
                    gap(*x.settings, x.startCoord + 0.5 * h * (x.startRate + axisVelocity(x, A, B)) -
                                         coordinateAt(j, *x.settings, state, state));
                worst = std::max(worst, std::abs(missing));
                if (std::abs(missing) <= kHeld) continue;
                Vector6 held;
                const double mass = heldAxisMass(g, x, A, B, &held);
                BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
                nudgeAxis(x, A, state.bodies[j.a], moveA, B, b, moveB, missing * mass);
                nudgeGeneral(g, A, state.bodies[j.a], moveA, B, b, moveB, held * (missing * mass));
            }
        }
        if (worst <= kHeld) break;
    }
}

void rememberJoints(const Model& model, const ContactSolverScratch& s, double h, State& state) {
    if (model.joints.empty()) return;
    const std::size_t n = model.joints.size();
    if (state.jointImpulses.size() != n) state.jointImpulses.assign(n, Vec3::Zero());
    if (state.jointTorques.size() != n) state.jointTorques.assign(n, Vec3::Zero());
    if (state.jointSteps.size() != n) state.jointSteps.assign(n, 0.0);
    if (state.jointForces.size() != n) state.jointForces.assign(n, Vec3::Zero());
    if (state.jointCouples.size() != n) state.jointCouples.assign(n, Vec3::Zero());
    // A joint whose bodies all stand still here (asleep, or parked while World cuts the rest
    // of the step) keeps what it had, as the contacts of sleeping pairs do; the others are
    // written below if they have rows, else cleared.
    auto idle = [&](int b) {
        return b < 0 || state.isAsleep(b) || model.bodies[b].motion != Motion::Dynamic;
    };
    for (std::size_t k = 0; k < n; ++k) {
        const JointModel& j = model.joints[k];
        if (idle(j.a) && idle(j.b)) continue;
        state.jointImpulses[k].setZero();
        state.jointTorques[k].setZero();
        state.jointForces[k].setZero();
        state.jointCouples[k].setZero();
        state.jointSteps[k] = h;
    }
    for (const JointRow& r : s.jointRows) {
        const JointModel& j = model.joints[r.joint];
        // What the joint carried: its rows' impulse and the projection's, over the step.
        Vec3 impulse =
            s.projectedImpulse.size() == model.joints.size() ? s.projectedImpulse[r.joint] : Vec3::Zero();
        Vec3 reported = Vec3::Zero();  // the force beyond what breaking counts
        if (r.general < 0) {
            state.jointSteps[r.joint] = h;
            state.jointImpulses[r.joint] = r.lambda / h;
            impulse += r.ball ? r.lambda : Vec3(r.lambda.x() * r.n);
            for (int i = 0; i < r.angulars; ++i)  // a ball's cone and twist limits: a couple
                state.jointCouples[r.joint] += s.angularRows[r.angularBegin + i].lambda / h *
                                               s.angularRows[r.angularBegin + i].axis;
            if (r.angulars && s.projectedCouple.size() == model.joints.size())
                state.jointCouples[r.joint] += s.projectedCouple[r.joint] / h;
        } else {
            const ContactSolverScratch::GeneralRow& g = s.generalRows[r.general];
            state.jointSteps[r.joint] = h;
            state.jointImpulses[r.joint] = g.lin.leftCols(g.nl) * g.lambda.head(g.nl) / h;
            state.jointTorques[r.joint] = g.ang.leftCols(g.na) * g.lambda.segment(g.nl, g.na) / h;
            impulse += g.lin.leftCols(g.nl) * g.lambda.head(g.nl);
            const Vec3 projected =
                s.projectedCouple.size() == model.joints.size() ? s.projectedCouple[r.joint] : Vec3::Zero();
            state.jointCouples[r.joint] = state.jointTorques[r.joint] + projected / h;
            // A motor's and the limits' push along the free axis: a couple about a hinge's
            // axis, a force along a slider's (reported; breaking is the constraint's alone).
            for (int k = 0; k < g.axes; ++k) {
                const AxisRow& x = s.axisRows[g.axisBegin + k];
                double axial = (x.motorLambda + x.lowerLambda + x.upperLambda) / h;
                for (int i = 0; i < x.drives; ++i) axial += s.driveRows[x.driveBegin + i].lambda / h;
                state.jointCouples[r.joint] += axial * x.JAx.tail<3>();
                reported += axial * x.JAx.head<3>();
            }
        }
        state.jointForces[r.joint] = impulse / h + reported;
        const double force = impulse.norm() / h;
        // Breaking: after this step the joint acts no more (and starts no next step warm).
        if (force > j.breakForce) {
            if (state.jointBrokenAt.empty()) state.jointBrokenAt.assign(model.joints.size(), std::nan(""));
            state.jointBrokenAt[r.joint] = state.time;
            state.jointImpulses[r.joint].setZero();
            state.jointTorques[r.joint].setZero();
        }
    }
}

namespace {

bool turnedFar(const Vec3& then, const Vec3& now) {
    return then.cross(now).norm() > 0.2 * then.norm() * now.norm() || then.dot(now) < 0.0;
}

bool turnedFar(const Quat& then, const Quat& now) {
    return std::abs(then.dot(now)) < std::cos(0.1);
}

// A Newton step on a hinge's, slider's, fixed or six-axis joint's rows (as projectionPass's
// for the others); returns the error it found. A free axis past one of its limits joins the
// rows, held at the bound, so that one step closes both (positions only: the limit's
// velocity row has stopped the approach). Apart, the rows' step moved the coordinate past
// its stop and the stop's nudge opened the rows, pass after pass: a ragdoll's knee stayed
// 1e-12 off for all 100 passes.
double projectGeneral(State& state, ContactSolverScratch& s, double h, const State* from, const State& at,
                      const JointModel& j, bool moveA, bool moveB, const SolverBody& A, const SolverBody& B) {
    BodyState& a = state.bodies[j.a];
    BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
    ContactSolverScratch::GeneralRow now, then;
    Vector6 C;
    const double near = hingeNear(state, j);
    const int free = freeAxes(j);
    bool limited = false;
    for (int k = 0; k < free && !limited; ++k) limited = freeAxis(j, k).limited;
    std::array<AxisRow, 6> axes;
    generalRows(j, a, b, now, &C, near, limited ? axes.data() : nullptr);
    const double error = C.lpNorm<Eigen::Infinity>();  // (the rows past m are zero)
    const int m = now.m;
    std::array<int, 6> stops{};  // the free axes past a limit, as rows m, m + 1, ...
    int extra = 0;
    double past = 0.0;
    for (int k = 0; limited && k < free; ++k) {
        const JointAxis& x = freeAxis(j, k);
        const double c = axes[k].coord;
        const double by = !x.limited ? 0.0 : c < x.lower ? c - x.lower : c > x.upper ? c - x.upper : 0.0;
        if (std::abs(by) <= kHeld || m + extra >= 6) continue;
        past = std::max(past, std::abs(by));
        stops[extra] = k;
        now.JA.col(m + extra) = axes[k].JAx;
        now.JB.col(m + extra) = axes[k].JBx;
        C[m + extra++] = by;
    }
    const double found = std::max(error, past);
    if (found <= kHeld) return found;
    // (As for the others: a body that turned far since the start is left to the passes
    // along the directions now; but a stop past with the rows held is moved back along the
    // directions now, positions only, as a stop always was.)
    const bool far = from && (turnedFar(at.bodies[j.a].q, a.q) || (b && turnedFar(at.bodies[j.b].q, b->q)));
    if (far && error > kHeld) return found;
    now.m = m + extra;
    // The rows at the start; at the poses now themselves (the passes along the directions
    // now) they are the ones just made.
    if (&at == &state || far) {
        then = now;
    } else {
        std::array<AxisRow, 6> axes0;
        generalRows(j, at.bodies[j.a], b ? &at.bodies[j.b] : nullptr, then, nullptr, near,
                    extra ? axes0.data() : nullptr);
        for (int i = 0; i < extra; ++i) {
            then.JA.col(m + i) = axes0[stops[i]].JAx;
            then.JB.col(m + i) = axes0[stops[i]].JBx;
        }
        then.m = m + extra;
    }
    const Matrix6 K = generalMass(now, then, A, B);
    // K is the rows' block and the identity past them: well conditioned, so partial pivoting
    // does (full pivoting was a tenth of ragdoll-pile's step).
    const Vector6 lambda = -K.partialPivLu().solve(C);
    if (!lambda.allFinite()) return found;
    nudgeGeneral(then, A, a, moveA, B, b, moveB, lambda);
    if (from && h != 0.0 && !far) {  // the rows' move was made by the impulse λ / h over the step
        Vector6 rows = lambda;
        rows.tail(6 - m).setZero();  // (the stops' moves give no velocity)
        s.projectedImpulse[j.index] += then.lin.leftCols(then.nl) * rows.head(then.nl) / h;
        s.projectedCouple[j.index] += then.ang.leftCols(then.na) * rows.segment(then.nl, then.na) / h;
        if (moveA) applyToBody(s.bodies[j.a], then.JA * (rows / h));
        if (moveB) applyToBody(s.bodies[j.b], then.JB * (rows / h));
    }
    return found;
}

// One joint of a pass (see projectionPass); returns its error (m or rad) as it found it.
double projectOne(const Model& model, State& state, ContactSolverScratch& s, double h, const State* from,
                  const JointModel& j) {
    const SolverBody still;  // the world, and bodies that cannot move
    const bool moveA = movable(model, state, j.a), moveB = movable(model, state, j.b);
    const SolverBody& A = moveA ? s.bodies[j.a] : still;
    const SolverBody& B = moveB ? s.bodies[j.b] : still;
    BodyState& a = state.bodies[j.a];
    const Vec3 rA = a.q * j.anchorA;
    const Vec3 rB = j.b >= 0 ? Vec3(state.bodies[j.b].q * j.anchorB) : Vec3::Zero();
    const Vec3 pA = a.x + rA;
    const Vec3 pB = j.b >= 0 ? Vec3(state.bodies[j.b].x + rB) : j.anchorB;
    const State& at = from ? *from : state;
    if (isGeneral(j.type)) return projectGeneral(state, s, h, from, at, j, moveA, moveB, A, B);
    const Vec3 arA = at.bodies[j.a].q * j.anchorA;  // the arms the impulse acts at
    const Vec3 arB = j.b >= 0 ? Vec3(at.bodies[j.b].q * j.anchorB) : Vec3::Zero();
    if (j.swingLimited || j.twistLimited) {  // (as a hinge's: its rows at once)
        if (from && (turnedFar(at.bodies[j.a].q, a.q) || (j.b >= 0 && turnedFar(at.bodies[j.b].q, state.bodies[j.b].q))))
            return (pA - pB).norm();
        return projectLimitedBall(state, s, h, from, at, j, moveA, moveB, A, B);
    }
    // A body that turned far in the step (a whipping chain's end at 1/30 s): the start's
    // arms no longer tell how the anchor moves, and the Newton steps along them can run
    // away; such a joint is left to the passes along the directions now.
    if (from && (turnedFar(arA, rA) || turnedFar(arB, rB))) return (pA - pB).norm();
    Vec3 J = Vec3::Zero();
    double error = 0.0;
    if (j.type == JointType::Ball) {
        const Vec3 C = pA - pB;
        error = C.norm();
        if (C.norm() <= kHeld) return error;
        J = -((moveFor(A, rA, arA) + moveFor(B, rB, arB)).inverse() * C);
    } else {
        const Vec3 d = pA - pB;
        const double length = d.norm();
        const Vec3 d0 = at.bodies[j.a].x + arA - (j.b >= 0 ? Vec3(at.bodies[j.b].x + arB) : j.anchorB);
        if (!(length > kDegenerate) || !(d0.norm() > kDegenerate)) return 0.0;
        double C = length - j.length;
        if (j.type == JointType::Rope) C = std::max(C, 0.0);
        error = std::abs(C);
        if (std::abs(C) <= kHeld) return error;
        const Vec3 n0 = d0 / d0.norm();
        // A Newton step on the length, the impulse along that line.
        const double slope = (d / length).dot((moveFor(A, rA, arA) + moveFor(B, rB, arB)) * n0);
        if (!(slope > 0.0)) return error;
        J = (-C / slope) * n0;
    }
    if (!J.allFinite()) return error;
    if (moveA) nudge(A, a, arA, J);
    if (moveB) nudge(B, state.bodies[j.b], arB, -J);
    if (from && h != 0.0) {  // the move was made by the impulse J / h over the step
        if (moveA) applyImpulse(s.bodies[j.a], arA, J / h);
        if (moveB) applyImpulse(s.bodies[j.b], arB, -J / h);
        s.projectedImpulse[j.index] += J / h;
    }
    return error;
}

// Where a body stood when a joint was last found holding (its pose, to the bit).
bool samePlace(const ContactSolverScratch::JointCheck::Place& p, const BodyState& b) {
    return std::memcmp(p.x.data(), b.x.data(), sizeof(double) * 3) == 0 &&
           std::memcmp(p.q.coeffs().data(), b.q.coeffs().data(), sizeof(double) * 4) == 0;
}

// One Gauss-Seidel pass of Newton steps over the active joints; returns the largest error
// it found. With `from` (the step's start) the impulses act along the joints' directions
// there and, with h ≠ 0, also change the solver bodies' velocities (RATTLE); without, along
// the directions now, positions only (a plain nonlinear Gauss-Seidel projection). With
// `checks` (the positions-only passes), joints found holding are remembered as held.
double projectionPass(const Model& model, State& state, ContactSolverScratch& s, double h, const State* from,
                      std::vector<ContactSolverScratch::JointCheck>* checks = nullptr) {
    double worst = 0.0;
    for (const JointModel& j : model.joints) {
        if (!active(model, state, j)) continue;
        // A joint found holding, its bodies not moved since (to the bit), holds as it did:
        // it is passed over (a pile of ragdolls' passes went on for the few that converge
        // slowly, every joint of every ragdoll measured each pass).
        ContactSolverScratch::JointCheck* c = checks ? &(*checks)[j.index] : nullptr;
        const BodyState& a = state.bodies[j.a];
        const BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
        if (c && c->held && samePlace(c->a, a) && (!b || samePlace(c->b, *b))) {
            worst = std::max(worst, c->error);
            continue;
        }
        ContactSolverScratch::JointCheck before;
        if (c) {
            before.a = {a.x, a.q};
            if (b) before.b = {b->x, b->q};
        }
        const double error = projectOne(model, state, s, h, from, j);
        worst = std::max(worst, error);
        if (c) {
            *c = before;
            c->error = error;
            c->held = error <= kHeld && samePlace(before.a, a) && (!b || samePlace(before.b, *b));
        }
    }
    return worst;
}

}  // namespace

void projectJoints(const Model& model, State& state, ContactSolverScratch& s, double h, const State* start) {
    if (start && h != 0.0) {
        s.projectedImpulse.assign(model.joints.size(), Vec3::Zero());
        s.projectedCouple.assign(model.joints.size(), Vec3::Zero());
    }
    // First RATTLE's projection, a few passes (a lone joint converges in two or three);
    // then whatever a long chain has left, along the directions now, which Gauss-Seidel
    // converges on safely (the first kind, iterated long, ran away on a whipping chain).
    // Each group of joints is solved together first (Newton over all its rows); the
    // Gauss-Seidel passes then take ropes, groups too large and what is left.
    double worst = HUGE_VAL;
    if (start) {
        projectGroups(model, state, s, h, start, kNewtonSteps);
        for (int pass = 0; pass < kRattlePasses && worst > kHeld; ++pass)
            worst = projectionPass(model, state, s, h, start);
    }
    projectGroups(model, state, s, 0.0, nullptr, kNewtonSteps);
    worst = HUGE_VAL;
    s.jointChecks.assign(model.joints.size(), {});
    for (int pass = 0; pass < kProjectionPasses && worst > kHeld; ++pass)
        worst = projectionPass(model, state, s, 0.0, nullptr, &s.jointChecks);
    s.jointsOpen = smallGroupsOpen(model, state, s);
    s.jointsOpenAll = worst;
    if (start && h != 0.0)
        for (const JointModel& j : model.joints)
            for (int i : {j.a, j.b})
                if (movable(model, state, i)) s.bodies[i].x = state.bodies[i].x;
}

}  // namespace tumble
