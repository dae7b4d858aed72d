// The joints of a scene: checked (named bodies, finite anchors, a length a rope can have,
// axes where the type has one)
// and resolved to body indices and anchors from each centre of mass (compile.cpp calls it
// last, when the bodies' mass properties are known).
#include "model/compile_joints.h"

#include "common/pair_key.h"

#include <tumble/errors.h>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace tumble {

namespace {

std::string at(size_t i) {
    return "joints[" + std::to_string(i) + "]";
}

void finiteAtLeast0(double v, const std::string& field) {
    if (!std::isfinite(v) || v < 0.0) throw SceneError(field, "must be a finite number, at least 0");
}

// A ball joint's swing cone and twist range.
void validateBallLimits(const JointDesc& j, const std::string& p) {
    if (j.swingLimit)
        for (double angle : *j.swingLimit)
            if (!(angle > 0.0 && angle < M_PI))
                throw SceneError(p + ".swing_limit", "must be angles greater than 0 and less than pi (rad)");
    if (j.twistLimits) {
        const auto [lower, upper] = *j.twistLimits;
        if (!(lower >= -M_PI && upper <= M_PI))
            throw SceneError(p + ".twist_limits", "must be angles within [-pi, pi] (rad)");
        if (lower > upper) throw SceneError(p + ".twist_limits", "the lower limit is above the upper one");
    }
}

// What acts on a free axis: a hinge's or slider's (`p` the joint), a six-axis joint's
// (`p` its axis); `linear`: the axis is along (forces, N), else about (torques, N m).
struct AxisSettings {
    const std::optional<std::array<double, 2>>& limits;
    const std::optional<JointDesc::Motor>& motor;
    const std::optional<JointDesc::Spring>& spring;
    const std::optional<JointDesc::Servo>& servo;
};

void validateDrives(const AxisSettings& j, const std::string& p, bool linear) {
    if (j.limits) {
        const auto [lower, upper] = *j.limits;
        if (!std::isfinite(lower) || !std::isfinite(upper))
            throw SceneError(p + ".limits", "must be finite numbers");
        if (lower > upper) throw SceneError(p + ".limits", "the lower limit is above the upper one");
    }
    if (j.motor) {
        if (!std::isfinite(j.motor->speed)) throw SceneError(p + ".motor.speed", "must be a finite number");
        if (!std::isfinite(j.motor->maxForce) || j.motor->maxForce < 0.0)
            throw SceneError(p + (linear ? ".motor.max_force" : ".motor.max_torque"),
                             "must be a finite number, at least 0");
    }
    if (j.spring) {
        finiteAtLeast0(j.spring->stiffness, p + ".spring.stiffness");
        finiteAtLeast0(j.spring->damping, p + ".spring.damping");
        if (!std::isfinite(j.spring->rest)) throw SceneError(p + ".spring.rest", "must be a finite number");
    }
    if (!j.servo) return;
    const JointDesc::Servo& v = *j.servo;
    if (j.motor)
        throw SceneError(p + ".servo",
                         "a joint has one drive: a motor (a speed) or a servo (a target), not both");
    if (!std::isfinite(v.target)) throw SceneError(p + ".servo.target", "must be a finite number");
    for (size_t k = 0; k < v.keys.size(); ++k) {
        const std::string key = p + ".servo.keys[" + std::to_string(k) + "]";
        if (!std::isfinite(v.keys[k].time)) throw SceneError(key + ".time", "must be a finite number");
        if (!std::isfinite(v.keys[k].target)) throw SceneError(key + ".target", "must be a finite number");
        if (k > 0 && !(v.keys[k].time > v.keys[k - 1].time))
            throw SceneError(key + ".time", "must be later than the key before");
    }
    const std::string most = p + (linear ? ".servo.max_force" : ".servo.max_torque");
    if (std::isnan(v.maxForce) || !(v.maxForce > 0.0))
        throw SceneError(most, "must be greater than 0 (leave it out for no bound)");
    if (v.timeConstant != 0.0) {
        if (!std::isfinite(v.timeConstant) || v.timeConstant < 0.0)
            throw SceneError(p + ".servo.time_constant", "must be a finite number greater than 0");
        if (v.stiffness != 0.0 || v.damping != 0.0)
            throw SceneError(p + ".servo.time_constant",
                             "give either time_constant or stiffness and damping, not both");
        return;
    }
    finiteAtLeast0(v.stiffness, p + ".servo.stiffness");
    finiteAtLeast0(v.damping, p + ".servo.damping");
    if (!(v.stiffness > 0.0))
        throw SceneError(p + ".servo.stiffness",
                         "must be greater than 0 (or give time_constant instead of stiffness and damping)");
}

const char* const kAxisNames[6] = {"x", "y", "z", "rx", "ry", "rz"};

// A six-axis joint's axes: what acts on one needs it free; an angle's range within ±π (its
// coordinate is a rotation vector's component).
void validateSixAxis(const JointDesc& j, const std::string& p) {
    for (int i = 0; i < 6; ++i) {
        const JointDesc::Axis& x = j.axes[i];
        const std::string q = p + ".axes." + kAxisNames[i];
        if (!x.free && (x.limits || x.motor || x.spring || x.servo))
            throw SceneError(q, "a locked axis has no limits, motor, spring or servo");
        validateDrives({x.limits, x.motor, x.spring, x.servo}, q, i < 3);
        if (i >= 3 && x.limits && !((*x.limits)[0] >= -M_PI && (*x.limits)[1] <= M_PI))
            throw SceneError(q + ".limits", "must be angles within [-pi, pi] (rad)");
        // (An angle a servo or spring aims at beyond ±π could never be reached: past π the
        // coordinate is the turn the other way.)
        auto within = [&](double angle, const std::string& field) {
            if (i >= 3 && !(std::abs(angle) <= M_PI)) throw SceneError(field, "must be an angle within [-pi, pi] (rad)");
        };
        if (x.spring) within(x.spring->rest, q + ".spring.rest");
        if (x.servo) {
            within(x.servo->target, q + ".servo.target");
            for (size_t k = 0; k < x.servo->keys.size(); ++k)
                within(x.servo->keys[k].target, q + ".servo.keys[" + std::to_string(k) + "].target");
        }
    }
}

}  // namespace

Vec3 firstCrossAxis(const Vec3& axis) {
    int along = 0;
    axis.cwiseAbs().maxCoeff(&along);
    const Vec3 first = along == 0 ? Vec3::UnitY() : Vec3::UnitX();
    return (first - first.dot(axis) * axis).normalized();
}

void validateJoints(const SceneDesc& scene) {
    std::map<std::string, const BodyDesc*> bodies;
    for (const BodyDesc& b : scene.bodies) bodies[b.name] = &b;
    std::set<std::string> names;
    for (size_t i = 0; i < scene.joints.size(); ++i) {
        const JointDesc& j = scene.joints[i];
        const std::string p = at(i);
        if (j.name.empty()) throw SceneError(p + ".name", "must not be empty");
        if (!names.insert(j.name).second)
            throw SceneError(p + ".name", "'" + j.name + "' is already the name of another joint");
        const auto a = bodies.find(j.bodyA);
        if (a == bodies.end()) throw SceneError(p + ".body_a", "no body is named '" + j.bodyA + "'");
        const BodyDesc* b = nullptr;
        if (!j.bodyB.empty()) {
            const auto it = bodies.find(j.bodyB);
            if (it == bodies.end()) throw SceneError(p + ".body_b", "no body is named '" + j.bodyB + "'");
            if (j.bodyB == j.bodyA) throw SceneError(p + ".body_b", "a joint needs two different bodies");
            b = it->second;
        }
        if (a->second->motion != Motion::Dynamic && (!b || b->motion != Motion::Dynamic))
            throw SceneError(p, "joins nothing that moves: one of its bodies must be dynamic");
        if (!j.anchorA.allFinite()) throw SceneError(p + ".anchor_a", "must be finite numbers");
        if (!j.anchorB.allFinite()) throw SceneError(p + ".anchor_b", "must be finite numbers");
        if (!std::isfinite(j.length)) throw SceneError(p + ".length", "must be a finite number");
        const bool line = j.type == JointType::Distance || j.type == JointType::Rope;
        if (!line && j.length >= 0.0)
            throw SceneError(p + ".length",
                             std::string("a ") + toString(j.type) +
                                 " joint has no length (only distance and rope joints have one)");
        const bool axial = j.type == JointType::Hinge || j.type == JointType::Slider;
        const bool six = j.type == JointType::SixAxis;
        if (!six && j.axes != JointDesc().axes)
            throw SceneError(p + ".axes", std::string("a ") + toString(j.type) +
                                              " joint has none (only six_axis joints do)");
        if (six && j.axisB)
            throw SceneError(p + ".axis_b", "a six_axis joint's frame on body_b is body_a's as placed: give axis_a only");
        if (six) validateSixAxis(j, p);
        const bool cone = j.type == JointType::Ball && (j.swingLimit || j.twistLimits);
        if (axial && !j.axisA)
            throw SceneError(p + ".axis_a",
                             std::string("is missing (a ") + toString(j.type) + " joint needs its axis)");
        if (cone && !j.axisA)
            throw SceneError(p + ".axis_a",
                             "is missing (a ball joint's swing_limit and twist_limits are about its axis)");
        if (!axial && !six && j.type != JointType::Ball && (j.axisA || j.axisB))
            throw SceneError(p + (j.axisA ? ".axis_a" : ".axis_b"),
                             std::string("a ") + toString(j.type) +
                                 " joint has no axis (hinge, slider, ball and six_axis joints have one)");
        if (j.type == JointType::Ball && j.axisB && !j.axisA)
            throw SceneError(p + ".axis_a", "is missing (a ball joint's axis_b goes with its axis_a)");
        if (j.type != JointType::Ball && (j.swingLimit || j.twistLimits))
            throw SceneError(p + (j.swingLimit ? ".swing_limit" : ".twist_limits"),
                             std::string("a ") + toString(j.type) + " joint has none (only ball joints do)");
        validateBallLimits(j, p);
        if (!axial && (j.limits || j.motor || j.spring || j.servo))
            throw SceneError(
                p + (j.limits ? ".limits" : j.motor ? ".motor" : j.spring ? ".spring" : ".servo"),
                std::string("a ") + toString(j.type) + " joint has none (only hinge and slider joints do)");
        validateDrives({j.limits, j.motor, j.spring, j.servo}, p, j.type == JointType::Slider);
        if (j.breakForce && !(std::isfinite(*j.breakForce) && *j.breakForce > 0.0))
            throw SceneError(p + ".break_force", "must be a finite number greater than 0");
        for (const auto& [axis, field] : {std::pair{&j.axisA, ".axis_a"}, std::pair{&j.axisB, ".axis_b"}}) {
            if (!*axis) continue;
            if (!(*axis)->allFinite()) throw SceneError(p + field, "must be finite numbers");
            if (!((*axis)->norm() > 1e-9)) throw SceneError(p + field, "must not be the zero vector");
        }
    }
}

namespace {

// The solver's copy of what acts on a free axis.
void compileAxis(const AxisSettings& d, JointAxis& j) {
    if (d.limits) {
        j.limited = true;
        j.lower = (*d.limits)[0];
        j.upper = (*d.limits)[1];
    }
    if (d.motor) {
        j.motor = true;
        j.motorSpeed = d.motor->speed;
        j.motorMax = d.motor->maxForce;
    }
    if (d.spring) {
        j.spring = true;
        j.springStiffness = d.spring->stiffness;
        j.springDamping = d.spring->damping;
        j.springRest = d.spring->rest;
    }
    if (d.servo) {
        j.servo = true;
        j.servoTarget = d.servo->target;
        j.servoMax = d.servo->maxForce;
        j.servoStiffness = d.servo->stiffness;
        j.servoDamping = d.servo->damping;
        j.servoTimeConstant = d.servo->timeConstant;
        j.servoKeys = d.servo->keys;
    }
}

// A six-axis joint's frame (x its axis_a, y the first of A's frame axes across it, z = x × y)
// in A's axes and, as the scene places the bodies, in B's; its locked and free axes.
void compileSixAxis(const JointDesc& d, const Quat& relative, JointModel& j) {
    const Vec3 x = d.axisA ? d.axisA->normalized() : Vec3::UnitX();
    const Vec3 y = firstCrossAxis(x);
    j.frameA.col(0) = x;
    j.frameA.col(1) = y;
    j.frameA.col(2) = x.cross(y);
    j.frameB = relative.toRotationMatrix() * j.frameA;
    j.axisA = x;
    j.axisB = j.frameB.col(0);
    for (int i = 0; i < 6; ++i) {
        const JointDesc::Axis& a = d.axes[i];
        if (!a.free) {
            j.locked |= 1u << i;
            continue;
        }
        JointAxis& axis = j.axes.emplace_back();
        axis.axis = i;
        compileAxis({a.limits, a.motor, a.spring, a.servo}, axis);
    }
}

}  // namespace

void compileJoints(const SceneDesc& scene, const State& start, Model& m) {
    if (scene.joints.empty()) return;
    std::map<std::string, int> index;
    for (size_t i = 0; i < scene.bodies.size(); ++i) index[scene.bodies[i].name] = static_cast<int>(i);
    m.jointed.assign(m.bodies.size(), 0);
    for (size_t i = 0; i < scene.joints.size(); ++i) {
        const JointDesc& d = scene.joints[i];
        JointModel j;
        j.name = d.name;
        j.type = d.type;
        j.a = index.at(d.bodyA);
        j.b = d.bodyB.empty() ? -1 : index.at(d.bodyB);
        j.anchorA = d.anchorA - m.bodies[j.a].centerOfMass;
        j.anchorB = j.b < 0 ? d.anchorB : Vec3(d.anchorB - m.bodies[j.b].centerOfMass);
        // The anchors in the world at the start, for a length taken from the scene.
        const Vec3 pa = start.bodies[j.a].x + start.bodies[j.a].q * j.anchorA;
        const Vec3 pb = j.b < 0 ? j.anchorB : Vec3(start.bodies[j.b].x + start.bodies[j.b].q * j.anchorB);
        j.length = d.length >= 0.0 ? d.length : (pa - pb).norm();
        // Axes and the relative orientation as the scene places the bodies.
        const Quat qa = start.bodies[j.a].q;
        const Quat qb = j.b < 0 ? Quat::Identity() : start.bodies[j.b].q;
        if (d.axisA) {
            j.axisA = d.axisA->normalized();
            j.axisB = d.axisB ? d.axisB->normalized() : Vec3(qb.conjugate() * (qa * j.axisA));
        }
        j.relative = (qb.conjugate() * qa).normalized();
        compileAxis({d.limits, d.motor, d.spring, d.servo}, j);
        if (j.type == JointType::SixAxis) compileSixAxis(d, j.relative, j);
        j.index = static_cast<int>(i);
        if (d.breakForce) j.breakForce = *d.breakForce;
        j.collideConnected = d.collideConnected;
        if (d.swingLimit) {
            j.swingLimited = true;
            j.swingLimit = *d.swingLimit;
            // A's first frame axis across its axis, as the scene places A, in B's frame.
            const Vec3 across = qb.conjugate() * (qa * firstCrossAxis(j.axisA));
            j.swingCross = (across - across.dot(j.axisB) * j.axisB).normalized();
        }
        if (d.twistLimits) {
            j.twistLimited = true;
            j.twistLower = (*d.twistLimits)[0];
            j.twistUpper = (*d.twistLimits)[1];
        }
        if (j.type == JointType::Rope && !(j.length > 0.0))
            throw SceneError(at(i) + ".length", "a rope must be longer than 0");
        // A joint that does not hold in the scene as written is pulled together in the
        // first step, which gives its bodies the speed of that move: said, not refused
        // (the editor's joints start where the user put them; a file may be off by a typo).
        const double size = std::max(collision::boundingRadius(m.bodies[j.a].collider), 1e-3);
        const Vec3 gap = pa - pb;
        double off = 0.0;
        if (j.type == JointType::Ball || j.type == JointType::Hinge || j.type == JointType::Fixed)
            off = gap.norm();
        else if (j.type == JointType::Slider)
            off = (gap - gap.dot(qb * j.axisB) * (qb * j.axisB)).norm();
        else if (j.type == JointType::Distance)
            off = std::abs(gap.norm() - j.length);
        else if (j.type == JointType::SixAxis)
            for (int k = 0; k < 3; ++k)
                if (j.locked & (1u << k)) off = std::max(off, std::abs((qb * j.frameB.col(k)).dot(gap)));
        if (off > 1e-4 * size) {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", off);
            m.notes.push_back(at(i) + " (" + d.name + "): does not hold in the scene as written (off by " +
                              text +
                              " m); the first step pulls it together, giving its bodies that move's speed");
        }
        m.jointed[j.a] = 1;
        if (j.b >= 0) {
            m.jointed[j.b] = 1;
            if (!j.collideConnected) m.jointPairs.push_back(pairKey(std::min(j.a, j.b), std::max(j.a, j.b)));
        }
        m.joints.push_back(j);
    }
    std::sort(m.jointPairs.begin(), m.jointPairs.end());
}

}  // namespace tumble
