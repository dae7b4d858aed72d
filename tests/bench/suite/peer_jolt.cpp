// Jolt Physics behind the benchmark's adapter interface (issue 53): built only when a Jolt
// source tree is named (cmake -DTUMBLE_JOLT_SOURCE=DIR, or the environment variable
// TUMBLE_JOLT_SOURCE at configure time), Jolt built by its own build files
// (tests/bench/suite/CMakeLists.txt). What Jolt is given, and how, is in jolt_world.cpp.
//
// Modes:
//   defaults        Jolt's PhysicsSettings as they come (10 velocity, 2 position iterations)
//   scene-iterations  settings.solverIterations velocity iterations (Tumble's count)
//   sharp-boxes     defaults, boxes and cylinders without a convex radius (as Jolt's
//                   PerformanceTest makes its pyramid's boxes)
//   careful         defaults with continuous collision (LinearCast) on every dynamic body and
//                   the angular speed limit raised to 1e4 rad/s
// Refused: springs, moving kinematic bodies, sliders, distance, rope and six-axis joints, a
// ball joint's cone and twist limits, servos, breaking joints.
#include "engine_adapter.h"
#include "jolt_world.h"
#include "peer_common.h"

namespace tumble::bench {
namespace {

jolt::V3 jv(const Vec3& v) {
    return {v.x(), v.y(), v.z()};
}
jolt::Q4 jq(const Quat& q) {
    return {q.w(), q.x(), q.y(), q.z()};
}

// Tumble's collider as Jolt's shape description; false for what it does not take.
bool shapeOf(const collision::Shape& c, jolt::Shape* out, std::string* why) {
    switch (c.kind) {
        case collision::Kind::Sphere: out->kind = jolt::ShapeKind::Sphere; break;
        case collision::Kind::Box: out->kind = jolt::ShapeKind::Box; break;
        case collision::Kind::Capsule: out->kind = jolt::ShapeKind::Capsule; break;
        case collision::Kind::Cylinder: out->kind = jolt::ShapeKind::Cylinder; break;
        case collision::Kind::Hull:
            out->kind = jolt::ShapeKind::Hull;
            for (const Vec3& v : c.hull->vertices) out->points.push_back(jv(v));
            break;
        case collision::Kind::Mesh:
            out->kind = jolt::ShapeKind::Mesh;
            for (const Vec3& v : c.mesh->vertices) out->points.push_back(jv(v));
            for (const auto& t : c.mesh->triangles) out->triangles.push_back({int(t[0]), int(t[1]), int(t[2])});
            break;
        case collision::Kind::Compound:
            out->kind = jolt::ShapeKind::Compound;
            for (const collision::Compound::Part& p : c.compound->parts) {
                jolt::Shape::Part part;
                if (!shapeOf(p.shape, &part.shape, why)) return false;
                part.position = jv(p.pose.p);
                part.orientation = jq(Quat(p.pose.R).normalized());
                out->parts.push_back(std::move(part));
            }
            break;
        case collision::Kind::Plane: *why = "a plane inside another shape"; return false;
    }
    out->radius = c.radius;
    out->halfHeight = c.halfHeight;
    out->halfExtents = jv(c.halfExtents);
    return true;
}

class JoltAdapter final : public EngineAdapter {
public:
    std::string name() const override { return "jolt"; }
    std::vector<std::string> modes() const override {
        return {"defaults", "scene-iterations", "sharp-boxes", "careful"};
    }

    bool load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) override;
    void step() override;
    double time() const override { return time_; }
    int bodyCount() const override { return int(ps_.model.bodies.size()); }
    BodySample body(int i) const override;
    int contactCount() const override { return world_ ? world_->contactCount() : 0; }

private:
    peer::PeerScene ps_;
    std::unique_ptr<jolt::World> world_;
    std::vector<BodySample> still_;  // per body: where a static one stands
    double dt_ = 0.0, time_ = 0.0;
    bool loads_ = false;
};

bool JoltAdapter::load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) {
    world_.reset();
    still_.clear();
    if (mode != "defaults" && mode != "scene-iterations" && mode != "sharp-boxes" && mode != "careful") {
        if (why) *why = "unknown Jolt mode '" + mode + "'";
        return false;
    }
    peer::PeerCaps caps;
    caps.meshTriangles = true;
    caps.jointTypes = peer::jointBit(JointType::Ball) | peer::jointBit(JointType::Hinge) | peer::jointBit(JointType::Fixed);
    caps.jointLimits = true;
    caps.jointMotors = true;
    caps.compounds = true;
    std::string reason;
    if (!peer::prepare(scene, caps, &ps_, &reason)) {
        if (why) *why = reason;
        return false;
    }
    dt_ = dt;
    time_ = 0.0;
    loads_ = peer::hasLoads(ps_.model);
    jolt::Settings settings;
    settings.gravity = jv(scene.settings.gravity);
    settings.dt = dt;
    settings.sleeping = scene.settings.sleeping;
    settings.maxBodies = int(ps_.model.bodies.size());
    if (mode == "scene-iterations") settings.velocitySteps = std::max(1, scene.settings.solverIterations);
    settings.sharpBoxes = mode == "sharp-boxes";
    settings.careful = mode == "careful";
    world_ = std::make_unique<jolt::World>(settings);

    const Model& m = ps_.model;
    for (int i = 0; i < int(m.bodies.size()); ++i) {
        const BodyModel& b = m.bodies[size_t(i)];
        jolt::Body out;
        if (b.shape.type == ShapeType::Plane) {
            Vec3 n;
            double offset;
            peer::worldPlane(b, scene.bodies[size_t(i)].position, ps_.q[size_t(i)], &n, &offset);
            out.shape.kind = jolt::ShapeKind::Plane;
            out.shape.planeNormal = jv(n);
            out.shape.planeOffset = offset;
        } else if (!shapeOf(b.collider, &out.shape, &reason)) {
            if (why) *why = "bodies[" + std::to_string(i) + "]: " + reason;
            return false;
        }
        out.dynamic = b.motion == Motion::Dynamic;
        out.position = jv(scene.bodies[size_t(i)].position);
        out.orientation = jq(ps_.q[size_t(i)]);
        out.restitution = b.restitution;
        out.friction = b.friction;
        if (out.dynamic) {
            out.mass = b.mass;
            out.centerOfMass = jv(b.centerOfMass);
            for (int r = 0; r < 3; ++r)
                for (int k = 0; k < 3; ++k) out.inertia[size_t(3 * r + k)] = b.inertia(r, k);
            out.velocity = jv(ps_.v[size_t(i)]);
            out.angularVelocity = jv(ps_.w[size_t(i)]);
        }
        if (world_->addBody(out, &reason) < 0) {
            if (why) *why = "bodies[" + std::to_string(i) + "]: " + reason;
            world_.reset();
            return false;
        }
        BodySample s;
        s.x = ps_.com[size_t(i)];
        s.q = ps_.q[size_t(i)];
        still_.push_back(s);
    }
    for (const JointModel& j : m.joints) {
        if (j.servo || std::isfinite(j.breakForce) || j.swingLimited || j.twistLimited) {
            if (why) *why = "joints[" + std::to_string(j.index) + "] (" + j.name + "): servos, breaking and cone or twist limits are not translated to Jolt";
            world_.reset();
            return false;
        }
        jolt::Joint out;
        out.kind = j.type == JointType::Ball ? jolt::JointKind::Ball
                   : j.type == JointType::Hinge ? jolt::JointKind::Hinge
                                                : jolt::JointKind::Fixed;
        out.a = j.a;
        out.b = j.b;
        Vec3 pa, pb, axis;
        peer::jointStart(ps_, j, &pa, &pb, &axis);
        out.anchorA = jv(pa);
        out.anchorB = jv(pb);
        if (j.type == JointType::Hinge) {
            out.axis = jv(axis);
            out.normal = jv(peer::anyPerpendicular(axis));
        }
        out.limited = j.limited;
        out.lower = j.lower;
        out.upper = j.upper;
        out.motor = j.motor;
        out.motorSpeed = j.motorSpeed;
        out.motorMax = j.motorMax;
        out.collide = j.collideConnected;
        if (!world_->addJoint(out, &reason)) {
            if (why) *why = "joints[" + std::to_string(j.index) + "] (" + j.name + "): " + reason;
            world_.reset();
            return false;
        }
    }
    world_->ready();
    return true;
}

void JoltAdapter::step() {
    if (loads_) {
        for (int i : ps_.model.dynamicBodies) {
            const BodySample s = body(i);
            Vec3 F, T;
            peer::appliedLoad(ps_.model, i, time_, s.q, s.v, s.w, &F, &T);
            if (!F.isZero(0.0) || !T.isZero(0.0)) world_->push(i, jv(F), jv(T));
        }
    }
    world_->step();
    time_ += dt_;
}

BodySample JoltAdapter::body(int i) const {
    if (ps_.model.bodies[size_t(i)].motion != Motion::Dynamic) return still_[size_t(i)];
    jolt::V3 x, v, w;
    jolt::Q4 q;
    world_->sample(i, &x, &q, &v, &w);
    BodySample s;
    s.x = Vec3(x.x, x.y, x.z);
    s.q = Quat(q.w, q.x, q.y, q.z).normalized();
    s.v = Vec3(v.x, v.y, v.z);
    s.w = Vec3(w.x, w.y, w.z);
    return s;
}

}  // namespace

std::unique_ptr<EngineAdapter> makeJoltAdapter() {
    return std::make_unique<JoltAdapter>();
}

}  // namespace tumble::bench
