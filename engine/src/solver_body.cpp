#include "solver_body.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace tumble {

namespace {

void loadBody(const Model& model, const State& state, int i, SolverBody& o) {
    const BodyModel& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    o.x = s.x;
    if (b.motion == Motion::Kinematic) {
        o.v = b.kinematicVelocity;
        o.w = b.kinematicAngularVelocity;
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

void bodiesOf(const std::vector<collision::Manifold>& contacts, std::vector<int>& out) {
    out.clear();
    for (const collision::Manifold& m : contacts) {
        out.push_back(m.bodyA);
        out.push_back(m.bodyB);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

void loadSolverBodies(const Model& model, const State& state, std::vector<SolverBody>& out) {
    out.assign(model.bodies.size(), SolverBody{});
    for (size_t i = 0; i < out.size(); ++i) loadBody(model, state, static_cast<int>(i), out[i]);
}

void loadSolverBodies(const Model& model, const State& state, std::vector<SolverBody>& out,
                      const std::vector<int>& only) {
    out.assign(model.bodies.size(), SolverBody{});
    for (int i : only) loadBody(model, state, i, out[i]);
}

void storeSolverBodies(const Model& model, const std::vector<SolverBody>& bodies, State& state) {
    for (int i : model.dynamicBodies) storeBody(model, bodies[i], i, state);
}

void storeSolverBodies(const Model& model, const std::vector<SolverBody>& bodies, State& state,
                       const std::vector<int>& only) {
    for (int i : only) storeBody(model, bodies[i], i, state);
}

Eigen::Matrix4d leastNormInverse(const Eigen::Matrix4d& K, int k) {
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

Eigen::Vector4d pushingImpulses(const Eigen::Matrix4d& K, const Eigen::Matrix4d& Kinv, const Eigen::Vector4d& g,
                                int k, SubsetInverses* cache) {
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
    for (int i = 0; i < 4; ++i) lambda[i] = i < k ? std::max(lambda[i], 0.0) : 0.0;  // the last one may still pull
    return lambda;
}

void tangentFrame(const Vec3& n, Vec3& t1, Vec3& t2) {
    // The axis least aligned with n gives a well-conditioned first tangent.
    const Vec3 a = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57735 ? Vec3::UnitY() : Vec3::UnitZ());
    t1 = n.cross(a).normalized();
    t2 = n.cross(t1);
}

}  // namespace tumble
