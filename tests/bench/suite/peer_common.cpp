#include "peer_common.h"

#include <tumble/errors.h>

#include <cmath>
#include <exception>

namespace tumble::bench::peer {

bool standsStill(const BodyModel& b) {
    return b.standsStill();
}

bool prepare(const SceneDesc& scene, const PeerCaps& caps, PeerScene* out, std::string* why) {
    auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    out->scene = scene;
    try {
        out->model = compile(scene);
    } catch (const std::exception& e) {
        return fail(std::string("the scene does not compile: ") + e.what());
    }
    const Model& m = out->model;
    for (const ForceTerm& f : m.forces) {
        if (f.type == ForceType::Spring)
            return fail("bodies[" + std::to_string(f.body) + "] (" + m.bodies[f.body].name +
                        "): springs are not translated to the peers");
    }
    for (const JointModel& j : m.joints) {
        const std::string who = "joints[" + std::to_string(j.index) + "] (" + j.name + "): ";
        if (!(caps.jointTypes & jointBit(j.type)))
            return fail(who + "a " + toString(j.type) + " joint is not translated to this peer");
        if (j.limited && !caps.jointLimits) return fail(who + "joint limits are not translated to this peer");
        // (Bullet's and ODE's hinge stops take angles within [-pi, pi] only.)
        if (j.limited && j.type == JointType::Hinge && (j.lower < -M_PI || j.upper > M_PI))
            return fail(who + "hinge limits past [-pi, pi] are not translated to the peers");
        if (j.motor && !caps.jointMotors) return fail(who + "joint motors are not translated to this peer");
        if (std::isfinite(j.breakForce) && !caps.jointBreaking)
            return fail(who + "breaking joints are not translated to this peer");
        // (A peer run without them would be another scene.)
        if (j.spring) return fail(who + "joint springs are not translated to the peers");
        if (j.servo && !(caps.hingeServos && j.type == JointType::Hinge && j.servoTimeConstant > 0.0))
            return fail(who + "this joint's servo is not translated to this peer");
        if ((j.swingLimited || j.twistLimited) && !caps.ballLimits)
            return fail(who + "a ball joint's cone and twist limits are not translated to this peer");
    }
    const int n = int(m.bodies.size());
    out->com.resize(n);
    out->q.resize(n);
    out->v.resize(n);
    out->w.resize(n);
    for (int i = 0; i < n; ++i) {
        const BodyModel& b = m.bodies[i];
        const BodyDesc& d = scene.bodies[i];
        const std::string who = "bodies[" + std::to_string(i) + "] (" + b.name + "): ";
        const bool moves = !b.standsStill();
        if (b.motion == Motion::Kinematic && moves && !caps.movingKinematic)
            return fail(who + "a moving kinematic body is not translated to this peer");
        if (b.shape.type == ShapeType::Plane && moves) return fail(who + "a plane must stand still");
        if (b.shape.type == ShapeType::Compound && !caps.compounds)
            return fail(who + "compound bodies are not translated to this peer yet");
        if (b.shape.type == ShapeType::Mesh && b.shape.collision == MeshCollision::Triangles) {
            if (moves) return fail(who + "a triangle mesh must stand still in the peers");
            if (!caps.meshTriangles)
                return fail(who + "this peer collides with a mesh's convex hull only, not its triangles");
        }
        if (b.shape.type == ShapeType::Mesh && b.shape.collision == MeshCollision::ConvexHull &&
            !b.collider.hull)
            return fail(who + "the mesh has no convex hull");
        if (b.path)
            return fail(who +
                        "an animated body (keyed path) is Tumble's own; the peers move kinematic bodies at "
                        "constant velocity");
        out->q[i] = d.orientation.normalized();
        out->com[i] = d.position + out->q[i] * b.centerOfMass;
        if (b.motion == Motion::Dynamic) {
            out->v[i] = d.velocity;
            out->w[i] = d.angularVelocity;
        } else if (b.motion == Motion::Kinematic) {
            out->v[i] = b.kinematicVelocity;
            out->w[i] = b.kinematicAngularVelocity;
        } else {
            out->v[i] = Vec3::Zero();
            out->w[i] = Vec3::Zero();
        }
    }
    return true;
}

void jointStart(const PeerScene& ps, const JointModel& j, Vec3* anchorA, Vec3* anchorB, Vec3* axis) {
    *anchorA = ps.com[j.a] + ps.q[j.a] * j.anchorA;
    *anchorB = j.b < 0 ? j.anchorB : Vec3(ps.com[j.b] + ps.q[j.b] * j.anchorB);
    const bool axial = j.type == JointType::Hinge || j.type == JointType::Slider;
    *axis = axial ? Vec3(ps.q[j.a] * j.axisA) : Vec3::Zero();
}

double servoSpeed(const JointModel& j, double c, double v, double t, double h) {
    const double tau = j.servoTimeConstant, x = c - j.servoTargetAt(t + h);
    return (v - (v + x / tau) * h / tau) * std::exp(-h / tau);
}

Vec3 anyPerpendicular(const Vec3& axis) {
    const Vec3 other = std::abs(axis.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    return axis.cross(other).normalized();
}

void appliedLoad(const Model& model, int i, double t, const Quat& q, const Vec3& v, const Vec3& w,
                 Vec3* force, Vec3* torque) {
    const BodyModel& b = model.bodies[i];
    Vec3 F = Vec3::Zero(), T = Vec3::Zero();
    if (b.motion != Motion::Dynamic) {
        *force = F;
        *torque = T;
        return;
    }
    const Mat3 R = q.toRotationMatrix();
    for (const ForceTerm& f : model.forces) {
        if (f.body != i || !f.activeAt(t)) continue;
        const Vec3 vec = f.frame == Frame::Body ? Vec3(R * f.vector) : f.vector;
        if (f.type == ForceType::Force) {
            F += vec;
            T += (R * f.arm).cross(vec);
        } else if (f.type == ForceType::Torque) {
            T += vec;
        }
    }
    // Tumble damps momentum: F -= c P, tau -= c L, with L = R I_body R^T w.
    if (b.linearDamping > 0.0) F -= b.linearDamping * b.mass * v;
    if (b.angularDamping > 0.0) T -= b.angularDamping * (R * b.inertia * R.transpose() * w);
    *force = F;
    *torque = T;
}

bool hasLoads(const Model& model) {
    for (int i : model.dynamicBodies) {
        const BodyModel& b = model.bodies[i];
        if (b.linearDamping > 0.0 || b.angularDamping > 0.0) return true;
    }
    return !model.forces.empty();
}

void worldPlane(const BodyModel& b, const Vec3& position, const Quat& q, Vec3* n, double* d) {
    const Vec3 nb = b.collider.normal.normalized();
    *n = q * nb;
    *d = b.collider.distance + n->dot(position);
}

Quat zToY() {
    // A quarter turn about x by -90 degrees: (0, 0, 1) -> (0, 1, 0).
    const double h = std::sqrt(0.5);
    return Quat(h, -h, 0.0, 0.0);
}

}  // namespace tumble::bench::peer
