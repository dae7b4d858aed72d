// Small builders for scenes written in code by the engine tests.
#pragma once

#include <tumble/scene.h>
#include <tumble/world.h>

#include "test_meshes.h"
#include "test_random.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace tumble::test {

inline BodyDesc sphereBody(const std::string& name, double radius, double mass) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = radius;
    b.mass = mass;
    return b;
}

/// A cylinder about its y axis (a disc, a wheel) of `radius` and `halfHeight`.
inline BodyDesc cylinderBody(const std::string& name, double radius, double halfHeight, double mass) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Cylinder;
    b.shape.radius = radius;
    b.shape.halfHeight = halfHeight;
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

/// A static box (no mass) of `halfExtents` at `position`.
inline BodyDesc staticBoxBody(const std::string& name, const Vec3& halfExtents, const Vec3& position) {
    BodyDesc b = boxBody(name, halfExtents, 1.0);
    b.motion = Motion::Static;
    b.mass.reset();
    b.position = position;
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

/// A static hemispherical bowl of radius R (hemisphereBowl: the inside of a UV sphere of
/// `rings` x `segments`), its lowest point at the origin, as a triangle mesh.
inline BodyDesc meshBowl(double R, int rings, int segments) {
    BodyDesc b;
    b.name = "bowl";
    b.motion = Motion::Static;
    b.shape.type = ShapeType::Mesh;
    b.shape.collision = MeshCollision::Triangles;
    b.shape.file = "bowl (built by the test)";
    b.shape.meshData = std::make_shared<const TriangleMesh>(hemisphereBowl(R, rings, segments));
    b.position = Vec3(0, R, 0);
    return b;
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

/// Steps `kept` n times by h, and `fresh` the same way but given its own state before every
/// step (World::setState: nothing carried over from the steps before but the state). The
/// time of the first step after which their states differ, or -1 when they agree throughout.
inline double firstDifferenceFromFresh(World& kept, World& fresh, long n, double h) {
    for (long k = 0; k < n; ++k) {
        kept.step(h);
        const State own = fresh.state();
        fresh.setState(own);
        fresh.step(h);
        if (hashState(kept.state()) != hashState(fresh.state())) return kept.state().time;
    }
    return -1.0;
}

/// Takes n steps of h.
inline void stepN(World& w, long n, double h) {
    for (long k = 0; k < n; ++k) w.step(h);
}

/// The ground (restitution 0.2, friction 0.6) and n octahedral rocks (jittered, as hulls:
/// one vertex on each half axis 0.2-0.3 m out) in a heap over it, 4 to a row; mass 1 kg,
/// or random in 0.5-2 kg.
inline std::vector<BodyDesc> rockHeap(int n, std::uint64_t seed, bool randomMass) {
    std::vector<BodyDesc> bodies{groundPlane(0.2, 0.6)};
    Rng rng{seed};
    for (int i = 0; i < n; ++i) {
        BodyDesc rock;
        rock.name = "rock" + std::to_string(i);
        rock.shape.type = ShapeType::Mesh;
        rock.shape.file = "rock (built by the test)";
        auto mesh = std::make_shared<TriangleMesh>();
        mesh->vertices = {{rng.uniform(0.2, 0.3), 0, 0}, {-rng.uniform(0.2, 0.3), 0, 0}, {0, rng.uniform(0.2, 0.3), 0},
                          {0, -rng.uniform(0.2, 0.3), 0}, {0, 0, rng.uniform(0.2, 0.3)}, {0, 0, -rng.uniform(0.2, 0.3)}};
        mesh->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
        rock.shape.meshData = mesh;
        rock.mass = randomMass ? rng.uniform(0.5, 2.0) : 1.0;
        rock.position = Vec3(0.7 * (i % 4) - 1.0, 0.4 + 0.5 * (i / 4), 0.7 * ((i / 2) % 2) + 0.1 * (i % 3));
        bodies.push_back(rock);
    }
    return bodies;
}

/// The ground (restitution 0, random friction) and 10 random boxes and spheres (restitution
/// and friction 0..1, masses 0.5..5 kg, spinning) one above the other, 1.1 m apart: more
/// than two half-diagonals (2 × 0.52 m), so none overlap at the start.
inline std::vector<BodyDesc> randomDropPile(std::uint64_t seed) {
    Rng rng{seed};
    std::vector<BodyDesc> bodies{groundPlane(0.0, rng.uniform(0, 1))};
    for (int k = 0; k < 10; ++k) {
        BodyDesc b = k % 2 ? sphereBody("s", rng.uniform(0.1, 0.3), 1.0)
                           : boxBody("b", Vec3(rng.uniform(0.1, 0.3), rng.uniform(0.1, 0.3), rng.uniform(0.1, 0.3)),
                                     1.0);
        b.name += std::to_string(k);
        b.mass = rng.uniform(0.5, 5.0);
        b.restitution = rng.uniform(0, 1);
        b.friction = rng.uniform(0, 1);
        b.position = Vec3(rng.uniform(-0.3, 0.3), 0.6 + 1.1 * k, rng.uniform(-0.3, 0.3));
        b.orientation =
            Quat(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).normalized();
        b.angularVelocity = Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        bodies.push_back(b);
    }
    return bodies;
}

}  // namespace tumble::test
