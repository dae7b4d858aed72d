#include "solver/solver_body.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace tumble {

namespace {

void loadBody(const Model& model, const State& state, int i, SolverBody& o) {
    const BodyModel& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    o.v.setZero();  // every field, whatever the entry held before
    o.w.setZero();
    o.invMass = 0.0;
    o.invI.setZero();
    o.touched = false;
    o.x = s.x;
    if (b.motion == Motion::Kinematic) {
        o.v = b.path ? s.P : b.kinematicVelocity;
        o.w = b.path ? s.L : b.kinematicAngularVelocity;
    } else if (b.motion == Motion::Dynamic && !state.isAsleep(i) && b.sphericalInertia) {
        // derive() without the rotation matrix, which a ball's or a cube's I⁻¹ does not need.
        o.v = b.invMass * s.P;
        o.w = angularVelocity(b, s);
        o.invMass = b.invMass;
        o.invI = b.invInertia;
    } else if (b.motion == Motion::Dynamic && !state.isAsleep(i)) {
        const Derived d = derive(b, s);
        o.v = d.v;
        o.w = d.omega;
        o.invMass = b.invMass;
        o.invI = d.invInertiaWorld;
    }
}

void storeBody(const Model& model, const SolverBody& body, int i, State& state) {
    if (model.bodies[i].motion != Motion::Dynamic || state.isAsleep(i) || !body.touched) return;
    const BodyModel& b = model.bodies[i];
    BodyState& s = state.bodies[i];
    const Mat3 R = s.q.toRotationMatrix();
    s.P = b.mass * body.v;
    s.L = R * (b.inertia * (R.transpose() * body.w));
}

}  // namespace

SolverBody solverBody(const Model& model, const State& state, int i) {
    SolverBody o;
    loadBody(model, state, i, o);
    return o;
}

void uniqueBodies(std::vector<int>& list, std::vector<std::uint8_t>& seen) {
    // Flags first, then a sort of the distinct bodies only: a pile's manifolds name each
    // body eight times over, and sorting all of them was 7 % of a step of piles-sleep-off.
    size_t n = 0;
    for (int b : list) {
        if (static_cast<size_t>(b) >= seen.size()) seen.resize(static_cast<size_t>(b) + 1, 0);
        if (!seen[b]) seen[b] = 1, list[n++] = b;
    }
    list.resize(n);
    for (int b : list) seen[b] = 0;
    std::sort(list.begin(), list.end());
}

void bodiesOf(const collision::ManifoldList& contacts, std::vector<std::uint8_t>& seen,
              std::vector<int>& out) {
    out.clear();
    for (const collision::Manifold& m : contacts) {
        out.push_back(m.bodyA);
        out.push_back(m.bodyB);
    }
    uniqueBodies(out, seen);
}

void sizeSolverBodies(const Model& model, std::vector<SolverBody>& out) {
    out.assign(model.bodies.size(), SolverBody{});
}

void loadSolverBodies(const Model& model, const State& state, std::vector<SolverBody>& out,
                      const std::vector<int>& only) {
    // Sized once: only the entries of `only` are written and read (every caller indexes the
    // bodies of its contacts, which `only` lists); clearing all of them cost a 3 000-body
    // pile half a megabyte of writes per call, several calls per look at the step.
    if (out.size() != model.bodies.size()) sizeSolverBodies(model, out);
    for (int i : only) loadBody(model, state, i, out[i]);
}

bool chordVelocity(const Model& model, const State& state, const State& before, int i, BodyVelocity& out) {
    const double h = state.time - before.time;
    if (!model.bodies[i].path || !(h > 0.0)) return false;
    const BodyState &b0 = before.bodies[i], &b1 = state.bodies[i];
    out.v = (b1.x - b0.x) / h;
    const Eigen::AngleAxisd turn(b1.q * b0.q.conjugate());  // (the short way: an angle within [0, π])
    out.w = (turn.angle() / h) * turn.axis();
    return true;
}

template <class Body>
void chordVelocities(const Model& model, const State& state, const State& before, std::vector<Body>& out,
                     const std::vector<int>& only) {
    if (model.kinematicBodies.empty()) return;
    for (int i : only) chordVelocity(model, state, before, i, out[i]);
}

template void chordVelocities(const Model&, const State&, const State&, std::vector<SolverBody>&,
                              const std::vector<int>&);
template void chordVelocities(const Model&, const State&, const State&, std::vector<BodyVelocity>&,
                              const std::vector<int>&);

void loadVelocities(const Model& model, const State& state, std::vector<BodyVelocity>& out,
                    const std::vector<int>& only) {
    if (out.size() != model.bodies.size()) out.assign(model.bodies.size(), BodyVelocity{});
    SolverBody b;
    for (int i : only) {
        loadBody(model, state, i, b);
        out[i] = b;
    }
}

void storeSolverBodies(const Model& model, const std::vector<SolverBody>& bodies, State& state,
                       const std::vector<int>& only) {
    for (int i : only) storeBody(model, bodies[i], i, state);
}

namespace {

// The pseudo-inverse by eigen-decomposition: the reference, for any K.
Eigen::Matrix4d pseudoInverseByEigen(const Eigen::Matrix4d& K, int k) {
    Eigen::Matrix4d Kk = Eigen::Matrix4d::Zero();
    Kk.topLeftCorner(k, k) = K.topLeftCorner(k, k);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(Kk);
    const Eigen::Vector4d& l = eig.eigenvalues();
    const double cut = 1e-9 * l.cwiseAbs().maxCoeff();
    Eigen::Vector4d inv = Eigen::Vector4d::Zero();
    for (int i = 0; i < 4; ++i)
        if (l[i] > cut) inv[i] = 1.0 / l[i];
    return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

// The vector orthogonal to the rows of the 3 x 4 matrix (a, b, c): its cofactors.
Eigen::Vector4d orthogonalTo(const Eigen::Vector4d& a, const Eigen::Vector4d& b, const Eigen::Vector4d& c) {
    auto det3 = [&](int i, int j, int l) {
        return a[i] * (b[j] * c[l] - b[l] * c[j]) - a[j] * (b[i] * c[l] - b[l] * c[i]) +
               a[l] * (b[i] * c[j] - b[j] * c[i]);
    };
    return Eigen::Vector4d(det3(1, 2, 3), -det3(0, 2, 3), det3(0, 1, 3), -det3(0, 1, 2));
}

// Conditioning a fast answer must have; below it the eigen-decomposition decides what is
// null (it cuts at 1e-9 of the largest eigenvalue).
constexpr double kFastCondition = 1e-6;

// The inverse of the symmetric M (4 x 4 cofactors) when its condition number in the 1-norm
// is below 1 / kFastCondition.
bool conditionedInverse(const Eigen::Matrix4d& M, Eigen::Matrix4d& inv) {
    inv = M.inverse();
    const double norm = M.cwiseAbs().colwise().sum().maxCoeff();
    const double normInv = inv.cwiseAbs().colwise().sum().maxCoeff();
    return std::isfinite(normInv) && norm * normInv * kFastCondition < 1.0;
}

}  // namespace

// The k points of one manifold share its normal, so their K = J M⁻¹ Jᵀ has rank 3 at most
// (each row of J is (n, r × n) for a body, and r × n lies in the plane normal to n): four
// points always have a null direction u, the impulses that cancel out. K⁺ is then
// (K + s u uᵀ)⁻¹ - u uᵀ / s for any s > 0, a 4 x 4 cofactor inverse instead of an
// eigen-decomposition (which was a fifth of a resting pile's step); fewer points invert
// K directly. A K that is not that well conditioned (points in a line, nearly coincident)
// takes the eigen-decomposition.
Eigen::Matrix4d leastNormInverse(const Eigen::Matrix4d& K, int k) {
    if (k == 1) {
        // What the eigen-decomposition gives for one point, without it (a subset of one
        // point in pushingImpulses: a third of hull-rain's inverses went the long way).
        Eigen::Matrix4d inv = Eigen::Matrix4d::Zero();
        if (K(0, 0) > 0.0) inv(0, 0) = 1.0 / K(0, 0);
        return inv;
    }
    const double scale = K.topLeftCorner(k, k).trace() / k;
    if (!(scale > 0.0)) return pseudoInverseByEigen(K, k);
    if (k < 4) {
        // Padded with the scale of K, so that the condition is K's own.
        Eigen::Matrix4d M = scale * Eigen::Matrix4d::Identity();
        M.topLeftCorner(k, k) = K.topLeftCorner(k, k);
        Eigen::Matrix4d inv;
        if (!conditionedInverse(M, inv)) return pseudoInverseByEigen(K, k);
        inv.bottomRightCorner(4 - k, 4 - k).setZero();
        inv.topRightCorner(k, 4 - k).setZero();
        inv.bottomLeftCorner(4 - k, k).setZero();
        return inv;
    }
    // The null direction: orthogonal to three rows of K (the best of the four choices).
    Eigen::Vector4d u = Eigen::Vector4d::Zero();
    for (int skip = 0; skip < 4; ++skip) {
        int r[3], n = 0;
        for (int i = 0; i < 4; ++i)
            if (i != skip) r[n++] = i;
        const Eigen::Vector4d c = orthogonalTo(K.row(r[0]), K.row(r[1]), K.row(r[2]));
        if (c.squaredNorm() > u.squaredNorm()) u = c;
    }
    const double length = u.norm();
    if (!(length > 0.0)) return pseudoInverseByEigen(K, k);
    u /= length;
    // u must be null (rank 3): else (rank 4, or rank < 3 where u is noise) the reference.
    if ((K * u).norm() > 1e-12 * scale) return pseudoInverseByEigen(K, k);
    const Eigen::Matrix4d M = K + scale * u * u.transpose();
    Eigen::Matrix4d inv;
    if (!conditionedInverse(M, inv)) return pseudoInverseByEigen(K, k);
    return inv - (u * u.transpose()) / scale;
}

Eigen::Matrix4d leastNormInverseReference(const Eigen::Matrix4d& K, int k) {
    return pseudoInverseByEigen(K, k);
}

namespace {

// The least-norm inverse of the na × na sub-block Ks of the points in `mask`, from the cache
// when it was computed before.
Eigen::Matrix4d subsetInverse(const Eigen::Matrix4d& Ks, int na, std::uint8_t mask, SubsetInverses* cache) {
    if (!cache) return leastNormInverse(Ks, na);
    for (int i = 0; i < 2; ++i)
        if (cache->mask[i] == mask) return cache->inverse[i];
    const int slot = cache->next;
    cache->next = 1 - slot;
    cache->mask[slot] = mask;
    cache->inverse[slot] = leastNormInverse(Ks, na);
    return cache->inverse[slot];
}

}  // namespace

Eigen::Vector4d pushingImpulses(const Eigen::Matrix4d& K, const Eigen::Matrix4d& Kinv,
                                const Eigen::Vector4d& g, int k, SubsetInverses* cache) {
    Eigen::Vector4d lambda = Kinv * g;
    bool active[4] = {true, true, true, true};
    for (int round = 1; round < k; ++round) {
        bool dropped = false;
        for (int i = 0; i < k; ++i)
            if (active[i] && lambda[i] < 0.0) active[i] = false, dropped = true;
        if (!dropped) break;
        int map[4], na = 0;
        std::uint8_t mask = 0;
        for (int i = 0; i < k; ++i)
            if (active[i]) map[na++] = i, mask |= static_cast<std::uint8_t>(1u << i);
        lambda.setZero();
        if (na == 0) break;
        Eigen::Matrix4d Ks = Eigen::Matrix4d::Zero();
        Eigen::Vector4d gs = Eigen::Vector4d::Zero();
        for (int i = 0; i < na; ++i) {
            gs[i] = g[map[i]];
            for (int j = 0; j < na; ++j) Ks(i, j) = K(map[i], map[j]);
        }
        const Eigen::Vector4d sol = subsetInverse(Ks, na, mask, cache) * gs;
        for (int i = 0; i < na; ++i) lambda[map[i]] = sol[i];
    }
    for (int i = 0; i < 4; ++i)
        lambda[i] = i < k ? std::max(lambda[i], 0.0) : 0.0;  // the last one may still pull
    return lambda;
}

void tangentFrame(const Vec3& n, Vec3& t1, Vec3& t2) {
    // The axis least aligned with n gives a well-conditioned first tangent.
    const Vec3 a = std::abs(n.x()) < 0.57735 ? Vec3::UnitX()
                                             : (std::abs(n.y()) < 0.57735 ? Vec3::UnitY() : Vec3::UnitZ());
    t1 = n.cross(a).normalized();
    t2 = n.cross(t1);
}

}  // namespace tumble
