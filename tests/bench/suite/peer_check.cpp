// tumble_peer_check: each peer adapter (Bullet, ODE, MuJoCo) in each of its modes against
// closed forms, so a wrong convention in an adapter (quaternion order, body-frame angular
// velocity, centre-of-mass offset, combine rules) shows before the benchmark measures it.
//
//   free fall    a sphere thrown up and sideways, 1 s at dt = 1/240: position against the
//                closed form. A semi-implicit (symplectic) Euler step is exact for the
//                discrete recurrence x_n = x0 + n dt v0 + g dt^2 n(n+1)/2, RK4 for
//                x0 + v0 t + g t^2 / 2; each mode is checked against its own (1e-9 relative)
//                and the error against the continuous form is printed.
//   spin         a box with an offset centre of mass, tilted, spinning near its major axis
//                without gravity, 2 s: the centre of mass stays put (1e-9 m), |L| and the
//                kinetic energy stay within 2 % (modes without a gyroscopic term: printed,
//                not checked; they do not conserve L).
//   bounce       a ball dropped from 1 m onto a plane, both restitution 0.5: the first apex
//                after the bounce at e^2 h = 0.25 m within 5 % (MuJoCo, soft contacts: 30 %;
//                Bullet's modes with speculative contacts lose the bounce: not checked).
//   rest         a cylinder, a capsule, a turned box and an off-centre convex hull resting on
//                a plane: centre-of-mass heights within 5 mm (shape axes and offsets).
//   joints       a ball (r 0.1 m, 1 kg) on a ball joint 1 m below a fixed point, let go at
//                0.1 rad: the period between the first and third crossings of the vertical
//                against 2 pi sqrt(I_p / m g L) = 2.0101 s within 1 % (anchor frames); a bar
//                hinged at one end to the world, level, gravity turning it to negative angles:
//                with limits [-1, 0] it stops at -1 rad, with [0, 1] it stays at 0 (within
//                0.1 rad after 2 s: the sign and zero of the hinge angle). A peer that does not
//                translate limits prints n/a for the second, not a failure. The same bar
//                lifted by a servo by its time constant to +0.5 rad: there within 0.02 rad
//                after 2 s, never past it by more (a peer without servos: n/a); a ball
//                joint's swing cone of 0.5 rad holding a bob pushed at 4 m/s (within 0.05).
//
// Prints a table; exits 1 when a check fails, 2 when no peer was built.
#include "engine_adapter.h"

#include <tumble/mass.h>
#include <tumble/model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

using namespace tumble;
using namespace tumble::bench;

namespace {

constexpr double kDt = 1.0 / 240.0;
const Vec3 kG(0.0, -9.81, 0.0);

SceneDesc freeFallScene() {
    SceneDesc s;
    s.settings.gravity = kG;
    s.settings.sleeping = false;
    BodyDesc b;
    b.name = "ball";
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = 0.5;
    b.mass = 2.0;
    b.position = Vec3(1.0, 10.0, -2.0);
    b.velocity = Vec3(1.5, 4.0, 0.5);
    s.bodies.push_back(b);
    return s;
}

SceneDesc spinScene() {
    SceneDesc s;
    s.settings.gravity = Vec3::Zero();
    s.settings.sleeping = false;
    BodyDesc b;
    b.name = "box";
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = Vec3(0.5, 0.3, 0.1);
    b.mass = 3.0;
    b.centerOfMass = Vec3(0.1, -0.05, 0.02);
    b.position = Vec3(0.5, 2.0, 0.0);
    b.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    b.angularVelocity = b.orientation * Vec3(0.3, 0.2, 6.0);  // near the body's z, its major axis
    s.bodies.push_back(b);
    return s;
}

SceneDesc bounceScene() {
    SceneDesc s;
    s.settings.gravity = kG;
    s.settings.sleeping = false;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.shape.normal = Vec3(0, 1, 0);
    ground.shape.distance = 0.0;
    ground.restitution = 0.5;
    ground.friction = 0.5;
    s.bodies.push_back(ground);
    BodyDesc ball;
    ball.name = "ball";
    ball.shape.type = ShapeType::Sphere;
    ball.shape.radius = 0.5;
    ball.mass = 1.0;
    ball.position = Vec3(0.0, 1.5, 0.0);  // 1 m of clearance
    ball.restitution = 0.5;
    ball.friction = 0.5;
    s.bodies.push_back(ball);
    return s;
}

// Four shapes resting on a plane, spaced apart: an upright cylinder (r 0.3, half height 0.6),
// an upright capsule (r 0.2, half height 0.4), a box turned a quarter about x, and a convex
// hull of an off-centre box mesh (0..1 x 0..0.5 x 0..0.8 in the body frame). A wrong axis
// (z for y) or a wrong centre-of-mass offset puts a body at another height.
SceneDesc restScene() {
    SceneDesc s;
    s.settings.gravity = kG;
    s.settings.sleeping = false;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.restitution = 0.0;
    s.bodies.push_back(ground);
    auto add = [&](const char* name, const ShapeDesc& shape, const Vec3& at, const Quat& q) {
        BodyDesc b;
        b.name = name;
        b.shape = shape;
        b.mass = 1.0;
        b.position = at;
        b.orientation = q;
        b.restitution = 0.0;
        s.bodies.push_back(b);
    };
    ShapeDesc cyl;
    cyl.type = ShapeType::Cylinder;
    cyl.radius = 0.3;
    cyl.halfHeight = 0.6;
    add("cylinder", cyl, Vec3(-3, 0.61, 0), Quat::Identity());
    ShapeDesc cap;
    cap.type = ShapeType::Capsule;
    cap.radius = 0.2;
    cap.halfHeight = 0.4;
    add("capsule", cap, Vec3(0, 0.61, 0), Quat::Identity());
    ShapeDesc box;
    box.type = ShapeType::Box;
    box.halfExtents = Vec3(0.5, 0.2, 0.35);
    add("box", box, Vec3(3, 0.36, 0), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())));
    auto mesh = std::make_shared<TriangleMesh>();
    for (int k = 0; k < 8; ++k)
        mesh->vertices.emplace_back(k & 1 ? 1.0 : 0.0, k & 2 ? 0.5 : 0.0, k & 4 ? 0.8 : 0.0);
    // Counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z.
    const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces) {
        mesh->triangles.push_back({f[0], f[1], f[2]});
        mesh->triangles.push_back({f[0], f[2], f[3]});
    }
    ShapeDesc hull;
    hull.type = ShapeType::Mesh;
    hull.file = "offset-box.obj";
    hull.meshData = mesh;
    add("hull", hull, Vec3(6, 0.01, 0), Quat::Identity());
    return s;
}

struct Row {
    std::string engine, mode;
    std::string fall, spin, bounce, rest, joints;
    bool ok = true;
};

// A ball hung on a ball joint 1 m below the world point (0, 3, 0), let go at `angle` in the
// x-y plane.
SceneDesc ballPendulum(double angle) {
    SceneDesc s;
    s.settings.gravity = kG;
    s.settings.sleeping = false;
    BodyDesc b;
    b.name = "bob";
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = 0.1;
    b.mass = 1.0;
    b.position = Vec3(0, 3, 0) + Vec3(std::sin(angle), -std::cos(angle), 0.0);
    s.bodies.push_back(b);
    JointDesc j;
    j.name = "pivot";
    j.type = JointType::Ball;
    j.bodyA = "bob";
    j.anchorA = Vec3(-std::sin(angle), std::cos(angle), 0.0);
    j.anchorB = Vec3(0, 3, 0);
    s.joints.push_back(j);
    return s;
}

// A 1 m bar (1 kg) level along x, hinged at its -x end to the world about z, with limits.
SceneDesc limitedBar(double lower, double upper) {
    SceneDesc s;
    s.settings.gravity = kG;
    s.settings.sleeping = false;
    BodyDesc b;
    b.name = "bar";
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = Vec3(0.5, 0.05, 0.05);
    b.mass = 1.0;
    b.position = Vec3(0.5, 3, 0);
    s.bodies.push_back(b);
    JointDesc j;
    j.name = "hinge";
    j.type = JointType::Hinge;
    j.bodyA = "bar";
    j.anchorA = Vec3(-0.5, 0, 0);
    j.anchorB = Vec3(0, 3, 0);
    j.axisA = Vec3(0, 0, 1);
    j.limits = std::array<double, 2>{lower, upper};
    s.joints.push_back(j);
    return s;
}


std::string fmt(const char* f, double a, double b = 0.0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, f, a, b);
    return buf;
}

// Free fall: the error against the form this mode integrates exactly.
std::string checkFall(EngineAdapter& e, const std::string& mode, bool* ok) {
    const SceneDesc scene = freeFallScene();
    std::string why;
    if (!e.load(scene, mode, kDt, &why)) {
        *ok = false;
        return "refused: " + why;
    }
    const int n = 240;
    for (int k = 0; k < n; ++k) e.step();
    const BodySample s = e.body(0);
    const BodyDesc& b = scene.bodies[0];
    const double t = n * kDt;
    const Vec3 exact = b.position + b.velocity * t + 0.5 * kG * t * t;
    const Vec3 discrete = b.position + b.velocity * t + 0.5 * kG * kDt * kDt * double(n) * double(n + 1);
    const double errExact = (s.x - exact).norm() / exact.norm();
    const double errDiscrete = (s.x - discrete).norm() / discrete.norm();
    const bool rk4 = mode == "rk4";
    const double err = rk4 ? errExact : errDiscrete;
    const double errV = (s.v - (b.velocity + kG * t)).norm() / (b.velocity + kG * t).norm();
    if (!(err <= 1e-9) || !(errV <= 1e-9)) *ok = false;
    return fmt(rk4 ? "exact %.1e" : "euler %.1e", err) + fmt(" (vs t^2/2 %.1e)", errExact);
}

std::string checkSpin(EngineAdapter& e, const std::string& mode, bool* ok) {
    const SceneDesc scene = spinScene();
    std::string why;
    if (!e.load(scene, mode, kDt, &why)) {
        *ok = false;
        return "refused: " + why;
    }
    const BodyModel bm = compile(scene).bodies[0];
    auto momentum = [&](const BodySample& s) {
        const Mat3 R = s.q.toRotationMatrix();
        return Vec3(R * bm.inertia * R.transpose() * s.w);
    };
    const BodySample s0 = e.body(0);
    const Vec3 com0 = scene.bodies[0].position + scene.bodies[0].orientation * bm.centerOfMass;
    const Vec3 L0 = momentum(s0);
    const double E0 = 0.5 * s0.w.dot(L0);
    const double L0exact = (scene.bodies[0].orientation * bm.inertia *
                            scene.bodies[0].orientation.conjugate() * scene.bodies[0].angularVelocity)
                               .norm();
    double worstL = std::abs(L0.norm() - L0exact) / L0exact, worstE = 0.0, worstX = (s0.x - com0).norm();
    for (int k = 0; k < 480; ++k) {
        e.step();
        const BodySample s = e.body(0);
        const Vec3 L = momentum(s);
        worstL = std::max(worstL, std::abs(L.norm() - L0exact) / L0exact);
        worstE = std::max(worstE, std::abs(0.5 * s.w.dot(L) - E0) / E0);
        worstX = std::max(worstX, (s.x - com0).norm());
        if (!std::isfinite(L.norm())) worstL = INFINITY;
    }
    const bool gyro = mode.find("nogyro") == std::string::npos && mode != "no-gyro";
    if (!(worstX <= 1e-9)) *ok = false;
    if (gyro && !(worstL <= 0.02 && worstE <= 0.02)) *ok = false;
    return fmt("|L| %.1e E %.1e", worstL, worstE) + fmt(" x %.0e", worstX) + (gyro ? "" : " (no gyro)");
}

std::string checkBounce(EngineAdapter& e, const std::string& mode, bool* ok) {
    const SceneDesc scene = bounceScene();
    std::string why;
    if (!e.load(scene, mode, kDt, &why)) {
        *ok = false;
        return "refused: " + why;
    }
    const double r = scene.bodies[1].shape.radius;
    bool bounced = false;
    double apex = -1.0, prevV = 0.0;
    int contacts = 0;
    for (int k = 0; k < 3 * 240; ++k) {
        e.step();
        const BodySample s = e.body(1);
        contacts = std::max(contacts, e.contactCount());
        if (!bounced && s.v.y() > 0.0) bounced = true;
        if (bounced && prevV > 0.0 && s.v.y() <= 0.0) {
            apex = s.x.y() - r;
            break;
        }
        prevV = s.v.y();
    }
    const double ratio = apex / 1.0;
    // MuJoCo's contact is a spring-damper resolved over 8 steps at this dt (peer_mujoco.cpp):
    // its bounce converges to e only as dt shrinks, so it gets a wider band.
    const double tolerance = e.name() == "mujoco" ? 0.30 : 0.05;
    // Bullet's speculative contacts (all its modes but touching-contacts) stop a falling ball
    // at the surface and lose the bounce (peer_bullet.cpp): printed, not checked.
    const bool speculative = e.name() == "bullet" && mode != "touching-contacts";
    if (contacts < 1 || (!speculative && !(std::abs(ratio - 0.25) <= tolerance * 0.25))) *ok = false;
    return fmt("apex %.4f h (%+.1f %%)", ratio, 100.0 * (ratio / 0.25 - 1.0)) +
           (speculative ? std::string(" speculative") : fmt(" contacts %g", contacts));
}

// Heights of the centres of mass after 1.5 s at rest: cylinder 0.6, capsule 0.6, box 0.35
// (its z half extent, turned onto y), hull 0.25; within 5 mm.
std::string checkRest(EngineAdapter& e, const std::string& mode, bool* ok) {
    const SceneDesc scene = restScene();
    std::string why;
    if (!e.load(scene, mode, kDt, &why)) {
        *ok = false;
        return "refused: " + why;
    }
    for (int k = 0; k < 360; ++k) e.step();
    const double want[] = {0.6, 0.6, 0.35, 0.25};
    double worst = 0.0;
    int which = 0;
    for (int i = 0; i < 4; ++i) {
        const double err = std::abs(e.body(i + 1).x.y() - want[i]);
        if (!(err <= worst)) which = i + 1;
        worst = std::isfinite(err) ? std::max(worst, err) : INFINITY;
    }
    if (!(worst <= 5e-3)) *ok = false;
    return fmt("height %.1e m", worst) + " (" + scene.bodies[which].name + ")";
}

std::string checkJoints(EngineAdapter& e, const std::string& mode, bool* ok) {
    std::string why;
    if (!e.load(ballPendulum(0.1), mode, kDt, &why)) {
        *ok = false;
        return "refused: " + why;
    }
    // The times the bob crosses the vertical below the pivot (x = 0), interpolated.
    std::vector<double> crossings;
    double lastX = e.body(0).x.x();
    for (int k = 0; k < 4 * 240 && crossings.size() < 3; ++k) {
        e.step();
        const double x = e.body(0).x.x();
        if ((lastX > 0.0) != (x > 0.0)) crossings.push_back(e.time() - kDt * x / (x - lastX));
        lastX = x;
    }
    const double want = 2.0 * M_PI * std::sqrt((0.4 * 0.01 + 1.0) / 9.81);
    const double period = crossings.size() == 3 ? crossings[2] - crossings[0] : NAN;
    const double err = period / want - 1.0;
    if (!(std::abs(err) <= 0.01)) *ok = false;
    std::string out = fmt("period %+.2f %%", 100.0 * err);
    // The hinge's angle: the bar's direction about z after 2 s.
    double angles[2] = {NAN, NAN};
    const double limits[2][2] = {{-1.0, 0.0}, {0.0, 1.0}};
    for (int c = 0; c < 2; ++c) {
        if (!e.load(limitedBar(limits[c][0], limits[c][1]), mode, kDt, &why)) return out + ", limits n/a";
        for (int k = 0; k < 2 * 240; ++k) e.step();
        const Vec3 dir = e.body(0).q * Vec3::UnitX();
        angles[c] = std::atan2(dir.y(), dir.x());
    }
    if (!(std::abs(angles[0] + 1.0) <= 0.1) || !(std::abs(angles[1]) <= 0.1)) *ok = false;
    out += fmt(", limits at %+.2f and %+.2f rad", angles[0], angles[1]);
    // A servo by its time constant (0.1 s, at most 50 N m) lifting the bar to +0.5 rad
    // against gravity: at 0.5 after 2 s, never past it (within 0.02 rad).
    SceneDesc servo = limitedBar(0.0, 0.0);
    servo.joints[0].limits.reset();
    JointDesc::Servo drive;
    drive.target = 0.5;
    drive.maxForce = 50.0;
    drive.timeConstant = 0.1;
    servo.joints[0].servo = drive;
    if (!e.load(servo, mode, kDt, &why)) return out + ", servo n/a";
    double most = -INFINITY, angle = NAN;
    for (int k = 0; k < 2 * 240; ++k) {
        e.step();
        const Vec3 dir = e.body(0).q * Vec3::UnitX();
        angle = std::atan2(dir.y(), dir.x());
        most = std::max(most, angle);
    }
    if (!(std::abs(angle - 0.5) <= 0.02) || !(most <= 0.52)) *ok = false;
    out += fmt(", servo at %+.3f (most %+.3f) rad", angle, most);
    // A swing cone of 0.5 rad about the bob's hanging axis: pushed at 4 m/s (free, it would
    // swing to 1.4 rad), it stays in the cone (within 0.05 rad over 2 s).
    SceneDesc cone = ballPendulum(0.0);
    cone.joints[0].axisA = Vec3::UnitY();
    cone.joints[0].swingLimit = std::array<double, 2>{0.5, 0.5};
    cone.bodies[0].velocity = Vec3(4, 0, 0);
    if (!e.load(cone, mode, kDt, &why)) return out + ", cone n/a";
    double swing = 0.0;
    for (int k = 0; k < 2 * 240; ++k) {
        e.step();
        swing = std::max(swing, std::acos(std::clamp((e.body(0).q * Vec3::UnitY()).y(), -1.0, 1.0)));
    }
    if (!(swing <= 0.55) || !(swing > 0.4)) *ok = false;
    return out + fmt(", cone 0.5: most %.3f rad", swing);
}

}  // namespace

int main() {
    struct Peer {
        const char* name;
        std::function<std::unique_ptr<EngineAdapter>()> make;
    };
    const std::vector<Peer> peers = {
        {"bullet", makeBulletAdapter}, {"ode", makeOdeAdapter}, {"mujoco", makeMujocoAdapter}, {"jolt", makeJoltAdapter}};
    std::vector<Row> rows;
    int built = 0;
    for (const Peer& p : peers) {
        auto e = p.make();
        if (!e) {
            std::printf("%-7s not built\n", p.name);
            continue;
        }
        ++built;
        for (const std::string& mode : e->modes()) {
            Row row{e->name(), mode, "", "", "", "", "", true};
            row.fall = checkFall(*e, mode, &row.ok);
            row.spin = checkSpin(*e, mode, &row.ok);
            row.bounce = checkBounce(*e, mode, &row.ok);
            row.rest = checkRest(*e, mode, &row.ok);
            row.joints = checkJoints(*e, mode, &row.ok);
            rows.push_back(row);
        }
    }
    std::printf("%-7s %-20s %-36s %-40s %-34s %-28s %-44s\n", "engine", "mode", "free fall (rel. error)",
                "spin (worst drift)", "bounce e=0.5 (apex / h, want 0.25)", "rest (worst height error)",
                "joints (period; hinge limits -1 and 0)");
    bool all = true;
    for (const Row& r : rows) {
        std::printf("%-7s %-20s %-36s %-40s %-34s %-28s %-44s %s\n", r.engine.c_str(), r.mode.c_str(),
                    r.fall.c_str(), r.spin.c_str(), r.bounce.c_str(), r.rest.c_str(), r.joints.c_str(),
                    r.ok ? "ok" : "FAIL");
        all = all && r.ok;
    }
    if (built == 0) return 2;
    return all ? 0 : 1;
}
