// The last contact stage of a step: overlap deeper than the contact margin that the
// contact solver left, moved out before the step's poses are shown (issue 45).
//
// The contact solver finds its points at the end of the free step and places the bodies
// again from the step's start with the velocities it solved. Where that answer differs
// much from the free step (a tilted box whose first corner lands turns its second corner
// down; a body struck within a pile), a feature that was farther than the margin at the
// end of the free step, so never a contact point, can end deep inside another body; and a
// point that was deep at the end of the free step (a step that ran out of cuts) is removed
// by the solver's position pass only in part. Both showed bodies 3-10 cm inside the floor
// in a recorded frame of a pile landing at 1/30 s.
//
// A body is looked at again only if it can hide such an overlap: its pose moved from the
// free step's end by more than the margin (turned by an angle θ, a surface point moves at
// most θ r). Otherwise every feature that was apart by the margin there is apart still,
// and the solver saw the others (and a point it left deep, it moved little). So a pile at
// rest costs nothing here, and a body resting a little deeper than the margin (the
// solver's budgeted pass, contact_energy.cpp) is left to the solver. The bodies looked at are
// tested against every body their box reaches, at their poses as they stand; where a point
// is deeper than the margin and the slop, overlap beyond half the margin and the slop is
// pushed out by position passes, with the bodies a push moves tested in turn. Velocities
// are kept in body axes (a turn changes no kinetic energy); the potential energy the lifts
// add is taken from the moved bodies' kinetic energy (their momenta scaled), so the stage
// makes no energy while there is motion to pay for it.
#pragma once

#include <tumble/collision.h>

#include <tumble/model.h>
#include <tumble/profile.h>
#include "collision/broadphase.h"
#include "solver/solver_body.h"

#include <cstdint>
#include <vector>

namespace tumble {

struct SettleScratch {
    struct Point {
        int a = -1, b = -1;
        double keep = 0.0;            // overlap left to the contact solver
        Vec3 localA, localB, localN;  // each body's deepest point, and the normal in b's axes
    };
    std::vector<std::uint8_t> looked;   // per body: tested in this call
    std::vector<std::uint8_t> pending;  // per body: to be tested
    std::vector<std::uint8_t> movable;  // per body: may be pushed (dynamic, awake, no joint)
    std::vector<int> toTest, tested, moved;
    std::vector<std::uint8_t> wasMoved;                         // per body: pushed in this call
    std::vector<int> level, queue, firstPoint, pointsOf, fill;  // levelPoints
    std::vector<SolverBody> body;                               // per body: masses as pushes left them
    std::vector<Mat3> rotation;
    std::vector<collision::Pose> pose;  // per body: as it stands after the solve
    std::vector<Vec3> startX;           // per moved body: centre of mass before the stage
    std::vector<Vec3> bodySpin;         // ... and its angular velocity in body axes
    collision::ManifoldList found;
    std::vector<Point> points;
};

struct SettleResult {
    int looked = 0;  // bodies tested
    int moved = 0;   // bodies pushed
};

/// `freeEnd`: each body's pose at the end of its free step (the contacts' poses);
/// `contacts`: the manifolds found there; `broadphase`: as the step's last detection left
/// it; `resting`: the resting speed (a body slower is at rest); `sizes`: bounding radii; `jointPairs`: sorted
/// keys of the joined pairs (they do not collide); `jointed`: bodies with a joint (left where the joints hold
/// them).
SettleResult settleOverlap(const Model& model, State& state, const std::vector<collision::Pose>& freeEnd,
                           const collision::ManifoldList& contacts, const std::vector<double>& sizes,
                           const collision::Broadphase& broadphase, double resting,
                           const std::vector<std::uint64_t>& jointPairs, const std::vector<int>& jointed,
                           double margin, SettleScratch& s, EnergyLedger& ledger);

}  // namespace tumble
