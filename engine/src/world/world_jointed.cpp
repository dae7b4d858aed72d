// World::step: a step is cut where a force switches on or off (stepPiece between). Steps of
// scenes with joints: a step the joints could not keep is taken again in halves
// (stepJointed); a mechanism alone (joints, no contacts, nothing that only takes energy)
// with the fourth-order integrator is stepped as a fourth-order composition of the
// second-order constrained step (stepComposed).
#include <tumble/world.h>

#include "common/pair_key.h"
#include "world/world_scratch.h"

#include <algorithm>
#include <cmath>

namespace tumble {

namespace {

// Whether the model is a mechanism the composed step is exact for: the fourth-order
// integrator; joints that hold both ways (no rope, limit, motor, spring, servo or breaking:
// one-sided, soft or driven rows, and a breaking force met within a piece, are not symmetric in time); no
// damping and no force switched on or off (the middle piece runs backwards in time); and no
// two bodies that could touch (every pair that is not static-static is a joint's pair), so
// that no contact or impact is ever met backwards.
bool composable(const Model& m) {
    if (m.integrator->id != Integrator::Splitting4 || m.joints.empty() || m.bodies.size() > 64) return false;
    for (const JointModel& j : m.joints)
        if (j.type == JointType::Rope || j.limited || j.swingLimited || j.twistLimited || j.motor || j.spring ||
            j.servo || std::isfinite(j.breakForce) ||
            std::any_of(j.axes.begin(), j.axes.end(), [](const JointAxis& x) { return x.acted(); }))
            return false;
    for (const BodyModel& b : m.bodies)
        if (b.linearDamping != 0.0 || b.angularDamping != 0.0 ||
            (b.motion == Motion::Kinematic && !b.standsStill()))
            return false;
    if (!m.forceSwitchTimes.empty()) return false;
    for (int a = 0; a < static_cast<int>(m.bodies.size()); ++a)
        for (int b = a + 1; b < static_cast<int>(m.bodies.size()); ++b) {
            if (m.bodies[a].motion == Motion::Static && m.bodies[b].motion == Motion::Static) continue;
            if (!m.mayCollide(a, b)) continue;
            if (!std::binary_search(m.jointPairs.begin(), m.jointPairs.end(), pairKey(a, b))) return false;
        }
    return true;
}

}  // namespace

void World::prepareJointedSteps() {
    Scratch& s = *scratch_;
    for (const JointModel& j : model_.joints)
        for (int i : {j.a, j.b}) {
            if (i < 0) continue;
            const BodyModel& b = model_.bodies[i];
            if (b.motion == Motion::Dynamic) s.jointedBodies.push_back(i);
            if (b.motion == Motion::Kinematic && !b.standsStill()) s.jointsPassive = false;
        }
    // (A spring's energy comes back as the step's rounding of its oscillation: not a gain
    // the halves would mend; a servo drives.)
    auto drives = [](const JointAxis& x) { return x.motor || x.spring || x.servo; };
    for (const JointModel& j : model_.joints)
        s.jointsPassive = s.jointsPassive && !drives(j) && std::none_of(j.axes.begin(), j.axes.end(), drives);
    // (Every group's energy counts since a chain of ball joints of any length is solved as
    // one (joint_projection.cpp): a 100-link chain let go level at 1/60 s gained up to 4e-4
    // of its energy without the check, 3e-5 with it (49 of 301 steps split, 20 % more
    // time). When a group of more than 64 joints was left to Gauss-Seidel, which gives and
    // takes energy as its passes go, the check split a fifth of its steps for gains its total
    // energy never showed, and cost 50 % more: large groups were left out then.)
    std::sort(s.jointedBodies.begin(), s.jointedBodies.end());
    s.jointedBodies.erase(std::unique(s.jointedBodies.begin(), s.jointedBodies.end()), s.jointedBodies.end());
    for (int i : s.jointedBodies)
        s.jointedWeight += model_.bodies[i].mass * model_.settings.gravity.norm() * s.sizes[i];
    s.composed = composable(model_);
    // The fourth-order integrator asked for a mechanism it cannot compose: its joints are
    // stepped at second order, which the run says (stdout's integrator: is still the one asked).
    if (model_.integrator->id == Integrator::Splitting4 && !model_.joints.empty() && !s.composed) {
        model_.notes.push_back(
            "splitting-4: the joints here are stepped at second order (the fourth-order composition "
            "needs a mechanism alone: no rope, limit, motor, spring, servo or breaking force, no damping, no force "
            "switched on or off, no two bodies that could touch, at most 64 bodies); free "
            "rotations are still fourth order");
    }
}

void World::step(double h) {
    const std::vector<double>& switches = model_.forceSwitchTimes;
    if (switches.empty() || !(h > 0.0)) {
        stepPiece(h);
        return;
    }
    const double end = state_.time + h, near = 1e-9 * h;
    auto next = std::upper_bound(switches.begin(), switches.end(), state_.time - near);
    if (next != switches.end() && *next <= state_.time + near) state_.time = *next++;  // at the start
    for (; next != switches.end() && *next < end - near; ++next) {
        stepPiece(*next - state_.time);
        state_.time = *next;  // (the piece's sum may differ in its last bit)
    }
    stepPiece(end - state_.time);
    state_.time = end;
}

// One step of h in which no force switches.
void World::stepPiece(double h) {
    if (model_.joints.empty())
        stepWhole(h);
    else if (scratch_->composed)
        stepComposed(h);
    else
        stepJointed(h, 0);
}

double World::jointedKinetic() const {
    double kinetic = 0.0;
    for (int i : scratch_->jointedBodies) {
        const BodyState& b = state_.bodies[i];
        kinetic +=
            0.5 * (b.P.squaredNorm() / model_.bodies[i].mass + b.L.dot(angularVelocity(model_.bodies[i], b)));
    }
    return kinetic;
}

// A step just taken (from s.jointRedo[splits].start, or composedRedo's) that its joints did
// not keep, taken again from its start as two halves, each of which may split once more
// (at most four pieces). Not kept: a joint left open (`held` false), its projection (joints.h)
// not converged (a 50-link chain whipping at 1/30 s opened by 0.25 % of its length, and held
// to 1e-13 m at 1/35 s and shorter); or, where joints can only take energy out (no motor,
// no moving kinematic body), joints that gave the bodies more than a thousandth of their
// kinetic energy and weight (`kinetic` at the start): the same chain at 1/20 s gained 41 % of
// its energy in one step whose projection converged. A step split for its energy alone is
// weighed against its halves where every joint held (`allHeld`: groups of any size; a
// 100-link chain whose whip its Newton steps leave to Gauss-Seidel opened by 2.8 mm, not
// 0.16, when its gaining steps were kept): where they gave at least 0.4 of what a smooth error would
// (two halves give a quarter of a second-order step's error, a sixteenth of a fourth-order
// one's), its gain is the method's own, and the step is kept as first taken. RATTLE's energy error
// oscillates: a double pendulum of capsules at 1/60 s swings through +0.6 % and back in a fast swing, and
// taking only its gaining steps again, in halves, while keeping those that lost made that a drift (0.86 %
// lost in 10 s; 9.4 % with splitting-4 when the composition's backward piece was split
// alone: that piece gains what the others lose). Whether a split was made.
bool World::splitFor(double h, int splits, bool composed, double gained, double kinetic, bool held,
                     bool allHeld) {
    Scratch& s = *scratch_;
    const bool gave = s.jointsPassive && gained > 1e-3 * (kinetic + s.jointedWeight);
    if (held && !gave) return false;
    Scratch::JointRedoPair& r = (composed ? s.composedRedo : s.jointRedo)[splits];
    const double end = state_.time;
    if (held) r.end = {state_, ledger_, s.energy};
    state_ = r.start.state;
    ledger_ = r.start.ledger;
    s.energy = r.start.guard;
    forgetStill(s.still);  // (what the step taken back found still)
    ++profile_.jointSplits;
    if (composed) {
        stepComposed(0.5 * h, splits + 1);
        stepComposed(end - state_.time, splits + 1);
    } else {
        const bool weigh = gained != 0.0;  // (not in a composed step's pieces)
        stepJointed(0.5 * h, splits + 1, weigh);
        stepJointed(end - state_.time, splits + 1, weigh);
    }
    state_.time = end;  // (the halves' sum may differ from h in its last bit)
    if (!held || !allHeld) return true;
    Scratch::JointRedoPair& again =
        (composed ? s.composedRedo : s.jointRedo)[splits];  // (the halves may have grown it)
    const double smooth = composed ? 1.0 / 16 : 1.0 / 4;  // what halves give of a step's error, by its order
    if (again.start.ledger.lostInJoints - ledger_.lostInJoints > 0.4 * smooth * gained) {
        state_ = again.end.state;
        ledger_ = again.end.ledger;
        s.energy = again.end.guard;
        forgetStill(s.still);
    }
    return true;
}

void World::stepJointed(double h, int splits, bool weigh) {
    constexpr int kMostSplits = 2;
    Scratch& s = *scratch_;
    if (splits >= kMostSplits) {
        stepWhole(h);
        return;
    }
    if (static_cast<int>(s.jointRedo.size()) <= splits) s.jointRedo.resize(splits + 1);
    s.jointRedo[splits].start = {state_, ledger_, s.energy};
    const double kinetic = weigh ? jointedKinetic() : 0.0;
    s.solver.stepJointsOpen = s.solver.stepJointsOpenAll = 0.0;
    stepWhole(h);
    const double open = 1e-3 * s.touchTolerance;  // (kTouchTolerance: 1e-5 of the largest size)
    const double gained = weigh ? s.jointRedo[splits].start.ledger.lostInJoints - ledger_.lostInJoints : 0.0;
    splitFor(h, splits, false, gained, kinetic, !(s.solver.stepJointsOpen > open),
             !(s.solver.stepJointsOpenAll > open));
}

// Yoshida's triple jump: steps of g1 h, g0 h and g1 h (g0 = -2^(1/3) g1 < 0) make a
// fourth-order step of any symmetric second-order one. The constrained step (RATTLE: the
// free Strang step, the positions projected with impulses along the joints at the start,
// the velocity rows at the end) is symmetric, so a pendulum's period error falls from
// (ωh)²/24 to O(h⁴): 7.2e-6 -> see tst_joints pendulumPeriod. Its energy is weighed over
// the three pieces together (splitFor), the backward one gaining what the others lose.
void World::stepComposed(double h, int splits) {
    constexpr int kMostSplits = 2;
    Scratch& s = *scratch_;
    const bool weigh = splits < kMostSplits;
    if (weigh) {
        if (static_cast<int>(s.composedRedo.size()) <= splits) s.composedRedo.resize(splits + 1);
        s.composedRedo[splits].start = {state_, ledger_, s.energy};
    }
    const double kinetic = weigh ? jointedKinetic() : 0.0;
    s.solver.composedJointsOpenAll = 0.0;
    const double c = std::cbrt(2.0), g1 = 1.0 / (2.0 - c), g0 = -c / (2.0 - c);
    const double end = state_.time + h;
    stepJointed(g1 * h, 0, false);
    stepJointed(g0 * h, 0, false);
    stepJointed(end - state_.time, 0, false);
    state_.time = end;
    if (weigh)
        splitFor(h, splits, true, s.composedRedo[splits].start.ledger.lostInJoints - ledger_.lostInJoints,
                 kinetic, true, !(s.solver.composedJointsOpenAll > 1e-3 * s.touchTolerance));
}

}  // namespace tumble
