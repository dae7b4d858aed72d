// What the energy ledger must say (issue 44): a body at rest books nothing, no contact or
// friction loss is negative, and the parts add up to the change of the scene's energy.
// The scales here are those of rounding, which a ledger of floating-point sums cannot beat.
#pragma once

#include <tumble/model.h>
#include <tumble/world.h>

#include <QString>

#include <algorithm>
#include <cmath>

namespace tumble::test {

/// Σ m |g| (|x| + 1 m) over the dynamic bodies: the size of their potential energies, whose
/// rounding (a position is kept to 1e-16 of itself) bounds what a ledger entry of a resting
/// scene can book a step: about 1e-15 of this.
inline double weightTimesHeight(const World& w) {
    double sum = 0.0;
    const double g = w.model().settings.gravity.norm();
    for (size_t i = 0; i < w.model().bodies.size(); ++i) {
        const BodyModel& b = w.model().bodies[i];
        if (b.motion == Motion::Dynamic) sum += b.mass * g * (w.state().bodies[i].x.norm() + 1.0);
    }
    return sum;
}

/// The energy the ledger does not account for: the change of the scene's energy (kinetic,
/// gravity, springs) since `start`, plus what it booked as lost, less its position
/// correction and what moving kinematic and animated bodies did through contacts. Zero, up
/// to rounding and the integrator's own error, in a scene where nothing else drives the
/// bodies (no applied force but gravity and springs, no damping, no motor, no joint to a
/// moving kinematic body).
inline double ledgerGap(const World& w, double start) {
    const EnergyLedger& l = w.ledger();
    return energy(w.model(), w.state()).total() - start + l.lostInContacts + l.lostInFriction +
           l.lostInJoints - l.positionCorrection - l.doneByKinematic;
}

inline QString describeLedger(const World& w, double start) {
    const EnergyLedger& l = w.ledger();
    return QString(
               "energy %1 -> %2 J; contacts %3, friction %4, joints %5, correction %6 J, by kinematic "
               "bodies %8 J; gap %7 J")
        .arg(start, 0, 'g', 10)
        .arg(energy(w.model(), w.state()).total(), 0, 'g', 10)
        .arg(l.lostInContacts, 0, 'g', 4)
        .arg(l.lostInFriction, 0, 'g', 4)
        .arg(l.lostInJoints, 0, 'g', 4)
        .arg(l.positionCorrection, 0, 'g', 4)
        .arg(ledgerGap(w, start), 0, 'g', 3)
        .arg(l.doneByKinematic, 0, 'g', 6);
}

}  // namespace tumble::test
