#include "joint_projection.h"

#include "contact_energy.h"
#include "joint_general.h"
#include "joint_math.h"

#include <Eigen/LU>

#include <algorithm>
#include <numeric>

namespace tumble {

using namespace joint;

namespace {


int root(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// One joint of a group as the solve sees it at the present iterate.
struct Rows {
    const JointModel* joint = nullptr;
    int offset = 0, count = 0;           // its rows in the group's system: 3 (ball) or 1
    Vec3 nowA, nowB, thenA, thenB;       // arms now, and where the impulse acts
    Eigen::Matrix<double, 3, Eigen::Dynamic> E, D;  // the rows' error and impulse directions
    Eigen::VectorXd C;
};

// The group's rows at the bodies' present poses; the largest error, and in `sum` the sum
// of the squared errors (what a Newton step must lower: its direction descends on it).
double measure(const Model& /*model*/, const State& state, const State& at, std::vector<Rows>& rows,
               double* sum = nullptr) {
    double worst = 0.0;
    if (sum) *sum = 0.0;
    for (Rows& r : rows) {
        const JointModel& j = *r.joint;
        const BodyState& a = state.bodies[j.a];
        r.nowA = a.q * j.anchorA;
        r.nowB = j.b >= 0 ? Vec3(state.bodies[j.b].q * j.anchorB) : Vec3::Zero();
        r.thenA = at.bodies[j.a].q * j.anchorA;
        r.thenB = j.b >= 0 ? Vec3(at.bodies[j.b].q * j.anchorB) : Vec3::Zero();
        const Vec3 d = a.x + r.nowA - (j.b >= 0 ? Vec3(state.bodies[j.b].x + r.nowB) : j.anchorB);
        if (j.type == JointType::Ball) {
            r.E = Mat3::Identity();
            r.D = Mat3::Identity();
            r.C = d;
        } else {
            const Vec3 d0 = at.bodies[j.a].x + r.thenA - (j.b >= 0 ? Vec3(at.bodies[j.b].x + r.thenB) : j.anchorB);
            const double length = d.norm();
            r.E = length > kDegenerate ? Vec3(d / length) : Vec3::Zero();
            r.D = d0.norm() > kDegenerate ? Vec3(d0 / d0.norm()) : Vec3::Zero();
            r.C = Eigen::VectorXd::Constant(1, length - j.length);
        }
        worst = std::max(worst, r.C.cwiseAbs().maxCoeff());
        if (sum) *sum += r.C.squaredNorm();
    }
    return worst;
}

}  // namespace

void projectGroups(const Model& model, State& state, ContactSolverScratch& s, double h, const State* from,
                   int iterations) {
    // The groups: joints joined through bodies that move (the world and still bodies join
    // nothing).
    const int n = static_cast<int>(model.bodies.size());
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<int> members;
    for (int k = 0; k < static_cast<int>(model.joints.size()); ++k) {
        const JointModel& j = model.joints[k];
        // Ropes (one-sided) and the joints that hold orientation (joint_general.h) are left
        // to the Gauss-Seidel passes.
        if (!active(model, state, j) || j.type == JointType::Rope || isGeneral(j.type)) continue;
        members.push_back(k);
        if (movable(model, state, j.a) && movable(model, state, j.b)) parent[root(parent, j.a)] = root(parent, j.b);
    }
    auto groupOf = [&](int k) {
        const JointModel& j = model.joints[k];
        return root(parent, movable(model, state, j.a) ? j.a : j.b);
    };
    std::stable_sort(members.begin(), members.end(), [&](int x, int y) { return groupOf(x) < groupOf(y); });
    const State& at = from ? *from : state;
    for (std::size_t first = 0; first < members.size();) {
        std::size_t last = first;
        while (last < members.size() && groupOf(members[last]) == groupOf(members[first])) ++last;
        const int count = static_cast<int>(last - first);
        if (count > kMostGroupJoints) {
            first = last;
            continue;
        }
        std::vector<Rows> rows(count);
        int size = 0;
        for (int k = 0; k < count; ++k) {
            rows[k].joint = &model.joints[members[first + k]];
            rows[k].offset = size;
            rows[k].count = rows[k].joint->type == JointType::Ball ? 3 : 1;
            size += rows[k].count;
        }
        double squares = 0.0;
        double error = measure(model, state, at, rows, &squares);
        for (int it = 0; it < iterations && error > kHeld; ++it) {
            // K(k, l): how joint k's error moves per unit impulse of joint l's rows, through
            // the bodies the two share (+ on a joint's first body, - on its second).
            Eigen::MatrixXd K = Eigen::MatrixXd::Zero(size, size);
            Eigen::VectorXd C(size);
            for (const Rows& rk : rows) {
                C.segment(rk.offset, rk.count) = rk.C;
                for (const Rows& rl : rows) {
                    Mat3 M = Mat3::Zero();
                    auto add = [&](int body, double sk, const Vec3& nowK, double sl, const Vec3& thenL) {
                        if (body >= 0 && movable(model, state, body)) M += sk * sl * moveFor(s.bodies[body], nowK, thenL);
                    };
                    const JointModel &jk = *rk.joint, &jl = *rl.joint;
                    if (jk.a == jl.a) add(jk.a, 1, rk.nowA, 1, rl.thenA);
                    if (jk.a == jl.b) add(jk.a, 1, rk.nowA, -1, rl.thenB);
                    if (jk.b >= 0 && jk.b == jl.a) add(jk.b, -1, rk.nowB, 1, rl.thenA);
                    if (jk.b >= 0 && jk.b == jl.b) add(jk.b, -1, rk.nowB, -1, rl.thenB);
                    if (!M.isZero(0.0))
                        K.block(rk.offset, rl.offset, rk.count, rl.count) = rk.E.transpose() * M * rl.D;
                }
            }
            const Eigen::VectorXd lambda = Eigen::PartialPivLU<Eigen::MatrixXd>(K).solve(-C);
            if (!lambda.allFinite()) break;
            // Every joint's impulse from the same linearisation, then the error again. Along
            // the start's directions (RATTLE, which also sets the velocities) only a full
            // step that halves the error is taken: partial ones, given to the velocities, put
            // energy into a whipping chain. Positions alone take halved steps (up to six)
            // as long as the error falls.
            std::vector<BodyState> saved;
            for (const Rows& r : rows) {
                saved.push_back(state.bodies[r.joint->a]);
                if (r.joint->b >= 0) saved.push_back(state.bodies[r.joint->b]);
            }
            auto restore = [&] {  // (a body of two joints was saved twice, both before any move)
                std::size_t v = 0;
                for (const Rows& r : rows) {
                    state.bodies[r.joint->a] = saved[v++];
                    if (r.joint->b >= 0) state.bodies[r.joint->b] = saved[v++];
                }
            };
            double scale = 1.0, next = error, nextSquares = squares;
            bool lower = false;
            const int tries = from ? 1 : 6;
            for (int t = 0; t < tries && !lower; ++t, scale *= 0.5) {
                if (t > 0) {
                    // Back to the poses, and to their arms: measure() set each row's arms
                    // to the poses it measured, and the next try must push where this one did.
                    restore();
                    measure(model, state, at, rows);
                }
                for (const Rows& r : rows) {
                    const JointModel& j = *r.joint;
                    const Vec3 J = scale * (r.D * lambda.segment(r.offset, r.count));
                    if (movable(model, state, j.a)) nudge(s.bodies[j.a], state.bodies[j.a], r.thenA, J);
                    if (movable(model, state, j.b)) nudge(s.bodies[j.b], state.bodies[j.b], r.thenB, -J);
                }
                next = measure(model, state, at, rows, &nextSquares);
                lower = from ? nextSquares < 0.25 * squares : nextSquares < squares;
                if (lower) break;
            }
            if (!lower) {  // no step helps: left as it was, to Gauss-Seidel
                restore();
                measure(model, state, at, rows);
                break;
            }
            if (from && h != 0.0)  // the move as the impulse J / h over the step (RATTLE)
                for (const Rows& r : rows) {
                    const JointModel& j = *r.joint;
                    const Vec3 J = scale * (r.D * lambda.segment(r.offset, r.count));
                    if (movable(model, state, j.a)) applyImpulse(s.bodies[j.a], r.thenA, J / h);
                    if (j.index < static_cast<int>(s.projectedImpulse.size())) s.projectedImpulse[j.index] += J / h;
                    if (movable(model, state, j.b)) applyImpulse(s.bodies[j.b], r.thenB, -J / h);
                }
            error = next;
            squares = nextSquares;
        }
        first = last;
    }
}

namespace {

// Per joint of `joints`, the number of joints in its group: joints joined through bodies
// for which `moves` holds (every joint type counted).
template <class Moves>
std::vector<int> groupSizes(const Model& model, const std::vector<int>& joints, Moves&& moves) {
    const int n = static_cast<int>(model.bodies.size());
    std::vector<int> parent(n), size(n, 0), out;
    std::iota(parent.begin(), parent.end(), 0);
    auto anchorOf = [&](const JointModel& j) { return root(parent, moves(j.a) ? j.a : j.b); };
    for (int k : joints) {
        const JointModel& j = model.joints[k];
        if (moves(j.a) && moves(j.b)) parent[root(parent, j.a)] = root(parent, j.b);
    }
    for (int k : joints) ++size[anchorOf(model.joints[k])];
    for (int k : joints) out.push_back(size[anchorOf(model.joints[k])]);
    return out;
}

}  // namespace

double smallGroupsOpen(const Model& model, const State& state, const ContactSolverScratch& s) {
    std::vector<int> joints;
    for (const JointModel& j : model.joints)
        if (active(model, state, j) && j.index < static_cast<int>(s.jointChecks.size())) joints.push_back(j.index);
    const std::vector<int> sizes = groupSizes(model, joints, [&](int i) { return movable(model, state, i); });
    double open = 0.0;
    for (std::size_t k = 0; k < joints.size(); ++k)
        if (sizes[k] <= kMostGroupJoints) open = std::max(open, s.jointChecks[joints[k]].error);
    return open;
}

int largestJointGroup(const Model& model) {
    std::vector<int> joints(model.joints.size());
    std::iota(joints.begin(), joints.end(), 0);
    const std::vector<int> sizes =
        groupSizes(model, joints, [&](int i) { return i >= 0 && model.bodies[i].motion == Motion::Dynamic; });
    return sizes.empty() ? 0 : *std::max_element(sizes.begin(), sizes.end());
}

}  // namespace tumble
