#include "solver/contact_rows.h"

#include <algorithm>
#include <cmath>

namespace tumble {

using Point = ContactSolverScratch::Point;

namespace {

// Of the bodies' motion: a block whose change is below it is quiet (updateBlock).
constexpr double kQuietShare = 1e-4;

// The normal velocity of A's point relative to B's.
double normalVelocity(const SolverBody& A, const SolverBody& B, const Point& p) {
    return p.n.dot(A.v - B.v) + p.armA.dot(A.w) - p.armB.dot(B.w);
}

// Changes a body's velocities by dv, dw. A body that cannot move (invMass 0, its spins 0)
// is not written: the blocks of two regions run side by side (block_regions.h) and share
// the ground.
[[gnu::always_inline]] inline void kick(SolverBody& b, const Vec3& dv, const Vec3& dw) {
    if (!(b.invMass > 0.0)) return;
    b.v += dv;
    b.w += dw;
    b.touched = true;
}

// The normal impulse d at the point: on A along n, on B against it.
void pushPoint(SolverBody& A, SolverBody& B, const Point& p, double d) {
    kick(A, (A.invMass * d) * p.n, d * p.spinA);
    kick(B, -((B.invMass * d) * p.n), -(d * p.spinB));
}

double normalPoint(ContactSolverScratch& s, Point& p) {
    SolverBody& A = s.bodies[p.a];
    SolverBody& B = s.bodies[p.b];
    const double vn = normalVelocity(A, B, p);
    const double old = p.lambdaN;
    p.lambdaN = std::max(0.0, old - p.kn * (vn - p.target));
    const double d = p.lambdaN - old;
    if (d != 0.0) pushPoint(A, B, p, d);
    return std::abs(d);
}

}  // namespace

void preparePoint(const SolverBody& A, const SolverBody& B, const Vec3& rA, const Vec3& rB, Point& p) {
    p.armA = rA.cross(p.n);
    p.armB = rB.cross(p.n);
    // A body that cannot move (invMass 0: static, kinematic, asleep, held by the shock pass)
    // has invI 0 too: its spins are zero without the product.
    p.spinA = A.invMass > 0.0 ? Vec3(A.invI * p.armA) : Vec3::Zero();
    p.spinB = B.invMass > 0.0 ? Vec3(B.invI * p.armB) : Vec3::Zero();
    // n · ((I⁻¹ (r × n)) × r) = (r × n) · I⁻¹ (r × n): the effective mass from the arms.
    p.kn = 1.0 / (A.invMass + B.invMass + p.armA.dot(p.spinA) + p.armB.dot(p.spinB));
}

void prepareBlock(const SolverBody& A, const SolverBody& B, ContactSolverScratch::Block& block,
                  const ContactSolverScratch& s) {
    const int k = block.count;
    const Point* q = &s.points[block.begin];
    // K(i, j) = mA + mB + n · ((I⁻¹ (r_j × n)) × r_i) for each body, and n · (a × r) =
    // a · (r × n): the points' own arms and spins (preparePoint) give it in two dot products.
    // Symmetric, as it must be: the upper triangle mirrored.
    for (int i = 0; i < k; ++i)
        for (int j = i; j < k; ++j)
            block.K(i, j) = block.K(j, i) =
                A.invMass + B.invMass + q[j].spinA.dot(q[i].armA) + q[j].spinB.dot(q[i].armB);
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
    // A round body (sphere, capsule) rolls on its surface point, not on the midpoint between
    // the surfaces: the midpoint's arm is short by half the depth, and a ball found sunk by
    // g h²/2 at the end of the integration rolled on a radius g h²/4 too small and kept a
    // slip of ω g h²/4 (0.02 m/s at 1/60 s). The shift is exactly zero for other shapes.
    Vec3 shiftA = Vec3::Zero(), shiftB = Vec3::Zero();
    for (int i = 0; i < k; ++i) {
        if (!g[i].roundA && !g[i].roundB) continue;
        // The surface point less the midpoint, as prepare found them (rA less half the
        // depth along n, less rA; the same for B the other way).
        const Vec3 rA = g[i].position - A.x, rB = g[i].position - B.x;
        if (g[i].roundA) shiftA += Vec3(rA - 0.5 * g[i].depth * n) - rA;
        if (g[i].roundB) shiftB += Vec3(rB + 0.5 * g[i].depth * n) - rB;
    }
    block.rA += shiftA / k;
    block.rB += shiftB / k;
    tangentFrame(n, block.t1, block.t2);
    for (int t = 0; t < 2; ++t) {
        const Vec3& dir = t == 0 ? block.t1 : block.t2;
        block.armA[t] = block.rA.cross(dir);
        block.armB[t] = block.rB.cross(dir);
        block.spinA[t] = A.invMass > 0.0 ? Vec3(A.invI * block.armA[t]) : Vec3::Zero();
        block.spinB[t] = B.invMass > 0.0 ? Vec3(B.invI * block.armB[t]) : Vec3::Zero();
    }
    block.twistA = A.invMass > 0.0 ? Vec3(A.invI * n) : Vec3::Zero();
    block.twistB = B.invMass > 0.0 ? Vec3(B.invI * n) : Vec3::Zero();
    // K of the two tangents: velocity change along t_i per unit impulse along t_j, from the
    // arms and spins above as for the normals.
    const Vec3 t[2] = {block.t1, block.t2};
    Eigen::Matrix2d Kt;
    for (int i = 0; i < 2; ++i)
        for (int j = i; j < 2; ++j)
            Kt(i, j) = Kt(j, i) = (A.invMass + B.invMass) * t[i].dot(t[j]) +
                                  block.spinA[j].dot(block.armA[i]) + block.spinB[j].dot(block.armB[i]);
    block.tangentMass = Kt.inverse();
    const double twist = n.dot(block.twistA) + n.dot(block.twistB);
    block.twistMass = twist > 0.0 ? 1.0 / twist : 0.0;
    block.radius = 0.0;
    for (int i = 0; i < k; ++i) block.radius += (g[i].position - c).norm() / k;
}

namespace {

// The block's slip at its centroid, along t1 and t2, between the bodies A and B.
inline Eigen::Vector2d slipOf(const ContactSolverScratch::Block& block, const SolverBody& A,
                              const SolverBody& B) {
    const Vec3 dv = A.v - B.v;
    return {block.t1.dot(dv) + block.armA[0].dot(A.w) - block.armB[0].dot(B.w),
            block.t2.dot(dv) + block.armA[1].dot(A.w) - block.armB[1].dot(B.w)};
}

// A change of the block's friction impulses (tangential, twist) applied to A and B.
// Always inlined: called out of frictionBlock, the solver's hottest loop, it cost hull-rain
// 1.5 % of its step.
[[gnu::always_inline]] inline void pushFriction(const ContactSolverScratch::Block& block, SolverBody& A,
                                                SolverBody& B, const Eigen::Vector2d& dT, double dTwist) {
    if (dT.isZero(0.0) && dTwist == 0.0) return;
    const Vec3 J = dT[0] * block.t1 + dT[1] * block.t2;
    kick(A, A.invMass * J, dT[0] * block.spinA[0] + dT[1] * block.spinA[1] + dTwist * block.twistA);
    kick(B, -(B.invMass * J), -(dT[0] * block.spinB[0] + dT[1] * block.spinB[1] + dTwist * block.twistB));
}

}  // namespace

void applyFriction(ContactSolverScratch& s, ContactSolverScratch::Block& block, const Eigen::Vector2d& dT,
                   double dTwist) {
    pushFriction(block, s.bodies[s.points[block.begin].a], s.bodies[s.points[block.begin].b], dT, dTwist);
}

namespace {

// normalBlock for a block of K ≥ 2 points, with K known to the compiler: the vectors and
// K's corner are fixed-size (no loops over four padded slots, no branch per slot). The
// least-norm impulses of the whole block are taken when none of them pulls, the common
// case; else pushingImpulses lets the pulling points go (it starts from the same product).
template <int K>
double normalBlockOf(ContactSolverScratch& s, ContactSolverScratch::Block& block,
                     std::vector<SubsetInverses>& pool, bool* wantsEntry) {
    using VecK = Eigen::Matrix<double, K, 1>;
    Point* q = &s.points[block.begin];
    SolverBody& A = s.bodies[q[0].a];
    SolverBody& B = s.bodies[q[0].b];
    VecK lambda, vn, target;
    // The points share the normal: n · (vA - vB) once (normalVelocity's first term).
    const double along = q[0].n.dot(A.v - B.v);
    bool idle = true;  // nothing pushes and nothing approaches faster than its target
    for (int i = 0; i < K; ++i) {
        lambda[i] = q[i].lambdaN;
        vn[i] = along + q[i].armA.dot(A.w) - q[i].armB.dot(B.w);
        target[i] = q[i].target;
        idle = idle && lambda[i] == 0.0 && vn[i] >= target[i];
    }
    // λ = 0 already solves this block (a side neighbour in a pile, a point still apart).
    if (idle) return 0.0;
    // What the impulses must add to the velocity the point would have without them.
    const VecK rhs = target - (vn - block.K.template topLeftCorner<K, K>() * lambda);
    VecK wanted = block.Kinv.template topLeftCorner<K, K>() * rhs;
    if ((wanted.array() < 0.0).any()) {
        Eigen::Vector4d g = Eigen::Vector4d::Zero();
        g.template head<K>() = rhs;
        if (block.subsets < 0 && !wantsEntry) {
            block.subsets = static_cast<int>(pool.size());
            pool.emplace_back();
        }
        if (block.subsets >= 0) {
            wanted = pushingImpulses(block.K, block.Kinv, g, K, &pool[block.subsets]).template head<K>();
        } else {  // (the answer is the same with the pool's entry or without)
            *wantsEntry = true;
            SubsetInverses once;
            wanted = pushingImpulses(block.K, block.Kinv, g, K, &once).template head<K>();
        }
    }
    // The changes summed per body: one impulse along n and one change of spin each.
    const VecK d = wanted - lambda;
    Vec3 spinA = Vec3::Zero(), spinB = Vec3::Zero();
    for (int i = 0; i < K; ++i) {
        q[i].lambdaN = wanted[i];
        spinA += d[i] * q[i].spinA;
        spinB += d[i] * q[i].spinB;
    }
    const double total = d.sum();
    const double changed = d.cwiseAbs().maxCoeff();
    if (total == 0.0 && spinA.isZero(0.0) && spinB.isZero(0.0)) return changed;
    const Vec3& n = q[0].n;
    kick(A, (A.invMass * total) * n, spinA);
    kick(B, -((B.invMass * total) * n), -spinB);
    return changed;
}

}  // namespace

// The normal impulses of one manifold together: the least-norm impulses that give every
// point its target velocity, none pulling (pushingImpulses).
double normalBlock(ContactSolverScratch& s, ContactSolverScratch::Block& block,
                   std::vector<SubsetInverses>& pool, bool* wantsEntry) {
    switch (block.count) {
        case 1: return normalPoint(s, s.points[block.begin]);
        case 2: return normalBlockOf<2>(s, block, pool, wantsEntry);
        case 3: return normalBlockOf<3>(s, block, pool, wantsEntry);
        default: return normalBlockOf<4>(s, block, pool, wantsEntry);
    }
}

double normalImpulse(const ContactSolverScratch& s, const ContactSolverScratch::Block& block) {
    double normal = 0.0;
    for (int i = 0; i < block.count; ++i) normal += s.points[block.begin + i].lambdaN;
    return normal;
}

Eigen::Vector2d slipVelocity(const ContactSolverScratch& s, const ContactSolverScratch::Block& block) {
    const Point& p = s.points[block.begin];
    return slipOf(block, s.bodies[p.a], s.bodies[p.b]);
}

// Friction of one manifold: stop the sliding and the twisting at the centroid, within
// the Coulomb limits of the current normal impulses.
double frictionBlock(ContactSolverScratch& s, ContactSolverScratch::Block& block) {
    if (block.mu <= 0.0) return 0.0;
    const Point* q = &s.points[block.begin];
    double normal = 0.0;  // (normalImpulse, over the points in hand)
    for (int i = 0; i < block.count; ++i) normal += q[i].lambdaN;
    const double limit = block.mu * normal;
    // No normal impulse holds no friction: nothing to do when none is held.
    if (limit == 0.0 && block.lambdaT.isZero(0.0) && block.lambdaTwist == 0.0) return 0.0;
    SolverBody& A = s.bodies[q[0].a];
    SolverBody& B = s.bodies[q[0].b];
    Eigen::Vector2d l = block.lambdaT - block.tangentMass * slipOf(block, A, B);
    const double norm = l.norm();
    if (norm > limit) l *= limit / norm;
    // The twist is always clamped: a one-point patch (radius 0) may hold none, whatever
    // was remembered.
    double tw = block.lambdaTwist - block.twistMass * q[0].n.dot(A.w - B.w);
    tw = std::clamp(tw, -limit * block.radius, limit * block.radius);
    const Eigen::Vector2d dT = l - block.lambdaT;
    const double dTwist = tw - block.lambdaTwist;
    block.lambdaT = l;
    block.lambdaTwist = tw;
    pushFriction(block, A, B, dT, dTwist);
    // The twist's change as an impulse at the patch's radius (a one-point patch holds none
    // after its clamp, but may let go of a remembered one).
    const double twistChange = block.radius > 0.0       ? std::abs(dTwist) / block.radius
                               : std::abs(dTwist) > 0.0 ? HUGE_VAL
                                                        : 0.0;
    return std::max(std::max(std::abs(dT[0]), std::abs(dT[1])), twistChange);
}

bool blockQuiet(const ContactSolverScratch& s, int k) {
    const Point& p = s.points[s.blocks[k].begin];
    const long quiet = s.quietSince[k];
    return quiet >= 0 && s.changedAt[p.a] < quiet && s.changedAt[p.b] < quiet;
}

bool updateBlock(ContactSolverScratch& s, int k, double quietSpeed) {
    return !blockQuiet(s, k) && updateBlockAt(s, k, quietSpeed, ++s.tick, nullptr);
}

bool updateBlockAt(ContactSolverScratch& s, int k, double quietSpeed, long tick, std::vector<int>* wants) {
    ContactSolverScratch::Block& block = s.blocks[k];
    const Point& p = s.points[block.begin];
    const double friction = frictionBlock(s, block);  // friction first, then the normals
    bool wantsEntry = false;
    const double change = std::max(friction, normalBlock(s, block, s.subsets, wants ? &wantsEntry : nullptr));
    if (wantsEntry) wants->push_back(k);
    // Quiet: a change below `quietSpeed`, or below kQuietShare of how fast the two bodies
    // move (their speeds and their spins at the patch, summed as 1-norms: a bound within a
    // factor of three). A body at rest is held to `quietSpeed` alone (the stacks stand to
    // rounding); in a heap still landing and rolling the blocks went on for all twenty
    // passes, changing velocities of 1 m/s by 1e-10 m/s (hull-rain: 97 of the 121 blocks
    // not in still islands took every pass; instructions in the step -9 % with the share).
    // (The bodies' motion is only read when the change passes the resting tolerance.)
    // The 1-norms change with a turn of the world (by up to √3): a stack carried by a moving
    // lift takes other passes when turned (1e-6 m apart in 0.07 s; tst_invariance bounds the
    // lift and turntable samples). As lengths, or as the motion against each other at the
    // patch (also the same in a moving frame), fewer blocks went quiet: resting heaps reached
    // their still islands less often (tst_still_islands) and a landing pile was 2 % past the
    // margin in one pose (tst_landing_overlap). Not changed yet.
    const auto belowShare = [&] {
        const SolverBody& A = s.bodies[p.a];
        const SolverBody& B = s.bodies[p.b];
        const double motion = A.v.cwiseAbs().sum() + B.v.cwiseAbs().sum() +
                              A.w.cwiseAbs().sum() * block.rA.cwiseAbs().sum() +
                              B.w.cwiseAbs().sum() * block.rB.cwiseAbs().sum();
        return !(change > kQuietShare * motion * p.kn);
    };
    if (!(change > quietSpeed * p.kn) || belowShare()) {
        s.quietSince[k] = tick;
        return false;
    }
    s.quietSince[k] = -1;
    for (int i : {p.a, p.b})
        if (s.bodies[i].invMass > 0.0) s.changedAt[i] = tick;
    return true;
}

}  // namespace tumble
