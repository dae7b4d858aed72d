// Joints (issue 20): checked against closed forms and conservation: a 50-link chain's
// length at the steps people use, a rod's spinning dumbbell keeping its angular momentum,
// a rope that lets a body fall freely until it is taut and never pushes, the sample
// Newton's cradle on strings, welds, sliders, motors and limits, breaking, sleeping, and the
// scene's validation. (Periods and energies of pendulums: tst_joint_accuracy.cpp.)
#include "joint_checks.h"
#include "scene_builders.h"
#include "turned_world.h"

#include <tumble/errors.h>
#include <tumble/io/scene_file.h>
#include <tumble/world.h>

#include <QtTest>

#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::test;

namespace {

constexpr double g = 9.81;

}  // namespace

// A door (a 10 kg slab 0.8 x 2 x 0.04 m) hinged to the world about the vertical through its
// centre, turning at `spin` rad/s, its angle limited to [lower, upper]; no gravity.
SceneDesc doorOnHinge(double spin, double lower, double upper) {
    BodyDesc door = boxBody("door", Vec3(0.4, 1.0, 0.02), 10.0);
    door.angularVelocity = Vec3(0, spin, 0);
    SceneDesc scene = sceneOf({door}, Vec3::Zero());
    scene.settings.sleeping = false;
    JointDesc hinge = joint("hinge", JointType::Hinge, "door", Vec3::Zero(), "", Vec3::Zero());
    hinge.axisA = Vec3::UnitY();
    hinge.limits = std::array<double, 2>{lower, upper};
    scene.joints.push_back(hinge);
    return scene;
}

class TestJoints : public QObject {
    Q_OBJECT
private slots:
    // A chain of 50 boxes on ball joints, hung from the world and let go level, at the steps
    // people use, as built and in a world turned and shifted (seed 7): it swings down, its
    // joints open by less than 0.1 % of its length in all (issue 20's bound) and its energy
    // never rises above the start by more than 1e-3. The chain's Newton projection
    // (joint_projection.cpp) holds every joint to 1e-13 m in most steps; when the whipping
    // end has turned too far in a step, the projection stops early or converges to poses
    // that give the chain energy (+41 % in one step at 1/20 s): such a step is taken again in
    // halves (World::stepJointed), which this test sees happen at 1/30 s and 1/20 s. A chain
    // of 100 links is more than one dense system takes (64 joints): it is solved along the
    // chain (block-tridiagonal). Its whip is chaotic. Until its positions-only Newton steps
    // weighed turns more once a full step failed (2026-12-06) it opened by 0.19 % as built
    // and 0.06 % turned; now 7e-14 in both (and in 9 of seeds 1-11; the others 0.014 % and
    // 0.069 %). At 1/30 and 1/20 s it still comes apart in some poses (as built it holds
    // to 1e-13; seed 7 turned, both steps open by 2 m), as it did in every pose before.
    void chainHoldsItsLength_data() {
        QTest::addColumn<int>("links");
        QTest::addColumn<double>("h");
        QTest::addColumn<double>("bound");
        QTest::addColumn<bool>("splits");  // whether steps are seen taken again in halves
        QTest::addColumn<int>("seed");  // 0: as built; else the world turned and shifted (turned_world.h)
        for (int seed : {0, 7}) {
            const QString world = seed ? ", turned" : "";
            auto row = [&](const char* name) -> QTestData& { return QTest::newRow(qPrintable(name + world)); };
            row("1/60 s") << 50 << 1.0 / 60.0 << 1e-3 << false << seed;
            row("1/30 s") << 50 << 1.0 / 30.0 << 1e-3 << true << seed;
            row("1/20 s") << 50 << 1.0 / 20.0 << 1e-3 << true << seed;
            row("100 links, 1/60 s") << 100 << 1.0 / 60.0 << 1e-3 << false << seed;
        }
    }
    void chainHoldsItsLength() {
        QFETCH(int, links);
        QFETCH(double, h);
        QFETCH(double, bound);
        QFETCH(bool, splits);
        QFETCH(int, seed);
        SceneDesc s;
        const double half = 0.1;
        for (int i = 0; i < links; ++i) {
            BodyDesc b = boxBody("link" + std::to_string(i), Vec3(half, 0.02, 0.02), 0.5);
            b.position = Vec3(half + 2 * half * i, 12.0, 0.0);
            s.bodies.push_back(b);
            if (i == 0)
                s.joints.push_back(joint("top", JointType::Ball, b.name, Vec3(-half, 0, 0), "", Vec3(0, 12, 0)));
            else
                s.joints.push_back(joint("j" + std::to_string(i), JointType::Ball, b.name, Vec3(-half, 0, 0),
                                         "link" + std::to_string(i - 1), Vec3(half, 0, 0)));
        }
        s.settings.sleeping = false;
        const WorldPose pose = seed ? randomWorldPose(seed) : WorldPose{};
        World w(turnedScene(s, pose));
        const double e0 = energy(w);
        const double length = 2 * half * links;
        double worstOpen = 0.0, worstGap = 0.0, most = e0;
        long steps = 0;
        while (w.state().time < 5.0) {
            w.step(h);
            ++steps;
            most = std::max(most, energy(w));
            double open = 0.0;
            for (size_t j = 0; j < w.model().joints.size(); ++j) {
                open += anchorGap(w, int(j));
                worstGap = std::max(worstGap, anchorGap(w, int(j)));
            }
            worstOpen = std::max(worstOpen, open);
            QVERIFY(w.state().bodies.back().x.allFinite());
        }
        const double gained = (most - e0) / std::abs(e0);
        qInfo("joints open by %.2e of the chain's length at most (one joint by %.1e m); energy at most %+.2e of "
              "the start, %+.2e at the end; %ld splits in %ld steps",
              worstOpen / length, worstGap, gained, (energy(w) - e0) / std::abs(e0), w.profile().jointSplits, steps);
        QVERIFY2(worstOpen < bound * length, qPrintable(QString::number(worstOpen / length)));
        QVERIFY2(gained < 1e-3, qPrintable(QString::number(gained)));
        // Every step asked for lands on its time, split or not.
        QCOMPARE_LE(std::abs(w.state().time - steps * h), 1e-12);
        if (splits) QVERIFY(w.profile().jointSplits > 0);
        const Vec3 up = pose.direction(Vec3::UnitY());
        QVERIFY(up.dot(w.state().bodies.back().x - pose.t) < 12.0 - 1.0);  // it swung down
    }

    // A necklace of 80 balls on rods (distance joints), hung from the world by one end and let
    // go level at 1/60 s: more joints than one dense system takes and not ball joints, so
    // its Newton steps solve the rods together by a sparse LU. Every rod keeps its length
    // to a micrometre (1e-13 m measured) and the necklace gains no energy to speak of (4e-5 of
    // it). Left to Gauss-Seidel, as such groups were before, a rod was off by 7 mm.
    void necklaceHoldsItsRods() {
        SceneDesc s;
        const int balls = 80;
        const double rod = 0.2;
        for (int i = 0; i < balls; ++i) {
            BodyDesc b = sphereBody("ball" + std::to_string(i), 0.05, 0.2);
            b.position = Vec3(rod * (i + 1), 12.0, 0.0);
            s.bodies.push_back(b);
            if (i == 0)
                s.joints.push_back(
                    joint("top", JointType::Distance, b.name, Vec3::Zero(), "", Vec3(0, 12, 0)));
            else
                s.joints.push_back(joint("rod" + std::to_string(i), JointType::Distance, b.name, Vec3::Zero(),
                                         "ball" + std::to_string(i - 1), Vec3::Zero()));
        }
        s.settings.sleeping = false;
        World w(s);
        const double e0 = energy(w);
        double worst = 0.0, most = e0;
        while (w.state().time < 3.0) {
            w.step(1.0 / 60.0);
            most = std::max(most, energy(w));
            for (size_t j = 0; j < w.model().joints.size(); ++j)
                worst = std::max(worst, std::abs(anchorGap(w, int(j)) - rod));
            QVERIFY(w.state().bodies.back().x.allFinite());
        }
        const double gained = (most - e0) / std::abs(e0);
        qInfo("rods off their length by %.2e m at most; energy at most %+.2e of the start; %ld splits", worst,
              gained, w.profile().jointSplits);
        QVERIFY2(worst < 1e-6, qPrintable(QString::number(worst)));
        QVERIFY2(gained < 1e-3, qPrintable(QString::number(gained)));
        QVERIFY(w.state().bodies.back().x.y() < 12.0 - 1.0);  // it swung down
    }

    // Two balls on a rod of 1 m spinning in free space: the distance held, the momentum and
    // the angular momentum kept.
    void spinningDumbbell() {
        BodyDesc a = sphereBody("a", 0.1, 1.0), b = sphereBody("b", 0.1, 3.0);
        a.position = Vec3(-0.75, 0, 0);
        b.position = Vec3(0.25, 0, 0);
        a.velocity = Vec3(0, -3, 0.5);
        b.velocity = Vec3(0, 1, 0.5);
        SceneDesc s = sceneOf({a, b}, Vec3::Zero());
        s.settings.sleeping = false;
        s.joints.push_back(joint("rod", JointType::Distance, "a", Vec3::Zero(), "b", Vec3::Zero()));
        World w(s);
        auto momentum = [&] { return Vec3(w.state().bodies[0].P + w.state().bodies[1].P); };
        auto angular = [&] {
            Vec3 L = Vec3::Zero();
            for (int i = 0; i < 2; ++i) L += w.state().bodies[i].x.cross(w.state().bodies[i].P) + w.state().bodies[i].L;
            return L;
        };
        const Vec3 P0 = momentum(), L0 = angular();
        double worstGap = 0.0;
        for (int k = 0; k < 600; ++k) {
            w.step(1.0 / 120.0);
            worstGap = std::max(worstGap, std::abs((w.state().bodies[0].x - w.state().bodies[1].x).norm() - 1.0));
        }
        qInfo("rod length off by %.1e m; momentum %.1e, angular momentum %.1e", worstGap, (momentum() - P0).norm(),
              (angular() - L0).norm());
        QVERIFY(worstGap < 1e-9);
        QVERIFY((momentum() - P0).norm() < 1e-9);
        QVERIFY((angular() - L0).norm() < 1e-3 * L0.norm());
    }

    // A ball on a 1 m rope from the world point (0, 3, 0), let go 0.4 m below it: it falls
    // freely (the rope slack: no force) until the rope is taut, then never goes farther.
    // Thrown up towards the anchor, the rope does not push it.
    void ropeOnlyPulls() {
        BodyDesc bob = sphereBody("bob", 0.05, 1.0);
        bob.position = Vec3(0.0, 2.6, 0.0);
        SceneDesc s = sceneOf({bob});
        s.settings.sleeping = false;
        s.joints.push_back(joint("rope", JointType::Rope, "bob", Vec3::Zero(), "", Vec3(0, 3, 0), 1.0));
        World w(s);
        const double h = 1.0 / 240.0;
        // Slack for sqrt(2 · 0.6 / g) = 0.35 s: free fall.
        for (int k = 0; k < 60; ++k) w.step(h);
        const double t = w.state().time;
        QVERIFY(std::abs(w.state().bodies[0].x.y() - (2.6 - 0.5 * g * t * t)) < 1e-3);
        double farthest = 0.0;
        for (int k = 0; k < 480; ++k) {
            w.step(h);
            farthest = std::max(farthest, (w.state().bodies[0].x - Vec3(0, 3, 0)).norm());
        }
        QVERIFY2(farthest <= 1.0 + 1e-9, qPrintable(QString::number(farthest - 1.0)));
        QVERIFY(farthest > 1.0 - 1e-6);  // taut at some point
        // Thrown up from below the anchor: it rises as in free flight.
        bob.velocity = Vec3(0, 2, 0);
        s.bodies[0] = bob;
        World up(s);
        up.step(h);
        QVERIFY(std::abs(up.state().bodies[0].P.y() - (2.0 - g * h)) < 1e-9);
    }

    // The sample Newton's cradle on strings (resources/scenes/newtons-cradle-strings.json):
    // five touching balls of 1 kg, each hung by two distance joints in a V from points 1 m
    // above it, the first let go at 30 degrees. Each swings as a simple pendulum of L = 1 m
    // about the line through its anchors, T = 4 sqrt(L/g) K(sin 15 deg) = 2.0410 s; e = 1, so
    // the impact passes through the three resting balls and the last rises to 30 degrees at
    // T/2, the first back to 30 degrees at T, the middle three still.
    void newtonsCradleOnStrings() {
        SceneDesc scene = io::readSceneFile(std::string(TUMBLE_SCENES_DIR) + "/newtons-cradle-strings.json");
        QCOMPARE(scene.joints.size(), size_t(10));
        World w(scene);
        const double T = 4.0 * std::sqrt(1.0 / g) * ellipticK(std::sin(std::numbers::pi / 12.0));
        const double h = scene.settings.dt;
        auto angle = [&](int ball) {  // degrees from the vertical, towards +x
            const Vec3& x = w.state().bodies[ball].x;
            const double x0 = -0.4 + 0.2 * (ball - 1);
            return std::atan2(x.x() - x0, 2.0 - x.y()) * 180.0 / std::numbers::pi;
        };
        double peak5 = 0.0, peak5At = 0.0, back1 = 0.0, back1At = 0.0, middle = 0.0, gap = 0.0;
        const double e0 = energy(w);
        double drift = 0.0;
        while (w.state().time < 1.25 * T) {
            w.step(h);
            const double t = w.state().time;
            if (angle(5) > peak5) peak5 = angle(5), peak5At = t;
            if (t > 0.75 * T && -angle(1) > back1) back1 = -angle(1), back1At = t;
            for (int k : {2, 3, 4}) middle = std::max(middle, std::abs(angle(k)));
            for (int k = 0; k < 10; ++k) gap = std::max(gap, anchorGap(w, k) - std::sqrt(1.25));
            drift = std::max(drift, std::abs(energy(w) - e0));
        }
        qInfo("last ball up to %.4f deg at %.4f s (T/2 = %.4f); first back to %.4f deg at %.4f s (T = %.4f); "
              "middle balls within %.1e deg; strings' length held to %.1e m; energy within %.1e J",
              peak5, peak5At, T / 2, back1, back1At, T, middle, gap, drift);
        QVERIFY2(std::abs(peak5 - 30.0) < 0.05, qPrintable(QString::number(peak5)));
        QVERIFY2(std::abs(peak5At - T / 2) < 2 * h, qPrintable(QString::number(peak5At)));
        QVERIFY2(std::abs(back1 - 30.0) < 0.05, qPrintable(QString::number(back1)));
        QVERIFY2(std::abs(back1At - T) < 2 * h, qPrintable(QString::number(back1At)));
        QVERIFY2(middle < 0.05, qPrintable(QString::number(middle)));
        QVERIFY2(gap < 1e-9, qPrintable(QString::number(gap)));
        QVERIFY2(drift < 3e-4, qPrintable(QString::number(drift)));
    }

    // A fixed joint makes one rigid body of two: two cubes of 1 m and 1 kg side by side,
    // welded, thrown tumbling in empty space (ω off every principal axis), move as one box
    // of 2 × 1 × 1 m and 2 kg does (the same inertia): after 3 s the pair's middle and the
    // cubes' orientation are the single box's, and the weld is held to 1e-9.
    void fixedJointIsOneBody() {
        const Vec3 v(0.5, 1.0, -0.25), omega(0.3, 1.5, 0.7);
        BodyDesc left = boxBody("left", Vec3(0.5, 0.5, 0.5), 1.0), right = boxBody("right", Vec3(0.5, 0.5, 0.5), 1.0);
        left.position = Vec3(-0.5, 0, 0);
        right.position = Vec3(0.5, 0, 0);
        for (BodyDesc* b : {&left, &right}) {
            b->velocity = v + omega.cross(b->position);
            b->angularVelocity = omega;
        }
        SceneDesc pair = sceneOf({left, right}, Vec3::Zero());
        pair.settings.sleeping = false;
        pair.joints.push_back(joint("weld", JointType::Fixed, "left", Vec3(0.5, 0, 0), "right", Vec3(-0.5, 0, 0)));
        BodyDesc whole = boxBody("whole", Vec3(1.0, 0.5, 0.5), 2.0);
        whole.velocity = v;
        whole.angularVelocity = omega;
        SceneDesc one = sceneOf({whole}, Vec3::Zero());
        one.settings.sleeping = false;
        // The pair and the box are integrated apart (two free steps and a projection, one
        // free step), so they differ by the integrator's error, second order in h: a
        // quarter at half the step.
        double turns[2] = {0, 0};
        for (int k = 0; k < 2; ++k) {
            World a(pair), b(one);
            const double h = k == 0 ? 1.0 / 240.0 : 1.0 / 480.0;
            double worstGap = 0.0;
            while (a.state().time < 3.0 - 1e-9) {
                a.step(h);
                b.step(h);
                worstGap = std::max(worstGap, anchorGap(a, 0));
            }
            const BodyState &l = a.state().bodies[0], &r = a.state().bodies[1], &w1 = b.state().bodies[0];
            const double place = (0.5 * (l.x + r.x) - w1.x).norm();
            turns[k] = l.q.angularDistance(w1.q);
            const double weld = l.q.angularDistance(r.q);
            qInfo("h = 1/%.0f, after 3 s: the middle %.1e m from the single box's centre, orientation %.2e rad "
                  "from its; weld held to %.1e m and %.1e rad",
                  1.0 / h, place, turns[k], worstGap, weld);
            QVERIFY2(place < 1e-6, qPrintable(QString::number(place)));
            QVERIFY2(worstGap < 1e-9 && weld < 1e-9, qPrintable(QString::number(worstGap)));
        }
        QVERIFY2(turns[0] < 1e-4, qPrintable(QString::number(turns[0])));
        QVERIFY2(turns[1] < 0.35 * turns[0], qPrintable(QString::number(turns[1] / turns[0])));
    }

    // A slider to the world along a rail 30 degrees above the horizontal: the block slides
    // down it with a = g sin 30° from rest, s = g t² / 4, without turning or leaving the line.
    void sliderOnAnIncline() {
        const double angle = std::numbers::pi / 6.0;
        const Vec3 along(std::cos(angle), std::sin(angle), 0);
        BodyDesc block = boxBody("block", Vec3(0.2, 0.1, 0.1), 2.0);
        block.position = Vec3(0, 5, 0);
        block.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
        SceneDesc scene = sceneOf({block});
        scene.settings.sleeping = false;
        JointDesc rail = joint("rail", JointType::Slider, "block", Vec3::Zero(), "", Vec3(0, 5, 0));
        rail.axisA = block.orientation.conjugate() * along;  // the rail's direction in the block's frame
        scene.joints.push_back(rail);
        World w(scene);
        const double h = 1.0 / 240.0;
        double worstOff = 0.0, worstTurn = 0.0;
        while (w.state().time < 1.0 - 1e-9) {
            w.step(h);
            const BodyState& b = w.state().bodies[0];
            const Vec3 d = b.x - Vec3(0, 5, 0);
            worstOff = std::max(worstOff, (d - d.dot(along) * along).norm());
            worstTurn = std::max(worstTurn, b.q.angularDistance(block.orientation));
        }
        const double s = (w.state().bodies[0].x - Vec3(0, 5, 0)).dot(along);
        const double expected = -0.5 * g * std::sin(angle) * 1.0;  // down the rail, t = 1 s
        qInfo("slid %.9f m in 1 s, expected %.9f; off the line %.1e m, turned %.1e rad", s, expected, worstOff,
              worstTurn);
        QVERIFY2(std::abs(s - expected) < 1e-6, qPrintable(QString::number(s)));
        QVERIFY2(worstOff < 1e-9 && worstTurn < 1e-9, qPrintable(QString::number(worstOff)));
    }

    // A hinge's motor: a wheel (a cylinder of 2 kg, r 0.5 m, turning about its axis y: I =
    // m r² / 2 = 0.25 kg m²) at rest, driven towards 3 rad/s with at most 0.5 N m in empty
    // space: it spins up at α = τ / I = 2 rad/s² until t = 1.5 s and turns at 3 rad/s after.
    void hingeMotorReachesItsSpeed() {
        BodyDesc wheel;
        wheel.name = "wheel";
        wheel.shape.type = ShapeType::Cylinder;
        wheel.shape.radius = 0.5;
        wheel.shape.halfHeight = 0.1;
        wheel.mass = 2.0;
        SceneDesc scene = sceneOf({wheel}, Vec3::Zero());
        scene.settings.sleeping = false;
        JointDesc axle = joint("axle", JointType::Hinge, "wheel", Vec3::Zero(), "", Vec3::Zero());
        axle.axisA = Vec3::UnitY();
        axle.motor = JointDesc::Motor{3.0, 0.5};
        scene.joints.push_back(axle);
        World w(scene);
        const double h = 1.0 / 240.0;
        double worstEarly = 0.0, worstLate = 0.0;
        while (w.state().time < 3.0 - 1e-9) {
            w.step(h);
            const double t = w.state().time;
            const double spin = derive(w.model().bodies[0], w.state().bodies[0]).omega.y();
            if (t < 1.5 - 1e-9) worstEarly = std::max(worstEarly, std::abs(spin - 2.0 * t));
            if (t > 1.5 + h) worstLate = std::max(worstLate, std::abs(spin - 3.0));
        }
        qInfo("spin-up off 2 t by at most %.1e rad/s; then off 3 rad/s by %.1e", worstEarly, worstLate);
        QVERIFY2(worstEarly < 1e-9, qPrintable(QString::number(worstEarly)));
        QVERIFY2(worstLate < 1e-9, qPrintable(QString::number(worstLate)));
    }

    // A hinge's limits stop a door: a slab turning about the vertical at 1 rad/s from the
    // middle of its range [-0.5, 0.5] rad reaches the stop at t = 0.5 s and stays there (the
    // stop is inelastic), never past it by more than the projection's 1e-9.
    void hingeLimitStopsADoor() {
        World w(doorOnHinge(1.0, -0.5, 0.5));
        const double h = 1.0 / 240.0;
        double worstPast = 0.0, early = 0.0, restSpin = 0.0;
        while (w.state().time < 2.0 - 1e-9) {
            w.step(h);
            const double t = w.state().time;
            const Quat& q = w.state().bodies[0].q;
            const double angle = 2.0 * std::atan2(q.y(), q.w());
            worstPast = std::max(worstPast, angle - 0.5);
            if (t < 0.5 - 1e-9) early = std::max(early, std::abs(angle - t));
            if (t > 0.5 + 2 * h) restSpin = std::max(restSpin, derive(w.model().bodies[0], w.state().bodies[0]).omega.norm());
        }
        const Quat& q = w.state().bodies[0].q;
        const double final = 2.0 * std::atan2(q.y(), q.w());
        qInfo("free turn off t by %.1e rad; past the stop by %.1e rad; at rest to %.1e rad/s at %.12f rad", early,
              worstPast, restSpin, final);
        QVERIFY2(early < 1e-9, qPrintable(QString::number(early)));
        QVERIFY2(worstPast < 1e-9, qPrintable(QString::number(worstPast)));
        QVERIFY2(restSpin < 1e-9, qPrintable(QString::number(restSpin)));
        QVERIFY2(std::abs(final - 0.5) < 1e-9, qPrintable(QString::number(final)));
    }

    // Limits past a half turn: the same door turning at 4 rad/s with a range of
    // [-0.5, 3π/2] rad passes π (where the angle read from the poses alone jumps to -π)
    // and stops at 3π/2 at t = 3π/8 s; its pose then reads -π/2, and the hinge's angle, counted
    // on from step to step (State::hingeAngles), 3π/2. Read within [-π, π], the stop was
    // never reached and the door turned on for ever.
    void hingeLimitPastHalfATurn() {
        const double stop = 1.5 * M_PI;
        World w(doorOnHinge(4.0, -0.5, stop));
        const double h = 1.0 / 240.0, reach = stop / 4.0;
        double early = 0.0, past = 0.0, restSpin = 0.0;
        while (w.state().time < 3.0 - 1e-9) {
            w.step(h);
            const double t = w.state().time, angle = w.state().hingeAngles.at(0);
            past = std::max(past, angle - stop);
            if (t < reach - 1e-9) early = std::max(early, std::abs(angle - 4.0 * t));
            if (t > reach + 2 * h) restSpin = std::max(restSpin, derive(w.model().bodies[0], w.state().bodies[0]).omega.norm());
        }
        const Quat& q = w.state().bodies[0].q;
        const double sign = q.w() < 0.0 ? -1.0 : 1.0;
        const double pose = 2.0 * std::atan2(sign * q.y(), sign * q.w());  // within [-π, π]: 3π/2 reads -π/2
        qInfo("free turn off 4 t by %.1e rad; past the stop by %.1e rad; at rest to %.1e rad/s; angle %.12f, pose %.12f",
              early, past, restSpin, w.state().hingeAngles.at(0), pose);
        QVERIFY2(early < 1e-9, qPrintable(QString::number(early)));
        QVERIFY2(past < 1e-9, qPrintable(QString::number(past)));
        QVERIFY2(restSpin < 1e-9, qPrintable(QString::number(restSpin)));
        QVERIFY2(std::abs(w.state().hingeAngles.at(0) - stop) < 1e-9, qPrintable(QString::number(w.state().hingeAngles.at(0))));
        QVERIFY2(std::abs(pose - (stop - 2.0 * M_PI)) < 1e-9, qPrintable(QString::number(pose)));
    }

    // A slider's limit: a block on a vertical rail falls freely (s = -g t² / 2) until its
    // offset reaches the lower limit of -1 m at t = sqrt(2 / g), and rests there.
    void sliderLimitStopsAFall() {
        BodyDesc block = boxBody("block", Vec3(0.1, 0.1, 0.1), 1.0);
        block.position = Vec3(0, 3, 0);
        SceneDesc scene = sceneOf({block});
        scene.settings.sleeping = false;
        JointDesc rail = joint("rail", JointType::Slider, "block", Vec3::Zero(), "", Vec3(0, 3, 0));
        rail.axisA = Vec3::UnitY();
        rail.limits = std::array<double, 2>{-1.0, 1.0};
        scene.joints.push_back(rail);
        World w(scene);
        const double h = 1.0 / 240.0, hit = std::sqrt(2.0 / g);
        double early = 0.0, past = 0.0;
        while (w.state().time < 1.5 - 1e-9) {
            w.step(h);
            const double t = w.state().time, y = w.state().bodies[0].x.y() - 3.0;
            if (t < hit - h) early = std::max(early, std::abs(y + 0.5 * g * t * t));
            past = std::max(past, -1.0 - y);
        }
        const double y = w.state().bodies[0].x.y() - 3.0;
        const double v = w.state().bodies[0].P.norm();
        qInfo("free fall off by %.1e m; past the limit by %.1e m; rests at %.12f m, momentum %.1e", early, past, y, v);
        QVERIFY2(early < 1e-9, qPrintable(QString::number(early)));
        QVERIFY2(past < 1e-9, qPrintable(QString::number(past)));
        QVERIFY2(std::abs(y + 1.0) < 1e-9 && v < 1e-9, qPrintable(QString::number(y)));
    }

    // An impact passes through a joint at its moment, as through a contact: a ball (1 kg,
    // 2 m/s, e = 1) hits the end of a dumbbell of two such balls on a rod, along the rod, in
    // empty space. As one collision of 1 kg with 2 kg: the ball leaves at -v/3, the dumbbell
    // at 2v/3, kinetic energy kept (a rod pulled into line only at the end of the step
    // would have kept neither: the balls at v/2 and 0).
    void impactPassesThroughAJoint() {
        BodyDesc ball = sphereBody("ball", 0.1, 1.0), a = sphereBody("a", 0.1, 1.0), b = sphereBody("b", 0.1, 1.0);
        ball.position = Vec3(-0.5, 0, 0);
        ball.velocity = Vec3(2, 0, 0);
        a.position = Vec3(0, 0, 0);
        b.position = Vec3(0.5, 0, 0);
        for (BodyDesc* x : {&ball, &a, &b}) x->restitution = 1.0, x->friction = 0.0;
        SceneDesc scene = sceneOf({ball, a, b}, Vec3::Zero());
        scene.settings.sleeping = false;
        scene.joints.push_back(joint("rod", JointType::Distance, "a", Vec3::Zero(), "b", Vec3::Zero()));
        World w(scene);
        while (w.state().time < 0.5 - 1e-9) w.step(1.0 / 60.0);
        const double vBall = w.state().bodies[0].P.x(), vA = w.state().bodies[1].P.x(), vB = w.state().bodies[2].P.x();
        const double ke = 0.5 * (vBall * vBall + vA * vA + vB * vB);
        qInfo("after: ball %.9f m/s, dumbbell %.9f and %.9f m/s; kinetic energy %.9f J of 2", vBall, vA, vB, ke);
        QVERIFY2(std::abs(vBall + 2.0 / 3.0) < 1e-6, qPrintable(QString::number(vBall)));
        QVERIFY2(std::abs(vA - 4.0 / 3.0) < 1e-6 && std::abs(vB - 4.0 / 3.0) < 1e-6, qPrintable(QString::number(vA)));
        QVERIFY2(std::abs(ke - 2.0) < 1e-6, qPrintable(QString::number(ke)));
    }

    // The sample door (resources/scenes/hinged-door.json): 20 kg, 0.8 × 2 × 0.04 m, on a
    // hinge at its edge (I = 4.2693 kg m²), opened by a motor of 1 rad/s and at most 20 N m
    // up to its limit at 1.5 rad: it spins up at α = 4.6846 rad/s² for 0.2135 s, turns at 1
    // rad/s, reaches the limit at t = 1.6067 s and stays. (The motor's impulse comes after
    // each step's free move, so the angle lags by α h t / 2 while it spins up: first order.)
    void doorSample() {
        SceneDesc scene = io::readSceneFile(std::string(TUMBLE_SCENES_DIR) + "/hinged-door.json");
        World w(scene);
        const double I = 20.0 * (0.64 + 0.0016) / 12.0 + 20.0 * 0.16, alpha = 20.0 / I;
        const double spunUp = 1.0 / alpha, hit = spunUp + (1.5 - 0.5 * alpha * spunUp * spunUp);
        const double h = scene.settings.dt;
        double reached = -1.0, worstSpeed = 0.0, worstPast = 0.0;
        auto angle = [&] {
            const Quat& q = w.state().bodies[2].q;
            return 2.0 * std::atan2(q.y(), q.w());
        };
        while (w.state().time < 3.0 - 1e-9) {
            w.step(h);
            const double t = w.state().time, a = angle();
            const double spin = derive(w.model().bodies[2], w.state().bodies[2]).omega.y();
            if (reached < 0.0 && a >= 1.5 - 1e-9) reached = t;
            if (t > spunUp + h && t < hit - 2 * h) worstSpeed = std::max(worstSpeed, std::abs(spin - 1.0));
            worstPast = std::max(worstPast, a - 1.5);
        }
        qInfo("at the limit at %.4f s (closed form %.4f); at 1 rad/s to %.1e; past the limit by %.1e rad; ends at "
              "%.12f rad",
              reached, hit, worstSpeed, worstPast, angle());
        QVERIFY2(std::abs(reached - hit) < 2 * h, qPrintable(QString::number(reached)));
        QVERIFY2(worstSpeed < 1e-9, qPrintable(QString::number(worstSpeed)));
        QVERIFY2(worstPast < 1e-9 && std::abs(angle() - 1.5) < 1e-9, qPrintable(QString::number(angle())));
    }

    // The sample chain (resources/scenes/chain.json: 20 capsule links on ball joints, let go
    // held out level) at 1/240, 1/30 and 1/60 s: it folds onto itself and its links collide
    // with each other, and its energy never rises by more than 0.5 % (it went 137 J -> 2e15 J
    // at 1/240 before impacts passed through joints), the joints held to 1e-9 m. At 1/60 the
    // whipping end lifted the energy by 15 % for a moment (t = 2.4 s) while a halved Newton
    // step of the joints' projection was tried from the last try's arms; now by 0.06 %.
    void chainSampleGainsNoEnergy_data() {
        QTest::addColumn<double>("dt");
        QTest::newRow("1/240") << 1.0 / 240.0;
        QTest::newRow("1/30") << 1.0 / 30.0;
        QTest::newRow("1/60") << 1.0 / 60.0;
    }
    void chainSampleGainsNoEnergy() {
        QFETCH(double, dt);
        SceneDesc scene = io::readSceneFile(std::string(TUMBLE_SCENES_DIR) + "/chain.json");
        scene.settings.dt = dt;
        World w(scene);
        auto energyNow = [&] {
            double e = 0.0;
            for (int i : w.model().dynamicBodies) {
                const BodyState& b = w.state().bodies[i];
                const Derived d = derive(w.model().bodies[i], b);
                e += 0.5 * w.model().bodies[i].mass * d.v.squaredNorm() + 0.5 * d.omega.dot(b.L) +
                     w.model().bodies[i].mass * g * b.x.y();
            }
            return e;
        };
        const double e0 = energyNow();
        double most = e0, gap = 0.0, mostAt = 0.0;
        while (w.state().time < 6.0 - 1e-9) {
            w.step(dt);
            if (energyNow() > most) mostAt = w.state().time;
            most = std::max(most, energyNow());
            for (size_t k = 0; k < w.model().joints.size(); ++k) gap = std::max(gap, anchorGap(w, int(k)));
        }
        qInfo("dt %.4f: energy from %.3f J, at most %.3f J (t = %.3f s), at the end %.3f J; joints held to %.1e m", dt,
              e0, most, mostAt, energyNow(), gap);
        QVERIFY2(most < 1.005 * e0, qPrintable(QString::number(most)));
        QVERIFY2(gap < 1e-9, qPrintable(QString::number(gap)));
    }

    // Breaking: a 2 kg ball on a 1 m rod (distance joint) with a breaking force of 30 N,
    // let go level with its pivot. The rod's tension at the angle φ from the vertical is
    // m g 3 cos φ, so the rod breaks at cos φ = 30 / (3 m g), φ = 59.36°, and the ball flies
    // free from there (its velocity then changes by g alone). Hanging at rest (19.6 N) it
    // holds.
    void aJointBreaksAtItsForce() {
        const double m = 2.0, L = 1.0, limit = 30.0;
        const Vec3 pivot(0, 3, 0);
        BodyDesc bob = sphereBody("bob", 0.05, m);
        bob.position = pivot + Vec3(L, 0, 0);
        SceneDesc scene = sceneOf({bob});
        scene.settings.sleeping = false;
        JointDesc rod = joint("rod", JointType::Distance, "bob", Vec3::Zero(), "", pivot);
        rod.breakForce = limit;
        scene.joints.push_back(rod);
        World w(scene);
        const double h = 1.0 / 240.0;
        double brokeAt = -1.0, angleAtBreak = 0.0, worstFree = 0.0;
        Vec3 lastV = Vec3::Zero();
        while (w.state().time < 1.0 - 1e-9) {
            w.step(h);
            const BodyState& b = w.state().bodies[0];
            const Vec3 v = b.P / m;
            if (brokeAt < 0.0 && w.state().jointBroken(0)) {
                brokeAt = w.state().jointBrokenAt[0];
                const Vec3 d = b.x - pivot;
                angleAtBreak = std::atan2(d.x(), -d.y()) * 180.0 / std::numbers::pi;
            } else if (brokeAt > 0.0) {
                worstFree = std::max(worstFree, (v - lastV - Vec3(0, -g * h, 0)).norm());
            }
            lastV = v;
        }
        const double expected = std::acos(limit / (3.0 * m * g)) * 180.0 / std::numbers::pi;
        qInfo("broke at t = %.4f s at %.3f deg from the vertical (closed form %.3f); then free to %.1e m/s a step",
              brokeAt, angleAtBreak, expected, worstFree);
        QVERIFY(brokeAt > 0.0);
        // Within two steps of its swing there (the force is the step's average, and the step
        // that carried too much is the last one the rod acts in).
        const double perStep = std::sqrt(2.0 * g * std::cos(expected * std::numbers::pi / 180.0) / L) * h * 180.0 /
                               std::numbers::pi;
        QVERIFY2(std::abs(angleAtBreak - expected) < 2.0 * perStep, qPrintable(QString::number(angleAtBreak)));
        QVERIFY2(worstFree < 1e-9, qPrintable(QString::number(worstFree)));

        // Hanging still, it carries m g = 19.6 N and holds.
        bob.position = pivot - Vec3(0, L, 0);
        SceneDesc still = sceneOf({bob});
        still.settings.sleeping = false;
        still.joints.push_back(rod);
        World hanging(still);
        while (hanging.state().time < 2.0 - 1e-9) hanging.step(h);
        QVERIFY(!hanging.state().jointBroken(0));
        QVERIFY(std::abs(hanging.state().bodies[0].x.y() - 2.0) < 1e-9);
    }

    // Sleeping: a chain of three balls on rods hanging still from the world falls asleep as
    // one island (joints are its edges), and a push on the top ball at t = 1.5 s wakes all
    // three at once; the bottom one moves on the next steps.
    void aJointedAssemblySleepsAndWakesAsOne() {
        std::vector<BodyDesc> balls;
        for (int k = 0; k < 3; ++k) {
            BodyDesc b = sphereBody("ball-" + std::to_string(k), 0.05, 1.0);
            b.position = Vec3(0, 2.0 - 0.5 * k, 0);
            balls.push_back(b);
        }
        ForceDesc push;
        push.vector = Vec3(5, 0, 0);
        push.start = 1.5;
        push.end = 1.6;
        balls[0].forces.push_back(push);
        SceneDesc scene = sceneOf(balls);
        scene.settings.sleeping = true;
        scene.joints.push_back(joint("hook", JointType::Distance, "ball-0", Vec3::Zero(), "", Vec3(0, 2.5, 0)));
        scene.joints.push_back(joint("rod-1", JointType::Distance, "ball-1", Vec3::Zero(), "ball-0", Vec3::Zero()));
        scene.joints.push_back(joint("rod-2", JointType::Distance, "ball-2", Vec3::Zero(), "ball-1", Vec3::Zero()));
        World w(scene);
        const double h = 1.0 / 240.0;
        while (w.state().time < 1.45) w.step(h);
        for (int k = 0; k < 3; ++k) QVERIFY2(w.state().isAsleep(k), qPrintable(QString::number(k)));
        const Vec3 bottom = w.state().bodies[2].x;
        while (w.state().time < 1.55) w.step(h);
        for (int k = 0; k < 3; ++k) QVERIFY2(!w.state().isAsleep(k), qPrintable(QString::number(k)));
        while (w.state().time < 1.8) w.step(h);
        QVERIFY2((w.state().bodies[2].x - bottom).x() > 1e-3, qPrintable(QString::number((w.state().bodies[2].x - bottom).x())));
        for (int k = 0; k < 3; ++k) QVERIFY(std::abs(anchorGap(w, k) - 0.5) < 1e-9);  // the rods keep 0.5 m
    }

    // A bad joint is refused with the field named.
    void badJointsAreRefused() {
        BodyDesc a = sphereBody("a", 0.1, 1.0), ground = boxBody("ground", Vec3(1, 0.1, 1), 1.0);
        ground.mass.reset();
        ground.motion = Motion::Static;
        auto refused = [&](const JointDesc& j, const QString& field) {
            SceneDesc s = sceneOf({a, ground});
            s.joints.push_back(j);
            try {
                World w(s);
            } catch (const SceneError& e) {
                return QString::fromStdString(e.path()) == field;
            }
            return false;
        };
        QVERIFY(refused(joint("", JointType::Ball, "a", Vec3::Zero(), "", Vec3::Zero()), "joints[0].name"));
        QVERIFY(refused(joint("j", JointType::Ball, "nobody", Vec3::Zero(), "", Vec3::Zero()), "joints[0].body_a"));
        QVERIFY(refused(joint("j", JointType::Ball, "a", Vec3::Zero(), "nobody", Vec3::Zero()), "joints[0].body_b"));
        QVERIFY(refused(joint("j", JointType::Ball, "a", Vec3::Zero(), "a", Vec3::Zero()), "joints[0].body_b"));
        QVERIFY(refused(joint("j", JointType::Ball, "ground", Vec3::Zero(), "", Vec3::Zero()), "joints[0]"));
        QVERIFY(refused(joint("j", JointType::Ball, "a", Vec3(NAN, 0, 0), "", Vec3::Zero()), "joints[0].anchor_a"));
        QVERIFY(refused(joint("j", JointType::Rope, "a", Vec3::Zero(), "", Vec3::Zero(), 0.0), "joints[0].length"));
        QVERIFY(refused(joint("j", JointType::Ball, "a", Vec3::Zero(), "", Vec3::Zero(), 1.0), "joints[0].length"));
        // A joint that does not hold in the scene as written runs, with a note naming it.
        SceneDesc off = sceneOf({a, ground});
        off.joints.push_back(joint("pin", JointType::Ball, "a", Vec3::Zero(), "", Vec3(0.1, 0, 0)));
        const World offWorld(off);
        QCOMPARE(offWorld.model().notes.size(), size_t(1));
        QCOMPARE(QString::fromStdString(offWorld.model().notes[0]),
                 QString("joints[0] (pin): does not hold in the scene as written (off by 0.1 m); the first step pulls "
                         "it together, giving its bodies that move's speed"));
        off.joints[0].anchorB = a.position;
        QVERIFY(World(off).model().notes.empty());
        // A scene without joints is what it was.
        World plain(sceneOf({a, ground}));
        QVERIFY(plain.model().joints.empty() && plain.model().jointed.empty());
    }
};

QTEST_GUILESS_MAIN(TestJoints)
#include "tst_joints.moc"
