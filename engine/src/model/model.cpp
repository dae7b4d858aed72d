// Quantities derived from a body's state: velocities, world inertia, energy.
#include <tumble/model.h>

#include "common/pair_key.h"
#include "model/joint_coordinate.h"

#include <algorithm>

namespace tumble {

bool Model::mayCollide(int a, int b) const {
    if (!filtered) return true;
    if (!(groupCollides[bodies[a].group] >> bodies[b].group & 1)) return false;
    return !std::binary_search(pairsApart.begin(), pairsApart.end(), pairKey(std::min(a, b), std::max(a, b)));
}

Derived derive(const BodyModel& b, const BodyState& s) {
    Derived d;
    d.R = s.q.toRotationMatrix();
    switch (b.motion) {
        case Motion::Dynamic:
            // R c1 Rᵀ = c1: a ball's or a cube's inverse inertia needs no turning.
            d.invInertiaWorld =
                b.sphericalInertia ? b.invInertia : Mat3(d.R * b.invInertia * d.R.transpose());
            d.v = b.invMass * s.P;
            d.omega = b.sphericalInertia ? Vec3(b.invInertia(0, 0) * s.L) : Vec3(d.invInertiaWorld * s.L);
            break;
        case Motion::Kinematic:
        case Motion::Animated:  // (compiled as kinematic with a path)
            d.invInertiaWorld.setZero();
            d.v = b.path ? s.P : b.kinematicVelocity;
            d.omega = b.path ? s.L : b.kinematicAngularVelocity;
            break;
        case Motion::Static:
            d.invInertiaWorld.setZero();
            d.v.setZero();
            d.omega.setZero();
            break;
    }
    return d;
}

Vec3 angularVelocity(const BodyModel& b, const BodyState& s) {
    return b.sphericalInertia ? Vec3(b.invInertia(0, 0) * s.L) : derive(b, s).omega;
}

void placeOnPath(const BodyModel& b, double t, BodyState& s) {
    const PathPoint p = b.path->at(t);
    const Vec3 arm = p.orientation * b.centerOfMass;
    s.x = p.position + arm;
    s.q = p.orientation;
    s.P = p.velocity + p.angularVelocity.cross(arm);
    s.L = p.angularVelocity;
}

Vec3 bodyFramePosition(const BodyModel& b, const BodyState& s) {
    return s.x - s.q * b.centerOfMass;
}

Energy energy(const Model& model, const State& state) {
    Energy e;
    for (int i : model.dynamicBodies) {
        const BodyModel& b = model.bodies[i];
        const BodyState& s = state.bodies[i];
        const Derived d = derive(b, s);
        e.kinetic += 0.5 * (s.P.dot(d.v) + s.L.dot(d.omega));
        e.potential -= b.mass * model.settings.gravity.dot(s.x);
    }
    for (const ForceTerm& f : model.forces) {
        if (f.type != ForceType::Spring || !f.activeAt(state.time)) continue;
        const BodyState& s = state.bodies[f.body];
        const double stretch = (s.x + s.q * f.arm - f.anchor).norm() - f.restLength;
        e.potential += 0.5 * f.stiffness * stretch * stretch;
    }
    if (!model.joints.empty()) e.potential += joint::jointSpringEnergy(model, state);
    return e;
}

}  // namespace tumble
