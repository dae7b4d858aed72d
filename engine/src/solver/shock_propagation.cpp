#include "solver/shock_propagation.h"

#include "solver/contact_rows.h"

#include <algorithm>

namespace tumble {

using Point = ContactSolverScratch::Point;

namespace {

// Support levels: 0 for a body that cannot move (static, kinematic, asleep), else the least
// number of contacts between it and such a body (a large number when none is reached).
void supportLevels(ContactSolverScratch& s) {
    constexpr int kUnreached = 1 << 29;
    // (The blocks name the solve's bodies only: one island's, of a world of thousands.)
    s.level.resize(s.bodies.size());
    for (int i : s.involved) s.level[i] = s.bodies[i].invMass == 0.0 ? 0 : kUnreached;
    // Relaxation over the blocks; a pile is as many rounds deep as it has layers.
    for (bool changed = true; changed;) {
        changed = false;
        for (const auto& block : s.blocks) {
            const Point& p = s.points[block.begin];
            int& la = s.level[p.a];
            int& lb = s.level[p.b];
            if (la + 1 < lb) lb = la + 1, changed = true;
            if (lb + 1 < la) la = lb + 1, changed = true;
        }
    }
}

}  // namespace

// The last passes, from the ground up (shock propagation): level by level, the bodies of
// the lower level stand still while the contacts between them and the next level are
// solved (a few passes, so that a body on two supports settles on both), so each body
// ends at rest on what holds it, or moving with it, whatever the iterations left. A tall
// or heavy-on-light stack needs far more Gauss-Seidel passes than a step has to carry its
// weight down to the ground (the error shrinks by a fixed factor per pass, and that factor
// nears 1 as the stack grows); without these passes the stack sinks into itself each step
// until the warm start has caught up. The impulses they add are kept for the next step's
// warm start, where the lower bodies then feel them: at rest they find nothing left to do
// (their normal impulses; friction only on a support at rest, see below).
void shockPass(ContactSolverScratch& s, int passes, bool converged, double quietSpeed, double stillSpeed) {
    // At the passes' fixed point with every contact against a body that cannot move (a ball
    // on the ground, boxes side by side on it), no level holds anything still: nothing to do.
    if (converged && std::all_of(s.blocks.begin(), s.blocks.end(), [&](const ContactSolverScratch::Block& b) {
            const Point& p = s.points[b.begin];
            return s.bodies[p.a].invMass == 0.0 || s.bodies[p.b].invMass == 0.0;
        }))
        return;
    supportLevels(s);
    const int nb = static_cast<int>(s.blocks.size());
    auto lowerLevel = [&](int b) {
        const Point& p = s.points[s.blocks[b].begin];
        return std::min(s.level[p.a], s.level[p.b]);
    };
    s.order.clear();
    for (int b = 0; b < nb; ++b) {
        const Point& p = s.points[s.blocks[b].begin];
        if (s.level[p.a] != s.level[p.b]) s.order.push_back(b);  // a level's own contacts are done
    }
    // By level, and within a level in block order (a stable sort's order, without its buffer).
    std::sort(s.order.begin(), s.order.end(), [&](int x, int y) {
        const int lx = lowerLevel(x), ly = lowerLevel(y);
        return lx < ly || (lx == ly && x < y);
    });
    std::vector<SolverBody>& saved = s.savedBodies;
    std::vector<int>& frozenBodies = s.frozenBodies;
    saved.clear();
    frozenBodies.clear();
    bool atFixedPoint = converged;  // nothing has changed since the passes' fixed point
    for (size_t g = 0; g < s.order.size();) {
        const int level = lowerLevel(s.order[g]);
        size_t e = g;
        while (e < s.order.size() && lowerLevel(s.order[e]) == level) ++e;
        // The lower level stands still; the blocks are prepared again for that.
        const size_t frozenBefore = frozenBodies.size();
        for (size_t k = g; k < e; ++k) {
            const Point& p = s.points[s.blocks[s.order[k]].begin];
            const int lower = s.level[p.a] < s.level[p.b] ? p.a : p.b;
            SolverBody& body = s.bodies[lower];
            if (body.invMass == 0.0) continue;
            frozenBodies.push_back(lower);
            saved.push_back(body);
            body.invMass = 0.0;
            body.invI.setZero();
        }
        // Nothing held still and nothing changed below: these blocks are at their fixed
        // point already (a ball on the ground, the bottom layer of a pile).
        if (atFixedPoint && frozenBodies.size() == frozenBefore) {
            g = e;
            continue;
        }
        atFixedPoint = false;
        // Nothing held still (the ground's contacts): the blocks are the passes' own, as
        // prepared, and more passes over them skip the quiet ones as the passes do.
        if (frozenBodies.size() == frozenBefore) {
            for (int pass = 0; pass < passes; ++pass)
                for (size_t k = g; k < e; ++k) updateBlock(s, s.order[k], quietSpeed);
            g = e;
            continue;
        }
        s.frozen.clear();
        for (size_t k = g; k < e; ++k) {
            ContactSolverScratch::Block block = s.blocks[s.order[k]];
            Point* q = &s.points[block.begin];
            for (int i = 0; i < block.count; ++i) {
                const SolverBody &A = s.bodies[q[i].a], &B = s.bodies[q[i].b];
                const Vec3& at = s.geometry[block.begin + i].position;
                preparePoint(A, B, at - A.x, at - B.x, q[i]);
            }
            prepareBlock(s.bodies[q[0].a], s.bodies[q[0].b], block, s);
            block.subsets = -1;  // its K is new: its sub-inverses are frozenSubsets'
            s.frozen.push_back(block);
        }
        s.frozenSubsets.clear();
        for (int pass = 0; pass < passes; ++pass)
            for (size_t k = 0; k < s.frozen.size(); ++k) {
                frictionBlock(s, s.frozen[k]);
                normalBlock(s, s.frozen[k], s.frozenSubsets);
            }
        // What these passes added to the friction is remembered only where the support
        // stands still under the upper body (at the patch, slower than `stillSpeed`, what
        // the solve takes as its passes' rounding: stopRoundingMotion): then it holds the
        // upper body on a support at rest, a load that the support will carry next step.
        // On a support that the passes left moving it matched the upper body to that
        // motion, an error of the passes and not a force: it is applied and counted
        // (shockT) but not remembered. Remembered, it came back in the next warm start as a
        // push on the support that the support had never felt, and with few passes that
        // grew step by step: pyramid-15 with 5 passes at 1/240 s, sleeping off, turned its
        // twists of 1e-13 N m s at 2.7 s into 8 N m s at 6 s (x1.09 a step) and its ledger
        // into 1e78 J; tower-20 with 2 or 3 passes and the 1 kg box under 100 kg with 1
        // diverged alike. (Normals stay remembered: what they push the support with is the
        // weight it carries.)
        for (size_t k = g; k < e; ++k) {
            ContactSolverScratch::Block& block = s.blocks[s.order[k]];
            const ContactSolverScratch::Block& solved = s.frozen[k - g];
            const Point& p = s.points[block.begin];
            const bool lowerIsA = s.level[p.a] < s.level[p.b];
            const SolverBody& support = s.bodies[lowerIsA ? p.a : p.b];
            const Vec3 at = support.v + support.w.cross(lowerIsA ? block.rA : block.rB);
            if (at.norm() <= stillSpeed && std::abs(p.n.dot(support.w)) * block.radius <= stillSpeed) {
                block.lambdaT = solved.lambdaT;
                block.lambdaTwist = solved.lambdaTwist;
            } else {
                block.shockT = solved.lambdaT - block.lambdaT;
                block.shockTwist = solved.lambdaTwist - block.lambdaTwist;
            }
        }
        g = e;
    }
    for (size_t k = 0; k < frozenBodies.size(); ++k) {
        SolverBody& body = s.bodies[frozenBodies[k]];
        body.invMass = saved[k].invMass;
        body.invI = saved[k].invI;
    }
}

}  // namespace tumble
