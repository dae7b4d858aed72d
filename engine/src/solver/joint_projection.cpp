#include "solver/joint_projection.h"

#include "solver/block_elimination.h"
#include "solver/contact_energy.h"
#include "solver/joint_cone.h"
#include "solver/joint_general.h"
#include "solver/joint_math.h"

#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <optional>

namespace tumble {

using namespace joint;

namespace {

constexpr int kLimitRounds = 4;  // positions only: rounds that add the limits a group's steps carried past
constexpr double kTurnWeight = 0.1;  // inverse inertias scaled by it in a damped Newton step (newtonSteps)

int root(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// A joint's rows' Jacobian on one body: a column per row, (v, ω).
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

// One joint of a group as the solve sees it at the present iterate.
struct Rows {
    const JointModel* joint = nullptr;
    int offset = 0, count = 0;      // its rows in the group's system: 3 (ball), 1, or a general joint's
    Vec3 nowA, nowB, thenA, thenB;  // ball, distance: arms now, and where the impulse acts
    Eigen::Matrix<double, 3, Eigen::Dynamic> E, D;  // the rows' error and impulse directions
    // Hinge, slider, fixed (joint_general.h): the rows now and where the impulse acts.
    bool general = false;
    ContactSolverScratch::GeneralRow now, then;
    // A positions-only solve: the free axes past a limit as the group found them (freeAxis
    // k, the bound it is held at), rows after the joint's own.
    std::array<int, 6> limitAxis{};
    std::array<double, 6> limitBound{};
    int limits = 0;
    // A limited ball joint past its cone or twist range in a positions-only solve: made a
    // general joint of its point rows and those bounds' (joint_cone.h limitedBallRows).
    std::array<int, 3> ballBounds{};
    int bounds = 0;
    Eigen::VectorXd C;
};

// Adds to r's rows the limits its joint is past (more than kHeld) at the poses of `state` that
// it does not hold yet: a hinge's, slider's or six-axis joint's stops (Rows::limits) or a
// limited ball's cone and twist bounds (Rows::bounds, which make it general). Positions only:
// measure() makes the rows' Jacobians. Returns whether it added any.
bool addPastLimits(const JointModel& j, const State& state, Rows& r) {
    const BodyState& a = state.bodies[j.a];
    const BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
    const int before = r.count;
    if (j.type == JointType::Ball) {
        if (!j.swingLimited && !j.twistLimited) return false;
        std::array<int, 3> past{};
        const int n = ballBoundsPast(j, a, b, past.data());
        for (int i = 0; i < n; ++i)
            if (std::find(r.ballBounds.begin(), r.ballBounds.begin() + r.bounds, past[i]) ==
                r.ballBounds.begin() + r.bounds)
                r.ballBounds[r.bounds++] = past[i];
        r.general = r.bounds > 0;
        r.count = 3 + r.bounds;
        return r.count != before;
    }
    if (!isGeneral(j.type)) return false;
    const int free = freeAxes(j);
    bool limited = false;
    for (int k = 0; k < free && !limited; ++k) limited = freeAxis(j, k).limited;
    if (!limited) return false;
    ContactSolverScratch::GeneralRow g;
    std::array<AxisRow, 6> axes;
    generalRows(j, a, b, g, nullptr, hingeNear(state, j), axes.data());
    for (int k = 0; k < free && r.count < 6; ++k) {
        const JointAxis& x = freeAxis(j, k);
        if (!x.limited) continue;
        if (std::find(r.limitAxis.begin(), r.limitAxis.begin() + r.limits, k) != r.limitAxis.begin() + r.limits)
            continue;
        const double c = axes[k].coord;
        if (c >= x.lower - kHeld && c <= x.upper + kHeld) continue;
        r.limitAxis[r.limits] = k;
        r.limitBound[r.limits++] = c < x.lower ? x.lower : x.upper;
        ++r.count;
    }
    return r.count != before;
}

// The group's rows at the bodies' present poses; the largest error, and in `sum` the sum
// of the squared errors (what a Newton step must lower: its direction descends on it).
double measure(const Model& /*model*/, const State& state, const State& at, std::vector<Rows>& rows,
               double* sum = nullptr) {
    double worst = 0.0;
    if (sum) *sum = 0.0;
    for (Rows& r : rows) {
        const JointModel& j = *r.joint;
        const BodyState& a = state.bodies[j.a];
        if (r.general && r.bounds) {
            Vector6 error;
            const BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
            limitedBallRows(j, a, b, r.ballBounds.data(), r.bounds, r.now, &error);
            if (&at == &state) r.then = r.now;
            r.C = error.head(r.count);
            if (r.count > 0) worst = std::max(worst, r.C.cwiseAbs().maxCoeff());  // (a six-axis joint all free: none)
            if (sum) *sum += r.C.squaredNorm();
            continue;
        }
        if (r.general) {
            Vector6 error;
            const BodyState* b = j.b >= 0 ? &state.bodies[j.b] : nullptr;
            std::array<AxisRow, 6> axes;
            generalRows(j, a, b, r.now, &error, hingeNear(state, j), r.limits ? axes.data() : nullptr);
            for (int i = 0, m = r.now.m; i < r.limits; ++i) {  // the limits past, held at their bounds
                const AxisRow& x = axes[r.limitAxis[i]];
                r.now.JA.col(m + i) = x.JAx;
                r.now.JB.col(m + i) = x.JBx;
                error[m + i] = x.coord - r.limitBound[i];
            }
            if (&at == &state) r.then = r.now;  // (else made once: the start does not move)
            r.C = error.head(r.count);
            if (r.count > 0) worst = std::max(worst, r.C.cwiseAbs().maxCoeff());  // (a six-axis joint all free: none)
            if (sum) *sum += r.C.squaredNorm();
            continue;
        }
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
            const Vec3 d0 =
                at.bodies[j.a].x + r.thenA - (j.b >= 0 ? Vec3(at.bodies[j.b].x + r.thenB) : j.anchorB);
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

// The pairs (k, l) of a group's joints that share a body that moves, each once, ascending:
// the blocks of K that are not zero (a chain's joints share a body with their two
// neighbours only, so its K is block-tridiagonal).
std::vector<std::pair<int, int>> sharingPairs(const Model& model, const State& state,
                                              const std::vector<Rows>& rows) {
    std::vector<std::pair<int, int>> byBody;  // (body, joint)
    for (int k = 0; k < static_cast<int>(rows.size()); ++k)
        for (int body : {rows[k].joint->a, rows[k].joint->b})
            if (movable(model, state, body)) byBody.emplace_back(body, k);
    std::sort(byBody.begin(), byBody.end());
    std::vector<std::pair<int, int>> pairs;
    for (std::size_t first = 0; first < byBody.size();) {
        std::size_t last = first;
        while (last < byBody.size() && byBody[last].first == byBody[first].first) ++last;
        for (std::size_t x = first; x < last; ++x)
            for (std::size_t y = first; y < last; ++y) pairs.emplace_back(byBody[x].second, byBody[y].second);
        first = last;
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}

// How joint k's anchor gap moves per unit impulse at joint l's anchors, through the bodies
// the two share (+ on a joint's first body, - on its second).
Mat3 shared(const Model& model, const State& state, const ContactSolverScratch& s, const Rows& rk,
            const Rows& rl) {
    Mat3 M = Mat3::Zero();
    auto add = [&](int body, double sk, const Vec3& nowK, double sl, const Vec3& thenL) {
        if (body >= 0 && movable(model, state, body)) M += sk * sl * moveFor(s.bodies[body], nowK, thenL);
    };
    const JointModel &jk = *rk.joint, &jl = *rl.joint;
    if (jk.a == jl.a) add(jk.a, 1, rk.nowA, 1, rl.thenA);
    if (jk.a == jl.b) add(jk.a, 1, rk.nowA, -1, rl.thenB);
    if (jk.b >= 0 && jk.b == jl.a) add(jk.b, -1, rk.nowB, 1, rl.thenA);
    if (jk.b >= 0 && jk.b == jl.b) add(jk.b, -1, rk.nowB, -1, rl.thenB);
    return M;
}

// A joint's Jacobian on `body` (its A or its B: B's columns carry the minus), as the error
// moves (`now`) or as its impulse acts (the other).
Jacobian jacobian(const Rows& r, int body, bool now) {
    const JointModel& j = *r.joint;
    const bool onA = body == j.a;
    if (r.general) {
        const ContactSolverScratch::GeneralRow& g = now ? r.now : r.then;
        return (onA ? g.JA : g.JB).leftCols(r.count);
    }
    const Vec3& arm = onA ? (now ? r.nowA : r.thenA) : (now ? r.nowB : r.thenB);
    const auto& dirs = now ? r.E : r.D;
    Jacobian J(6, r.count);
    for (int i = 0; i < r.count; ++i) J.col(i) << dirs.col(i), arm.cross(dirs.col(i));
    return onA ? J : Jacobian(-J);
}

Block block(const Model& model, const State& state, const ContactSolverScratch& s, const Rows& rk,
            const Rows& rl) {
    if (!rk.general && !rl.general) {
        const Mat3 M = shared(model, state, s, rk, rl);
        if (M.isZero(0.0)) return Block::Zero(rk.count, rl.count);
        return rk.E.transpose() * M * rl.D;
    }
    Block K = Block::Zero(rk.count, rl.count);
    const JointModel &jk = *rk.joint, &jl = *rl.joint;
    for (int body : {jk.a, jk.b}) {
        if (body < 0 || !movable(model, state, body) || (body != jl.a && body != jl.b)) continue;
        const SolverBody& B = s.bodies[body];
        const Jacobian then = jacobian(rl, body, false);
        Jacobian MJ(6, rl.count);
        MJ.topRows<3>() = B.invMass * then.topRows<3>();
        MJ.bottomRows<3>() = B.invI * then.bottomRows<3>();
        K += jacobian(rk, body, true).transpose() * MJ;
    }
    return K;
}

// Moves joint r's bodies (poses) as its impulses `lambda` would in unit time.
void moveRows(const Model& model, State& state, const ContactSolverScratch& s, const Rows& r,
              const Eigen::VectorXd& lambda) {
    const JointModel& j = *r.joint;
    const bool moveA = movable(model, state, j.a), moveB = movable(model, state, j.b);
    if (r.general) {
        Vector6 l = Vector6::Zero();
        l.head(r.count) = lambda;
        const SolverBody still;
        nudgeGeneral(r.then, moveA ? s.bodies[j.a] : still, state.bodies[j.a], moveA,
                     moveB ? s.bodies[j.b] : still, j.b >= 0 ? &state.bodies[j.b] : nullptr, moveB, l);
        return;
    }
    const Vec3 J = r.D * lambda;
    if (moveA) nudge(s.bodies[j.a], state.bodies[j.a], r.thenA, J);
    if (moveB) nudge(s.bodies[j.b], state.bodies[j.b], r.thenB, -J);
}

// Gives the velocities the impulses λ / h over the step that made that move (RATTLE), and
// adds the impulse on A (and a general joint's couple) to the joint's projected force.
void giveVelocity(const Model& model, const State& state, ContactSolverScratch& s, const Rows& r,
                  const Eigen::VectorXd& lambda, double h) {
    const JointModel& j = *r.joint;
    const bool moveA = movable(model, state, j.a), moveB = movable(model, state, j.b);
    const bool known = j.index < static_cast<int>(s.projectedImpulse.size());
    if (r.general) {
        Vector6 l = Vector6::Zero();
        l.head(r.count) = lambda / h;
        if (moveA) applyToBody(s.bodies[j.a], r.then.JA * l);
        if (moveB) applyToBody(s.bodies[j.b], r.then.JB * l);
        if (known) {
            s.projectedImpulse[j.index] += r.then.lin.leftCols(r.then.nl) * l.head(r.then.nl);
            s.projectedCouple[j.index] += r.then.ang.leftCols(r.then.na) * l.segment(r.then.nl, r.then.na);
        }
        return;
    }
    const Vec3 J = r.D * lambda;
    if (moveA) applyImpulse(s.bodies[j.a], r.thenA, J / h);
    if (known) s.projectedImpulse[j.index] += J / h;
    if (moveB) applyImpulse(s.bodies[j.b], r.thenB, -J / h);
}

// The joints of a group in the order of a path, when the group is one (each joint shares
// bodies with two others at most, and no ring: a chain, a rope of links, a bridge): then K
// is block-tridiagonal in that order. Empty when it is not.
std::vector<int> pathOrder(int count, const std::vector<std::pair<int, int>>& pairs) {
    std::vector<std::array<int, 2>> next(count, {-1, -1});
    int links = 0;
    for (const auto& [k, l] : pairs) {
        if (k >= l) continue;
        for (auto [x, y] : {std::pair{k, l}, std::pair{l, k}}) {
            if (next[x][0] < 0)
                next[x][0] = y;
            else if (next[x][1] < 0)
                next[x][1] = y;
            else
                return {};
        }
        ++links;
    }
    if (links != count - 1) return {};  // a ring (the groups are joined)
    int at = 0;
    while (at < count && next[at][1] >= 0) ++at;
    std::vector<int> order;
    for (int from = -1; at >= 0 && static_cast<int>(order.size()) < count;) {
        order.push_back(at);
        const int to = next[at][0] != from ? next[at][0] : next[at][1];
        from = at;
        at = to;
    }
    if (static_cast<int>(order.size()) != count) return {};
    return order;
}

// K λ = -C for a chain of ball joints in path order (`order`): block elimination along the
// path and back substitution, three 3×3 blocks a joint. Not invertible: no step (NaN).
Eigen::VectorXd alongPath(const Model& model, const State& state, const ContactSolverScratch& s,
                          const std::vector<Rows>& rows, const std::vector<int>& order, int size) {
    const std::size_t n = order.size();
    std::vector<Mat3> pivotInverse(n), upper(n);
    std::vector<Vec3> y(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Rows& r = rows[order[i]];
        Mat3 pivot = shared(model, state, s, r, r);  // a ball joint's rows are the axes: K's block is M
        Vec3 rhs = -r.C;
        if (i > 0) {
            const Mat3 g = shared(model, state, s, r, rows[order[i - 1]]) * pivotInverse[i - 1];
            pivot -= g * upper[i - 1];
            rhs -= g * y[i - 1];
        }
        bool invertible = false;
        pivot.computeInverseWithCheck(pivotInverse[i], invertible, 0.0);
        if (!invertible || !pivotInverse[i].allFinite())
            return Eigen::VectorXd::Constant(size, std::numeric_limits<double>::quiet_NaN());
        y[i] = rhs;
        if (i + 1 < n) upper[i] = shared(model, state, s, r, rows[order[i + 1]]);
    }
    Eigen::VectorXd lambda(size);
    Vec3 x = Vec3::Zero();
    for (std::size_t i = n; i-- > 0;) {
        x = pivotInverse[i] * (i + 1 < n ? Vec3(y[i] - upper[i] * x) : y[i]);
        lambda.segment<3>(rows[order[i]].offset) = x;
    }
    return lambda;
}

// The Newton step's impulses: K λ = -C over the group's rows. Along the path (`path`, in
// its order) for a chain of ball joints, its blocks all 3 × 3 (chain-100 took 1.21 times as
// long by the general elimination); by elimination (`plan`) when the group's pattern allows
// it (block_elimination.h: a group whose moving bodies form a tree, any size); else up to
// kMostGroupJoints joints by a dense LU and a larger group by a sparse LU, the pattern's
// ordering found once per group (`lu`, made at the first such solve). Not finite: no step.
Eigen::VectorXd newtonImpulses(const Model& model, const State& state, const ContactSolverScratch& s,
                               const std::vector<Rows>& rows, const std::vector<std::pair<int, int>>& pairs,
                               const std::vector<int>& path, const Elimination& plan, int size,
                               std::optional<Eigen::SparseLU<Eigen::SparseMatrix<double>>>& lu) {
    Eigen::VectorXd C(size);
    for (const Rows& r : rows) C.segment(r.offset, r.count) = r.C;
    if (!path.empty()) return alongPath(model, state, s, rows, path, size);
    if (!plan.empty()) {
        std::vector<Block> blocks;
        blocks.reserve(pairs.size());
        for (const auto& [k, l] : pairs) blocks.push_back(block(model, state, s, rows[k], rows[l]));
        std::vector<int> offsets, sizes;
        for (const Rows& r : rows) {
            offsets.push_back(r.offset);
            sizes.push_back(r.count);
        }
        return solveByElimination(plan, blocks, offsets, sizes, -C);
    }
    if (static_cast<int>(rows.size()) <= kMostGroupJoints) {
        Eigen::MatrixXd K = Eigen::MatrixXd::Zero(size, size);
        for (const auto& [k, l] : pairs)
            K.block(rows[k].offset, rows[l].offset, rows[k].count, rows[l].count) =
                block(model, state, s, rows[k], rows[l]);
        return Eigen::PartialPivLU<Eigen::MatrixXd>(K).solve(-C);
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (const auto& [k, l] : pairs) {
        // Every shared pair's entries, zeros too: the pattern stays the one analysed.
        const Block b = block(model, state, s, rows[k], rows[l]);
        for (int i = 0; i < b.rows(); ++i)
            for (int j = 0; j < b.cols(); ++j)
                entries.emplace_back(rows[k].offset + i, rows[l].offset + j, b(i, j));
    }
    Eigen::SparseMatrix<double> K(size, size);
    K.setFromTriplets(entries.begin(), entries.end());
    if (!lu) lu.emplace().analyzePattern(K);
    lu->factorize(K);
    if (lu->info() != Eigen::Success)
        return Eigen::VectorXd::Constant(size, std::numeric_limits<double>::quiet_NaN());
    return lu->solve(-C);
}

// While it lives, the inverse inertias of a group's bodies scaled by kTurnWeight: the metric a
// positions-only Newton step moves the bodies in, once a full step has failed (see newtonSteps).
class DampedTurns {
public:
    DampedTurns(ContactSolverScratch& s, const std::vector<Rows>& rows) : s_(s) {
        for (const Rows& r : rows)
            for (int b : {r.joint->a, r.joint->b})
                if (b >= 0 && std::none_of(kept_.begin(), kept_.end(), [&](const auto& k) { return k.first == b; }))
                    kept_.emplace_back(b, s.bodies[b].invI);
        for (const auto& [b, invI] : kept_) s.bodies[b].invI = kTurnWeight * invI;
    }
    ~DampedTurns() {
        for (const auto& [b, invI] : kept_) s_.bodies[b].invI = invI;
    }
    DampedTurns(const DampedTurns&) = delete;
    DampedTurns& operator=(const DampedTurns&) = delete;

private:
    ContactSolverScratch& s_;
    std::vector<std::pair<int, Mat3>> kept_;
};

// Newton steps (up to `iterations`) on a group's rows until its error is within kHeld; with
// `from`, RATTLE's (along the start's directions, given to the velocities), else positions
// only. Stops where no step lowers the error, leaving the rest to the Gauss-Seidel passes.
void newtonSteps(const Model& model, State& state, ContactSolverScratch& s, double h, const State* from,
                 const State& at, std::vector<Rows>& rows, const std::vector<std::pair<int, int>>& pairs,
                 int iterations) {
    int size = 0;
    for (Rows& r : rows) {
        r.offset = size;
        size += r.count;
    }
    const int count = static_cast<int>(rows.size());
    const bool balls = std::all_of(rows.begin(), rows.end(), [](const Rows& r) {
        return r.joint->type == JointType::Ball && !r.general;
    });
    const std::vector<int> path = balls ? pathOrder(count, pairs) : std::vector<int>{};
    Elimination plan;  // (made at the first step: most groups need none)
    bool planned = !path.empty();
    std::optional<Eigen::SparseLU<Eigen::SparseMatrix<double>>> lu;  // made when a large group needs it
    std::optional<DampedTurns> damped;  // once a full positions-only step has failed
    double squares = 0.0;
    double error = measure(model, state, at, rows, &squares);
    for (int it = 0; it < iterations && error > kHeld; ++it) {
        if (!planned) {
            plan = eliminationOf(count, pairs);
            planned = true;
        }
        const Eigen::VectorXd lambda = newtonImpulses(model, state, s, rows, pairs, path, plan, size, lu);
        if (!lambda.allFinite()) break;
        // Every joint's impulse from the same linearisation, then the error again. Along
        // the start's directions (RATTLE, which also sets the velocities) only a full
        // step that halves the error is taken: partial ones, given to the velocities, put
        // energy into a whipping chain. Positions alone take halved steps (up to six;
        // twelve in a group of more than 64 joints) as long as the error falls.
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
        const bool wasDamped = damped.has_value();
        const int tries = from ? 1 : (count > kMostGroupJoints ? 12 : 6);
        for (int t = 0; t < tries && !lower; ++t, scale *= 0.5) {
            if (t > 0) {
                // Back to the poses, and to their arms: measure() set each row's arms
                // to the poses it measured, and the next try must push where this one did.
                restore();
                measure(model, state, at, rows);
            }
            for (const Rows& r : rows)
                moveRows(model, state, s, r, scale * lambda.segment(r.offset, r.count));
            next = measure(model, state, at, rows, &nextSquares);
            lower = from ? nextSquares < 0.25 * squares : nextSquares < squares;
            if (lower) break;
            if (from || damped) continue;
            // Positions only, a full step that does not lower the error: the step turned
            // bodies so far that the linearisation missed (a chain nearly straight folded
            // into a zigzag, whose links' turns shorten it at second order). From here on
            // the group moves in a metric that weighs turns more (inverse inertias times
            // kTurnWeight), its steps more translation than turn. chain-100: projections
            // left open after 100 Gauss-Seidel passes (gaps up to 8 mm), 149 in 704 -> 28
            // (largest gap 2.8 mm -> 1e-13 m); a 100-link chain at 1/20 and 1/30 s no
            // longer comes apart (tst_joints). The move is still along the rows' directions
            // (the centre of mass stays), positions only; RATTLE's keeps the true inertia.
            // (Weights of 0.3 and 0.01 each let a chain of the test's grid gain energy.)
            restore();
            measure(model, state, at, rows);
            damped.emplace(s, rows);
            break;
        }
        if (!lower && damped && !wasDamped) {  // the same iteration again, damped
            --it;
            continue;
        }
        if (!lower) {  // no step helps: left as it was, to Gauss-Seidel
            restore();
            measure(model, state, at, rows);
            break;
        }
        if (from && h != 0.0) {  // the move as the impulse J / h over the step (RATTLE)
            // (The poses are where the nudges put them; only the velocities are given.)
            for (const Rows& r : rows)
                giveVelocity(model, state, s, r, scale * lambda.segment(r.offset, r.count), h);
        }
        error = next;
        squares = nextSquares;
    }
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
        // Ropes (one-sided) are left to the Gauss-Seidel passes; limits past join their
        // joint's rows in a positions-only solve (addPastLimits).
        if (!active(model, state, j) || j.type == JointType::Rope) continue;
        // (A six-axis joint with every axis free has no rows: its stops are the passes'.)
        if (j.type == JointType::SixAxis && j.locked == 0) continue;
        members.push_back(k);
        if (movable(model, state, j.a) && movable(model, state, j.b))
            parent[root(parent, j.a)] = root(parent, j.b);
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
        std::vector<Rows> rows(count);
        for (int k = 0; k < count; ++k) {
            rows[k].joint = &model.joints[members[first + k]];
            const JointModel& j = *rows[k].joint;
            rows[k].general = isGeneral(j.type);
            if (rows[k].general) {  // (the start's rows, once: measure() makes those now)
                generalRows(j, at.bodies[j.a], j.b >= 0 ? &at.bodies[j.b] : nullptr, rows[k].then, nullptr,
                            hingeNear(state, j));
                rows[k].count = rows[k].then.m;
            } else {
                rows[k].count = j.type == JointType::Ball ? 3 : 1;
            }
        }
        const std::vector<std::pair<int, int>> pairs = sharingPairs(model, state, rows);
        // Positions only, in rounds: the Newton steps may carry a stop or a cone bound past
        // that the group did not hold when it began; it joins the rows, held at its bound,
        // and the steps go on (a ragdoll's knee carried past its limit by its hip's move
        // was left to the passes, 25-37 of them each projection in ragdoll-pile).
        if (!from)
            for (Rows& r : rows) addPastLimits(*r.joint, state, r);
        for (int round = 0;; ++round) {
            newtonSteps(model, state, s, h, from, at, rows, pairs, iterations);
            if (from || round == kLimitRounds) break;
            bool more = false;
            for (Rows& r : rows) more = addPastLimits(*r.joint, state, r) || more;
            if (!more) break;
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
        if (active(model, state, j) && j.index < static_cast<int>(s.jointChecks.size()))
            joints.push_back(j.index);
    const std::vector<int> sizes = groupSizes(model, joints, [&](int i) { return movable(model, state, i); });
    double open = 0.0;
    for (std::size_t k = 0; k < joints.size(); ++k)
        if (sizes[k] <= kMostGroupJoints) open = std::max(open, s.jointChecks[joints[k]].error);
    return open;
}

}  // namespace tumble
