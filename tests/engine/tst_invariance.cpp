// One pose proves one pose (issue 44): the closed-form motions hold for bodies placed in
// any orientation, and a scene turned and shifted as a whole (gravity too) moves as the
// original does, turned and shifted. A failure names its seed and writes its scene.
#include "scene_builders.h"
#include "turned_world.h"

#include <tumble/integrators.h>

#include <QtTest>

#include <cmath>

using namespace tumble;
using namespace tumble::test;

namespace {

double kinetic(const World& w) { return energy(w.model(), w.state()).kinetic; }

// The angle between two directions (well resolved near zero).
double angleOf(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace

class TestInvariance : public QObject {
    Q_OBJECT
private slots:
    // A box (half extents 0.5, 0.2, 0.1; 2 kg; no gravity) placed in a random orientation
    // and spun at 30 rad/s about one of its principal axes, 3 s: the energy and |L| stay to
    // rounding whatever the pose, the axis and the step; about the two stable axes (the
    // largest and the smallest moment) the spin stays on its axis to rounding too. About
    // the middle axis rounding grows into a flip (e^(20 t): physics), but the energy holds.
    // Before the fix 81 of 102 such runs changed the energy by 1 % to 110 %.
    void principalSpinInAnyPose_data() {
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<double>("h");
        QTest::addColumn<int>("axis");
        QTest::addColumn<int>("seed");
        for (const char* name : {"splitting", "splitting-4"})
            for (double h : {1.0 / 60, 1.0 / 1000})
                for (int axis = 0; axis < 3; ++axis)
                    for (int seed = 1; seed <= 6; ++seed)
                        QTest::addRow("%s h=%g axis %d seed %d", name, h, axis, seed) << name << h << axis << seed;
    }
    void principalSpinInAnyPose() {
        QFETCH(QString, integrator);
        QFETCH(double, h);
        QFETCH(int, axis);
        QFETCH(int, seed);
        BodyDesc b = boxBody("box", Vec3(0.5, 0.2, 0.1), 2.0);
        b.orientation = randomWorldPose(seed).R;
        const Vec3 spinAxis = b.orientation * Vec3::Unit(axis);
        b.angularVelocity = 30.0 * spinAxis;
        World w(sceneOf({b}, Vec3::Zero(), integrator.toStdString()));
        const double e0 = kinetic(w), l0 = w.state().bodies[0].L.norm();
        double worstE = 0, worstL = 0, worstAxis = 0;
        const long n = std::lround(3.0 / h);
        for (long k = 0; k < n; ++k) {
            w.step(h);
            worstE = std::max(worstE, std::abs(kinetic(w) - e0) / e0);
            worstL = std::max(worstL, std::abs(w.state().bodies[0].L.norm() - l0) / l0);
            worstAxis = std::max(worstAxis, angleOf(omegaOf(w, 0), spinAxis));
        }
        const QString what = QString("energy %1, |L| %2, spin off its axis by %3 rad")
                                 .arg(worstE, 0, 'g', 3)
                                 .arg(worstL, 0, 'g', 3)
                                 .arg(worstAxis, 0, 'g', 3);
        QVERIFY2(worstE < 1e-12, qPrintable(what));
        QVERIFY2(worstL < 1e-14, qPrintable(what));
        if (axis != 1) QVERIFY2(worstAxis < 1e-12, qPrintable(what));  // x and z: the stable axes
    }

    // The cylinder of issue 44 (r 0.3, half height 0.05, 2 kg) turned 90° about x and spun
    // at 30 rad/s about its own axis (now world z), dt 1/1000, 2 s: its spin stays (0, 0, 30)
    // and its energy 40.5 J (before: a jump to (-5.7, 2.6, 31.5) at 0.57 s, +13 % energy).
    void symmetricTopTurnedKeepsItsSpin_data() {
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<bool>("sleeping");
        for (const char* name : {"splitting", "splitting-4"})
            for (bool sleeping : {false, true})
                QTest::addRow("%s sleeping %s", name, sleeping ? "on" : "off") << name << sleeping;
    }
    void symmetricTopTurnedKeepsItsSpin() {
        QFETCH(QString, integrator);
        QFETCH(bool, sleeping);
        BodyDesc b;
        b.name = "disc";
        b.shape.type = ShapeType::Cylinder;
        b.shape.radius = 0.3;
        b.shape.halfHeight = 0.05;
        b.mass = 2.0;
        b.orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
        b.angularVelocity = Vec3(0, 0, 30);
        SceneDesc scene = sceneOf({b}, Vec3::Zero(), integrator.toStdString());
        scene.settings.sleeping = sleeping;
        World w(scene);
        const double e0 = kinetic(w);
        double worstSpin = 0, worstE = 0;
        for (int k = 0; k < 2000; ++k) {
            w.step(1e-3);
            worstSpin = std::max(worstSpin, (omegaOf(w, 0) - Vec3(0, 0, 30)).norm());
            worstE = std::max(worstE, std::abs(kinetic(w) - e0) / e0);
        }
        QVERIFY2(std::abs(e0 - 0.5 * (0.5 * 2.0 * 0.09) * 900) < 1e-12, qPrintable(QString::number(e0)));
        QVERIFY2(worstSpin < 30 * 1e-12 && worstE < 1e-12,
                 qPrintable(QString("spin off by %1 rad/s, energy %2").arg(worstSpin).arg(worstE)));
    }
};

QTEST_APPLESS_MAIN(TestInvariance)
#include "tst_invariance.moc"
