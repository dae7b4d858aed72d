// Issue 45, item 1: impacts found whenever the paths touch within a step, grazes of edges
// and corners included, at the steps people use. A ball falling past the top edge of a box
// met it only inside a step at 1/30 s, apart at the step's start and end, and flew on through
// the box's corner: its approach there (0.57 m/s) was under the resting speed (2 g h =
// 0.65 m/s, though gravity presses nothing together across a level normal), and the time of
// impact swept the chord of the step rather than the fall's parabola (1.4 mm off at 1/30 s).
#include "collision/reference.h"
#include "scene_builders.h"
#include "turned_world.h"

#include <tumble/world.h>

#include <QtTest>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

using namespace tumble;
using namespace tumble::test;

namespace {

constexpr double kG = 9.81;

// The shot: a ball (r 0.1 m, 0.5 kg, e 0.7, no friction, no spin) from (1.2603,
// 1.2943) at (1.0102, -1.8642) m/s past the top right edge (1.2, 1.2) of a static box (half
// extents 0.3, 0.6, 1.0 at (0.9, 0.6, 0)).
struct Shot {
    Vec3 x0{1.2603, 1.2943, 0}, v0{1.0102, -1.8642, 0}, edge{1.2, 1.2, 0};
    double r = 0.1, e = 0.7;
    Vec3 at(double t) const { return x0 + v0 * t + 0.5 * Vec3(0, -kG, 0) * t * t; }
    Vec3 velocity(double t) const { return v0 + Vec3(0, -kG, 0) * t; }
    double gap(double t) const {  // from the centre to the edge line (along z), less r
        const Vec3 d = at(t) - edge;
        return std::hypot(d.x(), d.y()) - r;
    }
};

// The closed form: the moment the ballistic path comes within r of the edge (bisection to
// rounding), the normal from the edge to the centre, v' = v - (1 + e)(v·n) n, then
// ballistic again; the ball's velocity and centre at T.
void closedForm(double T, Vec3& v, Vec3& x) {
    const Shot s;
    double lo = 0.0, hi = 0.05;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (s.gap(mid) > 0.0 ? lo : hi) = mid;
    }
    const double tc = 0.5 * (lo + hi);
    const Vec3 xc = s.at(tc);
    const Vec3 n = Vec3(xc.x() - s.edge.x(), xc.y() - s.edge.y(), 0).normalized();
    const Vec3 vc = s.velocity(tc);
    const Vec3 v1 = vc - (1.0 + s.e) * vc.dot(n) * n;
    const double dt = T - tc;
    v = v1 + Vec3(0, -kG, 0) * dt;
    x = xc + v1 * dt + 0.5 * Vec3(0, -kG, 0) * dt * dt;
}

SceneDesc edgeGraze() {
    const Shot s;
    BodyDesc box = material(boxBody("box", Vec3(0.3, 0.6, 1.0), 1.0), s.e, 0.0);
    box.motion = Motion::Static;
    box.mass.reset();
    box.position = Vec3(0.9, 0.6, 0);
    BodyDesc ball = material(sphereBody("ball", s.r, 0.5), s.e, 0.0);
    ball.position = s.x0;
    ball.velocity = s.v0;
    SceneDesc scene = sceneOf({box, ball});
    scene.settings.sleeping = false;
    return scene;
}

// The nearest point of a box (half extents h, pose R, c) to p outside it.
Vec3 nearestOnBox(const Vec3& p, const Vec3& c, const Quat& R, const Vec3& h) {
    const Vec3 local = R.conjugate() * (p - c);
    return c + R * local.cwiseMax(-h).cwiseMin(h);
}

// The nearest point of a closed convex triangle mesh (world vertices) to p outside it.
Vec3 nearestOnMesh(const Vec3& p, const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris) {
    Vec3 best = v[0];
    for (const auto& t : tris) {
        const Vec3 q = collision::reference::closestPointOnTriangle(p, v[t[0]], v[t[1]], v[t[2]]);
        if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    }
    return best;
}

// The nearest point of a capsule's surface (segment ±hh along its y, radius rc) to p outside it.
Vec3 nearestOnCapsule(const Vec3& p, const Vec3& c, const Quat& R, double hh, double rc) {
    const Vec3 local = R.conjugate() * (p - c);
    const Vec3 onAxis(0, std::clamp(local.y(), -hh, hh), 0);
    return c + R * (onAxis + rc * (local - onAxis).normalized());
}

}  // namespace

class TestGrazes : public QObject {
    Q_OBJECT
private slots:
    // The edge graze against its closed form at 1/30, 1/60 and 1/240 s (impacts at
    // their moment), and at 1/30 s with impacts at the end of the step (the ball leaves the
    // box 2.3 mm inside at the step's end: the end's contact has nothing to stop, so that
    // mode finds the moment too), in the scene's pose and in a world turned and shifted at
    // random: within 1e-9 m/s and 1e-9 m at 0.3 s. (1.3e-10 measured; before, at 1/30 s the
    // ball kept vx 1.0102 against the closed form's 1.736991.)
    void edgeGrazeBouncesAsTheClosedForm_data() {
        QTest::addColumn<double>("h");
        QTest::addColumn<bool>("endOfStep");
        QTest::addColumn<int>("seed");
        for (int seed : {0, 11, 12}) {
            for (double h : {1.0 / 30, 1.0 / 60, 1.0 / 240})
                QTest::addRow("1/%.0f s, exact, pose %d", 1.0 / h, seed) << h << false << seed;
            QTest::addRow("1/30 s, end of step, pose %d", seed) << 1.0 / 30 << true << seed;
        }
    }
    void edgeGrazeBouncesAsTheClosedForm() {
        QFETCH(double, h);
        QFETCH(bool, endOfStep);
        QFETCH(int, seed);
        SceneDesc scene = edgeGraze();
        if (endOfStep) scene.settings.impacts = ImpactTiming::EndOfStep;
        const WorldPose pose = seed ? randomWorldPose(seed) : WorldPose{};
        if (seed) scene = turnedScene(scene, pose);
        World w(scene);
        const double T = 0.3;
        const long steps = std::lround(T / h);
        for (long k = 0; k < steps; ++k) w.step(h);
        Vec3 v, x;
        closedForm(steps * h, v, x);
        const Vec3 vEngine = pose.R.conjugate() * velocityOf(w, 1);
        const Vec3 xEngine = pose.R.conjugate() * (w.state().bodies[1].x - pose.t);
        qInfo("velocity off the closed form by %.1e m/s, the centre by %.1e m", (vEngine - v).norm(),
              (xEngine - x).norm());
        QVERIFY2((vEngine - v).norm() < 1e-9, qPrintable(QString::number((vEngine - v).norm())));
        QVERIFY2((xEngine - x).norm() < 1e-9, qPrintable(QString::number((xEngine - x).norm())));
    }

    // A ball (r 0.1 m, e 0.7, no friction) bouncing down six static box stairs (0.3 m deep,
    // 0.2 m high), thrown at 1.2 m/s: at 1/30 and 1/60 s its path at every tenth of a second
    // to 1.2 s is the 1/240 s one to 1e-9 m, in the scene's pose and in a turned world (the
    // impacts at their moments make the path independent of the step). Before, at 1/30 s a
    // step that ended 3.8 mm above the first stair had the end's contact cut the approach to
    // what closed the gap (a landing placed a step early): 3.8 mm off at 0.2 s, 3.6 cm at
    // 1.2 s, while 1/60 agreed to 1e-13.
    void stairsFollowTheirPathAtAnyStep_data() {
        QTest::addColumn<int>("seed");
        QTest::newRow("as built") << 0;
        QTest::newRow("turned") << 21;
    }
    void stairsFollowTheirPathAtAnyStep() {
        QFETCH(int, seed);
        std::vector<BodyDesc> bodies;
        for (int k = 0; k < 6; ++k) {
            BodyDesc step =
                material(boxBody("step" + std::to_string(k), Vec3(0.15, 0.1 * (6 - k), 1.0), 1.0), 0.7, 0.0);
            step.motion = Motion::Static;
            step.mass.reset();
            step.position = Vec3(0.3 * k, 0.1 * (6 - k), 0);
            bodies.push_back(step);
        }
        BodyDesc ball = material(sphereBody("ball", 0.1, 0.5), 0.7, 0.0);
        ball.position = Vec3(-0.1, 1.5, 0);
        ball.velocity = Vec3(1.2, 0, 0);
        bodies.push_back(ball);
        SceneDesc scene = sceneOf(bodies);
        scene.settings.sleeping = false;
        if (seed) scene = turnedScene(scene, randomWorldPose(seed));
        std::vector<std::vector<Vec3>> paths;
        for (int perSecond : {240, 60, 30}) {
            World w(scene);
            std::vector<Vec3> path;
            for (int k = 1; k <= 12; ++k) {
                while (w.state().time < 0.1 * k - 1e-9) w.step(1.0 / perSecond);
                path.push_back(w.state().bodies.back().x);
            }
            paths.push_back(path);
        }
        double worst = 0.0;
        for (int run = 1; run < 3; ++run)
            for (int k = 0; k < 12; ++k) worst = std::max(worst, (paths[run][k] - paths[0][k]).norm());
        qInfo("1/60 and 1/30 s within %.1e m of the 1/240 s path", worst);
        QVERIFY2(worst < 1e-9, qPrintable(QString::number(worst)));
    }

    // Thousands of random grazing shots at 1/30 s: a ball (r 0.1 m, e 0.5, no friction)
    // aimed to pass an edge or corner of a static box, the side or cap of a static capsule,
    // or a vertex or edge of a static octahedron (a convex hull, and the same as a triangle
    // mesh), in random poses, within ±3 cm of touching, inside the first step. The reference
    // is the exact ballistic path against the closed-form distance to the shape (to a mesh:
    // the nearest of its triangles): its nearest approach over the step (dense sampling,
    // golden sections), its first touch (bisection), the normal and the approach speed there.
    // A shot that comes deeper than 0.1 mm into the shape, meeting it faster than settling
    // (2 g h times gravity's share along the normal, at least a quarter: resting.h), must be
    // bounced in that step (1 913 such shots, none missed); one that stays clear by more than
    // the contact margin (g h², 1.1 cm) must fly on untouched (its velocity as gravity alone
    // gives it, to 1e-12). Not yet (left open in issue 45): slower grazes are left to the
    // contact at the end of the step, which does not stop those that have left by then
    // (counted here: 49 of 80 at boxes, 23 of 57 at capsules, 30 of 52 at hulls, 38 of 50 at
    // meshes; stopping them at their moment kept a ragdoll and rocks in a mesh bowl from ever
    // settling); and a graze within the margin may be touched by the end's contact, which
    // takes the edge for a plane.
    void randomGrazesAreNeverMissed_data() {
        QTest::addColumn<int>("kind");  // 0 box, 1 capsule, 2 octahedron as a hull, 3 as triangles
        QTest::newRow("boxes") << 0;
        QTest::newRow("capsules") << 1;
        QTest::newRow("hulls") << 2;
        QTest::newRow("meshes") << 3;
    }
    void randomGrazesAreNeverMissed() {
        QFETCH(int, kind);
        const bool capsule = kind == 1, octahedron = kind >= 2;
        const double h = 1.0 / 30, r = 0.1;
        const Vec3 g(0, -kG, 0);
        Rng rng{static_cast<std::uint64_t>(78 - kind)};
        int touched = 0, clear = 0, missed = 0, phantom = 0, slow = 0, slowMissed = 0;
        const double margin = kG * h * h;  // (World's contact margin, but for the touch tolerance)
        const int shots = 4000;
        for (int k = 0; k < shots; ++k) {
            // The shape.
            BodyDesc shape;
            Vec3 half;
            for (int i = 0; i < 3; ++i) half[i] = rng.uniform(0.1, 0.5);  // (draws in sequence)
            const double hh = rng.uniform(0.1, 0.4), rc = rng.uniform(0.05, 0.3);
            std::vector<Vec3> corners;  // an octahedron's vertices, one on each half axis
            const std::vector<std::array<int, 3>> faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
            if (octahedron) {
                for (int i = 0; i < 6; ++i) {
                    Vec3 axis = Vec3::Zero();
                    axis[i / 2] = i % 2 ? -1.0 : 1.0;
                    corners.push_back(rng.uniform(0.15, 0.5) * axis);
                }
                shape.name = "rock";
                shape.shape.type = ShapeType::Mesh;
                shape.shape.file = "rock (built by the test)";
                shape.shape.collision = kind == 2 ? MeshCollision::ConvexHull : MeshCollision::Triangles;
                auto mesh = std::make_shared<TriangleMesh>();
                mesh->vertices = corners;
                mesh->triangles = faces;
                shape.shape.meshData = mesh;
            } else if (capsule) {
                shape.name = "capsule";
                shape.shape.type = ShapeType::Capsule;
                shape.shape.radius = rc;
                shape.shape.halfHeight = hh;
            } else {
                shape = boxBody("box", half, 1.0);
            }
            shape.mass.reset();
            shape.motion = Motion::Static;
            shape.position = rng.vec(-1, 1);
            shape.orientation = randomWorldPose(static_cast<std::uint64_t>(rng.uniform(0, 1e9)), 0.0).R;
            shape.restitution = 0.5;
            shape.friction = 0.0;
            const Quat R = shape.orientation;
            std::vector<Vec3> world;
            for (const Vec3& v : corners) world.push_back(shape.position + R * v);
            // (Of a centre outside: a shot's centre never reaches the shape itself.)
            auto nearest = [&](const Vec3& p) {
                if (octahedron) return nearestOnMesh(p, world, faces);
                return capsule ? nearestOnCapsule(p, shape.position, R, hh, rc)
                               : nearestOnBox(p, shape.position, R, half);
            };
            auto distance = [&](const Vec3& p) {
                return capsule
                           ? (p - shape.position -
                              R * Vec3(0, std::clamp((R.conjugate() * (p - shape.position)).y(), -hh, hh), 0))
                                     .norm() -
                                 rc
                           : (p - nearest(p)).norm();
            };
            // A point of the surface where the shot grazes: a box's edge or corner, a
            // capsule's side or cap, an octahedron's vertex or edge; and an outward direction
            // there.
            Vec3 surface, out;
            if (octahedron) {  // a vertex, or a point of an edge between two of them
                const auto& f = faces[static_cast<int>(rng.uniform(0, 8))];
                const double u = rng.uniform() < 0.3 ? 0.0 : rng.uniform(0, 1);
                surface = world[f[0]] + u * (world[f[1]] - world[f[0]]);
                out = (surface - shape.position).normalized();
            } else if (capsule) {
                const Vec3 dir = rng.direction();
                const double y = std::clamp(rng.uniform(-hh - rc, hh + rc), -hh, hh);
                surface = shape.position + R * (Vec3(0, y, 0) + rc * dir);
                out = R * dir;
            } else {
                Vec3 local, n = Vec3::Zero();
                for (int i = 0; i < 3; ++i) {
                    const double sgn = rng.uniform() < 0.5 ? -1.0 : 1.0;
                    const bool free =
                        i == static_cast<int>(rng.uniform(0, 3)) && rng.uniform() < 0.7;  // along an edge
                    local[i] = free ? rng.uniform(-half[i], half[i]) : sgn * half[i];
                    if (!free) n[i] = sgn * rng.uniform(0.2, 1.0);
                }
                surface = shape.position + R * local;
                out = R * n.normalized();
            }
            // Passing at r ± 3 cm from that point at a moment inside the step, moving across
            // the outward direction (a graze), 1 to 4 m/s.
            const double pass = r + rng.uniform(-0.03, 0.03);
            Vec3 across = rng.direction();
            across = (across - across.dot(out) * out).normalized();
            const Vec3 v0 = rng.uniform(1.0, 4.0) * (across + rng.uniform(-0.2, 0.2) * out).normalized();
            const double ta = rng.uniform(0.2, 0.8) * h;
            const Vec3 aim = surface + pass * out;
            const Vec3 x0 = aim - v0 * ta - 0.5 * g * ta * ta;
            if (distance(x0) < r + 1e-3) continue;  // (touching at the start: not a graze)
            auto path = [&](double t) { return x0 + v0 * t + 0.5 * g * t * t; };
            // The nearest approach over [0, h]: dense samples, then golden sections.
            double best = 0.0, closest = distance(path(0.0));
            for (int i = 1; i <= 2000; ++i) {
                const double t = h * i / 2000.0, d = distance(path(t));
                if (d < closest) closest = d, best = t;
            }
            double lo = std::max(0.0, best - h / 2000), hi = std::min(h, best + h / 2000);
            for (int i = 0; i < 100; ++i) {
                const double m1 = hi - 0.618034 * (hi - lo), m2 = lo + 0.618034 * (hi - lo);
                if (distance(path(m1)) < distance(path(m2)))
                    hi = m2;
                else
                    lo = m1;
            }
            closest = std::min(closest, distance(path(0.5 * (lo + hi))));
            // The first touch (bisection between the start and the nearest approach), its
            // normal and how fast the path meets the surface along it.
            double approach = 0.0, settling = 0.0;
            if (closest < r) {
                double before = 0.0, after = 0.5 * (lo + hi);
                for (int i = 0; i < 200; ++i) {
                    const double mid = 0.5 * (before + after);
                    (distance(path(mid)) > r ? before : after) = mid;
                }
                const Vec3 at = path(before);
                const Vec3 n = (at - nearest(at)).normalized();
                approach = -(v0 + g * before).dot(n);
                settling = 2.0 * kG * h * std::max(std::abs(n.y()), 0.25);  // (resting.h)
            }
            BodyDesc ball = material(sphereBody("ball", r, 0.5), 0.5, 0.0);
            ball.position = x0;
            ball.velocity = v0;
            SceneDesc scene = sceneOf({shape, ball});
            scene.settings.sleeping = false;
            World w(scene);
            w.step(h);
            const bool bounced = (velocityOf(w, 1) - (v0 + g * h)).norm() > 1e-12;
            if (closest < r - 1e-4 && approach > 1.05 * settling) {
                ++touched;
                if (!bounced) {
                    ++missed;
                    qWarning("shot %d missed: the path comes %.2e m into the shape at %.3f m/s", k,
                             r - closest, approach);
                }
            } else if (closest < r - 1e-4) {
                ++slow;
                slowMissed += !bounced;
            } else if (closest > r + margin) {
                ++clear;
                if (bounced) {
                    ++phantom;
                    qWarning("shot %d bounced: the path stays %.2e m clear", k, closest - r);
                }
            }
        }
        qInfo(
            "%d shots met faster than settling (%d missed), %d slower (%d not stopped), %d passed clear by "
            "more "
            "than the margin (%d bounced)",
            touched, missed, slow, slowMissed, clear, phantom);
        // (The shots do graze both ways: GCC and clang draw some in another order, so the
        // counts differ a little between them.)
        QVERIFY(touched > shots / 40 && clear > shots / 40);
        QCOMPARE(missed, 0);
        QCOMPARE(phantom, 0);
    }
};

QTEST_GUILESS_MAIN(TestGrazes)
#include "tst_grazes.moc"
