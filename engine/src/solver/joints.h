// Stage: the joints, inside the contact solver (docs/architecture.md "Joints"). Their rows
// are updated in the same Gauss-Seidel passes as the contact blocks, on the same solver
// bodies, and warm-started from State::jointImpulses; after the bodies are re-placed, the
// joints' position error is removed by Newton projection (no velocity is changed, so no
// kinetic energy; the potential energy it moves is counted with the position passes').
#pragma once

#include "solver/contact_solver.h"

#include <tumble/model.h>
#include <tumble/state.h>

#include <vector>

namespace tumble {

/// Adds the bodies of the joints that can act now (one body awake and dynamic) to
/// `involved` (kept ascending, each once).
void addJointBodies(const Model& model, const State& state, std::vector<int>& involved,
                    std::vector<std::uint8_t>& seen);

/// The rows of the active joints at the bodies' loaded velocities (s.bodies), each started
/// from its impulse of the last step scaled to this step, at most `warmGrowth` times
/// (warmScale), and applied to the bodies. Whether any warm start was scaled up.
/// `impulsive` (a moment of impact, impact.cpp): no warm start and no motor (a finite force
/// gives no impulse in an instant), and a rope, limit or the like only where it is taut or
/// reached (then holding the rate at zero); `only`: the joints with a body flagged there.
bool prepareJoints(const Model& model, const State& state, double h, ContactSolverScratch& s,
                   bool impulsive = false, const std::vector<std::uint8_t>* only = nullptr,
                   double warmGrowth = 1.0);

/// One Gauss-Seidel update of joint row k; whether it changed a velocity by more than
/// `quietSpeed` (and then the bodies' changedAt stamps, for the contact blocks' skipping).
bool updateJoint(ContactSolverScratch& s, int k, double quietSpeed);

/// After the velocity rows: moves the bodies of each hinge or slider with a spring or servo
/// along its axis so that its coordinate has moved over the step by the mean of its rates at
/// the start and the end (joint_drive.h), from its place at s.stepStart.
void nudgeDrives(const Model& model, State& state, const ContactSolverScratch& s, double h);

/// The impulses to start the next step from (State::jointImpulses).
void rememberJoints(const Model& model, const ContactSolverScratch& s, double h, State& state);

/// Moves the jointed bodies (dynamic and awake) so that their joints hold to 1e-13 m
/// (Newton steps along each joint's rows, Gauss-Seidel over the joints, 50 passes at most).
/// With h > 0 the move is also given to the solver bodies' velocities, as the impulse that
/// made it over the step (the position half of RATTLE: the constraint force that keeps the
/// joint acts on the velocity too); h = 0 moves the poses only (drift left by other stages).
/// `start` (with h): the state at the start of the step, whose joint directions the
/// impulses act along (RATTLE's); null: the directions where the bodies are now.
void projectJoints(const Model& model, State& state, ContactSolverScratch& s, double h,
                   const State* start = nullptr);

}  // namespace tumble
