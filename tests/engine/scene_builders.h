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

/// Takes n steps of h.
inline void stepN(World& w, long n, double h) {
    for (long k = 0; k < n; ++k) w.step(h);
}

}  // namespace tumble::test
