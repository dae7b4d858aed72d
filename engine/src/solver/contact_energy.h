// The contact solver's energy: what it books to the ledger, and the limit that keeps
// contacts from creating energy (velocities scaled, overlap removed only as far as the
// contacts paid for the height). See docs/architecture.md "Collision response".
#pragma once

#include "solver/contact_solver.h"

#include <algorithm>

namespace tumble {

/// The energy of the bodies the contact solver moved (s.moving): at the start of the step,
/// as given to the solver, and as it leaves them. Gravity's part after the solve is
/// potentialStart + potentialRate (x = x0 + h v). What they may leave with, in(), is the
/// larger of what they had at the start and what they brought: a force may have done work
/// within the step, and an impact at its end may have taken energy out that placing the
/// bodies again from the start gives back as height (the impact counted as at the start).
struct EnergyBalance {
    double kineticStart = 0.0, kineticIn = 0.0, potentialIn = 0.0;
    double kineticOut = 0.0, potentialStart = 0.0, potentialRate = 0.0;
    double in() const { return std::max(kineticIn + potentialIn, kineticStart + potentialStart); }
    double out() const { return kineticOut + potentialStart + potentialRate; }
    double excess() const { return out() - in(); }
};

/// Moves a body by the positional impulse J at the offset r from its centre of mass, with
/// the inverse mass and world inverse inertia of b (the position passes, joint projection).
void nudge(const SolverBody& b, BodyState& s, const Vec3& r, const Vec3& J);

/// Kinetic energy of a body moving as b, its spin taken in the axes of its orientation q.
double kineticOf(const BodyModel& body, const Quat& q, const BodyVelocity& b);
/// What friction took this step (exact per row; see the definition).
double frictionLost(ContactSolverScratch& s);
/// The kinetic energy of the solve's moving bodies (s.involved, inverse mass above zero)
/// moving as `bodies` (s.bodies, or s.entry: what the solver was given).
double solvedKinetic(const Model& model, const State& state, const ContactSolverScratch& s,
                     const std::vector<SolverBody>& bodies);
double solvedKinetic(const Model& model, const State& state, const ContactSolverScratch& s,
                     const std::vector<BodyVelocity>& bodies);
/// Gravity's potential energy of the dynamic bodies `which` as they stand in `state`.
double gravityPotential(const Model& model, const State& state, const std::vector<int>& which);
/// The work the moving kinematic and animated bodies did through this solve's impulses
/// (normal, friction, twist; EnergyLedger::doneByKinematic), at their constant velocities.
double kinematicWork(const ContactSolverScratch& s);
/// Whether the contacts may only take energy out (no kinematic body among them that moves
/// in this solve: s.bodies' velocities, an animated body's over the solve's interval).
bool passive(const Model& model, const collision::ManifoldList& contacts, const ContactSolverScratch& s);
/// The balance of s.moving; `before`: the state at the start of the step (or its last part).
EnergyBalance energyBalance(const Model& model, const State& state, const State& before,
                            const ContactSolverScratch& s);
/// Scales the velocities of the bodies the solve pushed by the largest α ≤ 1 that leaves no
/// excess, and says in `e` what they leave with (a body at a point that no impulse reached
/// keeps its own, as it is stored); `h`: the step (or its part) the balance was taken over.
void limitEnergy(const Model& model, const State& state, EnergyBalance& e, ContactSolverScratch& s, double h);
/// Removes the overlap left by the step without touching velocities; `limited`: within the
/// energy the contacts took (between one and ten slops).
void correctOverlap(const Model& model, State& state, ContactSolverScratch& s,
                    const ContactSolverSettings& cfg, const EnergyBalance& e, bool limited);

}  // namespace tumble
