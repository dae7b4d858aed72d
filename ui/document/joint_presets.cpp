#include "document/joint_presets.h"

#include "document/body_presets.h"

#include <tumble/model.h>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

std::optional<JointDesc> presetJoint(JointType type, const SceneDesc& scene, const std::vector<int>& selection,
                                     std::string* why) {
    const auto refuse = [&](const char* text) {
        if (why) *why = text;
        return std::nullopt;
    };
    const int n = static_cast<int>(scene.bodies.size());
    if (selection.empty() || selection.size() > 2) return refuse("select one body (joined to the world) or two");
    for (int i : selection)
        if (i < 0 || i >= n) return refuse("select one body (joined to the world) or two");
    // Two bodies: the first picked is the base (B), the second the part that moves on it (A):
    // a hinge's motor at +1 rad/s turns the second picked the right-hand way about the axis.
    int a = selection.size() == 2 ? selection[1] : selection[0],
        b = selection.size() == 2 ? selection[0] : -1;
    const auto dynamic = [&](int i) { return i >= 0 && scene.bodies[i].motion == Motion::Dynamic; };
    if (!dynamic(a) && !dynamic(b)) return refuse("a joint needs a dynamic body among those selected");
    if (!dynamic(a)) std::swap(a, b);  // body_a is one that moves
    const BodyDesc& A = scene.bodies[a];
    const BodyDesc* B = b >= 0 ? &scene.bodies[b] : nullptr;

    JointDesc j;
    j.name = toString(type);
    j.type = type;
    j.bodyA = A.name;
    if (B) j.bodyB = B->name;
    if (type == JointType::Distance || type == JointType::Rope) {
        j.anchorA = Vec3::Zero();
        j.anchorB = B ? Vec3::Zero() : Vec3(A.position + Vec3(0, 1, 0));
        return j;
    }
    const Vec3 at = B ? Vec3(0.5 * (A.position + B->position)) : A.position;
    j.anchorA = A.orientation.conjugate() * (at - A.position);
    j.anchorB = B ? Vec3(B->orientation.conjugate() * (at - B->position)) : at;
    if (type == JointType::Hinge) j.axisA = A.orientation.conjugate() * Vec3::UnitY();
    if (type == JointType::Slider) j.axisA = A.orientation.conjugate() * Vec3::UnitX();
    return j;
}

std::optional<JointDesc> swappedJoint(const SceneDesc& scene, const JointDesc& j) {
    if (j.bodyB.empty()) return std::nullopt;  // the world cannot be body A
    JointDesc s = j;
    std::swap(s.bodyA, s.bodyB);
    std::swap(s.anchorA, s.anchorB);
    if (j.axisA) {
        // The new A's axis: B's as given, else A's as it lies at the start, in B's frame.
        const BodyFrame a = frameOf(scene, j.bodyA), b = frameOf(scene, j.bodyB);
        s.axisA = j.axisB ? *j.axisB : Vec3(b.q.conjugate() * (a.q * *j.axisA));
        s.axisB = *j.axisA;
    }
    // The coordinate is the other body's against this one: the same motion, the other sign.
    if (j.limits) s.limits = std::array<double, 2>{-(*j.limits)[1], -(*j.limits)[0]};
    if (j.motor) s.motor->speed = -j.motor->speed;
    if (j.spring) s.spring->rest = -j.spring->rest;
    if (j.servo) s.servo->target = -j.servo->target;
    // A ball's twist of the one against the other, the other sign; its cone is the angle
    // between the two axes, the same (an elliptical cone's directions are then the new A's).
    if (j.twistLimits) s.twistLimits = std::array<double, 2>{-(*j.twistLimits)[1], -(*j.twistLimits)[0]};
    return s;
}

bool insertServoKey(JointDesc& j, double time) {
    if (!j.servo) return false;
    std::vector<JointDesc::ServoKey>& keys = j.servo->keys;
    if (keys.empty()) keys.push_back({0.0, j.servo->target});
    JointModel m;  // the target at that time, as the engine reads the keys
    m.servoTarget = j.servo->target;
    m.servoKeys = keys;
    const double target = m.servoTargetAt(time);
    const auto at = std::lower_bound(keys.begin(), keys.end(), time,
                                     [](const JointDesc::ServoKey& k, double t) { return k.time < t; });
    if (at == keys.end() || std::abs(at->time - time) > 1e-9) keys.insert(at, {time, target});
    j.servo->target = keys.front().target;
    return true;
}

BodyFrame frameOf(const SceneDesc& scene, const std::string& name) {
    for (const BodyDesc& b : scene.bodies)
        if (!name.empty() && b.name == name) return {b.position, b.orientation.normalized()};
    return {};
}

Vec3 worldAnchorA(const SceneDesc& scene, const JointDesc& j) {
    return frameOf(scene, j.bodyA).toWorld(j.anchorA);
}

Vec3 worldAnchorB(const SceneDesc& scene, const JointDesc& j) {
    return frameOf(scene, j.bodyB).toWorld(j.anchorB);
}

std::optional<BallLimitFrame> ballLimitFrame(const SceneDesc& scene, const JointDesc& j) {
    if (j.type != JointType::Ball || !(j.swingLimit || j.twistLimits) || !j.axisA || !(j.axisA->norm() > 0.0))
        return std::nullopt;
    const BodyDesc* a = nullptr;
    for (const BodyDesc& b : scene.bodies)
        if (b.name == j.bodyA) a = &b;
    if (!a) return std::nullopt;
    const BodyFrame fa = frameOf(scene, j.bodyA), fb = frameOf(scene, j.bodyB);
    BallLimitFrame f;
    const Vec3 axis = fa.q * j.axisA->normalized();
    f.n = j.axisB && j.axisB->norm() > 0.0 ? Vec3(fb.q * j.axisB->normalized()) : axis;
    const Vec3 across = fa.q * firstCrossAxis(j.axisA->normalized());
    f.e1 = (across - across.dot(f.n) * f.n).normalized();
    f.anchor = worldAnchorB(scene, j);
    f.size = 1.2 * boundingRadius(a->shape);
    if (!f.e1.allFinite() || !(f.size > 0.0)) return std::nullopt;
    return f;
}

std::optional<Vec3> ballLimitGrip(const BallLimitFrame& f, const JointDesc& j, int grip) {
    const Vec3 e2 = f.n.cross(f.e1);
    if (grip == 0 || grip == 1) {
        if (!j.swingLimit) return std::nullopt;
        const double theta = (*j.swingLimit)[size_t(grip)];
        return f.anchor + f.size * (std::cos(theta) * f.n + std::sin(theta) * (grip == 0 ? f.e1 : e2));
    }
    if (grip == 2 || grip == 3) {
        if (!j.twistLimits) return std::nullopt;
        const double phi = (*j.twistLimits)[size_t(grip - 2)];
        return f.anchor + (f.size / 3.0) * (std::cos(phi) * f.e1 + std::sin(phi) * e2);
    }
    return std::nullopt;
}

}  // namespace tumble::ui
