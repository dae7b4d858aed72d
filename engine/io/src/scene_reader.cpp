// Scene file reader. Syntax, types, missing and unknown keys are checked here, with the
// path of the field; the values themselves are checked by tumble::validate, whose
// SceneError carries the same kind of path.
#include <tumble/errors.h>
#include <tumble/io/convex_parts_cache.h>
#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>
#include <tumble/model.h>

#include "unit_length.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>
#include <vector>

namespace tumble::io {

using nlohmann::json;

InputError::InputError(std::string file, std::string field, std::string message)
    : std::runtime_error(file + ": " + (field.empty() ? "" : field + ": ") + message),
      file_(std::move(file)),
      field_(std::move(field)),
      message_(std::move(message)) {}

namespace {

class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& path, const std::string& message) const {
        throw InputError(file_, path, message);
    }

    const json& object(const json& j, const std::string& path) const {
        if (!j.is_object()) fail(path, "must be an object");
        return j;
    }

    // Refuses keys outside `allowed`, so a misspelt key is never silently ignored.
    void onlyKeys(const json& j, const std::string& path, std::initializer_list<const char*> allowed) const {
        for (const auto& [key, value] : j.items()) {
            bool ok = false;
            for (const char* a : allowed) ok = ok || key == a;
            if (!ok) fail(join(path, key), "unknown key");
        }
    }

    const json& require(const json& j, const std::string& path, const char* key) const {
        auto it = j.find(key);
        if (it == j.end()) fail(join(path, key), "is missing");
        return *it;
    }

    double number(const json& j, const std::string& path) const {
        if (!j.is_number()) fail(path, "must be a number");
        const double v = j.get<double>();
        if (!std::isfinite(v)) fail(path, "must be a finite number");
        return v;
    }

    std::string string(const json& j, const std::string& path) const {
        if (!j.is_string()) fail(path, "must be a string");
        return j.get<std::string>();
    }

    bool boolean(const json& j, const std::string& path) const {
        if (!j.is_boolean()) fail(path, "must be true or false");
        return j.get<bool>();
    }

    int integer(const json& j, const std::string& path) const {
        if (!j.is_number_integer()) fail(path, "must be an integer");
        const auto v = j.get<long long>();
        if (v < -1000000000LL || v > 1000000000LL) fail(path, "is out of range");
        return static_cast<int>(v);
    }

    template <int N>
    Eigen::Matrix<double, N, 1> vector(const json& j, const std::string& path) const {
        if (!j.is_array() || j.size() != N)
            fail(path, "must be an array of " + std::to_string(N) + " numbers");
        Eigen::Matrix<double, N, 1> v;
        for (int k = 0; k < N; ++k) v[k] = number(j[k], path + "[" + std::to_string(k) + "]");
        return v;
    }

    Mat3 matrix(const json& j, const std::string& path) const {
        if (!j.is_array() || j.size() != 3) fail(path, "must be 3 rows of 3 numbers");
        Mat3 m;
        for (int r = 0; r < 3; ++r)
            m.row(r) = vector<3>(j[r], path + "[" + std::to_string(r) + "]").transpose();
        return m;
    }

    // An array of strings.
    std::vector<std::string> strings(const json& j, const std::string& path) const {
        if (!j.is_array()) fail(path, "must be an array of names");
        std::vector<std::string> out;
        for (size_t k = 0; k < j.size(); ++k)
            out.push_back(string(j[k], path + "[" + std::to_string(k) + "]"));
        return out;
    }

    // An array of pairs of names: [["a", "b"], ...].
    std::vector<std::array<std::string, 2>> namePairs(const json& j, const std::string& path) const {
        if (!j.is_array()) fail(path, "must be an array of pairs of names, [[\"a\", \"b\"], ...]");
        std::vector<std::array<std::string, 2>> out;
        for (size_t k = 0; k < j.size(); ++k) {
            const std::string at = path + "[" + std::to_string(k) + "]";
            if (!j[k].is_array() || j[k].size() != 2) fail(at, "must be a pair of names, [\"a\", \"b\"]");
            out.push_back({string(j[k][0], at + "[0]"), string(j[k][1], at + "[1]")});
        }
        return out;
    }

    // Reads `key` into `out` when present.
    template <typename F>
    void optional(const json& j, const std::string& path, const char* key, F&& read) const {
        auto it = j.find(key);
        if (it != j.end()) read(*it, join(path, key));
    }

    static std::string join(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }

    const std::string& file() const { return file_; }

private:
    std::string file_;
};

template <typename E>
E enumValue(const Reader& r, const json& j, const std::string& path, std::initializer_list<E> values) {
    const std::string s = r.string(j, path);
    std::string names;
    for (E e : values) {
        if (s == toString(e)) return e;
        names += names.empty() ? "" : ", ";
        names += toString(e);
    }
    r.fail(path, "'" + s + "' is not one of " + names);
}

Settings readSettings(const Reader& r, const json& j) {
    const std::string p = "settings";
    r.object(j, p);
    r.onlyKeys(j, p,
               {"gravity", "dt", "duration", "integrator", "frame_rate", "sleeping", "solver_iterations",
                "energy_guard", "impacts", "collision_groups", "groups_apart"});
    Settings s;
    r.optional(j, p, "gravity", [&](const json& v, const std::string& f) { s.gravity = r.vector<3>(v, f); });
    r.optional(j, p, "dt", [&](const json& v, const std::string& f) { s.dt = r.number(v, f); });
    r.optional(j, p, "duration", [&](const json& v, const std::string& f) { s.duration = r.number(v, f); });
    r.optional(j, p, "integrator",
               [&](const json& v, const std::string& f) { s.integrator = r.string(v, f); });
    r.optional(j, p, "frame_rate",
               [&](const json& v, const std::string& f) { s.frameRate = r.number(v, f); });
    r.optional(j, p, "sleeping", [&](const json& v, const std::string& f) { s.sleeping = r.boolean(v, f); });
    r.optional(j, p, "solver_iterations",
               [&](const json& v, const std::string& f) { s.solverIterations = r.integer(v, f); });
    r.optional(j, p, "energy_guard",
               [&](const json& v, const std::string& f) { s.energyGuard = r.boolean(v, f); });
    r.optional(j, p, "impacts", [&](const json& v, const std::string& f) {
        s.impacts = enumValue(r, v, f, {ImpactTiming::Exact, ImpactTiming::EndOfStep});
    });
    r.optional(j, p, "collision_groups",
               [&](const json& v, const std::string& f) { s.collisionGroups = r.strings(v, f); });
    r.optional(j, p, "groups_apart",
               [&](const json& v, const std::string& f) { s.groupsApart = r.namePairs(v, f); });
    return s;
}

ShapeDesc readShape(const Reader& r, const json& j, const std::string& p);

Quat readOrientation(const Reader& r, const json& v, const std::string& f) {
    const Eigen::Vector4d q = r.vector<4>(v, f);
    if (!(q.norm() > 1e-12)) r.fail(f, "must not be the zero quaternion");
    return unitLength(Quat(q[0], q[1], q[2], q[3]));
}

// A part of a compound (docs/scene-format.md "Compound bodies").
PartDesc readPart(const Reader& r, const json& j, const std::string& p) {
    r.object(j, p);
    r.onlyKeys(j, p, {"name", "shape", "position", "orientation", "density", "friction", "restitution"});
    PartDesc d;
    r.optional(j, p, "name", [&](const json& v, const std::string& f) { d.name = r.string(v, f); });
    const json& shape = r.require(j, p, "shape");
    // Refused before it is read: a file of compounds nested a million deep would take the
    // reader's stack down with it.
    if (shape.is_object() && shape.contains("type") && shape["type"] == "compound")
        r.fail(
            p + ".shape.type",
            "a part cannot be a compound (nested compounds are not supported: list its parts in this one)");
    d.shape = readShape(r, shape, p + ".shape");
    r.optional(j, p, "position",
               [&](const json& v, const std::string& f) { d.position = r.vector<3>(v, f); });
    r.optional(j, p, "orientation",
               [&](const json& v, const std::string& f) { d.orientation = readOrientation(r, v, f); });
    r.optional(j, p, "density", [&](const json& v, const std::string& f) { d.density = r.number(v, f); });
    r.optional(j, p, "friction", [&](const json& v, const std::string& f) { d.friction = r.number(v, f); });
    r.optional(j, p, "restitution",
               [&](const json& v, const std::string& f) { d.restitution = r.number(v, f); });
    return d;
}

ShapeDesc readShape(const Reader& r, const json& j, const std::string& p) {
    r.object(j, p);
    ShapeDesc s;
    s.type = enumValue(r, r.require(j, p, "type"), p + ".type",
                       {ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule, ShapeType::Cylinder,
                        ShapeType::Plane, ShapeType::Mesh, ShapeType::Compound});
    auto num = [&](const char* key) { return r.number(r.require(j, p, key), p + "." + key); };
    switch (s.type) {
        case ShapeType::Sphere:
            r.onlyKeys(j, p, {"type", "radius"});
            s.radius = num("radius");
            break;
        case ShapeType::Box:
            r.onlyKeys(j, p, {"type", "half_extents"});
            s.halfExtents = r.vector<3>(r.require(j, p, "half_extents"), p + ".half_extents");
            break;
        case ShapeType::Capsule:
        case ShapeType::Cylinder:
            r.onlyKeys(j, p, {"type", "radius", "half_height"});
            s.radius = num("radius");
            s.halfHeight = num("half_height");
            break;
        case ShapeType::Plane:
            r.onlyKeys(j, p, {"type", "normal", "distance"});
            s.normal = r.vector<3>(r.require(j, p, "normal"), p + ".normal");
            r.optional(j, p, "distance",
                       [&](const json& v, const std::string& f) { s.distance = r.number(v, f); });
            if (s.normal.norm() > 0.0 && s.normal.allFinite()) s.normal = unitLength(s.normal);
            break;
        case ShapeType::Mesh:
            r.onlyKeys(j, p, {"type", "file", "scale", "collision", "max_parts", "tolerance"});
            s.file = r.string(r.require(j, p, "file"), p + ".file");
            r.optional(j, p, "scale",
                       [&](const json& v, const std::string& f) { s.scale = r.vector<3>(v, f); });
            r.optional(j, p, "collision", [&](const json& v, const std::string& f) {
                s.collision = enumValue(
                    r, v, f,
                    {MeshCollision::ConvexHull, MeshCollision::Triangles, MeshCollision::ConvexParts});
            });
            // The split's options, only with the split.
            for (const char* key : {"max_parts", "tolerance"})
                if (j.contains(key) && s.collision != MeshCollision::ConvexParts)
                    r.fail(p + "." + key, "is for \"collision\": \"convex-parts\" only");
            r.optional(j, p, "max_parts",
                       [&](const json& v, const std::string& f) { s.maxParts = r.integer(v, f); });
            r.optional(j, p, "tolerance",
                       [&](const json& v, const std::string& f) { s.partsTolerance = r.number(v, f); });
            break;
        case ShapeType::Compound: {
            r.onlyKeys(j, p, {"type", "parts"});
            const std::string f = p + ".parts";
            const json& parts = r.require(j, p, "parts");
            if (!parts.is_array()) r.fail(f, "must be an array of parts");
            for (size_t k = 0; k < parts.size(); ++k)
                s.parts.push_back(readPart(r, parts[k], f + "[" + std::to_string(k) + "]"));
            break;
        }
    }
    return s;
}

ForceDesc readForce(const Reader& r, const json& j, const std::string& p) {
    r.object(j, p);
    ForceDesc f;
    f.type = enumValue(r, r.require(j, p, "type"), p + ".type",
                       {ForceType::Force, ForceType::Torque, ForceType::Spring});
    auto frame = [&](const json& v, const std::string& path) {
        f.frame = enumValue(r, v, path, {Frame::World, Frame::Body});
    };
    auto point = [&](const json& v, const std::string& path) { f.point = r.vector<3>(v, path); };
    auto num = [&](double& out) {
        return [&](const json& v, const std::string& path) { out = r.number(v, path); };
    };
    switch (f.type) {
        case ForceType::Force:
            r.onlyKeys(j, p, {"type", "vector", "point", "frame", "start", "end"});
            f.vector = r.vector<3>(r.require(j, p, "vector"), p + ".vector");
            r.optional(j, p, "point", point);
            r.optional(j, p, "frame", frame);
            break;
        case ForceType::Torque:
            r.onlyKeys(j, p, {"type", "vector", "frame", "start", "end"});
            f.vector = r.vector<3>(r.require(j, p, "vector"), p + ".vector");
            r.optional(j, p, "frame", frame);
            break;
        case ForceType::Spring:
            r.onlyKeys(j, p,
                       {"type", "anchor", "point", "stiffness", "rest_length", "damping", "start", "end"});
            f.anchor = r.vector<3>(r.require(j, p, "anchor"), p + ".anchor");
            r.optional(j, p, "point", point);
            f.stiffness = r.number(r.require(j, p, "stiffness"), p + ".stiffness");
            r.optional(j, p, "rest_length", num(f.restLength));
            r.optional(j, p, "damping", num(f.damping));
            break;
    }
    r.optional(j, p, "start", [&](const json& v, const std::string& path) { f.start = r.number(v, path); });
    r.optional(j, p, "end", [&](const json& v, const std::string& path) { f.end = r.number(v, path); });
    return f;
}

// One key of an animated body (docs/scene-format.md "Animated bodies"): its order and
// values are checked with the rest of the scene (validate).
BodyKey readKey(const Reader& r, const json& j, const std::string& p) {
    r.object(j, p);
    r.onlyKeys(j, p, {"time", "position", "orientation"});
    BodyKey k;
    k.time = r.number(r.require(j, p, "time"), p + ".time");
    k.position = r.vector<3>(r.require(j, p, "position"), p + ".position");
    r.optional(j, p, "orientation",
               [&](const json& v, const std::string& f) { k.orientation = readOrientation(r, v, f); });
    return k;
}

BodyDesc readBody(const Reader& r, const json& j, const std::string& p) {
    r.object(j, p);
    r.onlyKeys(j, p,
               {"name", "motion", "shape", "mass", "density", "inertia", "center_of_mass", "position",
                "orientation", "velocity", "angular_velocity", "restitution", "friction", "linear_damping",
                "angular_damping", "forces", "collision_group", "keys", "interpolation"});
    BodyDesc b;
    b.name = r.string(r.require(j, p, "name"), p + ".name");
    r.optional(j, p, "motion", [&](const json& v, const std::string& f) {
        b.motion = enumValue(r, v, f, {Motion::Dynamic, Motion::Static, Motion::Kinematic, Motion::Animated});
    });
    b.shape = readShape(r, r.require(j, p, "shape"), p + ".shape");
    r.optional(j, p, "collision_group",
               [&](const json& v, const std::string& f) { b.collisionGroup = r.string(v, f); });
    auto vec = [&](Vec3& out) {
        return [&](const json& v, const std::string& f) { out = r.vector<3>(v, f); };
    };
    auto num = [&](double& out) {
        return [&](const json& v, const std::string& f) { out = r.number(v, f); };
    };
    r.optional(j, p, "mass", [&](const json& v, const std::string& f) { b.mass = r.number(v, f); });
    r.optional(j, p, "density", [&](const json& v, const std::string& f) { b.density = r.number(v, f); });
    r.optional(j, p, "inertia", [&](const json& v, const std::string& f) { b.inertia = r.matrix(v, f); });
    r.optional(j, p, "center_of_mass",
               [&](const json& v, const std::string& f) { b.centerOfMass = r.vector<3>(v, f); });
    r.optional(j, p, "position", vec(b.position));
    r.optional(j, p, "orientation",
               [&](const json& v, const std::string& f) { b.orientation = readOrientation(r, v, f); });
    r.optional(j, p, "velocity", vec(b.velocity));
    r.optional(j, p, "angular_velocity", vec(b.angularVelocity));
    r.optional(j, p, "restitution", num(b.restitution));
    r.optional(j, p, "friction", num(b.friction));
    r.optional(j, p, "linear_damping", num(b.linearDamping));
    r.optional(j, p, "angular_damping", num(b.angularDamping));
    r.optional(j, p, "forces", [&](const json& v, const std::string& f) {
        if (!v.is_array()) r.fail(f, "must be an array");
        for (size_t k = 0; k < v.size(); ++k)
            b.forces.push_back(readForce(r, v[k], f + "[" + std::to_string(k) + "]"));
    });
    r.optional(j, p, "keys", [&](const json& v, const std::string& f) {
        if (!v.is_array()) r.fail(f, "must be an array of keys ({\"time\", \"position\", \"orientation\"})");
        for (size_t k = 0; k < v.size(); ++k)
            b.keys.push_back(readKey(r, v[k], f + "[" + std::to_string(k) + "]"));
    });
    r.optional(j, p, "interpolation", [&](const json& v, const std::string& f) {
        b.interpolation = enumValue(r, v, f, {KeyInterpolation::Linear, KeyInterpolation::Smooth});
    });
    return b;
}

// What acts on a free axis: the `limits`, `motor`, `spring` and `servo` of a hinge's or
// slider's object, or of a six-axis joint's axis (`what`: "hinge", "slider", "linear axis",
// "angular axis"; `axial`: it has a free axis; `linear`: its force is a force, else a torque).
void readAxisKeys(const Reader& r, const json& j, const std::string& p, const char* what, bool axial, bool linear,
                  JointDesc::Axis& x) {
    r.optional(j, p, "limits", [&](const json& v, const std::string& f) {
        const Eigen::Vector2d l = r.vector<2>(v, f);
        x.limits = std::array<double, 2>{l[0], l[1]};
    });
    r.optional(j, p, "motor", [&](const json& v, const std::string& f) {
        r.object(v, f);
        r.onlyKeys(v, f, {"speed", "max_torque", "max_force"});
        JointDesc::Motor m;
        m.speed = r.number(r.require(v, f, "speed"), f + ".speed");
        // A hinge's motor turns (a torque), a slider's pushes (a force).
        const char* key = linear ? "max_force" : "max_torque";
        const char* wrong = linear ? "max_torque" : "max_force";
        if (axial) {
            if (v.contains(wrong))
                r.fail(Reader::join(f, wrong), std::string("a ") + what + "'s motor gives a " +
                                                   (linear ? "force: max_force" : "torque: max_torque"));
        } else if (!v.contains(key)) {
            key = wrong;
        }
        m.maxForce = r.number(r.require(v, f, key), Reader::join(f, key));
        x.motor = m;
    });
    r.optional(j, p, "spring", [&](const json& v, const std::string& f) {
        r.object(v, f);
        r.onlyKeys(v, f, {"stiffness", "damping", "rest"});
        JointDesc::Spring s;
        s.stiffness = r.number(r.require(v, f, "stiffness"), f + ".stiffness");
        r.optional(v, f, "damping", [&](const json& x, const std::string& g) { s.damping = r.number(x, g); });
        r.optional(v, f, "rest", [&](const json& x, const std::string& g) { s.rest = r.number(x, g); });
        x.spring = s;
    });
    r.optional(j, p, "servo", [&](const json& v, const std::string& f) {
        r.object(v, f);
        const char* most = linear ? "max_force" : "max_torque";
        r.onlyKeys(v, f, {"target", "keys", most, "stiffness", "damping", "time_constant"});
        JointDesc::Servo s;
        r.optional(v, f, "keys", [&](const json& keys, const std::string& g) {
            if (!keys.is_array() || keys.empty()) r.fail(g, "must be an array of at least one {time, target}");
            for (size_t k = 0; k < keys.size(); ++k) {
                const std::string at = g + "[" + std::to_string(k) + "]";
                r.object(keys[k], at);
                r.onlyKeys(keys[k], at, {"time", "target"});
                s.keys.push_back({r.number(r.require(keys[k], at, "time"), at + ".time"),
                                  r.number(r.require(keys[k], at, "target"), at + ".target")});
            }
        });
        if (s.keys.empty())
            s.target = r.number(r.require(v, f, "target"), f + ".target");
        else if (v.contains("target"))
            r.fail(Reader::join(f, "target"), "give target or keys, not both");
        else
            s.target = s.keys.front().target;
        r.optional(v, f, most, [&](const json& x, const std::string& g) { s.maxForce = r.number(x, g); });
        r.optional(v, f, "stiffness", [&](const json& x, const std::string& g) { s.stiffness = r.number(x, g); });
        r.optional(v, f, "damping", [&](const json& x, const std::string& g) { s.damping = r.number(x, g); });
        r.optional(v, f, "time_constant",
                   [&](const json& x, const std::string& g) { s.timeConstant = r.number(x, g); });
        x.servo = s;
    });
}

// A joint of the top-level `joints` (docs/scene-format.md "Joints"). The bodies it names
// and what its type allows are checked with the rest of the scene (validate).
JointDesc readJoint(const Reader& r, const json& j, const std::string& p) {
    r.object(j, p);
    r.onlyKeys(j, p,
               {"name", "type", "body_a", "anchor_a", "axis_a", "body_b", "anchor_b", "axis_b", "length",
                "limits", "motor", "spring", "servo", "swing_limit", "twist_limits", "axes", "break_force",
                "collide_connected"});
    JointDesc d;
    d.name = r.string(r.require(j, p, "name"), p + ".name");
    d.type = enumValue(r, r.require(j, p, "type"), p + ".type",
                       {JointType::Ball, JointType::Distance, JointType::Rope, JointType::Hinge,
                        JointType::Slider, JointType::Fixed, JointType::SixAxis});
    d.bodyA = r.string(r.require(j, p, "body_a"), p + ".body_a");
    r.optional(j, p, "anchor_a", [&](const json& v, const std::string& f) { d.anchorA = r.vector<3>(v, f); });
    r.optional(j, p, "body_b", [&](const json& v, const std::string& f) {
        d.bodyB = r.string(v, f);
        if (d.bodyB.empty()) r.fail(f, "must name a body (leave it out to join body_a to the world)");
    });
    r.optional(j, p, "anchor_b", [&](const json& v, const std::string& f) { d.anchorB = r.vector<3>(v, f); });
    r.optional(j, p, "axis_a", [&](const json& v, const std::string& f) { d.axisA = r.vector<3>(v, f); });
    r.optional(j, p, "axis_b", [&](const json& v, const std::string& f) { d.axisB = r.vector<3>(v, f); });
    r.optional(j, p, "swing_limit", [&](const json& v, const std::string& f) {
        if (v.is_number()) {  // a circular cone
            const double angle = r.number(v, f);
            d.swingLimit = std::array<double, 2>{angle, angle};
        } else {
            if (!v.is_array() || v.size() != 2) r.fail(f, "must be an angle or an array of 2 angles");
            const Eigen::Vector2d l = r.vector<2>(v, f);
            d.swingLimit = std::array<double, 2>{l[0], l[1]};
        }
    });
    r.optional(j, p, "twist_limits", [&](const json& v, const std::string& f) {
        const Eigen::Vector2d l = r.vector<2>(v, f);
        d.twistLimits = std::array<double, 2>{l[0], l[1]};
    });
    {
        JointDesc::Axis x;
        const bool axial = d.type == JointType::Hinge || d.type == JointType::Slider;
        readAxisKeys(r, j, p, toString(d.type), axial, d.type == JointType::Slider, x);
        d.limits = x.limits;
        d.motor = x.motor;
        d.spring = x.spring;
        d.servo = x.servo;
    }
    r.optional(j, p, "axes", [&](const json& v, const std::string& f) {
        static const char* const names[6] = {"x", "y", "z", "rx", "ry", "rz"};
        r.object(v, f);
        r.onlyKeys(v, f, {"x", "y", "z", "rx", "ry", "rz"});
        for (int i = 0; i < 6; ++i)
            r.optional(v, f, names[i], [&](const json& x, const std::string& g) {
                JointDesc::Axis& axis = d.axes[i];
                if (x.is_string()) {
                    const std::string mode = x.get<std::string>();
                    if (mode != "locked" && mode != "free")
                        r.fail(g, "must be \"locked\", \"free\" or an object of limits, motor, spring and servo");
                    axis.free = mode == "free";
                    return;
                }
                if (!x.is_object())
                    r.fail(g, "must be \"locked\", \"free\" or an object of limits, motor, spring and servo");
                r.onlyKeys(x, g, {"limits", "motor", "spring", "servo"});
                axis.free = true;
                readAxisKeys(r, x, g, i < 3 ? "linear axis" : "angular axis", true, i < 3, axis);
            });
    });
    r.optional(j, p, "break_force", [&](const json& v, const std::string& f) { d.breakForce = r.number(v, f); });
    r.optional(j, p, "collide_connected",
               [&](const json& v, const std::string& f) { d.collideConnected = r.boolean(v, f); });
    r.optional(j, p, "length", [&](const json& v, const std::string& f) {
        d.length = r.number(v, f);
        if (!(d.length >= 0.0))
            r.fail(f, "must be at least 0 (leave it out for the anchors' distance at the start)");
    });
    return d;
}

// What the reader keeps track of while the JSON is parsed: the path being read and the
// keys of each open object.
struct Level {
    bool array = false;
    long index = -1;             // array: the element being read
    std::string key;             // object: the key being read
    std::set<std::string> keys;  // object: the keys seen so far
};

// nlohmann's DOM builder, told of every event first. (The library's parse callback would do
// the same, but its builder then looks through the whole enclosing array for a discarded
// element at the end of each object: quadratic, 34 s to load 200 000 bodies.)
class TrackingSax : public nlohmann::detail::json_sax_dom_parser<json> {
public:
    using Base = nlohmann::detail::json_sax_dom_parser<json>;
    TrackingSax(json& root, std::vector<Level>& levels, std::string& duplicate)
        : Base(root), levels_(levels), duplicate_(duplicate) {}

    bool null() { return element(), Base::null(); }
    bool boolean(bool v) { return element(), Base::boolean(v); }
    bool number_integer(json::number_integer_t v) { return element(), Base::number_integer(v); }
    bool number_unsigned(json::number_unsigned_t v) { return element(), Base::number_unsigned(v); }
    bool number_float(json::number_float_t v, const json::string_t& s) { return element(), Base::number_float(v, s); }
    bool string(json::string_t& v) { return element(), Base::string(v); }
    bool binary(json::binary_t& v) { return element(), Base::binary(v); }
    bool start_object(std::size_t n) {
        element();
        levels_.emplace_back();
        return Base::start_object(n);
    }
    bool start_array(std::size_t n) {
        element();
        levels_.emplace_back().array = true;
        return Base::start_array(n);
    }
    bool end_object() { return levels_.pop_back(), Base::end_object(); }
    bool end_array() { return levels_.pop_back(), Base::end_array(); }
    bool key(json::string_t& k) {
        Level& l = levels_.back();
        l.key = k;
        if (!l.keys.insert(l.key).second && duplicate_.empty()) duplicate_ = l.key;
        return Base::key(k);
    }

private:
    // A new element of the innermost array begins.
    void element() {
        if (!levels_.empty() && levels_.back().array) ++levels_.back().index;
    }
    std::vector<Level>& levels_;
    std::string& duplicate_;
};

// Parses JSON, refusing duplicate keys (the library would keep the last one silently), and
// naming the field of a number too large for a double (1e999), which the library refuses
// without saying where.
json parseJson(std::string_view text, const Reader& r) {
    std::vector<Level> levels;
    std::string duplicate;
    // The path of the value the parser was reading when it stopped: its element of the
    // innermost array has not been counted yet.
    auto where = [&] {
        std::string path;
        for (size_t i = 0; i < levels.size(); ++i) {
            const Level& l = levels[i];
            if (l.array)
                path += "[" + std::to_string(l.index + (i + 1 == levels.size() ? 1 : 0)) + "]";
            else
                path = Reader::join(path, l.key);
        }
        return path.empty() ? std::string("(top level)") : path;
    };
    json j;
    try {
        TrackingSax sax(j, levels, duplicate);
        json::sax_parse(text.begin(), text.end(), &sax);
    } catch (const json::out_of_range& e) {
        if (e.id == 406) r.fail(where(), "must be a finite number");  // "number overflow parsing '1e999'"
        r.fail("", std::string("malformed JSON: ") + e.what());
    } catch (const json::exception& e) {
        std::string what = e.what();
        const auto close = what.find("] ");
        if (close != std::string::npos) what = what.substr(close + 2);
        r.fail("", "malformed JSON: " + what);
    }
    if (!duplicate.empty())
        r.fail("", "malformed JSON: the key '" + duplicate + "' appears twice in one object");
    return j;
}

}  // namespace

SceneDesc parseScene(std::string_view text, const std::string& fileName,
                     const std::optional<std::filesystem::path>& baseDir) {
    const Reader r(fileName);
    const json j = parseJson(text, r);
    r.object(j, "(top level)");
    r.onlyKeys(j, "", {"format", "version", "settings", "bodies", "joints", "no_collide"});
    if (r.string(r.require(j, "", "format"), "format") != "tumble-scene") {
        r.fail("format", "must be \"tumble-scene\"");
    }
    const json& version = r.require(j, "", "version");
    if (!version.is_number_integer()) r.fail("version", "must be an integer");
    if (version.get<long long>() != kSceneVersion) {
        r.fail("version", "version " + version.dump() + " is not one this build reads (it reads " +
                              std::to_string(kSceneVersion) + ")");
    }
    SceneDesc scene;
    if (j.contains("settings")) scene.settings = readSettings(r, j["settings"]);
    const json& bodies = r.require(j, "", "bodies");
    if (!bodies.is_array()) r.fail("bodies", "must be an array");
    for (size_t i = 0; i < bodies.size(); ++i) {
        scene.bodies.push_back(readBody(r, bodies[i], "bodies[" + std::to_string(i) + "]"));
    }
    r.optional(j, "", "joints", [&](const json& v, const std::string& f) {
        if (!v.is_array()) r.fail(f, "must be an array");
        for (size_t i = 0; i < v.size(); ++i)
            scene.joints.push_back(readJoint(r, v[i], f + "[" + std::to_string(i) + "]"));
    });
    r.optional(j, "", "no_collide",
               [&](const json& v, const std::string& f) { scene.noCollide = r.namePairs(v, f); });
    const std::vector<SceneError> problems = sceneProblems(scene);
    if (!problems.empty()) {
        InputError e(fileName, problems.front().path(), problems.front().message());
        for (size_t k = 1; k < problems.size(); ++k) e.addMore(problems[k].what());
        throw e;
    }
    // After validation, so that a mesh is read only with a usable file name and scale.
    if (baseDir) loadSceneMeshes(scene, *baseDir, fileName);
    return scene;
}

SceneDesc readSceneFile(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(name, "", "is a directory, not a scene file");
    // Opening a FIFO waits for a writer for ever: anything but a file is refused first.
    const auto type = std::filesystem::status(path, ec).type();
    if (!ec && type != std::filesystem::file_type::regular && type != std::filesystem::file_type::not_found)
        throw InputError(name, "", "is not a regular file (a pipe, socket or device), not a scene file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(name, "", "cannot be read (missing, or no permission)");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw InputError(name, "", "could not be read to the end");
    SceneDesc scene = parseScene(text.str(), name, path.parent_path());
    // The convex parts made before, from the sidecar (a missing or stale one is made again).
    readConvexPartsCache(scene, convexPartsCachePath(path));
    return scene;
}

}  // namespace tumble::io
