// Animated (keyed) bodies, issue 50 item 1: what meets a keyed body sees its path's velocity.
// Closed forms, each in the world as built and in a world turned and shifted as a whole:
// a paddle at constant speed v throws a resting ball at 2v (e = 1) or carries it at v
// (e = 0), the work it did booked in the ledger; a paddle 1 cm thick at 1 m a step never
// passes through the ball; a box rides a lift without sinking or hopping and is thrown up
// at the lift's speed when the lift stops; a turntable at ω carries a box at a radius r by
// friction while μ g ≥ ω² r and lets it slide off beyond. Bad keys are refused, naming
// the field.
#include <QtTest>

#include <tumble/errors.h>
#include <tumble/model.h>
#include <tumble/world.h>

#include "ledger_checks.h"
#include "scene_builders.h"
#include "turned_world.h"

#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::test;

namespace {

BodyDesc animated(BodyDesc b, std::vector<BodyKey> keys, KeyInterpolation how = KeyInterpolation::Linear) {
    b.motion = Motion::Animated;
    b.mass.reset();
    b.keys = std::move(keys);
    b.interpolation = how;
    b.position = b.keys.front().position;
    b.orientation = b.keys.front().orientation;
    return b;
}

// The world as built (seed 0) or turned and shifted by a pose drawn from the seed.
WorldPose poseOf(int seed) {
    return seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
}

void addRows(const char* name, std::initializer_list<double> rates) {
    for (double rate : rates)
        for (int seed : {0, 7})
            QTest::newRow(
                qPrintable(QString("%1 1/%2 %3").arg(name).arg(rate).arg(seed ? "turned" : "as built")))
                << 1.0 / rate << seed;
}

// A thin paddle (half extents 0.05 x 0.5 x 0.5 m, or `thickness`) keyed along x from x0 at
// t = 0 at speed v for 2 s, and a 1 kg ball of radius 0.2 at rest at x = 0.5, no gravity,
// no friction; restitution e on both.
SceneDesc paddleScene(double v, double e, double x0 = -1.0, double halfThickness = 0.05) {
    BodyDesc paddle =
        animated(boxBody("paddle", Vec3(halfThickness, 0.5, 0.5), 1.0),
                 {{0.0, Vec3(x0, 0, 0), Quat::Identity()}, {2.0, Vec3(x0 + 2 * v, 0, 0), Quat::Identity()}});
    BodyDesc ball = sphereBody("ball", 0.2, 1.0);
    ball.position = Vec3(0.5, 0, 0);
    return sceneOf({material(paddle, e, 0.0), material(ball, e, 0.0)}, Vec3::Zero());
}

}  // namespace

class TestAnimated : public QObject {
    Q_OBJECT

private slots:
    // e = 1: the ball leaves at 2v and the paddle did 2 m v² of work, all of it the ball's;
    // e = 0: it rides at v, the paddle did m v² and the impact took half of it.
    void paddleThrowsBall_data() {
        QTest::addColumn<double>("dt");
        QTest::addColumn<int>("seed");
        QTest::addColumn<double>("e");
        for (double e : {1.0, 0.0})
            for (double rate : {240.0, 60.0, 30.0})
                for (int seed : {0, 7})
                    QTest::newRow(qPrintable(
                        QString("e %1 1/%2 %3").arg(e).arg(rate).arg(seed ? "turned" : "as built")))
                        << 1.0 / rate << seed << e;
    }
    void paddleThrowsBall() {
        QFETCH(double, dt);
        QFETCH(int, seed);
        QFETCH(double, e);
        const double v = 2.0;
        const WorldPose pose = poseOf(seed);
        World w(turnedScene(paddleScene(v, e), pose));
        stepN(w, std::lround(1.5 / dt), dt);
        const Vec3 ball = velocityOf(w, 1);
        const Vec3 want = pose.direction(Vec3((e == 1.0 ? 2.0 : 1.0) * v, 0, 0));
        QVERIFY2((ball - want).norm() < 1e-9, qPrintable(QString("ball at %1 %2 %3 m/s")
                                                             .arg(ball.x(), 0, 'g', 12)
                                                             .arg(ball.y(), 0, 'g', 12)
                                                             .arg(ball.z(), 0, 'g', 12)));
        // The paddle is where its keys say, moving as they say.
        const BodyState& paddle = w.state().bodies[0];
        QVERIFY((paddle.x - pose.point(Vec3(-1.0 + 1.5 * v, 0, 0))).norm() < 1e-12);
        QVERIFY((derive(w.model().bodies[0], paddle).v - pose.direction(Vec3(v, 0, 0))).norm() < 1e-12);
        const EnergyLedger& l = w.ledger();
        const double work = (e == 1.0 ? 2.0 : 1.0) * v * v, lost = e == 1.0 ? 0.0 : 0.5 * v * v;
        QVERIFY2(std::abs(l.doneByKinematic - work) < 1e-9 * work &&
                     std::abs(l.lostInContacts - lost) < 1e-9 * work,
                 qPrintable(QString("by the paddle %1 J, lost %2 J")
                                .arg(l.doneByKinematic, 0, 'g', 12)
                                .arg(l.lostInContacts, 0, 'g', 12)));
    }

    // A paddle 1 cm thick at 30 m/s, 1 m a step at 1/30 s: it meets the ball at its moment
    // and throws it at 60 m/s, never through it.
    void aFastPaddleNeverPassesThrough_data() {
        QTest::addColumn<double>("dt");
        QTest::addColumn<int>("seed");
        addRows("", {30.0, 60.0});
    }
    void aFastPaddleNeverPassesThrough() {
        QFETCH(double, dt);
        QFETCH(int, seed);
        const WorldPose pose = poseOf(seed);
        World w(turnedScene(paddleScene(30.0, 1.0, -3.0, 0.005), pose));
        stepN(w, std::lround(0.2 / dt), dt);
        const Vec3 ball = velocityOf(w, 1);
        QVERIFY2((ball - pose.direction(Vec3(60, 0, 0))).norm() < 1e-9,
                 qPrintable(QString("ball at %1 m/s").arg(ball.norm(), 0, 'g', 12)));
        const Vec3 ahead = pose.R.conjugate() * (w.state().bodies[1].x - w.state().bodies[0].x);
        QVERIFY(ahead.x() > 0.2);
    }

    // A lift keyed to rise 2 m at 1 m/s from 0.5 s to 2.5 s carries a 0.4 m box: in the rise
    // the box moves at the lift's 1 m/s and sits on it; when the lift stops the box goes on
    // up at 1 m/s (thrown as from a stopping lift), and lands back on it at rest.
    void aLiftCarriesABox_data() {
        QTest::addColumn<double>("dt");
        QTest::addColumn<int>("seed");
        addRows("", {240.0, 60.0, 30.0});
    }
    void aLiftCarriesABox() {
        QFETCH(double, dt);
        QFETCH(int, seed);
        const WorldPose pose = poseOf(seed);
        BodyDesc lift =
            animated(boxBody("lift", Vec3(1, 0.1, 1), 1.0),
                     {{0.5, Vec3::Zero(), Quat::Identity()}, {2.5, Vec3(0, 2, 0), Quat::Identity()}});
        BodyDesc box = boxBody("box", Vec3(0.2, 0.2, 0.2), 2.0);
        box.position = Vec3(0, 0.3, 0);
        World w(turnedScene(sceneOf({material(lift, 0.0, 0.5), material(box, 0.0, 0.5)}), pose));
        const Quat back = pose.R.conjugate();
        auto height = [&] { return (back * (w.state().bodies[1].x - w.state().bodies[0].x)).y(); };
        double lowest = HUGE_VAL, highest = -HUGE_VAL, top = -HUGE_VAL;
        while (w.state().time < 1.5 - 0.5 * dt) {
            w.step(dt);
            lowest = std::min(lowest, height());
            highest = std::max(highest, height());
        }
        // Sitting on it, 0.3 m above its centre, within the contact slop (1 mm here).
        QVERIFY2(
            lowest > 0.3 - 1e-3 && highest < 0.3 + 1e-9,
            qPrintable(QString("from %1 to %2 m above").arg(lowest, 0, 'g', 12).arg(highest, 0, 'g', 12)));
        const Vec3 v = back * velocityOf(w, 1);
        QVERIFY2((v - Vec3(0, 1, 0)).norm() < 1e-9,
                 qPrintable(QString("box at %1 m/s up").arg(v.y(), 0, 'g', 12)));
        while (w.state().time < 2.5 - 0.5 * dt) w.step(dt);
        w.step(dt);  // the first step after the stop: thrown up at 1 m/s less g dt
        const Vec3 thrown = back * velocityOf(w, 1);
        QVERIFY2(std::abs(thrown.y() - (1.0 - 9.81 * dt)) < 1e-9,
                 qPrintable(QString("thrown at %1 m/s").arg(thrown.y(), 0, 'g', 12)));
        while (w.state().time < 4.0 - 0.5 * dt) {
            w.step(dt);
            top = std::max(top, height());
        }
        // The flight's top: 1/(2g) above the lift's top, to the sampling of the steps.
        const double rise = 1.0 / (2 * 9.81);
        QVERIFY2(top <= 0.3 + rise + 1e-9 && top > 0.3 + rise - 9.81 * dt * dt,
                 qPrintable(QString("rose %1 m").arg(top - 0.3, 0, 'g', 12)));
        QVERIFY(std::abs(height() - 0.3) < 1e-3 && velocityOf(w, 1).norm() < 1e-6);
    }

    // A smooth lift (eased in and out, at most 3 m/s² each way, less than g): the box stays
    // on it, neither sinking nor hopping, and moves with it to within its change of speed
    // over a step.
    void aSmoothLiftCarriesABox_data() { aLiftCarriesABox_data(); }
    void aSmoothLiftCarriesABox() {
        QFETCH(double, dt);
        QFETCH(int, seed);
        const WorldPose pose = poseOf(seed);
        BodyDesc lift =
            animated(boxBody("lift", Vec3(1, 0.1, 1), 1.0),
                     {{0.0, Vec3::Zero(), Quat::Identity()}, {2.0, Vec3(0, 2, 0), Quat::Identity()}},
                     KeyInterpolation::Smooth);
        BodyDesc box = boxBody("box", Vec3(0.2, 0.2, 0.2), 2.0);
        box.position = Vec3(0, 0.3, 0);
        World w(turnedScene(sceneOf({material(lift, 0.0, 0.5), material(box, 0.0, 0.5)}), pose));
        const double start = energy(w.model(), w.state()).total();
        const Quat back = pose.R.conjugate();
        double lowest = HUGE_VAL, highest = -HUGE_VAL, slip = 0.0;
        while (w.state().time < 2.0 - 0.5 * dt) {
            w.step(dt);
            const double h = (back * (w.state().bodies[1].x - w.state().bodies[0].x)).y();
            lowest = std::min(lowest, h);
            highest = std::max(highest, h);
            slip = std::max(slip,
                            (velocityOf(w, 1) - derive(w.model().bodies[0], w.state().bodies[0]).v).norm());
        }
        QVERIFY2(
            lowest > 0.3 - 1e-3 && highest < 0.3 + 1e-9,
            qPrintable(QString("from %1 to %2 m above").arg(lowest, 0, 'g', 12).arg(highest, 0, 'g', 12)));
        QVERIFY2(slip <= 3.0 * dt + 1e-9,
                 qPrintable(QString("box and lift %1 m/s apart").arg(slip, 0, 'g', 6)));
        // The lift did the work of raising the box 2 m (m g h = 39.24 J; it ends at rest):
        // the ledger books it, and closes with it.
        const double lifted = 2.0 * 9.81 * 2.0;
        const EnergyLedger& l = w.ledger();
        const double gap = ledgerGap(w, start);
        QVERIFY2(std::abs(l.doneByKinematic - lifted) < 1e-2 * lifted && std::abs(gap) < 1e-3 * lifted,
                 qPrintable(QString("by the lift %1 J, %2")
                                .arg(l.doneByKinematic, 0, 'g', 8)
                                .arg(describeLedger(w, start))));
    }

    // A turntable at ω = 2 rad/s (keyed every quarter turn) with boxes (μ = 0.5) turning
    // with it: carried while μ g ≥ ω² r, so at 0.9 of r* = μ g / ω² a box turns with the
    // table, moving with the table's surface (to second order: its velocity, set where the
    // step's solve found it, is the surface's there, and the step then moves it), and at
    // 1.1 r* it slides off.
    // A box held by friction moves h v a step, the table's velocity where it is: on a
    // circle that is the symplectic step, which draws it in by ω² r h² / 2 a step, π ω r h
    // a turn (first order: 2.9 cm at 1/240 s here).
    void aTurntableCarriesWithinItsRadius_data() {
        QTest::addColumn<double>("dt");
        QTest::addColumn<int>("seed");
        addRows("", {240.0, 60.0, 30.0});
    }
    void aTurntableCarriesWithinItsRadius() {
        QFETCH(double, dt);
        QFETCH(int, seed);
        const WorldPose pose = poseOf(seed);
        const double omega = 2.0, mu = 0.5, g = 9.81, reach = mu * g / (omega * omega);
        std::vector<BodyKey> keys;
        for (int k = 0; k <= 8; ++k)
            keys.push_back({k * (std::numbers::pi / 2) / omega, Vec3::Zero(),
                            Quat(Eigen::AngleAxisd(k * std::numbers::pi / 2, Vec3::UnitY()))});
        BodyDesc table = animated(boxBody("table", Vec3(3, 0.1, 3), 1.0), keys);
        std::vector<BodyDesc> bodies{material(table, 0.0, mu)};
        const double inner = 0.9, outer = 1.1;
        for (double share : {inner, outer}) {
            const double r = share * reach, side = share < 1.0 ? 1.0 : -1.0;
            BodyDesc box =
                material(boxBody("box " + std::to_string(share), Vec3(0.1, 0.1, 0.1), 1.0), 0.0, mu);
            box.position = Vec3(side * r, 0.2, 0);
            box.velocity = Vec3(0, 0, -side * omega * r);  // ω ŷ × r
            box.angularVelocity = Vec3(0, omega, 0);
            bodies.push_back(box);
        }
        World w(turnedScene(sceneOf(bodies), pose));
        const double turn = 2 * std::numbers::pi / omega;
        double slip = 0.0;
        for (long n = std::lround(turn / dt); n > 0; --n) {
            w.step(dt);
            const Vec3 arm = w.state().bodies[1].x - pose.t;
            slip = std::max(slip, (velocityOf(w, 1) - pose.direction(Vec3(0, omega, 0)).cross(arm)).norm());
        }
        const Quat back = pose.R.conjugate();
        auto at = [&](int i) { return Vec3(back * (w.state().bodies[i].x - pose.t)); };
        const Vec3 kept = at(1), lost = at(2);
        const double r = std::hypot(kept.x(), kept.z());
        const double drift = std::numbers::pi * omega * inner * reach * dt;
        QVERIFY2(slip < 8 * omega * omega * inner * reach * dt * dt,
                 qPrintable(QString("the inner box slipped at %1 m/s").arg(slip, 0, 'g', 3)));
        QVERIFY2(r < inner * reach && r > inner * reach - 1.2 * drift && std::abs(kept.y() - 0.2) < 1e-3,
                 qPrintable(QString("the inner box at %1 %2 %3 m: radius %4 m, drawn in %5 (π ω r h: %6)")
                                .arg(kept.x(), 0, 'g', 8)
                                .arg(kept.y(), 0, 'g', 8)
                                .arg(kept.z(), 0, 'g', 8)
                                .arg(r, 0, 'g', 8)
                                .arg(inner * reach - r, 0, 'g', 3)
                                .arg(drift, 0, 'g', 3)));
        QVERIFY2(std::hypot(lost.x(), lost.z()) > 1.5 * outer * reach,
                 qPrintable(
                     QString("the outer box at radius %1 m").arg(std::hypot(lost.x(), lost.z()), 0, 'g', 8)));
    }

    // A pendulum hung from a carriage keyed to move at a constant 1 m/s swings as it would
    // from a pivot at rest (Galilean relativity), shifted by the carriage's travel: the joint
    // sees the carriage's velocity.
    void aPendulumOnAMovingCarriageSwingsAsOnAFixedOne_data() {
        QTest::addColumn<double>("dt");
        QTest::addColumn<int>("seed");
        addRows("", {240.0, 60.0});
    }
    void aPendulumOnAMovingCarriageSwingsAsOnAFixedOne() {
        QFETCH(double, dt);
        QFETCH(int, seed);
        const WorldPose pose = poseOf(seed);
        auto scene = [&](double v) {
            BodyDesc pivot = animated(
                boxBody("carriage", Vec3(0.1, 0.1, 0.1), 1.0),
                {{0.0, Vec3(0, 2, 0), Quat::Identity()}, {10.0, Vec3(10 * v, 2, 0), Quat::Identity()}});
            BodyDesc bob = sphereBody("bob", 0.1, 1.0);
            bob.position = Vec3(1, 2, 0);
            bob.velocity = Vec3(v, 0, 0);
            JointDesc rod;
            rod.name = "rod";
            rod.type = JointType::Distance;
            rod.bodyA = "bob";
            rod.bodyB = "carriage";
            SceneDesc s = sceneOf({pivot, bob});
            s.joints.push_back(rod);
            return turnedScene(s, pose);
        };
        World moving(scene(1.0)), fixed(scene(0.0));
        const long n = std::lround(2.0 / dt);
        stepN(moving, n, dt);
        stepN(fixed, n, dt);
        const Vec3 travel = pose.direction(Vec3(n * dt, 0, 0));
        const Vec3 gap = moving.state().bodies[1].x - travel - fixed.state().bodies[1].x;
        const Vec3 dv = velocityOf(moving, 1) - pose.direction(Vec3(1, 0, 0)) - velocityOf(fixed, 1);
        QVERIFY2(
            gap.norm() < 1e-6 && dv.norm() < 1e-6,
            qPrintable(QString("%1 m, %2 m/s apart").arg(gap.norm(), 0, 'g', 3).arg(dv.norm(), 0, 'g', 3)));
        // It swung: a quarter swing down from level is 0.45 s for a 1 m pendulum.
        QVERIFY(std::abs((pose.R.conjugate() * (fixed.state().bodies[1].x - pose.t)).y() - 2) > 0.1);
    }

    // Bad keys are refused naming the field.
    void badKeysAreRefused_data() {
        QTest::addColumn<int>("problem");
        QTest::addColumn<QString>("field");
        QTest::newRow("no keys") << 0 << "bodies[0].keys";
        QTest::newRow("repeated time") << 1 << "bodies[0].keys[1].time";
        QTest::newRow("unsorted time") << 2 << "bodies[0].keys[2].time";
        QTest::newRow("zero quaternion") << 3 << "bodies[0].keys[1].orientation";
        QTest::newRow("mass") << 4 << "bodies[0].mass";
        QTest::newRow("velocity") << 5 << "bodies[0].velocity";
        QTest::newRow("keys on a dynamic body") << 6 << "bodies[0].keys";
        QTest::newRow("infinite position") << 7 << "bodies[0].keys[0].position";
    }
    void badKeysAreRefused() {
        QFETCH(int, problem);
        QFETCH(QString, field);
        BodyDesc b =
            animated(boxBody("paddle", Vec3(0.1, 0.1, 0.1), 1.0), {{0, Vec3::Zero(), Quat::Identity()},
                                                                   {1, Vec3(1, 0, 0), Quat::Identity()},
                                                                   {2, Vec3(2, 0, 0), Quat::Identity()}});
        switch (problem) {
            case 0: b.keys.clear(); break;
            case 1: b.keys[1].time = 0; break;
            case 2: b.keys[2].time = 0.5; break;
            case 3: b.keys[1].orientation = Quat(0, 0, 0, 0); break;
            case 4: b.mass = 1.0; break;
            case 5: b.velocity = Vec3(1, 0, 0); break;
            case 6:
                b.motion = Motion::Dynamic;
                b.mass = 1.0;
                break;
            case 7: b.keys[0].position.x() = HUGE_VAL; break;
        }
        try {
            compile(sceneOf({b}));
            QFAIL("accepted");
        } catch (const SceneError& e) {
            QCOMPARE(QString::fromStdString(e.path()), field);
        }
    }

    // Before its first key and after its last it holds still; the run starts where the path
    // has it at t = 0, whatever `position` says.
    void holdsBeforeAndAfter() {
        BodyDesc b =
            animated(boxBody("paddle", Vec3(0.1, 0.1, 0.1), 1.0),
                     {{0.5, Vec3(1, 0, 0), Quat::Identity()}, {1.0, Vec3(2, 0, 0), Quat::Identity()}});
        b.position = Vec3(7, 7, 7);
        World w(sceneOf({b}, Vec3::Zero()));
        QVERIFY((w.state().bodies[0].x - Vec3(1, 0, 0)).norm() == 0.0);
        stepN(w, 60, 1.0 / 60);
        QVERIFY((w.state().bodies[0].x - Vec3(2, 0, 0)).norm() < 1e-15);
        QVERIFY(derive(w.model().bodies[0], w.state().bodies[0]).v.isZero(0.0));
    }
};

QTEST_GUILESS_MAIN(TestAnimated)
#include "tst_animated.moc"
