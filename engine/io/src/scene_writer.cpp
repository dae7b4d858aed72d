// Scene file writer: normalised JSON, keys in a fixed order, numbers that read back
// exactly (nlohmann writes the shortest form that round-trips).
#include <tumble/io/atomic_file.h>
#include <tumble/io/scene_file.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

#include "unit_length.h"

namespace tumble::io {

using ojson = nlohmann::ordered_json;

namespace {

ojson vec(const Vec3& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson quatJson(const Quat& orientation) {
    const Quat q = unitLength(orientation);
    return ojson::array({q.w(), q.x(), q.y(), q.z()});
}

ojson shapeJson(const ShapeDesc& s);

ojson partJson(const PartDesc& p) {
    ojson j;
    if (!p.name.empty()) j["name"] = p.name;
    j["shape"] = shapeJson(p.shape);
    j["position"] = vec(p.position);
    j["orientation"] = quatJson(p.orientation);
    if (p.density) j["density"] = *p.density;
    if (p.friction) j["friction"] = *p.friction;
    if (p.restitution) j["restitution"] = *p.restitution;
    return j;
}

ojson shapeJson(const ShapeDesc& s) {
    ojson j;
    j["type"] = toString(s.type);
    switch (s.type) {
    case ShapeType::Sphere: j["radius"] = s.radius; break;
    case ShapeType::Box: j["half_extents"] = vec(s.halfExtents); break;
    case ShapeType::Capsule:
    case ShapeType::Cylinder:
        j["radius"] = s.radius;
        j["half_height"] = s.halfHeight;
        break;
    case ShapeType::Plane:
        j["normal"] = vec(unitLength(s.normal));
        j["distance"] = s.distance;
        break;
    case ShapeType::Mesh:
        j["file"] = s.file;
        j["scale"] = vec(s.scale);
        j["collision"] = toString(s.collision);
        if (s.collision == MeshCollision::ConvexParts) {
            j["max_parts"] = s.maxParts;
            if (s.partsTolerance) j["tolerance"] = *s.partsTolerance;
        }
        break;
    case ShapeType::Compound:
        j["parts"] = ojson::array();
        for (const PartDesc& p : s.parts) j["parts"].push_back(partJson(p));
        break;
    }
    return j;
}

ojson forceJson(const ForceDesc& f) {
    ojson j;
    j["type"] = toString(f.type);
    switch (f.type) {
    case ForceType::Force:
        j["vector"] = vec(f.vector);
        if (f.point) j["point"] = vec(*f.point);
        j["frame"] = toString(f.frame);
        break;
    case ForceType::Torque:
        j["vector"] = vec(f.vector);
        j["frame"] = toString(f.frame);
        break;
    case ForceType::Spring:
        j["anchor"] = vec(f.anchor);
        if (f.point) j["point"] = vec(*f.point);
        j["stiffness"] = f.stiffness;
        j["rest_length"] = f.restLength;
        j["damping"] = f.damping;
        break;
    }
    if (f.start) j["start"] = *f.start;
    if (f.end) j["end"] = *f.end;
    return j;
}

ojson bodyJson(const BodyDesc& b) {
    ojson j;
    j["name"] = b.name;
    j["motion"] = toString(b.motion);
    j["shape"] = shapeJson(b.shape);
    if (b.mass) j["mass"] = *b.mass;
    if (b.density) j["density"] = *b.density;
    if (b.inertia) {
        const Mat3& I = *b.inertia;
        j["inertia"] = ojson::array({vec(I.row(0)), vec(I.row(1)), vec(I.row(2))});
    }
    if (b.centerOfMass) j["center_of_mass"] = vec(*b.centerOfMass);
    j["position"] = vec(b.position);
    j["orientation"] = quatJson(b.orientation);
    j["velocity"] = vec(b.velocity);
    j["angular_velocity"] = vec(b.angularVelocity);
    j["restitution"] = b.restitution;
    j["friction"] = b.friction;
    j["linear_damping"] = b.linearDamping;
    j["angular_damping"] = b.angularDamping;
    j["forces"] = ojson::array();
    for (const ForceDesc& f : b.forces) j["forces"].push_back(forceJson(f));
    if (b.collisionGroup != "default") j["collision_group"] = b.collisionGroup;
    if (b.motion == Motion::Animated || !b.keys.empty()) {
        j["interpolation"] = toString(b.interpolation);
        j["keys"] = ojson::array();
        for (const BodyKey& k : b.keys)
            j["keys"].push_back(ojson{
                {"time", k.time}, {"position", vec(k.position)}, {"orientation", quatJson(k.orientation)}});
    }
    return j;
}

ojson namePairs(const std::vector<std::array<std::string, 2>>& pairs) {
    ojson out = ojson::array();
    for (const auto& p : pairs) out.push_back(ojson::array({p[0], p[1]}));
    return out;
}

// What acts on a free axis (a hinge's or slider's, or a six-axis joint's) into `j`;
// `linear`: its force is a force (max_force), else a torque (max_torque).
void axisKeys(ojson& j, const JointDesc::Axis& x, bool linear) {
    if (x.limits) j["limits"] = ojson::array({(*x.limits)[0], (*x.limits)[1]});
    if (x.motor) {
        ojson& m = j["motor"];
        m["speed"] = x.motor->speed;
        m[linear ? "max_force" : "max_torque"] = x.motor->maxForce;
    }
    if (x.spring) {
        ojson& s = j["spring"];
        s["stiffness"] = x.spring->stiffness;
        if (x.spring->damping != 0.0) s["damping"] = x.spring->damping;
        if (x.spring->rest != 0.0) s["rest"] = x.spring->rest;
    }
    if (x.servo) {
        ojson& s = j["servo"];
        if (x.servo->keys.empty()) {
            s["target"] = x.servo->target;
        } else {
            ojson& keys = s["keys"];
            for (const JointDesc::ServoKey& k : x.servo->keys) {
                ojson key;
                key["time"] = k.time;
                key["target"] = k.target;
                keys.push_back(key);
            }
        }
        if (std::isfinite(x.servo->maxForce))
            s[linear ? "max_force" : "max_torque"] = x.servo->maxForce;
        if (x.servo->timeConstant > 0.0) {
            s["time_constant"] = x.servo->timeConstant;
        } else {
            s["stiffness"] = x.servo->stiffness;
            s["damping"] = x.servo->damping;
        }
    }
}

ojson jointJson(const JointDesc& d) {
    ojson j;
    j["name"] = d.name;
    j["type"] = toString(d.type);
    j["body_a"] = d.bodyA;
    j["anchor_a"] = vec(d.anchorA);
    if (d.axisA) j["axis_a"] = vec(*d.axisA);
    if (!d.bodyB.empty()) j["body_b"] = d.bodyB;  // absent: the world
    j["anchor_b"] = vec(d.anchorB);
    if (d.axisB) j["axis_b"] = vec(*d.axisB);  // absent: axis_a as it lies at the start
    if (d.length >= 0.0) j["length"] = d.length;  // absent: the anchors' distance at the start
    if (d.limits) j["limits"] = ojson::array({(*d.limits)[0], (*d.limits)[1]});
    if (d.swingLimit) {
        const auto [first, second] = *d.swingLimit;
        j["swing_limit"] = first == second ? ojson(first) : ojson::array({first, second});
    }
    if (d.twistLimits) j["twist_limits"] = ojson::array({(*d.twistLimits)[0], (*d.twistLimits)[1]});
    if (d.breakForce) j["break_force"] = *d.breakForce;
    if (d.collideConnected) j["collide_connected"] = true;
    axisKeys(j, {false, std::nullopt, d.motor, d.spring, d.servo}, d.type == JointType::Slider);
    if (d.type == JointType::SixAxis) {
        static const char* const names[6] = {"x", "y", "z", "rx", "ry", "rz"};
        ojson& axes = j["axes"];
        for (int i = 0; i < 6; ++i) {
            const JointDesc::Axis& x = d.axes[i];
            const bool plain = !x.limits && !x.motor && !x.spring && !x.servo;
            if (!x.free) {
                axes[names[i]] = "locked";
            } else if (plain) {
                axes[names[i]] = "free";
            } else {
                ojson& one = axes[names[i]];
                axisKeys(one, x, i < 3);
            }
        }
    }
    return j;
}

}  // namespace

std::string sceneToJson(const SceneDesc& scene) {
    ojson j;
    j["format"] = "tumble-scene";
    j["version"] = kSceneVersion;
    ojson& s = j["settings"];
    s["gravity"] = vec(scene.settings.gravity);
    s["dt"] = scene.settings.dt;
    s["duration"] = scene.settings.duration;
    // An empty integrator stays absent: the scene keeps following the engine's default.
    if (!scene.settings.integrator.empty()) s["integrator"] = scene.settings.integrator;
    s["frame_rate"] = scene.settings.frameRate;
    s["sleeping"] = scene.settings.sleeping;
    s["solver_iterations"] = scene.settings.solverIterations;
    s["energy_guard"] = scene.settings.energyGuard;
    // Written only when not the default: files of scenes that keep it stay as they were.
    if (scene.settings.impacts != ImpactTiming::Exact) s["impacts"] = toString(scene.settings.impacts);
    if (!scene.settings.collisionGroups.empty()) s["collision_groups"] = scene.settings.collisionGroups;
    if (!scene.settings.groupsApart.empty()) s["groups_apart"] = namePairs(scene.settings.groupsApart);
    j["bodies"] = ojson::array();
    for (const BodyDesc& b : scene.bodies) j["bodies"].push_back(bodyJson(b));
    // Only when there are joints: files of scenes without them stay as they were.
    if (!scene.joints.empty()) {
        j["joints"] = ojson::array();
        for (const JointDesc& d : scene.joints) j["joints"].push_back(jointJson(d));
    }
    if (!scene.noCollide.empty()) j["no_collide"] = namePairs(scene.noCollide);
    return j.dump(2) + "\n";
}

void writeSceneFile(const SceneDesc& scene, const std::filesystem::path& path) {
    writeFileAtomically(path, sceneToJson(scene));
}

}  // namespace tumble::io
