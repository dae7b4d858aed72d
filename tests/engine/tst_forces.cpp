// The forces stage against closed forms: torque of a force at a point (10), body-frame
// forces, springs, damping and start/end windows.
#include "scene_builders.h"

#include <QtTest>

#include <cmath>

using namespace tumble;
using namespace tumble::test;

class TestForces : public QObject {
    Q_OBJECT
private slots:
    // A force at a body point gives torque (q - x) × F: L grows linearly, P too.
    void forceAtPointMakesTorque() {
        BodyDesc b = boxBody("b", Vec3(0.5, 0.5, 0.5), 1.0);
        ForceDesc f;
        f.vector = Vec3(2, 0, 0);
        f.point = Vec3(0, 0.5, 0);
        b.forces.push_back(f);
        World w(sceneOf({b}, Vec3::Zero(), "rk4"));
        w.step(1e-6);  // so short that the arm has not turned
        QVERIFY((w.state().bodies[0].P - Vec3(2e-6, 0, 0)).norm() < 1e-18);
        const Vec3 torque = Vec3(0, 0.5, 0).cross(Vec3(2, 0, 0));  // (0, 0, -1)
        QVERIFY((w.state().bodies[0].L - torque * 1e-6).norm() < 1e-15);
    }

    // A body-frame force turns with the body; a world-frame one does not.
    void bodyFrameForceTurnsWithTheBody() {
        for (Frame frame : {Frame::World, Frame::Body}) {
            BodyDesc b = sphereBody("s", 0.5, 1.0);
            b.orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
            ForceDesc f;
            f.vector = Vec3(1, 0, 0);
            f.frame = frame;
            b.forces.push_back(f);
            World w(sceneOf({b}, Vec3::Zero()));
            w.step(0.5);
            const Vec3 expected = frame == Frame::World ? Vec3(0.5, 0, 0) : Vec3(0, 0.5, 0);
            QVERIFY((w.state().bodies[0].P - expected).norm() < 1e-15);
        }
    }

    // A damped spring under gravity settles where k (l - l0) = m g.
    void springSettlesAtEquilibrium() {
        BodyDesc b = sphereBody("bob", 0.1, 2.0);
        b.position = Vec3(0, -1, 0);
        ForceDesc s;
        s.type = ForceType::Spring;
        s.anchor = Vec3(0, 0, 0);
        s.stiffness = 100;
        s.restLength = 0.5;
        s.damping = 10;
        b.forces.push_back(s);
        World w(sceneOf({b}, Vec3(0, -9.81, 0), "rk4"));
        stepN(w, 20000, 0.001);
        QVERIFY(std::abs(w.state().bodies[0].x.y() - (-0.5 - 2.0 * 9.81 / 100)) < 1e-9);
    }

    // Linear damping: v(t) = v0 e^(-c t). Angular damping: L(t) = L0 e^(-c t).
    void dampingDecaysExponentially() {
        BodyDesc b = sphereBody("s", 0.5, 1.0);
        b.velocity = Vec3(3, 0, 0);
        b.angularVelocity = Vec3(0, 5, 0);
        b.linearDamping = 0.7;
        b.angularDamping = 1.3;
        World w(sceneOf({b}, Vec3::Zero(), "rk4"));
        stepN(w, 2000, 0.001);
        const Derived d = derive(w.model().bodies[0], w.state().bodies[0]);
        QVERIFY(std::abs(d.v.x() - 3 * std::exp(-0.7 * 2)) < 1e-11);
        QVERIFY(std::abs(d.omega.y() - 5 * std::exp(-1.3 * 2)) < 1e-11);
    }

    // A force acting over [0.1, 0.35) gives the impulse F · 0.25 exactly, because the
    // frame loop lands on its start and end.
    void forceWindowGivesExactImpulse() {
        BodyDesc b = sphereBody("s", 0.5, 1.0);
        ForceDesc f;
        f.vector = Vec3(0, 4, 0);
        f.start = 0.1;
        f.end = 0.35;
        b.forces.push_back(f);
        SceneDesc scene = sceneOf({b}, Vec3::Zero(), "euler");
        scene.settings.duration = 1.0;
        scene.settings.frameRate = 7;  // frames that do not fall on 0.1 or 0.35
        scene.settings.dt = 0.03;
        World w(scene);
        simulate(w, [](int, const State&) {});
        QCOMPARE(w.state().bodies[0].P.y(), 4 * 0.25);
    }

    // Gravity acts on dynamic bodies only.
    void gravityScalesWithMass() {
        BodyDesc heavy = sphereBody("heavy", 0.1, 5.0);
        heavy.position = Vec3(1, 0, 0);  // apart: they fall side by side
        World w(sceneOf({sphereBody("light", 0.1, 1.0), heavy}, Vec3(0, -2, 0)));
        w.step(0.25);
        QCOMPARE(w.state().bodies[0].P.y(), -0.5);
        QCOMPARE(w.state().bodies[1].P.y(), -2.5);
        QCOMPARE(w.state().bodies[0].x.y(), w.state().bodies[1].x.y());
    }
};

QTEST_APPLESS_MAIN(TestForces)
#include "tst_forces.moc"
