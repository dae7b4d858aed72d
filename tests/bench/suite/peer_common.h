// What the three peer adapters (Bullet, ODE, MuJoCo) share: the scene compiled by Tumble
// itself, so every engine simulates bodies with the same mass, inertia and centre of mass,
// the checks that refuse what no peer translates, and the applied forces evaluated the way
// Tumble's force stage does (forces.cpp), so each peer gets them as plain force and torque
// at the centre of mass.
#pragma once

#include <tumble/model.h>
#include <tumble/scene.h>

#include <string>
#include <vector>

namespace tumble::bench::peer {

/// The compiled scene and, per body, the pose and velocity at t = 0 as the peers want them.
struct PeerScene {
    SceneDesc scene;
    Model model;
    std::vector<Vec3> com;  ///< world centre of mass at t = 0
    std::vector<Quat> q;    ///< body to world at t = 0 (Tumble's body frame)
    std::vector<Vec3> v;    ///< world velocity of the centre of mass at t = 0
    std::vector<Vec3> w;    ///< world angular velocity at t = 0
};

/// What a peer can translate; the rest is refused with a reason.
struct PeerCaps {
    bool movingKinematic = false;  ///< kinematic bodies with a velocity
    bool meshTriangles = false;    ///< MeshCollision::Triangles on a static body
    /// The joint types this peer translates (bit 1 << JointType), and which of a joint's
    /// options: hinge and slider limits, motors, breaking.
    unsigned jointTypes = 0;
    bool jointLimits = false, jointMotors = false, jointBreaking = false;
    bool compounds = false;  ///< ShapeType::Compound (several shapes on one body)
    bool ballLimits = false;  ///< a ball joint's swing cone and twist range
    /// A hinge's servo by its time constant, driven as Tumble's through the peer's velocity
    /// motor (servoSpeed, each step).
    bool hingeServos = false;
};

/// The rate a hinge's servo by its time constant τ asks of the peer's velocity motor for the
/// step from t to t + h, its coordinate c and rate v now: the rate at t + h of the critically
/// damped path from (c − target(t + h), v), as Tumble's servo row (joint_drive.h) follows it.
double servoSpeed(const JointModel& j, double c, double v, double t, double h);

constexpr unsigned jointBit(JointType t) { return 1u << static_cast<unsigned>(t); }

/// Compiles the scene with Tumble (so mass properties are Tumble's) and refuses, with the
/// reason in `why`, what the peers do not translate: springs, planes on moving bodies,
/// triangle meshes on moving bodies, and whatever `caps` leaves out (a joint type or a
/// joint's option is named with the joint).
bool prepare(const SceneDesc& scene, const PeerCaps& caps, PeerScene* out, std::string* why);

/// Joint j's anchors in the world at t = 0 (on A, and on B or the world) and its axis in
/// the world as A carries it (hinge and slider; else zero).
void jointStart(const PeerScene& ps, const JointModel& j, Vec3* anchorA, Vec3* anchorB, Vec3* axis);

/// A unit vector square to the unit vector `axis`.
Vec3 anyPerpendicular(const Vec3& axis);

/// True for a body that never moves: static, or kinematic at zero velocity.
bool standsStill(const BodyModel& b);

/// The sum of body `i`'s applied forces and damping at time t, as a force at the centre of
/// mass and a torque about it, both world: Tumble's force stage (constant force or torque,
/// world or body frame, at a point; damping -c P and -c L). Gravity is left to the engine.
/// `q` is the body's orientation, `v` and `w` its velocities.
void appliedLoad(const Model& model, int i, double t, const Quat& q, const Vec3& v, const Vec3& w,
                 Vec3* force, Vec3* torque);

/// True when some dynamic body has an applied force, torque or damping.
bool hasLoads(const Model& model);

/// A world plane n·p = d from a static plane body's shape and pose.
void worldPlane(const BodyModel& b, const Vec3& position, const Quat& q, Vec3* n, double* d);

/// The rotation that takes z onto y: ODE and MuJoCo put the axis of a capsule or cylinder
/// on z, Tumble on y.
Quat zToY();

}  // namespace tumble::bench::peer
