// Jolt Physics behind a plain interface of doubles (issue 53): jolt_world.cpp alone includes
// Jolt's headers and is compiled with Jolt's own flags (its SIMD: -mavx2 and the rest), so
// no Eigen type crosses between code built with different vector widths. peer_jolt.cpp
// translates Tumble's compiled scene into these structs.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace tumble::bench::jolt {

struct V3 {
    double x = 0, y = 0, z = 0;
};
struct Q4 {
    double w = 1, x = 0, y = 0, z = 0;
};

enum class ShapeKind { Sphere, Box, Capsule, Cylinder, Hull, Plane, Mesh, Compound };

/// A shape in its body's frame (capsules and cylinders along y, as Tumble's and Jolt's).
struct Shape {
    ShapeKind kind = ShapeKind::Sphere;
    double radius = 0, halfHeight = 0;
    V3 halfExtents;
    std::vector<V3> points;                  ///< a hull's vertices; a mesh's
    std::vector<std::array<int, 3>> triangles;  ///< a mesh's (static bodies only)
    V3 planeNormal;                          ///< a plane's, world (static, at the identity)
    double planeOffset = 0;                  ///< n·p = offset
    struct Part;
    std::vector<Part> parts;  ///< a compound's
};
struct Shape::Part {
    Shape shape;
    V3 position;
    Q4 orientation;
};

struct Body {
    Shape shape;
    bool dynamic = false;
    V3 position;  ///< the body frame's origin, world
    Q4 orientation;
    // Dynamic bodies: Tumble's mass properties (the centre of mass in the body frame, the
    // inertia about it in body axes, row-major).
    double mass = 0;
    V3 centerOfMass;
    std::array<double, 9> inertia{};
    V3 velocity, angularVelocity;  ///< world, of the centre of mass
    double restitution = 0, friction = 0.5;
};

enum class JointKind { Ball, Hinge, Fixed };

struct Joint {
    JointKind kind = JointKind::Ball;
    int a = -1, b = -1;  ///< bodies; b < 0: the world
    V3 anchorA, anchorB;  ///< world, at the start
    V3 axis;              ///< world, a hinge's
    V3 normal;            ///< world, square to the axis (a hinge's reference)
    bool limited = false;
    double lower = 0, upper = 0;  ///< rad
    bool motor = false;
    double motorSpeed = 0, motorMax = 0;
    bool collide = false;  ///< the two bodies collide (else they pass through each other)
};

struct Settings {
    V3 gravity{0, -9.81, 0};
    double dt = 1.0 / 60.0;
    bool sleeping = true;
    /// 0: Jolt's defaults (10 velocity and 2 position iterations).
    int velocitySteps = 0, positionSteps = 0;
    /// Bodies to make room for (Jolt's PhysicsSystem is sized once).
    int maxBodies = 1024;
    /// Boxes and cylinders without Jolt's convex radius (its PerformanceTest's pyramid).
    bool sharpBoxes = false;
    /// Jolt at its most careful: continuous collision (EMotionQuality::LinearCast) on every
    /// dynamic body, and no angular speed limit to speak of (1e4 rad/s).
    bool careful = false;
};

/// One Jolt PhysicsSystem, single-threaded (JobSystemSingleThreaded).
class World {
public:
    explicit World(const Settings& settings);
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Adds a body; its index (the order of adding), or -1 with the reason in `why`.
    int addBody(const Body& body, std::string* why);
    bool addJoint(const Joint& joint, std::string* why);
    /// Call once all bodies are in (builds the broadphase tree, as Jolt asks).
    void ready();

    /// Adds a force and torque (world, at the centre of mass) for the next step only.
    void push(int body, const V3& force, const V3& torque);
    void step();

    /// Centre of mass, orientation (the body frame), velocity and angular velocity, world.
    void sample(int body, V3* x, Q4* q, V3* v, V3* w) const;
    /// Contact points of the manifolds found in the last step.
    int contactCount() const;

    /// "5.5.0 (single precision, ...)": what was built.
    static std::string version();

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::bench::jolt
