// One pose proves one pose: a scene turned and shifted as a whole (every body's pose and
// velocities, which carry planes and meshes, the gravity, world-frame forces, spring
// anchors and world-anchored joints) must move as the original does, turned and shifted the same way. These
// helpers build the turned scene, turn a state the same way, and measure how far two states are apart, for
// the tests that check an answer in both worlds.
#pragma once

#include <tumble/io/scene_file.h>
#include <tumble/scene.h>
#include <tumble/world.h>

#include "test_random.h"

#include <QDir>
#include <QString>

#include <algorithm>
#include <cstdint>
#include <string>

namespace tumble::test {

/// A rigid motion of the whole world: p -> R p + t.
struct WorldPose {
    Quat R = Quat::Identity();
    Vec3 t = Vec3::Zero();

    Vec3 point(const Vec3& p) const { return R * p + t; }
    Vec3 direction(const Vec3& d) const { return R * d; }
    Quat orientation(const Quat& q) const { return (R * q).normalized(); }
};

/// A pose drawn from `seed`: a rotation uniform over all turns (a unit quaternion drawn
/// uniformly from the 4-ball) and a shift of up to `reach` metres along each axis.
inline WorldPose randomWorldPose(std::uint64_t seed, double reach = 20.0) {
    Rng rng{seed};
    Quat q;
    do {
        q = Quat(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    } while (q.squaredNorm() > 1.0 || q.squaredNorm() < 1e-2);
    return {q.normalized(), rng.vec(-reach, reach)};
}

/// The scene as it reads in a world turned and shifted by `pose`.
inline SceneDesc turnedScene(SceneDesc s, const WorldPose& pose) {
    s.settings.gravity = pose.direction(s.settings.gravity);
    for (BodyDesc& b : s.bodies) {
        b.position = pose.point(b.position);
        b.orientation = pose.orientation(b.orientation);
        b.velocity = pose.direction(b.velocity);
        b.angularVelocity = pose.direction(b.angularVelocity);
        for (BodyKey& k : b.keys) {
            k.position = pose.point(k.position);
            k.orientation = pose.orientation(k.orientation);
        }
        for (ForceDesc& f : b.forces) {
            if (f.frame == Frame::World && f.type != ForceType::Spring) f.vector = pose.direction(f.vector);
            if (f.type == ForceType::Spring) f.anchor = pose.point(f.anchor);
        }
    }
    for (JointDesc& j : s.joints) {
        if (!j.bodyB.empty()) continue;  // both anchors and axes in the bodies' own frames
        j.anchorB = pose.point(j.anchorB);
        if (j.axisB) j.axisB = pose.direction(*j.axisB);
    }
    return s;
}

/// A state turned and shifted by `pose` (the centres, orientations, momenta).
inline State turnedState(State s, const WorldPose& pose) {
    for (BodyState& b : s.bodies) {
        b.x = pose.point(b.x);
        b.q = pose.orientation(b.q);
        b.P = pose.direction(b.P);
        b.L = pose.direction(b.L);
    }
    return s;
}

/// How far two states of the same scene are apart: the largest of the bodies' centre
/// distances (m), orientation angles (rad), and velocity and angular velocity differences
/// over `speedScale` (m/s, rad/s: 1 puts them on the same footing as the metres).
struct StateGap {
    double position = 0, angle = 0, velocity = 0, spin = 0;
    int body = -1;  ///< the body of the largest position or angle gap
    double worst() const { return std::max({position, angle, velocity, spin}); }
};

inline StateGap stateGap(const Model& model, const State& a, const State& b) {
    StateGap g;
    for (size_t i = 0; i < a.bodies.size(); ++i) {
        const BodyState& x = a.bodies[i];
        const BodyState& y = b.bodies[i];
        const Quat d = x.q.normalized().conjugate() * y.q.normalized();
        const double angle = 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
        const double position = (x.x - y.x).norm();
        if (std::max(position, angle) > std::max(g.position, g.angle)) g.body = static_cast<int>(i);
        g.position = std::max(g.position, position);
        g.angle = std::max(g.angle, angle);
        const BodyModel& m = model.bodies[i];
        g.velocity = std::max(g.velocity, m.invMass * (x.P - y.P).norm());
        g.spin = std::max(g.spin, (derive(m, x).omega - derive(m, y).omega).norm());
    }
    return g;
}

inline QString describe(const StateGap& g) {
    return QString("largest gap: %1 m, %2 rad (body %3), %4 m/s, %5 rad/s")
        .arg(g.position, 0, 'g', 3)
        .arg(g.angle, 0, 'g', 3)
        .arg(g.body)
        .arg(g.velocity, 0, 'g', 3)
        .arg(g.spin, 0, 'g', 3);
}

/// Where a failing test leaves its scene for a person to run: the turned scene written to
/// the system's temporary folder under `stem` and the seed, its path returned (to print).
inline QString keepFailedScene(const SceneDesc& scene, const std::string& stem, std::uint64_t seed) {
    const std::string path =
        QDir::tempPath().toStdString() + "/tumble-" + stem + "-seed" + std::to_string(seed) + ".json";
    try {
        io::writeSceneFile(scene, path);
    } catch (const std::exception& e) {
        return QString("(not written: %1)").arg(e.what());
    }
    return QString::fromStdString(path);
}

}  // namespace tumble::test
