#include "contact_rows.h"

#include <algorithm>
#include <cmath>

namespace tumble {

using Point = ContactSolverScratch::Point;

namespace {

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

}  // namespace

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
    const ContactSolverScratch::PointGeometry* g = &s.geometry[block.begin];
    for (int i = 0; i < k; ++i) c += g[i].position;
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
    for (int i = 0; i < k; ++i) block.radius += (g[i].position - c).norm() / k;
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

// The normal impulses of one manifold together: the least-norm impulses that give every
// point its target velocity, none pulling (pushingImpulses).
void normalBlock(ContactSolverScratch& s, const ContactSolverScratch::Block& block, SubsetInverses& subsets) {
    Point* q = &s.points[block.begin];
    const int k = block.count;
    if (k == 1) return normalPoint(s, q[0]);
    SolverBody& A = s.bodies[q[0].a];
    SolverBody& B = s.bodies[q[0].b];
    Eigen::Vector4d lambda = Eigen::Vector4d::Zero(), rhs = Eigen::Vector4d::Zero(),
                    vn = Eigen::Vector4d::Zero();
    bool idle = true;  // nothing pushes and nothing approaches faster than its target
    for (int i = 0; i < k; ++i) lambda[i] = q[i].lambdaN;
    for (int i = 0; i < k; ++i) {
        // What the impulses must add to the velocity the point would have without them.
        vn[i] = q[i].n.dot(relativeVelocity(A, q[i].rA, B, q[i].rB));
        rhs[i] = q[i].target - (vn[i] - block.K.row(i).dot(lambda));  // zero beyond k
        idle = idle && lambda[i] == 0.0 && vn[i] >= q[i].target;
    }
    // λ = 0 already solves this block (a side neighbour in a pile, a point still apart).
    if (idle) return;
    const Eigen::Vector4d wanted = pushingImpulses(block.K, block.Kinv, rhs, k, &subsets);
    // The changes summed per body: one impulse and one moment each, all along n.
    const Vec3& n = q[0].n;
    double total = 0.0;
    Vec3 armA = Vec3::Zero(), armB = Vec3::Zero();
    for (int i = 0; i < k; ++i) {
        const double d = wanted[i] - lambda[i];
        q[i].lambdaN = wanted[i];
        total += d;
        armA += d * q[i].rA;
        armB += d * q[i].rB;
    }
    if (total == 0.0 && armA.isZero(0.0)) return;
    A.v += (A.invMass * total) * n;
    A.w += A.invI * armA.cross(n);
    B.v -= (B.invMass * total) * n;
    B.w -= B.invI * armB.cross(n);
    A.touched = B.touched = true;
}

// Friction of one manifold: stop the sliding and the twisting at the centroid, within
// the Coulomb limits of the current normal impulses.
void frictionBlock(ContactSolverScratch& s, ContactSolverScratch::Block& block) {
    if (block.mu <= 0.0) return;
    double normal = 0.0;
    for (int i = 0; i < block.count; ++i) normal += s.points[block.begin + i].lambdaN;
    const double limit = block.mu * normal;
    // No normal impulse holds no friction: nothing to do when none is held.
    if (limit == 0.0 && block.lambdaT.isZero(0.0) && block.lambdaTwist == 0.0) return;
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

}  // namespace tumble
