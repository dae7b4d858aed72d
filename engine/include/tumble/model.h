// The compiled, fixed part of a simulation: mass properties, materials and forces
// of every body, resolved from a SceneDesc once. It never changes during a run.
#pragma once

#include <tumble/collision.h>
#include <tumble/errors.h>
#include <tumble/integrators.h>
#include <tumble/key_path.h>
#include <tumble/math.h>
#include <tumble/scene.h>
#include <tumble/state.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace tumble {

/// One applied force, torque or spring, ready to evaluate.
struct ForceTerm {
    int body = 0;
    ForceType type = ForceType::Force;
    Frame frame = Frame::World;
    Vec3 vector = Vec3::Zero();
    Vec3 arm = Vec3::Zero();          ///< body frame, from the centre of mass to the point
    Vec3 anchor = Vec3::Zero();       ///< spring, world
    double stiffness = 0.0;
    double restLength = 0.0;
    double damping = 0.0;
    double start = -std::numeric_limits<double>::infinity();
    double end = std::numeric_limits<double>::infinity();

    bool activeAt(double t) const { return t >= start && t < end; }
};

/// The fixed data of one body. Mass and inertia are meaningful for dynamic bodies only;
/// static and kinematic bodies have invMass = 0 and invInertia = 0. An animated body is
/// compiled as a kinematic one with a `path`: every stage that moves nothing of its own
/// treats the two alike, and its velocities are in its state (placeOnPath).
struct BodyModel {
    std::string name;
    Motion motion = Motion::Dynamic;
    ShapeDesc shape;                      ///< as described, without meshData (the collider has the mesh)
    collision::Shape collider;            ///< the shape as the collision stages see it
    double mass = 0.0;
    double invMass = 0.0;
    Mat3 inertia = Mat3::Zero();          ///< body axes, about the centre of mass
    Mat3 invInertia = Mat3::Zero();
    Vec3 principalMoments = Vec3::Zero(); ///< eigenvalues of inertia
    Mat3 principalAxes = Mat3::Identity();///< body frame, columns are the principal axes
    bool sphericalInertia = false;        ///< I⁻¹ exactly c·1 (a ball, a cube): the same in every frame
    Vec3 centerOfMass = Vec3::Zero();     ///< body frame
    double restitution = 0.5;
    double friction = 0.5;
    double linearDamping = 0.0;
    double angularDamping = 0.0;
    int group = 0;  ///< its collision group's index (Model::groupCollides; 0: "default")
    Vec3 kinematicVelocity = Vec3::Zero();         ///< kinematic bodies: constant, world
    Vec3 kinematicAngularVelocity = Vec3::Zero();  ///< kinematic bodies: constant, world
    /// Animated bodies (motion Kinematic here): the path of the body frame its keys give.
    std::shared_ptr<const KeyPath> path;

    /// The friction and restitution of a contact on `part` (a compound's part, which may
    /// have its own; any other shape's part is 0, the body's).
    double frictionOf(int part) const {
        return collider.kind == collision::Kind::Compound ? collider.compound->parts[part].friction
                                                          : friction;
    }
    double restitutionOf(int part) const {
        return collider.kind == collision::Kind::Compound ? collider.compound->parts[part].restitution
                                                          : restitution;
    }

    /// Static, or kinematic at zero velocity: never moves, so never wakes or pairs like a moving body.
    bool standsStill() const {
        return motion == Motion::Static ||
               (motion == Motion::Kinematic && !path && kinematicVelocity.isZero(0.0) &&
                kinematicAngularVelocity.isZero(0.0));
    }

    /// A kinematic or animated body: the most |v| + |ω| r its points within `reach` of the
    /// centre of mass reach over the run.
    double topSpeed(double reach) const {
        if (path) return path->fastest(reach + centerOfMass.norm());
        return kinematicVelocity.norm() + kinematicAngularVelocity.norm() * reach;
    }
};

/// A joint's free axis as its limits, motor, spring and servo act on it: a hinge's or a
/// slider's (JointModel is one: `axis` -1) or one of a six-axis joint's (JointModel::axes).
struct JointAxis {
    int axis = -1;  ///< six-axis: 0-2 along the joint frame's x, y, z; 3-5 about them
    /// Its range (JointDesc::limits), motor, spring (JointDesc::spring) and servo
    /// (JointDesc::servo; timeConstant > 0 replaces its stiffness and damping).
    bool limited = false;
    double lower = 0.0, upper = 0.0;
    bool motor = false;
    double motorSpeed = 0.0, motorMax = 0.0;
    bool spring = false;
    double springStiffness = 0.0, springDamping = 0.0, springRest = 0.0;
    bool servo = false;
    double servoTarget = 0.0, servoMax = HUGE_VAL, servoStiffness = 0.0, servoDamping = 0.0,
           servoTimeConstant = 0.0;
    std::vector<JointDesc::ServoKey> servoKeys;  ///< its target's keys (none: servoTarget)
    /// The servo's target at time t (its keys', linear between them).
    double servoTargetAt(double t) const;
    /// Whether anything acts along it (else a free axis is just free).
    bool acted() const { return limited || motor || spring || servo; }
};

/// A joint as the solver uses it: body indices (-1: the world) and each anchor from its
/// body's centre of mass, in the body's axes (a world point for the world). A hinge's or
/// slider's free axis is its JointAxis part.
struct JointModel : JointAxis {
    std::string name;
    JointType type = JointType::Ball;
    int a = -1, b = -1;
    Vec3 anchorA = Vec3::Zero(), anchorB = Vec3::Zero();
    double length = 0.0;  ///< distance and rope
    /// Hinge and slider: unit axes in A's and B's frames (B's: the world's for the world).
    Vec3 axisA = Vec3::UnitZ(), axisB = Vec3::UnitZ();
    /// Slider and fixed: A's orientation relative to B's (B's: the world's) to keep; a
    /// hinge's angle is measured from it.
    Quat relative = Quat::Identity();
    double breakForce = HUGE_VAL;  ///< N
    bool collideConnected = false;  ///< its two bodies still collide with each other
    int index = 0;                 ///< in Model::joints
    // (What few joints have, after what every step reads.)
    /// Ball: its swing cone (half-angles towards `swingCross`, A's first frame axis across
    /// its axis as placed, and axisB × it, in B's frame)
    /// and twist range (JointDesc::swingLimit, twistLimits; joint_cone.h).
    bool swingLimited = false, twistLimited = false;
    std::array<double, 2> swingLimit{M_PI, M_PI};
    Vec3 swingCross = Vec3::UnitX();
    double twistLower = -M_PI, twistUpper = M_PI;
    /// Six-axis: the joint frame (columns x, y, z) in A's axes and in B's (the world's for
    /// the world), the same frame as the scene places the bodies; the axes held at 0 (bit i:
    /// axis i, JointAxis::axis) and the others, which may be acted on.
    Mat3 frameA = Mat3::Identity(), frameB = Mat3::Identity();
    unsigned locked = 0;
    std::vector<JointAxis> axes;
};

struct Model {
    Settings settings;
    const IntegratorInfo* integrator = nullptr;
    std::vector<BodyModel> bodies;
    std::vector<JointModel> joints;
    std::vector<std::uint8_t> jointed;  ///< per body: 1 when a joint holds it (empty: no joints)
    /// The pairs of bodies a joint joins, as sorted pair keys (pair_key.h): they do not
    /// collide with each other (a chain's links overlap at their joints).
    std::vector<std::uint64_t> jointPairs;
    /// Collision filtering (Settings::collisionGroups, groupsApart, SceneDesc::noCollide):
    /// per group, the groups it collides with as bits; the body pairs kept apart by name as
    /// sorted pair keys. `filtered`: some pair is kept apart (else every pair may collide).
    std::vector<std::uint64_t> groupCollides;
    std::vector<std::uint64_t> pairsApart;
    bool filtered = false;
    /// Whether bodies a and b may collide (their groups, the pairs kept apart; joints aside).
    bool mayCollide(int a, int b) const;
    std::vector<ForceTerm> forces;   ///< grouped by body, in scene order
    std::vector<int> dynamicBodies;  ///< indices; the only bodies forces act on
    std::vector<int> kinematicBodies;
    /// Sorted times the stepper lands on: forces' starts and ends, animated bodies' keys.
    std::vector<double> forceSwitchTimes;
    /// Things the user should know that are not errors, e.g. "bodies[3] (rock): the mesh is
    /// not closed; mass properties come from its convex hull". The CLI prints them.
    std::vector<std::string> notes;
};

/// Checks every value of a scene; throws SceneError naming the first bad field.
void validate(const SceneDesc& scene);

/// Of a frame's axes x, y, z, the first across the unit `axis` (the one most in line with
/// it left out), made square to it: a ball joint's elliptical cone's first half-angle leans
/// towards it (JointDesc::swingLimit).
Vec3 firstCrossAxis(const Vec3& axis);

/// The joints' part of validate(): throws SceneError naming joints[i].field for an empty or
/// repeated name, a body that does not exist, a joint of a body with itself, one between
/// bodies that cannot move, a non-finite anchor or length (the joint panel checks an edit
/// with it before it is applied).
void validateJoints(const SceneDesc& scene);

/// Every problem validate() would find, in the order it checks (the settings, each body,
/// the joints): the first is the one it throws. A body with several bad fields counts
/// once (its first), and so do the settings and the joints: an editor can list them all
/// for a file at once instead of one per try.
std::vector<SceneError> sceneProblems(const SceneDesc& scene);

/// Compiles a scene: validates it (throws SceneError naming the field) and resolves
/// mass properties, materials and forces.
Model compile(const SceneDesc& scene);

/// The state at t = 0 that the scene describes.
State initialState(const Model& model, const SceneDesc& scene);

/// Velocity quantities derived from a body's state (the paper's v, R, I(t)⁻¹, ω).
struct Derived {
    Mat3 R;
    Vec3 v;
    Vec3 omega;
    Mat3 invInertiaWorld;
};
Derived derive(const BodyModel& body, const BodyState& s);
/// ω of a dynamic body, bit for bit derive()'s, without the rotation matrix for a ball or a
/// cube (three equal moments: I⁻¹ is c·1 in every frame).
Vec3 angularVelocity(const BodyModel& body, const BodyState& s);

/// An animated body (BodyModel::path) where its path has it at time t: its centre x and
/// orientation q, and its centre's velocity in P and its angular velocity in L (an animated
/// body has no momentum; its state holds its motion instead).
void placeOnPath(const BodyModel& body, double t, BodyState& s);

/// World pose of the body frame (not the centre of mass): what the CSV and the viewport show.
Vec3 bodyFramePosition(const BodyModel& body, const BodyState& s);

/// Kinetic, gravitational and spring energy of the whole state (J).
struct Energy {
    double kinetic = 0.0;
    double potential = 0.0;
    double total() const { return kinetic + potential; }
};
Energy energy(const Model& model, const State& state);

}  // namespace tumble
