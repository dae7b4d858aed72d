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
//                after the bounce at e^2 h = 0.25 m within 5 %.
//
// Prints a table; exits 1 when a check fails, 2 when no peer was built.
#include "engine_adapter.h"

#include <tumble/model.h>

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

struct Row {
    std::string engine, mode;
    std::string fall, spin, bounce;
    bool ok = true;
};

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
    if (!(std::abs(ratio - 0.25) <= 0.05 * 0.25) || contacts < 1) *ok = false;
    return fmt("apex %.4f h (%+.1f %%)", ratio, 100.0 * (ratio / 0.25 - 1.0)) + fmt(" contacts %g", contacts);
}

}  // namespace

int main() {
    struct Peer {
        const char* name;
        std::function<std::unique_ptr<EngineAdapter>()> make;
    };
    const std::vector<Peer> peers = {
        {"bullet", makeBulletAdapter}, {"ode", makeOdeAdapter}, {"mujoco", makeMujocoAdapter}};
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
            Row row{e->name(), mode, "", "", "", true};
            row.fall = checkFall(*e, mode, &row.ok);
            row.spin = checkSpin(*e, mode, &row.ok);
            row.bounce = checkBounce(*e, mode, &row.ok);
            rows.push_back(row);
        }
    }
    std::printf("%-7s %-20s %-36s %-40s %-34s %s\n", "engine", "mode", "free fall (rel. error)",
                "spin (worst drift)", "bounce e=0.5 (apex / h, want 0.25)", "");
    bool all = true;
    for (const Row& r : rows) {
        std::printf("%-7s %-20s %-36s %-40s %-34s %s\n", r.engine.c_str(), r.mode.c_str(), r.fall.c_str(),
                    r.spin.c_str(), r.bounce.c_str(), r.ok ? "ok" : "FAIL");
        all = all && r.ok;
    }
    if (built == 0) return 2;
    return all ? 0 : 1;
}
