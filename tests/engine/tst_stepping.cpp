// The frame loop, static and kinematic bodies, the non-finite guard and determinism.
#include "scene_builders.h"

#include <tumble/errors.h>
#include <tumble/io/scene_file.h>

#include <QtTest>

#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::test;

class TestStepping : public QObject {
    Q_OBJECT
private slots:
    // Frames at exactly k / frame_rate, steps never longer than dt.
    void landsOnEveryFrameTime() {
        SceneDesc scene = sceneOf({sphereBody("s", 0.1, 1.0)});
        scene.settings.duration = 2.0;
        scene.settings.frameRate = 60;
        scene.settings.dt = 0.001;  // 1/60 is not a whole number of these
        World w(scene);
        std::vector<double> times;
        const RunResult r = simulate(w, [&](int k, const State& s) {
            QCOMPARE(int(times.size()), k);
            times.push_back(s.time);
        });
        QCOMPARE(r.frames, 121);
        QCOMPARE(int(times.size()), 121);
        for (int k = 0; k < 121; ++k) QCOMPARE(times[k], k / 60.0);
        QCOMPARE(r.steps, 120L * 17);  // ceil((1/60) / 0.001) steps per frame
        // The state at each frame is the state at exactly that time: free fall from rest.
        QVERIFY(std::abs(w.state().bodies[0].x.y() - (-0.5 * 9.81 * 4.0)) < 1e-12);
    }

    void frameCountRounds() {
        Settings s;
        s.duration = 1.0;
        s.frameRate = 30;
        QCOMPARE(frameCount(s), 31);
        s.duration = 0.0;
        QCOMPARE(frameCount(s), 1);
        s.duration = 0.51;
        s.frameRate = 10;
        QCOMPARE(frameCount(s), 6);
    }

    void staticBodiesNeverMove() {
        BodyDesc ground;
        ground.name = "ground";
        ground.motion = Motion::Static;
        ground.shape.type = ShapeType::Plane;
        BodyDesc rock = boxBody("rock", Vec3(1, 1, 1), 1.0);
        rock.motion = Motion::Static;
        rock.mass.reset();
        rock.position = Vec3(3, 1, 0);
        World w(sceneOf({ground, rock, sphereBody("ball", 0.1, 1.0)}));
        const BodyState before = w.state().bodies[1];
        stepN(w, 100, 0.01);
        QCOMPARE(w.state().bodies[1].x, before.x);
        QCOMPARE(w.state().bodies[1].q.coeffs(), before.q.coeffs());
        QCOMPARE(w.model().dynamicBodies, std::vector<int>{2});
    }

    // A force acts for exactly its interval whatever the steps (issue 44): a 2 kg ball in
    // empty space pushed with 3 N from t = 0.51 s to 1.27 s, stepped by World::step with
    // steps of 0.1 s that straddle both times, ends at v = F (1.27 - 0.51) / m and where the
    // closed form puts it. A start that steps summed to 0.9999999999999999 s reach is taken
    // at the step's start: a push from t = 1 s stepped at 1/30 s acts from the 31st step.
    void forcesSwitchInsideAStep() {
        BodyDesc ball = sphereBody("ball", 0.1, 2.0);
        ForceDesc push;
        push.vector = Vec3(3, 0, 0);
        push.start = 0.51;
        push.end = 1.27;
        ball.forces.push_back(push);
        World w(sceneOf({ball}, Vec3::Zero()));
        stepN(w, 20, 0.1);
        const double a = 1.5, on = 1.27 - 0.51;
        QVERIFY(std::abs(velocityOf(w, 0).x() - a * on) < 1e-12);
        const double x = 0.5 * a * on * on + a * on * (2.0 - 1.27);
        QVERIFY2(std::abs(w.state().bodies[0].x.x() - x) < 1e-12,
                 qPrintable(QString::number(w.state().bodies[0].x.x() - x)));

        BodyDesc late = sphereBody("ball", 0.1, 1.0);
        push.start = 1.0;
        push.end.reset();
        late.forces = {push};
        World v(sceneOf({late}, Vec3::Zero()));
        stepN(v, 30, 1.0 / 30);
        QVERIFY(v.state().time < 1.0);  // (the sum of 30 steps of 1/30 s)
        stepN(v, 30, 1.0 / 30);
        QVERIFY(std::abs(velocityOf(v, 0).x() - 3.0) < 1e-12);
        QVERIFY(std::abs(v.state().bodies[0].x.x() - 1.5) < 1e-12);
    }

    // The deepest overlap is what a frame shows (issue 45): a box resting on the ground at
    // 1/30 s overlaps it by nothing, though the contacts found at the end of each free step
    // are g h² / 2 = 5.45 mm deep; a tilted box dropped on the ground overlaps it, after
    // every step, by as much as its lowest corner is below it.
    void deepestOverlapIsWhatAFrameShows() {
        const Vec3 half(0.4, 0.2, 0.3);
        for (const bool tilted : {false, true}) {
            BodyDesc box = boxBody("box", half, 2.0);
            box.position = Vec3(0, tilted ? 1.0 : half.y(), 0);
            if (tilted) box.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3(1, 0, 2).normalized()));
            SceneDesc scene = sceneOf({groundPlane(0.2, 0.5), box});
            scene.settings.sleeping = false;
            World w(scene);
            double worstFound = 0.0;
            for (int k = 0; k < 90; ++k) {
                w.step(1.0 / 30);
                const BodyState& b = w.state().bodies[1];
                double lowest = HUGE_VAL;
                for (int c = 0; c < 8; ++c) {
                    const Vec3 corner((c & 1 ? 1 : -1) * half.x(), (c & 2 ? 1 : -1) * half.y(),
                                      (c & 4 ? 1 : -1) * half.z());
                    lowest = std::min(lowest, (b.x + b.q * corner).y());
                }
                QVERIFY2(std::abs(w.deepestOverlap() - std::max(0.0, -lowest)) < 1e-12,
                         qPrintable(QString("t %1: %2 against %3")
                                        .arg(w.state().time)
                                        .arg(w.deepestOverlap())
                                        .arg(-lowest)));
                for (const auto& m : w.contacts()) worstFound = std::max(worstFound, m.maxDepth());
            }
            if (!tilted)
                QVERIFY2(std::abs(worstFound - 0.5 * 9.81 / 900) < 1e-9,
                         qPrintable(QString::number(worstFound)));
        }
    }

    // Kinematic bodies follow their velocities exactly and ignore gravity.
    void kinematicBodiesFollowTheirVelocity() {
        BodyDesc k = boxBody("platform", Vec3(1, 0.1, 1), 1.0);
        k.motion = Motion::Kinematic;
        k.mass.reset();
        k.velocity = Vec3(1, 0, 0.5);
        k.angularVelocity = Vec3(0, 2, 0);
        World w(sceneOf({k}, Vec3(0, -9.81, 0), "rk4"));
        stepN(w, 1000, 0.001);
        QVERIFY((w.state().bodies[0].x - Vec3(1, 0, 0.5)).norm() < 1e-12);
        const Quat expected(Eigen::AngleAxisd(2.0, Vec3::UnitY()));
        QVERIFY(w.state().bodies[0].q.angularDistance(expected) < 1e-12);
        const Derived d = derive(w.model().bodies[0], w.state().bodies[0]);
        QCOMPARE(d.v, Vec3(1, 0, 0.5));
    }

    // A stiff spring at a large Euler step blows up: the run stops and names the body.
    void nonFiniteStateStopsTheRun() {
        BodyDesc b = sphereBody("bob", 0.1, 1.0);
        b.position = Vec3(1, 0, 0);
        ForceDesc s;
        s.type = ForceType::Spring;
        s.stiffness = 1e12;
        b.forces.push_back(s);
        SceneDesc scene = sceneOf({sphereBody("other", 0.1, 1.0), b}, Vec3::Zero(), "euler");
        scene.settings.dt = 0.01;
        World w(scene);
        try {
            simulate(w, [](int, const State&) {});
            QFAIL("the run did not stop");
        } catch (const SimulationError& e) {
            QCOMPARE(e.body(), 1);
            QCOMPARE(QString::fromStdString(e.bodyName()), QString("bob"));
            QVERIFY(e.time() > 0 && e.time() < 5);
            QVERIFY(QString(e.what()).contains("'bob'"));
        }
    }

    // Same input, same output: bit for bit, every run, and pinned. The pinned digest
    // changes only when the physics changes on purpose; then update it here.
    void deterministicAndPinned() {
        const SceneDesc scene = io::readSceneFile(TUMBLE_SCENES_DIR "/tumbling-box.json");
        std::string hashes[2];
        for (std::string& h : hashes) {
            World w(scene);
            simulate(w, [](int, const State&) {});
            h = hashHex(hashState(w.state()));
        }
        QCOMPARE(hashes[0], hashes[1]);
        QCOMPARE(QString::fromStdString(hashes[0]), QString("8a942b3c76f439e3"));
    }

    void hashSeesEveryBit() {
        State s;
        s.bodies.resize(2);
        const std::uint64_t h0 = hashState(s);
        s.bodies[1].L.z() = std::nextafter(0.0, 1.0);
        QVERIFY(hashState(s) != h0);
        QCOMPARE(hashHex(0xabcull), std::string("0000000000000abc"));
    }
};

QTEST_APPLESS_MAIN(TestStepping)
#include "tst_stepping.moc"
