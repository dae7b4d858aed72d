// The scene description: what the editor edits, undoes and saves, and what the
// scene file holds. Plain values with defaults; World compiles it into a Model.
#pragma once

#include <tumble/math.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tumble {

struct TriangleMesh;  // tumble/mass.h
namespace mesh {
struct ConvexParts;  // tumble/convex_parts.h
}

/// Kinematic: moves at a constant velocity and angular velocity; animated: on the path its
/// keys give (BodyDesc::keys). Neither has mass or is moved by anything else.
enum class Motion { Dynamic, Static, Kinematic, Animated };
/// How an animated body moves between its keys (tumble/key_path.h).
enum class KeyInterpolation {
    Linear,  ///< straight at constant speed, turning at a constant rate about a fixed axis
    Smooth,  ///< C1 in position and rotation, easing in at the first key and out at the last
};
enum class ShapeType { Sphere, Box, Capsule, Cylinder, Plane, Mesh, Compound };
enum class MeshCollision { ConvexHull, Triangles, ConvexParts };
enum class ForceType { Force, Torque, Spring };
enum class Frame { World, Body };
/// When a collision of bodies that did not touch is resolved.
enum class ImpactTiming {
    Exact,      ///< at its moment: the step is cut there (bounce heights exact at any step)
    EndOfStep,  ///< at the end of the step that finds the bodies touching, as most engines do
};

const char* toString(Motion m);
const char* toString(ShapeType t);
const char* toString(MeshCollision c);
const char* toString(ForceType t);
const char* toString(Frame f);
const char* toString(ImpactTiming t);
const char* toString(KeyInterpolation k);

struct PartDesc;  // below: one part of a compound shape

/// A collision and mass shape in the body frame. Only the fields of `type` are used.
/// The axis of a capsule or cylinder is the body's y axis.
struct ShapeDesc {
    ShapeType type = ShapeType::Sphere;
    double radius = 0.5;                         ///< sphere, capsule, cylinder (m)
    double halfHeight = 0.5;                     ///< capsule, cylinder: half the segment (m)
    Vec3 halfExtents = Vec3(0.5, 0.5, 0.5);      ///< box (m)
    Vec3 normal = Vec3(0, 1, 0);                 ///< plane, unit length after loading
    double distance = 0.0;                       ///< plane: free side is n·p > distance (m)
    std::string file;                            ///< mesh, relative to the scene file
    Vec3 scale = Vec3(1, 1, 1);                  ///< mesh
    MeshCollision collision = MeshCollision::ConvexHull;  ///< mesh
    int maxParts = 16;                                    ///< mesh, convex-parts: at most this many parts
    /// Mesh, convex-parts: how far a part may reach out of the solid (m); absent: 1 % of the
    /// mesh's bounding-box diagonal.
    std::optional<double> partsTolerance;
    /// Mesh: the triangles of `file` as read, scaled, in the body frame. Filled by the scene
    /// loader (io::readSceneFile), or by code that builds a scene; never saved. compile()
    /// refuses a mesh body without it. Shared, so copies of a scene are cheap.
    std::shared_ptr<const TriangleMesh> meshData;
    /// Mesh, convex-parts: the parts, made from meshData with maxParts and partsTolerance
    /// (mesh::convexPartsFit), by the scene loader from the sidecar cache or by the editor in
    /// the background; never saved in the scene. compile() makes them itself when they are
    /// absent or were made from another mesh or options (seconds for a large mesh).
    std::shared_ptr<const mesh::ConvexParts> convexParts;
    /// Compound: the parts, each a shape of its own (any but a plane or a compound) placed
    /// in the body frame (docs/scene-format.md "Compound bodies").
    std::vector<PartDesc> parts;

    /// Compares what the file holds: meshData follows from file and scale, so it is left out.
    bool operator==(const ShapeDesc& o) const;
};

/// One part of a compound shape: its shape placed in the body frame, and what it is made
/// of when that differs from the body.
struct PartDesc {
    std::string name;                     ///< optional; shown by the editor
    ShapeDesc shape;                      ///< in the part's frame
    Vec3 position = Vec3::Zero();         ///< of the part's frame in the body frame
    Quat orientation = Quat::Identity();  ///< part to body
    std::optional<double> density;   ///< kg/m³; absent: the body's density, or a share of its mass by volume
    std::optional<double> friction;  ///< absent: the body's
    std::optional<double> restitution;  ///< absent: the body's

    bool operator==(const PartDesc& o) const;
};

/// A force, torque or spring acting on one body while start <= t < end.
struct ForceDesc {
    ForceType type = ForceType::Force;
    Vec3 vector = Vec3::Zero();                  ///< force (N) or torque (N m)
    std::optional<Vec3> point;                   ///< force, spring: body frame; default the centre of mass
    Frame frame = Frame::World;                  ///< frame in which `vector` is given
    Vec3 anchor = Vec3::Zero();                  ///< spring: fixed world point (m)
    double stiffness = 0.0;                      ///< spring: N/m
    double restLength = 0.0;                     ///< spring: m
    double damping = 0.0;                        ///< spring: N s/m along the spring
    std::optional<double> start;                 ///< s; absent: from the beginning
    std::optional<double> end;                   ///< s; absent: to the end

    bool operator==(const ForceDesc&) const = default;
};

/// One key of an animated body: where its frame is (as BodyDesc::position and orientation)
/// at `time`.
struct BodyKey {
    double time = 0.0;                    ///< s
    Vec3 position = Vec3::Zero();         ///< world position of the body frame origin
    Quat orientation = Quat::Identity();  ///< body to world

    bool operator==(const BodyKey& o) const {
        return time == o.time && position == o.position && orientation.coeffs() == o.orientation.coeffs();
    }
};

struct BodyDesc {
    std::string name;
    Motion motion = Motion::Dynamic;
    ShapeDesc shape;
    std::optional<double> mass;                  ///< kg; exactly one of mass, density
    std::optional<double> density;               ///< kg/m³
    std::optional<Mat3> inertia;                 ///< about the centre of mass, body axes
    std::optional<Vec3> centerOfMass;            ///< body frame
    Vec3 position = Vec3::Zero();                ///< world position of the body frame origin
    Quat orientation = Quat::Identity();         ///< body to world
    Vec3 velocity = Vec3::Zero();                ///< world velocity of the centre of mass
    Vec3 angularVelocity = Vec3::Zero();         ///< world frame, rad/s
    double restitution = 0.5;
    double friction = 0.5;
    double linearDamping = 0.0;                  ///< 1/s
    double angularDamping = 0.0;                 ///< 1/s
    std::vector<ForceDesc> forces;
    /// The collision group it is in (Settings::collisionGroups; "default" is always one).
    std::string collisionGroup = "default";
    /// Animated bodies: the keys, times strictly increasing (held before the first and after
    /// the last); `position` and `orientation` are where the editor shows it at rest.
    std::vector<BodyKey> keys;
    KeyInterpolation interpolation = KeyInterpolation::Linear;

    bool operator==(const BodyDesc& o) const;
};

/// Calls visit(shape, path) for a body's shape and, when it is a compound, for each part's
/// shape, with the path of each ("bodies[2].shape", "bodies[2].shape.parts[1].shape" for
/// `bodyPath` "bodies[2]"): what a loader of mesh files or an exporter of shapes goes over.
/// (Works for a const body too.)
template <class Body, class Visit>
void forEachShape(Body& body, const std::string& bodyPath, Visit&& visit) {
    visit(body.shape, bodyPath + ".shape");
    for (size_t j = 0; j < body.shape.parts.size(); ++j)
        visit(body.shape.parts[j].shape, bodyPath + ".shape.parts[" + std::to_string(j) + "].shape");
}

struct Settings {
    Vec3 gravity = Vec3(0, -9.81, 0);
    double dt = 1.0 / 240.0;
    double duration = 5.0;
    std::string integrator;                      ///< empty: the engine's default
    double frameRate = 60.0;
    bool sleeping = true;         ///< bodies at rest fall asleep (off: every body always simulated)
    int solverIterations = 20;    ///< velocity iterations of the contact solver per step
    /// Stop a run whose energy runs away (an unstable step), naming the body, the time and
    /// the likely cause; off: only a non-finite state stops it.
    bool energyGuard = true;
    /// Exact: each impact at its moment (up to 8 a step). EndOfStep: impacts found touching
    /// at the end of the step are resolved there, overlapping by up to the distance closed
    /// in a step; only bodies whose paths crossed without touching at the end (a fast body
    /// through a thin one) still cut the step. Much faster in big piles; bounces first order.
    ImpactTiming impacts = ImpactTiming::Exact;
    /// Named collision groups (at most 64 with "default", which is always one, listed or
    /// not): each body is in one (BodyDesc::collisionGroup).
    std::vector<std::string> collisionGroups;
    /// Pairs of groups whose bodies do not collide (a group with itself: its bodies pass
    /// through each other); every other pair of groups collides.
    std::vector<std::array<std::string, 2>> groupsApart;

    bool operator==(const Settings&) const = default;
};

/// The step a run takes between two frames (where no force switches on or off): a frame,
/// 1 / frame_rate, split into the fewest equal steps no longer than dt. It is dt when dt
/// divides a frame, a little shorter otherwise, and a whole frame when dt is longer than
/// one: the step is capped by the frame rate. (engine/src/world/simulate.cpp)
double stepUsed(const Settings& settings);
/// How many steps a frame takes (stepUsed's divisor).
long stepsPerFrame(const Settings& settings);
/// One line saying what the step is when it is not dt ("" when it is), for the command
/// line's notes, a sweep and the editor's settings: "settings.dt 0.0333 s is longer than a
/// frame (1/60 s): each frame is one step of 0.0166667 s; ...".
std::string stepNote(const Settings& settings);

/// A joint between two bodies, or a body and the world (issue 20; the design is in
/// docs/architecture.md "Joints", the file's `joints` in docs/scene-format.md). Built so
/// far: ball (the anchors held together), distance (a rigid rod between the anchors), rope
/// (the anchors at most `length` apart: it only pulls), hinge (the anchors together and the
/// axes in line: it turns about the axis only), slider (the two bodies keep their relative
/// orientation and A's anchor stays on the line through B's along the axis: it slides
/// along the axis only) and fixed (the two keep their relative pose: one rigid body).
enum class JointType { Ball, Distance, Rope, Hinge, Slider, Fixed, SixAxis };
const char* toString(JointType t);

struct JointDesc {
    std::string name;
    JointType type = JointType::Ball;
    std::string bodyA;             ///< a body's name
    std::string bodyB;             ///< another body's name; empty: the world
    Vec3 anchorA = Vec3::Zero();   ///< in bodyA's frame (the frame `position` and `orientation` place)
    Vec3 anchorB = Vec3::Zero();   ///< in bodyB's frame; a world point when bodyB is the world
    /// Distance and rope: the length (m); negative: the anchors' distance in the scene.
    double length = -1.0;
    /// Hinge and slider: the axis in bodyA's frame (any length but zero), and in bodyB's
    /// frame (the world's without bodyB); no axisB: axisA as it lies at the start.
    std::optional<Vec3> axisA, axisB;
    /// Hinge and slider: the range of the joint's coordinate, lower ≤ upper: the hinge's
    /// angle about its axis (rad, within [-π, π], 0 as the scene places the bodies, positive
    /// by the right hand about A's axis) or the slider's offset of A's anchor from B's along
    /// the axis (m). A stop is inelastic.
    std::optional<std::array<double, 2>> limits;
    /// Ball: a swing cone about B's axis (`axisB`, or `axisA` as placed) that A's axis stays
    /// in, as half-angles (rad, in (0, π)) towards A's first frame axis across its axis (of
    /// x, y, z, the one most in line with the axis left out; as the scene places A) and
    /// towards the axis × that one (equal: a circular cone), and the range of A's twist about
    /// its axis relative to B (rad, within [−π, π], 0 as placed). Both need `axisA`.
    std::optional<std::array<double, 2>> swingLimit;
    std::optional<std::array<double, 2>> twistLimits;
    /// Hinge and slider: drives the coordinate's rate towards `speed` (rad/s or m/s) with
    /// at most `maxForce` (N m for a hinge, N for a slider).
    struct Motor {
        double speed = 0.0;
        double maxForce = 0.0;
        bool operator==(const Motor&) const = default;
    };
    std::optional<Motor> motor;
    /// Hinge and slider: a spring and damper on the coordinate, pulling it towards `rest`
    /// with stiffness × (rest − coordinate) − damping × rate (N m/rad and N m s/rad for a
    /// hinge, N/m and N s/m for a slider). Solved implicitly in the step: stable at any
    /// stiffness and step (docs/architecture.md "Joint springs and servos").
    struct Spring {
        double stiffness = 0.0;
        double damping = 0.0;
        double rest = 0.0;
        bool operator==(const Spring&) const = default;
    };
    std::optional<Spring> spring;
    /// Hinge and slider: a position motor that drives the coordinate to `target` (rad or m)
    /// with at most `maxForce` (N m or N; infinite: no bound), either as a spring and damper
    /// of the given `stiffness` and `damping` or, with `timeConstant` (s) > 0, critically
    /// damped with that time constant whatever the bodies' masses.
    /// With `keys`, the target moves: at each key's time it is the key's, linear between
    /// keys, the first's before them and the last's after (a robot's program).
    struct ServoKey {
        double time = 0.0;
        double target = 0.0;
        bool operator==(const ServoKey&) const = default;
    };
    struct Servo {
        double target = 0.0;
        double maxForce = HUGE_VAL;
        double stiffness = 0.0, damping = 0.0;
        double timeConstant = 0.0;  ///< > 0: used instead of stiffness and damping
        std::vector<ServoKey> keys;  ///< none: `target` throughout
        bool operator==(const Servo&) const = default;
    };
    std::optional<Servo> servo;
    /// Six-axis: one of its six axes (x, y, z: A's anchor's offset from B's along the joint
    /// frame's axes, m; rx, ry, rz: the turn of A's frame from B's about them, rad, as the
    /// components of its rotation vector). Locked (held at 0) unless `free`; a free axis may
    /// have limits, a motor, a spring and a servo, as a hinge's or slider's coordinate.
    struct Axis {
        bool free = false;
        std::optional<std::array<double, 2>> limits;
        std::optional<Motor> motor;
        std::optional<Spring> spring;
        std::optional<Servo> servo;
        bool operator==(const Axis&) const = default;
    };
    /// Six-axis: x, y, z, rx, ry, rz. The joint frame's x is `axisA` (default body_a's x), its
    /// y the first of body_a's frame axes across it (made square), z = x × y; B's frame is A's
    /// as the scene places the bodies.
    std::array<Axis, 6> axes;
    /// Any joint: it breaks (for good, at the end of the step) when the force it carries
    /// passes this (N); none: it never breaks.
    std::optional<double> breakForce;
    /// The two bodies still collide with each other (false: a joint's bodies pass through
    /// each other, as a chain's links overlap at their joints).
    bool collideConnected = false;

    bool operator==(const JointDesc&) const = default;
};

struct SceneDesc {
    Settings settings;
    std::vector<BodyDesc> bodies;
    std::vector<JointDesc> joints;
    /// Pairs of bodies (by name) that do not collide, whatever their groups.
    std::vector<std::array<std::string, 2>> noCollide;

    bool operator==(const SceneDesc&) const = default;
};

}  // namespace tumble
