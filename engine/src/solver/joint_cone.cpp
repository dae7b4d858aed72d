#include "solver/joint_cone.h"

#include "solver/joint_general.h"
#include "solver/joint_math.h"

#include <algorithm>
#include <cmath>

namespace tumble::joint {

BallAngles ballAngles(const JointModel& j, const BodyState& a, const BodyState* b) {
    BallAngles out;
    const Quat qa = a.q, qb = b ? b->q : Quat::Identity();
    const Vec3 aA = qa * j.axisA, n = qb * j.axisB;
    const Vec3 lean = n.cross(aA);
    const double s = lean.norm();
    out.swing = std::atan2(s, n.dot(aA));
    if (s > 1e-12) {
        out.swingKnown = true;
        out.swingAxis = lean / s;
        const Vec3 d = (aA - aA.dot(n) * n).normalized();
        const Vec3 e1 = qb * j.swingCross, e2 = n.cross(e1);
        const double c = d.dot(e1), t = d.dot(e2);  // the lean's direction ψ: cos, sin
        const double d1 = c / j.swingLimit[0], d2 = t / j.swingLimit[1];
        out.swingBound = 1.0 / std::sqrt(d1 * d1 + d2 * d2);
        // φ − θ(ψ) changes by u·δ − θ'(ψ) dψ for a turn δ of A relative to B, and the lean
        // turns about n by dψ = (n − d cot φ)·δ; θ' = θ³ cos ψ sin ψ (1/θ₁² − 1/θ₂²), 0 on a
        // circle (where the row is u, to the bit).
        const double bound = out.swingBound;
        const double slope = bound * bound * bound * c * t *
                             (1.0 / (j.swingLimit[0] * j.swingLimit[0]) - 1.0 / (j.swingLimit[1] * j.swingLimit[1]));
        out.swingRow = out.swingAxis - slope * (n - d * (n.dot(aA) / s));
    } else {
        out.swingBound = std::min(j.swingLimit[0], j.swingLimit[1]);
    }
    // The twist about A's axis as placed relative to B (A's rotation since then, split).
    Quat e = qa * (qb * j.relative).conjugate();
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    const Vec3 m = (qb * j.relative) * j.axisA;
    out.twist = 2.0 * std::atan2(e.vec().dot(m), e.w());
    out.twist = std::remainder(out.twist, 2.0 * M_PI);
    // The twist's rate is w · (a + m) / (1 + a·m) for A's spin w relative to B's (the
    // twist being about m, A's axis where the placement puts it, and the swing the shortest
    // turn from m to a): the mean of the two, longer by 1 / cos of half the turn between
    // them. As the unit mean of a and n the rows saw the twist move slower than it does (and
    // about another axis where the scene placed A's axis off B's), and the projection's
    // Newton steps took 0.25-0.3 of the error a step where the swing was wide
    // (ragdoll-stairs: 12 steps, left to the passes; now two or three).
    const Vec3 mean = aA + m;
    const double along = 1.0 + aA.dot(m);
    out.twistAxis = along > 1e-9 ? Vec3(mean / along) : aA;
    return out;
}

double ballLimitsPast(const JointModel& j, const BallAngles& g) {
    double past = 0.0;
    if (j.swingLimited) past = std::max(past, g.swing - g.swingBound);
    if (j.twistLimited) past = std::max({past, j.twistLower - g.twist, g.twist - j.twistUpper});
    return past;
}

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// The bounds a limited ball joint is past at these angles (more than kHeld): their axes and
// how far past each is (the error its row removes). At most three: the cone, and the twist's
// lower or upper bound.
int pastBounds(const JointModel& j, const BallAngles& g, Vec3* axes, double* past) {
    int n = 0;
    if (j.swingLimited && g.swingKnown && g.swing - g.swingBound > kHeld) {
        axes[n] = g.swingRow;
        past[n++] = g.swing - g.swingBound;
    }
    if (j.twistLimited && (g.twist < j.twistLower - kHeld || g.twist > j.twistUpper + kHeld)) {
        axes[n] = g.twistAxis;
        past[n++] = g.twist < j.twistLower ? g.twist - j.twistLower : g.twist - j.twistUpper;
    }
    return n;
}

// The ball's three point rows and `na` angular rows along `axes` at these poses.
void ballRows(const JointModel& j, const BodyState& a, const BodyState* b, const Vec3* axes, int na,
              ContactSolverScratch::GeneralRow& rows) {
    const Vec3 rA = a.q * j.anchorA;
    rows.nl = 3;
    rows.lin = Mat3::Identity();
    rows.na = na;
    rows.ang.setZero();
    for (int i = 0; i < na; ++i) rows.ang.col(i) = axes[i];
    fillJacobians(rows, rA, b ? Vec3(a.x + rA - b->x) : Vec3::Zero());
}

}  // namespace

double projectLimitedBall(State& state, ContactSolverScratch& s, double h, const State* from, const State& at,
                          const JointModel& j, bool moveA, bool moveB, const SolverBody& A, const SolverBody& B) {
    BodyState& a = state.bodies[j.a];
    BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
    const Vec3 pA = a.x + a.q * j.anchorA;
    const Vec3 gap = pA - (b ? Vec3(b->x + b->q * j.anchorB) : j.anchorB);
    const BallAngles g = ballAngles(j, a, b);
    Vec3 axes[3];
    double past[3];
    const int na = pastBounds(j, g, axes, past);
    const double error = std::max(gap.norm(), ballLimitsPast(j, g));
    if (error <= kHeld) return error;
    ContactSolverScratch::GeneralRow now, then;
    ballRows(j, a, b, axes, na, now);
    // The impulse acts along the rows at the start (RATTLE's), the arms there.
    if (&at == &state) {
        then = now;
    } else {
        const BodyState* b0 = j.b >= 0 ? &at.bodies[j.b] : nullptr;
        const BallAngles g0 = ballAngles(j, at.bodies[j.a], b0);
        Vec3 axes0[3];
        for (int i = 0; i < na; ++i)
            axes0[i] = axes[i] == g.swingRow && g0.swingKnown ? g0.swingRow
                       : axes[i] == g.twistAxis                 ? g0.twistAxis
                                                                : axes[i];
        ballRows(j, at.bodies[j.a], b0, axes0, na, then);
    }
    Vector6 C = Vector6::Zero();
    C.head<3>() = gap;
    for (int i = 0; i < na; ++i) C[3 + i] = past[i];
    const Vector6 lambda = -generalMass(now, then, A, B).partialPivLu().solve(C);
    if (!lambda.allFinite()) return error;
    nudgeGeneral(then, A, a, moveA, B, b, moveB, lambda);
    if (from && h != 0.0) {  // the move was made by the impulse λ / h over the step
        s.projectedImpulse[j.index] += lambda.head<3>() / h;
        s.projectedCouple[j.index] += then.ang.leftCols(na) * lambda.segment(3, na) / h;
        if (moveA) applyToBody(s.bodies[j.a], then.JA * (lambda / h));
        if (moveB) applyToBody(s.bodies[j.b], then.JB * (lambda / h));
    }
    return error;
}

int ballBoundsPast(const JointModel& j, const BodyState& a, const BodyState* b, int* bounds) {
    const BallAngles g = ballAngles(j, a, b);
    int n = 0;
    if (j.swingLimited && g.swingKnown && g.swing - g.swingBound > kHeld) bounds[n++] = 0;
    if (j.twistLimited && g.twist < j.twistLower - kHeld) bounds[n++] = 1;
    if (j.twistLimited && g.twist > j.twistUpper + kHeld) bounds[n++] = 2;
    return n;
}

void limitedBallRows(const JointModel& j, const BodyState& a, const BodyState* b, const int* bounds, int count,
                     ContactSolverScratch::GeneralRow& rows, Vector6* error) {
    const BallAngles g = ballAngles(j, a, b);
    Vec3 axes[3];
    double past[3];
    for (int i = 0; i < count; ++i) {
        axes[i] = bounds[i] == 0 ? g.swingRow : g.twistAxis;
        past[i] = bounds[i] == 0 ? g.swing - g.swingBound : bounds[i] == 1 ? g.twist - j.twistLower : g.twist - j.twistUpper;
    }
    ballRows(j, a, b, axes, count, rows);
    if (!error) return;
    error->setZero();
    const Vec3 pA = a.x + a.q * j.anchorA;
    error->head<3>() = pA - (b ? Vec3(b->x + b->q * j.anchorB) : j.anchorB);
    for (int i = 0; i < count; ++i) (*error)[3 + i] = past[i];
}

}  // namespace tumble::joint
