#include "solver/joint_general.h"

#include <algorithm>

#include <cmath>

namespace tumble::joint {

namespace {

// A unit vector square to the unit vector n, and the third of the right-handed triple.
void across(const Vec3& n, Vec3& t1, Vec3& t2) {
    const Vec3 other = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : Vec3::UnitY();
    t1 = n.cross(other).normalized();
    t2 = n.cross(t1);
}

// The rotation vector of the unit quaternion e (the shorter way round).
Vec3 rotationVector(Quat e) {
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    const double s = e.vec().norm();
    if (!(s > 1e-12)) return 2.0 * e.vec();
    return (2.0 * std::atan2(s, e.w()) / s) * e.vec();
}

}  // namespace

void trackHingeAngles(const Model& model, State& state) {
    if (std::none_of(model.joints.begin(), model.joints.end(),
                     [](const JointModel& j) { return j.type == JointType::Hinge; }))
        return;
    const std::size_t n = model.joints.size();
    const bool known = state.hingeAngles.size() == n;
    if (!known) state.hingeAngles.assign(n, 0.0);
    for (const JointModel& j : model.joints) {
        if (j.type != JointType::Hinge) continue;
        const double near = known ? state.hingeAngles[j.index] : std::numeric_limits<double>::quiet_NaN();
        state.hingeAngles[j.index] =
            hingeAngle(j, state.bodies[j.a], j.b >= 0 ? &state.bodies[j.b] : nullptr, near);
    }
}

void fillJacobians(ContactSolverScratch::GeneralRow& rows, const Vec3& rA, const Vec3& rB) {
    rows.m = rows.nl + rows.na;
    rows.JA.setZero();
    rows.JB.setZero();
    for (int i = 0; i < rows.nl; ++i) {
        const Vec3 d = rows.lin.col(i);
        rows.JA.col(i) << d, rA.cross(d);
        rows.JB.col(i) << -d, -rB.cross(d);
    }
    for (int i = 0; i < rows.na; ++i) {
        const Vec3 e = rows.ang.col(i);
        rows.JA.col(rows.nl + i) << Vec3::Zero(), e;
        rows.JB.col(rows.nl + i) << Vec3::Zero(), -e;
    }
}

namespace {

// The inverse of SO(3)'s left Jacobian at the rotation vector t: the rate of t is
// Jl⁻¹(t) w for a turn Q = exp([t]×) that changes as Q' = [w]× Q.
Mat3 leftJacobianInverse(const Vec3& t) {
    Mat3 T;
    T << 0.0, -t.z(), t.y(), t.z(), 0.0, -t.x(), -t.y(), t.x(), 0.0;
    const double a = t.norm();
    // 1/a² − (1 + cos a) / (2 a sin a): 1/12 + a²/720 near 0.
    const double c = a < 1e-4 ? 1.0 / 12.0 + a * a / 720.0
                              : 1.0 / (a * a) - (1.0 + std::cos(a)) / (2.0 * a * std::sin(a));
    return Mat3::Identity() - 0.5 * T + c * T * T;
}

// A six-axis joint's rows: its locked axes as the rows, its free ones in `axes`; the error
// along each locked row in `error` (its coordinate: the locked ones are held at 0).
void sixAxisRows(const JointModel& j, const BodyState& a, const BodyState* b, const Vec3& rA, const Vec3& rB,
                 ContactSolverScratch::GeneralRow& rows, Vector6* error, AxisRow* axes) {
    const Quat qb = b ? b->q : Quat::Identity();
    const Mat3 WB = qb.toRotationMatrix() * j.frameB;
    const Vector6 c = sixAxisCoordinates(j, a, b);
    // Row i of the angular coordinates' rate against ω_A − ω_B (world): B's frame axes
    // through Jl⁻¹.
    const Mat3 G = WB * leftJacobianInverse(c.tail<3>()).transpose();
    rows.nl = rows.na = 0;
    rows.lin.setZero();
    rows.ang.setZero();
    Vector6 e = Vector6::Zero();
    for (int i = 0; i < 3; ++i)
        if (j.locked & (1u << i)) {
            e[rows.nl] = c[i];
            rows.lin.col(rows.nl++) = WB.col(i);
        }
    for (int i = 0; i < 3; ++i)
        if (j.locked & (1u << (3 + i))) {
            e[3 + rows.na] = c[3 + i];
            rows.ang.col(rows.na++) = G.col(i);
        }
    fillJacobians(rows, rA, rB);
    if (error) {
        error->setZero();
        error->head(rows.nl) = e.head(rows.nl);
        error->segment(rows.nl, rows.na) = e.segment(3, rows.na);
    }
    if (!axes) return;
    for (std::size_t k = 0; k < j.axes.size(); ++k) {
        AxisRow& x = axes[k];
        const int i = j.axes[k].axis;
        x.settings = &j.axes[k];
        x.coord = c[i];
        if (i < 3) {
            const Vec3 d = WB.col(i);
            x.JAx << d, rA.cross(d);
            x.JBx << -d, -rB.cross(d);
        } else {
            const Vec3 g = G.col(i - 3);
            x.JAx << Vec3::Zero(), g;
            x.JBx << Vec3::Zero(), -g;
        }
    }
}

}  // namespace

void generalRows(const JointModel& j, const BodyState& a, const BodyState* b,
                 ContactSolverScratch::GeneralRow& rows, Vector6* error, double near, AxisRow* axes) {
    const Quat qa = a.q, qb = b ? b->q : Quat::Identity();
    const Vec3 rA = qa * j.anchorA;
    const Vec3 pA = a.x + rA;
    const Vec3 pB = b ? Vec3(b->x + qb * j.anchorB) : j.anchorB;
    const Vec3 rB = b ? Vec3(pA - b->x) : Vec3::Zero();  // B's material point at A's anchor
    if (j.type == JointType::SixAxis) {
        sixAxisRows(j, a, b, rA, rB, rows, error, axes);
        return;
    }
    Vec3 t1, t2;
    Vec3 c = Vec3::Zero();  // the angular error vector
    AxisRow* x = axes;      // a hinge's or slider's free axis
    switch (j.type) {
        case JointType::Hinge: {
            const Vec3 aA = qa * j.axisA, aB = qb * j.axisB;
            across(aA, t1, t2);
            rows.nl = 3;
            rows.lin = Mat3::Identity();
            rows.na = 2;
            rows.ang.col(0) = t1;
            rows.ang.col(1) = t2;
            rows.ang.col(2).setZero();
            c = aB.cross(aA);
            if (x) {
                x->JAx << Vec3::Zero(), aA;
                x->JBx << Vec3::Zero(), -aA;
                x->coord = hingeAngle(j, a, b, near);
            }
            break;
        }
        case JointType::Slider: {
            const Vec3 aB = qb * j.axisB;
            across(aB, t1, t2);
            if (x) {
                x->JAx << aB, rA.cross(aB);
                x->JBx << -aB, -rB.cross(aB);
                x->coord = aB.dot(pA - pB);
            }
            rows.nl = 2;
            rows.lin.col(0) = t1;
            rows.lin.col(1) = t2;
            rows.lin.col(2).setZero();
            rows.na = 3;
            rows.ang = Mat3::Identity();
            c = rotationVector(qa * (qb * j.relative).conjugate());
            break;
        }
        default:  // fixed
            rows.nl = 3;
            rows.lin = Mat3::Identity();
            rows.na = 3;
            rows.ang = Mat3::Identity();
            c = rotationVector(qa * (qb * j.relative).conjugate());
            break;
    }
    if (x) x->settings = &j;
    fillJacobians(rows, rA, rB);
    if (error) {
        error->setZero();
        const Vec3 gap = pA - pB;
        for (int i = 0; i < rows.nl; ++i) (*error)[i] = rows.lin.col(i).dot(gap);
        for (int i = 0; i < rows.na; ++i) (*error)[rows.nl + i] = rows.ang.col(i).dot(c);
    }
}

Matrix6 generalMass(const ContactSolverScratch::GeneralRow& now, const ContactSolverScratch::GeneralRow& then,
                    const SolverBody& A, const SolverBody& B) {
    Matrix6 K = Matrix6::Identity();
    const int m = now.m;
    if (m == 0) return K;  // (a six-axis joint with every axis free and nothing past a stop)
    auto add = [&](const Matrix6& Jn, const Matrix6& Jt, const SolverBody& body) {
        if (body.invMass == 0.0 && body.invI.isZero(0.0)) return;
        Eigen::Matrix<double, 6, Eigen::Dynamic> MJ(6, m);
        MJ.topRows<3>() = body.invMass * Jt.topLeftCorner(3, m);
        MJ.bottomRows<3>() = body.invI * Jt.bottomLeftCorner(3, m);
        K.topLeftCorner(m, m) += Jn.leftCols(m).transpose() * MJ;
    };
    K.topLeftCorner(m, m).setZero();
    add(now.JA, then.JA, A);
    add(now.JB, then.JB, B);
    return K;
}

Vector6 generalVelocity(const ContactSolverScratch::GeneralRow& r, const SolverBody& A, const SolverBody& B) {
    Vector6 vA, vB;
    vA << A.v, A.w;
    vB << B.v, B.w;
    Vector6 out = r.JA.transpose() * vA + r.JB.transpose() * vB;
    out.tail(6 - r.m).setZero();
    return out;
}

double axisMass(const AxisRow& r, const SolverBody& A, const SolverBody& B) {
    const double inv =
        A.invMass * r.JAx.head<3>().squaredNorm() + r.JAx.tail<3>().dot(A.invI * r.JAx.tail<3>()) +
        B.invMass * r.JBx.head<3>().squaredNorm() + r.JBx.tail<3>().dot(B.invI * r.JBx.tail<3>());
    return inv > 0.0 ? 1.0 / inv : 0.0;
}

double axisVelocity(const AxisRow& r, const SolverBody& A, const SolverBody& B) {
    return r.JAx.head<3>().dot(A.v) + r.JAx.tail<3>().dot(A.w) + r.JBx.head<3>().dot(B.v) +
           r.JBx.tail<3>().dot(B.w);
}

void applyAxis(const AxisRow& r, SolverBody& A, SolverBody* B, double lambda) {
    A.v += (A.invMass * lambda) * r.JAx.head<3>();
    A.w += A.invI * (lambda * r.JAx.tail<3>());
    A.touched = true;
    if (!B) return;
    B->v += (B->invMass * lambda) * r.JBx.head<3>();
    B->w += B->invI * (lambda * r.JBx.tail<3>());
    B->touched = true;
}

void applyToBody(SolverBody& body, const Vector6& impulse) {
    body.v += body.invMass * impulse.head<3>();
    body.w += body.invI * impulse.tail<3>();
    body.touched = true;
}

void applyGeneral(const ContactSolverScratch::GeneralRow& r, SolverBody& A, SolverBody* B,
                  const Vector6& lambda) {
    applyToBody(A, r.JA * lambda);
    if (B) applyToBody(*B, r.JB * lambda);
}

namespace {

void move(const SolverBody& body, BodyState& s, const Vector6& impulse) {
    s.x += body.invMass * impulse.head<3>();
    const Vec3 turn = body.invI * impulse.tail<3>();
    const double angle = turn.norm();
    if (angle > 0.0) s.q = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * s.q).normalized();
}

}  // namespace

void nudgeGeneral(const ContactSolverScratch::GeneralRow& r, const SolverBody& A, BodyState& a, bool moveA,
                  const SolverBody& B, BodyState* b, bool moveB, const Vector6& lambda) {
    if (moveA) move(A, a, r.JA * lambda);
    if (moveB && b) move(B, *b, r.JB * lambda);
}

void nudgeAxis(const AxisRow& r, const SolverBody& A, BodyState& a, bool moveA,
               const SolverBody& B, BodyState* b, bool moveB, double lambda) {
    if (moveA) move(A, a, r.JAx * lambda);
    if (moveB && b) move(B, *b, r.JBx * lambda);
}

}  // namespace tumble::joint
