// Small builders for scenes written in code by the engine tests.
#pragma once

#include <tumble/scene.h>
#include <tumble/world.h>

namespace tumble::test {

inline BodyDesc sphereBody(const std::string& name, double radius, double mass) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = radius;
    b.mass = mass;
    return b;
}

inline BodyDesc boxBody(const std::string& name, const Vec3& halfExtents, double mass) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = halfExtents;
    b.mass = mass;
    return b;
}

inline SceneDesc sceneOf(std::vector<BodyDesc> bodies, const Vec3& gravity = Vec3(0, -9.81, 0),
                         const std::string& integrator = {}) {
    SceneDesc s;
    s.settings.gravity = gravity;
    s.settings.integrator = integrator;
    s.bodies = std::move(bodies);
    return s;
}

/// The static ground: the plane y = distance, free side up.
inline BodyDesc groundPlane(double restitution, double friction, double distance = 0.0) {
    BodyDesc b;
    b.name = "ground";
    b.motion = Motion::Static;
    b.shape.type = ShapeType::Plane;
    b.shape.normal = Vec3::UnitY();
    b.shape.distance = distance;
    b.restitution = restitution;
    b.friction = friction;
    return b;
}

inline BodyDesc material(BodyDesc b, double restitution, double friction) {
    b.restitution = restitution;
    b.friction = friction;
    return b;
}

/// Velocity of the centre of mass and angular velocity of body i.
inline Vec3 velocityOf(const World& w, int i) { return w.state().bodies[i].P * w.model().bodies[i].invMass; }
inline Vec3 omegaOf(const World& w, int i) { return derive(w.model().bodies[i], w.state().bodies[i]).omega; }

/// Takes n steps of h.
inline void stepN(World& w, long n, double h) {
    for (long k = 0; k < n; ++k) w.step(h);
}

}  // namespace tumble::test
