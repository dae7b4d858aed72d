#include <tumble/forces.h>

namespace tumble {

void accumulateForces(const Model& model, const std::vector<BodyState>& bodies, double t,
                      std::vector<Wrench>& out) {
    out.assign(bodies.size(), Wrench{});
    const Vec3& g = model.settings.gravity;
    for (int i : model.dynamicBodies) {
        const BodyModel& b = model.bodies[i];
        const BodyState& s = bodies[i];
        Wrench& w = out[i];
        w.force = b.mass * g;
        // Damping is a rate: dv/dt = -c v and dL/dt = -c L.
        if (b.linearDamping > 0.0) w.force -= b.linearDamping * s.P;
        if (b.angularDamping > 0.0) w.torque -= b.angularDamping * s.L;
    }
    for (const ForceTerm& f : model.forces) {
        if (!f.activeAt(t)) continue;
        const BodyState& s = bodies[f.body];
        Wrench& w = out[f.body];
        switch (f.type) {
            case ForceType::Force: {
                const Vec3 F = f.frame == Frame::Body ? Vec3(s.q * f.vector) : f.vector;
                w.force += F;
                w.torque += (s.q * f.arm).cross(F);  // (10)
                break;
            }
            case ForceType::Torque:
                w.torque += f.frame == Frame::Body ? Vec3(s.q * f.vector) : f.vector;
                break;
            case ForceType::Spring: {
                const BodyModel& b = model.bodies[f.body];
                const Vec3 r = s.q * f.arm;
                const Vec3 d = s.x + r - f.anchor;
                const double length = d.norm();
                if (length < 1e-12) break;  // no direction: the spring pulls nowhere
                const Vec3 dir = d / length;
                const Mat3 R = s.q.toRotationMatrix();
                const Vec3 omega = R * b.invInertia * R.transpose() * s.L;
                const Vec3 pointVelocity = b.invMass * s.P + omega.cross(r);
                const double magnitude =
                    -f.stiffness * (length - f.restLength) - f.damping * pointVelocity.dot(dir);
                const Vec3 F = magnitude * dir;
                w.force += F;
                w.torque += r.cross(F);
                break;
            }
        }
    }
}

}  // namespace tumble
