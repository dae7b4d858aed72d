// The joints' reactions (State::jointForces and jointCouples: what the trajectory export
// writes with --joint-forces), against statics and the closed forms of simple motions: a
// bob hanging still carries its weight, a welded bar its weight and the moment of it, a
// rod pendulum's tension is m g cos(theta) + m v^2 / L, and the door sample's hinge gives
// its motor's torque, the tangential and centripetal forces of the turning door, and its
// weight's moment.
#include "joint_checks.h"
#include "scene_builders.h"

#include <tumble/io/scene_file.h>
#include <tumble/world.h>

#include <QtTest>

#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::test;

namespace {

constexpr double g = 9.81;

void run(World& w, double seconds, double h) {
    while (w.state().time < seconds - 1e-9) w.step(h);
}

}  // namespace

class TestJointReactions : public QObject {
    Q_OBJECT
private slots:
    // A 2 kg ball hanging still from a world point by a ball joint at its top: the joint holds
    // it up with its weight, at every step size; no couple.
    void hangingBobCarriesItsWeight_data() {
        QTest::addColumn<double>("h");
        QTest::newRow("1/30") << 1.0 / 30;
        QTest::newRow("1/240") << 1.0 / 240;
    }
    void hangingBobCarriesItsWeight() {
        QFETCH(double, h);
        BodyDesc bob = sphereBody("bob", 0.1, 2.0);
        bob.position = Vec3(0, 2, 0);
        SceneDesc s = sceneOf({bob});
        s.settings.sleeping = false;
        s.joints.push_back(joint("top", JointType::Ball, "bob", Vec3(0, 0.5, 0), "", Vec3(0, 2.5, 0)));
        World w(s);
        QVERIFY(w.state().jointForces.empty());  // no step yet
        run(w, 1.0, h);
        const Vec3 f = w.state().jointForces[0];
        QVERIFY2((f - Vec3(0, 2.0 * g, 0)).norm() < 1e-9 * 2.0 * g, qPrintable(QString::number(f.y(), 'g', 17)));
        QCOMPARE(w.state().jointCouples[0].norm(), 0.0);
    }

    // A bar (1 kg, 1 m long along x) welded to the world at its left end: the weld carries
    // its weight and the weight's moment about the end, (c - anchor) x m g.
    void weldedBarCarriesItsWeightAndItsMoment() {
        BodyDesc bar = boxBody("bar", Vec3(0.5, 0.05, 0.05), 1.0);
        bar.position = Vec3(0, 2, 0);
        SceneDesc s = sceneOf({bar});
        s.settings.sleeping = false;
        s.joints.push_back(joint("weld", JointType::Fixed, "bar", Vec3(-0.5, 0, 0), "", Vec3(-0.5, 2, 0)));
        World w(s);
        run(w, 0.5, 1.0 / 60);
        const Vec3 f = w.state().jointForces[0], c = w.state().jointCouples[0];
        QVERIFY((f - Vec3(0, g, 0)).norm() < 1e-9 * g);
        const Vec3 moment = Vec3(0.5, 0, 0).cross(Vec3(0, g, 0));  // (0, 0, 4.905)
        QVERIFY2((c - moment).norm() < 1e-9 * moment.norm(), qPrintable(QString::number(c.z(), 'g', 17)));
    }

    // A rod pendulum (1 kg bob on a 1 m distance joint) let go at 1 rad: the rod pulls the
    // bob towards the pivot with m g cos(theta) + m v^2 / L. The force is over the last
    // step, so it is compared with the mean of that pull at the step's start and end: the
    // difference is second order in h (measured 1.83e-3 of m g at 1/60, 1.14e-4 at 1/240:
    // 16 times less at a 4 times shorter step).
    void rodTensionIsCentripetalPlusWeight_data() {
        QTest::addColumn<double>("h");
        QTest::addColumn<double>("tolerance");  // of m g
        QTest::newRow("1/60") << 1.0 / 60 << 2.5e-3;
        QTest::newRow("1/240") << 1.0 / 240 << 1.6e-4;
    }
    void rodTensionIsCentripetalPlusWeight() {
        QFETCH(double, h);
        QFETCH(double, tolerance);
        const Vec3 pivot(0, 3, 0);
        const double L = 1.0, theta0 = 1.0, m = 1.0;
        BodyDesc bob = sphereBody("bob", 0.05, m);
        bob.position = pivot + L * Vec3(std::sin(theta0), -std::cos(theta0), 0);
        SceneDesc s = sceneOf({bob});
        s.settings.sleeping = false;
        JointDesc rod = joint("rod", JointType::Distance, "bob", Vec3::Zero(), "", pivot);
        s.joints.push_back(rod);
        World w(s);
        auto tension = [&](const BodyState& b) {
            const Vec3 d = pivot - b.x;  // along the rod, towards the pivot
            const double cosTheta = d.normalized().y();  // from the vertical below the pivot
            const Vec3 v = b.P / m;
            return m * g * cosTheta + m * v.squaredNorm() / L;
        };
        double worst = 0.0;
        for (int k = 0; k < int(std::lround(3.0 / h)); ++k) {
            const BodyState before = w.state().bodies[0];
            w.step(h);
            const BodyState& after = w.state().bodies[0];
            // The mean of the rod's pull at the step's start and end, each along the rod then.
            const Vec3 expected = 0.5 * (tension(before) * (pivot - before.x).normalized() +
                                         tension(after) * (pivot - after.x).normalized());
            worst = std::max(worst, (w.state().jointForces[0] - expected).norm() / (m * g));
        }
        QVERIFY2(worst < tolerance, qPrintable(QString::number(worst, 'g', 3)));
    }

    // The door sample (20 kg, 0.8 m wide, hinged at its edge; motor 1 rad/s, at most 20 N m;
    // I about the hinge 4.2693 kg m^2): while it spins up the hinge gives the motor's 20 N m
    // about the axis and the tangential force m alpha d (alpha = 20 / I, d = 0.4 m); at
    // 1 rad/s the centripetal m w^2 d; always the weight and the weight's moment m g d.
    void doorHingeGivesMotorTorqueAndTheTurningForces() {
        World w(io::readSceneFile(TUMBLE_SCENES_DIR "/hinged-door.json"));
        const double h = 1.0 / 240, m = 20.0, d = 0.4, I = 4.2693, alpha = 20.0 / I;
        run(w, 0.05, h);
        Vec3 f = w.state().jointForces[0], c = w.state().jointCouples[0];
        QVERIFY(std::abs(f.y() - m * g) < 1e-9 * m * g);
        QVERIFY2(std::abs(c.y() - 20.0) < 1e-9 * 20.0, qPrintable(QString::number(c.y(), 'g', 17)));
        QVERIFY2(std::abs(Vec3(f.x(), 0, f.z()).norm() - m * alpha * d) < 2e-3 * m * alpha * d,
                 qPrintable(QString::number(Vec3(f.x(), 0, f.z()).norm(), 'g', 17)));
        QVERIFY(std::abs(Vec3(c.x(), 0, c.z()).norm() - m * g * d) < 1e-3 * m * g * d);
        run(w, 1.0, h);  // at 1 rad/s: the motor holds the speed with no torque
        f = w.state().jointForces[0];
        c = w.state().jointCouples[0];
        QVERIFY(std::abs(c.y()) < 1e-6);
        QVERIFY2(std::abs(Vec3(f.x(), 0, f.z()).norm() - m * 1.0 * d) < 1e-3 * m * d,
                 qPrintable(QString::number(Vec3(f.x(), 0, f.z()).norm(), 'g', 17)));
        run(w, 2.0, h);  // at its stop: the motor and the limit cancel about the axis
        c = w.state().jointCouples[0];
        QVERIFY(std::abs(c.y()) < 1e-6);
        QVERIFY(std::abs(c.norm() - m * g * d) < 1e-6 * m * g * d);
    }
};

QTEST_MAIN(TestJointReactions)
#include "tst_joint_reactions.moc"
