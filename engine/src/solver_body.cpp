#include "solver_body.h"

#include <cmath>

namespace tumble {

void loadSolverBodies(const Model& model, const State& state, std::vector<SolverBody>& out) {
    out.assign(model.bodies.size(), SolverBody{});
    for (size_t i = 0; i < out.size(); ++i) {
        const BodyModel& b = model.bodies[i];
        const BodyState& s = state.bodies[i];
        SolverBody& o = out[i];
        o.x = s.x;
        if (b.motion == Motion::Kinematic) {
            o.v = b.kinematicVelocity;
            o.w = b.kinematicAngularVelocity;
        } else if (b.motion == Motion::Dynamic && !state.isAsleep(static_cast<int>(i))) {
            const Derived d = derive(b, s);
            o.v = d.v;
            o.w = d.omega;
            o.invMass = b.invMass;
            o.invI = d.invInertiaWorld;
        }
    }
}

void storeSolverBodies(const Model& model, const std::vector<SolverBody>& bodies, State& state) {
    for (int i : model.dynamicBodies) {
        if (state.isAsleep(i) || !bodies[i].touched) continue;
        const BodyModel& b = model.bodies[i];
        BodyState& s = state.bodies[i];
        const Mat3 R = s.q.toRotationMatrix();
        s.P = b.mass * bodies[i].v;
        s.L = R * (b.inertia * (R.transpose() * bodies[i].w));
    }
}

namespace {

Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decompose(const Eigen::MatrixXd& K) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-9);
    cod.compute(K);
    return cod;
}

}  // namespace

Eigen::VectorXd leastNormSolve(const Eigen::MatrixXd& K, const Eigen::VectorXd& b) { return decompose(K).solve(b); }

Eigen::MatrixXd leastNormInverse(const Eigen::MatrixXd& K) { return decompose(K).pseudoInverse(); }

void tangentFrame(const Vec3& n, Vec3& t1, Vec3& t2) {
    // The axis least aligned with n gives a well-conditioned first tangent.
    const Vec3 a = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57735 ? Vec3::UnitY() : Vec3::UnitZ());
    t1 = n.cross(a).normalized();
    t2 = n.cross(t1);
}

}  // namespace tumble
