// The physical guards: a run that blows up stops with a message naming the body, the time
// and the likely cause (the energy guard stops it while the state is still finite); no
// correct scene trips it, whatever the integrator; settings.energyGuard off lets a run go on.
#include "guard/energy_guard.h"
#include "guard/likely_cause.h"
#include "scene_builders.h"

#include <tumble/errors.h>
#include <tumble/io/scene_file.h>

#include <QDir>
#include "sample_scenes.h"

#include <QtTest>

#include <cmath>
#include <cstdio>
#include <optional>

using namespace tumble;
using namespace tumble::test;

namespace {

// A 1 kg ball on a spring of stiffness k to the anchor (0, 1, 0), 0.1 m beyond its rest
// length of 1 m, with gravity.
SceneDesc springScene(double k, double dt, const std::string& integrator, double duration = 10.0) {
    BodyDesc bob = sphereBody("bob", 0.1, 1.0);
    bob.position = Vec3(0, -0.1, 0);
    ForceDesc s;
    s.type = ForceType::Spring;
    s.anchor = Vec3(0, 1, 0);
    s.stiffness = k;
    s.restLength = 1.0;
    bob.forces.push_back(s);
    SceneDesc scene = sceneOf({bob}, Vec3(0, -9.81, 0), integrator);
    scene.settings.dt = dt;
    scene.settings.duration = duration;
    scene.settings.frameRate = 50;
    return scene;
}

// Runs the scene to its end; the error when it stopped, and the world as it was then.
std::optional<SimulationError> run(World& w) {
    try {
        simulate(w, [](int, const State&) {});
    } catch (const SimulationError& e) {
        return e;
    }
    return std::nullopt;
}

bool allFinite(const State& s) {
    for (const BodyState& b : s.bodies)
        if (!b.x.allFinite() || !b.q.coeffs().allFinite() || !b.P.allFinite() || !b.L.allFinite())
            return false;
    return true;
}

// Runs a scene with the guard on; fails with the guard's message if it stops. Returns the
// largest rise of the energy seen at any frame, in units of what the guard allows
// (kEnergyGuardFactor stops the run), measured by a second guard checking every frame.
// Runs the scene for its duration; the largest energy rise the guard saw, or 1e300 (the
// test failed) if it stopped the run. With `spinStop`, a stop for a spin faster than the
// integrator follows is not a failure: its message comes back there.
double runClean(const SceneDesc& scene, std::string* spinStop = nullptr) {
    World w(scene);
    EnergyGuard side;
    armEnergyGuard(w.model(), w.state(), side);
    const int frames = frameCount(w.model().settings);
    for (int k = 1; k < frames; ++k) {
        try {
            advanceFrame(w, k);
            checkEnergy(w.model(), w.state(), side);
        } catch (const SimulationError& e) {
            const std::string what = e.what();
            if (spinStop && what.find(" follows (") != std::string::npos) {
                *spinStop = what;
                return side.worst;
            }
            QTest::qFail(e.what(), __FILE__, __LINE__);
            return 1e300;
        }
    }
    return side.worst;
}

// The largest turn per step (|ω| dt, rad) of a body with unequal moments over the scene's
// run, after every step: how fast the scene itself spins (checkSpin leaves balls and cubes
// out).
double largestTurn(const SceneDesc& scene) {
    World w(scene);
    const Model& m = w.model();
    double most = 0.0;
    while (w.state().time < m.settings.duration) {
        w.step(m.settings.dt);
        for (int i : m.dynamicBodies) {
            const Vec3& I = m.bodies[i].principalMoments;
            if (I.maxCoeff() - I.minCoeff() <= 1e-12 * I.maxCoeff()) continue;
            most = std::max(most, derive(m.bodies[i], w.state().bodies[i]).omega.norm() * m.settings.dt);
        }
    }
    return most;
}

std::string message(const SimulationError& e) {
    return e.what();
}

}  // namespace

class TestGuard : public QObject {
    Q_OBJECT
private slots:
    // rk4 holds a spring for ω dt < 2√2: here ω = √(1e5) = 316 1/s, so dt < 0.00894 s.
    // At dt = 0.01 s the energy grows ×4.5 a step; the guard stops the run long before
    // the state overflows, and says which spring needs which step.
    void stiffSpringStopsBeforeNonFinite() {
        const SceneDesc scene = springScene(1e5, 0.01, "rk4");
        World guarded(scene);
        const auto stop = run(guarded);
        QVERIFY2(stop, "the guard did not stop the run");
        QCOMPARE(stop->body(), 0);
        QCOMPARE(stop->bodyName(), std::string("bob"));
        QVERIFY(allFinite(guarded.state()));  // stopped before anything overflowed
        const std::string m = message(*stop);
        QVERIFY2(m.find("body 'bob' (bodies[0]) ran away at t = ") == 0, m.c_str());
        QVERIFY2(m.find("likely cause: dt = 0.01 s is too large for spring forces[0] of body 'bob' "
                        "(k = 1e+05 N/m, m = 1 kg: needs dt < 0.00894 s with rk4)") != std::string::npos,
                 m.c_str());
        char when[64];
        std::snprintf(when, sizeof when, "at t = %.9g s:", stop->time());
        QVERIFY2(m.find(when) != std::string::npos, m.c_str());

        // Unguarded, the same run goes on until the state overflows, later; the non-finite
        // guard then names the same cause.
        SceneDesc off = scene;
        off.settings.energyGuard = false;
        World unguarded(off);
        const auto overflow = run(unguarded);
        QVERIFY2(overflow, "the unguarded run did not overflow");
        const std::string n = message(*overflow);
        QVERIFY2(n.find("became non-finite") != std::string::npos, n.c_str());
        QVERIFY2(n.find("likely cause: dt = 0.01 s is too large for spring forces[0] of body 'bob'") !=
                     std::string::npos,
                 n.c_str());
        QVERIFY2(
            stop->time() < 0.25 * overflow->time(),
            qPrintable(QString("guard at %1 s, non-finite at %2 s").arg(stop->time()).arg(overflow->time())));
        qInfo("energy guard stops at t = %g s; unguarded, non-finite at t = %g s", stop->time(),
              overflow->time());
    }

    // The same spring with a step it can hold runs to its end, its energy kept.
    void stiffSpringWithSmallStepRunsClean() {
        const SceneDesc scene = springScene(1e5, 0.001, "rk4", 3.0);
        World w(scene);
        const double before = energy(w.model(), w.state()).total();
        QVERIFY(runClean(scene) < 1e-3);
        simulate(w, [](int, const State&) {});
        QCOMPARE(w.state().time, 3.0);
        QVERIFY(allFinite(w.state()));
        QVERIFY(energy(w.model(), w.state()).total() <= before);  // rk4 loses a little, never gains
    }

    // Explicit Euler multiplies a spring's energy by 1 + (ω dt)² every step: here ω dt =
    // 0.42, ×1.17 a step. The message says to change the integrator, and with the one it
    // names the same step runs clean.
    void explicitEulerOnASpring() {
        const SceneDesc scene = springScene(1e4, 1.0 / 240.0, "euler");
        World w(scene);
        const auto stop = run(w);
        QVERIFY2(stop, "the guard did not stop the run");
        QVERIFY(allFinite(w.state()));
        QVERIFY(stop->time() < 1.0);
        const std::string m = message(*stop);
        QVERIFY2(m.find("body 'bob' (bodies[0]) ran away at t = ") == 0, m.c_str());
        QVERIFY2(
            m.find("likely cause: explicit euler gains energy on spring forces[0] of body 'bob' "
                   "(k = 1e+04 N/m, m = 1 kg: undamped, at any step); use rk4 (stable for dt < 0.0283 s) "
                   "or symplectic-euler (dt < 0.02 s)") != std::string::npos,
            m.c_str());
        for (const char* other : {"rk4", "symplectic-euler"}) {
            SceneDesc fixed = springScene(1e4, 1.0 / 240.0, other, 3.0);
            QVERIFY(runClean(fixed) < 1.0);  // a hundredth of what stops a run
        }
    }

    // Energy that forces put in is not a runaway: a constant force and a constant torque
    // raise the kinetic energy without bound (quadratically in time), a spring switched on
    // late brings its stretch, a kinematic lift raises what it carries.
    void drivenScenesRunClean() {
        BodyDesc pushed = sphereBody("pushed", 0.1, 1.0);
        ForceDesc push;
        push.vector = Vec3(100, 0, 0);
        pushed.forces.push_back(push);
        BodyDesc spun = boxBody("spun", Vec3(0.3, 0.2, 0.1), 1.0);
        spun.position = Vec3(0, 5, 0);
        ForceDesc twist;
        twist.type = ForceType::Torque;
        // Spun up to about 14 rad/s in the 10 s (0.06 rad a step at 1/240 s): well below what
        // every integrator follows (the guard's spin check stops the first-order ones past
        // 0.5 rad a step; 5 times faster, symplectic Euler turned the box over to its minor
        // axis, where it spins 5 times faster again, and was stopped there).
        twist.vector = Vec3(0.01, 0.06, 0.004);
        spun.forces.push_back(twist);
        BodyDesc late = sphereBody("late", 0.1, 1.0);
        late.position = Vec3(0, -5, 0);
        ForceDesc spring;
        spring.type = ForceType::Spring;
        spring.anchor = Vec3(10, -5, 0);
        spring.stiffness = 50;
        spring.start = 2.0;
        late.forces.push_back(spring);
        for (const BodyDesc& driven : {pushed, spun, late}) {
            SceneDesc scene = sceneOf({driven}, Vec3::Zero());
            scene.settings.duration = 10.0;
            for (const IntegratorInfo& info : integrators()) {
                scene.settings.integrator = info.name;
                const double worst = runClean(scene);
                qInfo("%s, %s: largest rise %.3g", driven.name.c_str(), info.name, worst);
                // The bound is about the real work; explicit euler adds its own gain on a spring.
                QVERIFY(worst < (info.id == Integrator::Euler ? 10.0 : 2.0));
            }
        }

        // A kinematic platform lifting a box at 1 m/s for 60 s: 590 J/kg of potential energy.
        BodyDesc lift = boxBody("lift", Vec3(1, 0.1, 1), 1.0);
        lift.motion = Motion::Kinematic;
        lift.mass.reset();
        lift.velocity = Vec3(0, 1, 0);
        BodyDesc box = boxBody("box", Vec3(0.25, 0.25, 0.25), 2.0);
        box.position = Vec3(0, 0.35, 0);
        SceneDesc ride = sceneOf({lift, box});
        ride.settings.duration = 60.0;
        ride.settings.frameRate = 10;
        const double rideWorst = runClean(ride);
        qInfo("lift: largest rise %.3g", rideWorst);
        QVERIFY(rideWorst < 2.0);
    }

    // Every sample scene, for its whole duration, with its own settings and with every
    // integrator: no stop, and a rise of the energy at most a tenth of what stops a run. One
    // stop is right: for a spin faster than the integrator follows (Euler past 0.5 rad a
    // step), where the scene itself spins that fast with its own integrator (the tip of
    // chain.json whips at up to 140 rad/s, 0.58 rad a step at 1/240 s).
    void samplesNeverTrip_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<QString>("integrator");
        const QStringList files = sampleSceneFiles();
        QVERIFY(files.size() >= 10);
        for (const QString& f : files) {
            const Settings own =
                io::readSceneFile((QString(TUMBLE_SCENES_DIR) + "/" + f).toStdString()).settings;
            const std::string ownName = own.integrator.empty() ? defaultIntegrator().name : own.integrator;
            QTest::addRow("%s own (%s)", qPrintable(f), ownName.c_str()) << f << QString();
            for (const IntegratorInfo& info : integrators())
                if (info.name != ownName)
                    QTest::addRow("%s %s", qPrintable(f), info.name) << f << QString(info.name);
        }
    }

    void samplesNeverTrip() {
        QFETCH(QString, file);
        QFETCH(QString, integrator);
        SceneDesc scene = io::readSceneFile((QString(TUMBLE_SCENES_DIR) + "/" + file).toStdString());
        QVERIFY(scene.settings.energyGuard);  // on by default
        const SceneDesc own = scene;
        if (!integrator.isEmpty()) scene.settings.integrator = integrator.toStdString();
        std::string spinStop;
        const double worst = runClean(scene, integrator.isEmpty() ? nullptr : &spinStop);
        if (!spinStop.empty()) {
            // "... follows (0.5 rad a step; ...": the integrator's limit, against the scene's own spin.
            const size_t at = spinStop.find(" follows (") + 10;
            const double limit = std::stod(spinStop.substr(at));
            const double turn = largestTurn(own);
            qInfo("stopped for a spin (%s); with its own integrator the scene turns %.3g rad a step at most",
                  spinStop.c_str(), turn);
            QVERIFY2(turn > limit, spinStop.c_str());
        }
        qInfo("largest rise: %.3g (the guard stops at %g)", worst, kEnergyGuardFactor);
        QVERIFY2(worst < 0.1 * kEnergyGuardFactor, qPrintable(QString::number(worst)));
    }

    // 200 bodies dropped in layers onto the ground and each other: bouncy spheres and
    // boxes, two stacks, no stop and no rise near the limit.
    void largeBouncingAndStackingScene() {
        std::vector<BodyDesc> bodies{groundPlane(0.5, 0.5)};
        for (int layer = 0; layer < 4; ++layer) {
            for (int i = 0; i < 7; ++i) {
                for (int j = 0; j < 7; ++j) {
                    char name[32];
                    std::snprintf(name, sizeof name, "b%d_%d_%d", layer, i, j);
                    BodyDesc b = (i + j + layer) % 2 ? sphereBody(name, 0.2, 1.0 + 0.1 * i)
                                                     : boxBody(name, Vec3(0.2, 0.15, 0.25), 2.0);
                    b.position = Vec3(i * 0.7 + 0.05 * layer, 0.5 + layer * 0.8, j * 0.7 - 0.03 * layer);
                    b.orientation =
                        Quat(Eigen::AngleAxisd(0.3 * i + 0.2 * layer, Vec3(1, 2, 3).normalized()));
                    b = material(b, 0.1 + 0.8 * ((i * 7 + j) % 5) / 4.0, 0.4);
                    bodies.push_back(b);
                }
            }
        }
        for (int k = 0; k < 4; ++k) {  // two stacks of four
            for (int s = 0; s < 2; ++s) {
                char name[32];
                std::snprintf(name, sizeof name, "stack%d_%d", s, k);
                BodyDesc b = boxBody(name, Vec3(0.3, 0.3, 0.3), 5.0);
                b.position = Vec3(-2.0 - 1.5 * s, 0.3 + 0.6 * k, 0);
                bodies.push_back(material(b, 0.0, 0.6));
            }
        }
        SceneDesc scene = sceneOf(bodies);
        scene.settings.duration = 4.0;
        scene.settings.frameRate = 30;
        QCOMPARE(int(scene.bodies.size()), 205);
        const double worst = runClean(scene);
        qInfo("largest rise: %.3g (the guard stops at %g)", worst, kEnergyGuardFactor);
        QVERIFY2(worst < 0.1 * kEnergyGuardFactor, qPrintable(QString::number(worst)));
    }

    // Off, the guard lets a run that gains energy go to its end (or to a non-finite state:
    // stiffSpringStopsBeforeNonFinite).
    void settingOffLetsTheRunGoOn() {
        SceneDesc scene = springScene(1e4, 1.0 / 240.0, "euler", 1.0);
        scene.settings.energyGuard = false;
        World w(scene);
        const double before = energy(w.model(), w.state()).total();
        const auto stop = run(w);
        QVERIFY2(!stop, stop ? stop->what() : "");
        QCOMPARE(w.state().time, 1.0);
        QVERIFY(allFinite(w.state()));
        QVERIFY(energy(w.model(), w.state()).total() > 1e6 * before);  // what the guard stops
    }

    // A drill spun at 1 000 rad/s (4.2 rad a step at 1/240 s): the splittings sub-step it and
    // keep its energy; Euler, symplectic Euler and RK4 would turn it over to its minor axis
    // (kinetic energy x4.3, |L| unchanged, nothing runs away), so the run stops at the first
    // check (8 steps), naming the body, its spin and a step that works. (Symplectic Euler at
    // 0.4 rad a step turns the drill over within the half second, and is stopped as it spins
    // up about the minor axis.)
    void spinTooFastForTheIntegrator_data() {
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<double>("spin");
        QTest::addColumn<bool>("stops");
        QTest::newRow("rk4 4.2 rad a step") << "rk4" << 1000.0 << true;
        QTest::newRow("rk4 1 rad a step") << "rk4" << 240.0 << false;
        QTest::newRow("euler 4.2 rad a step") << "euler" << 1000.0 << true;
        QTest::newRow("symplectic-euler 0.6 rad a step") << "symplectic-euler" << 144.0 << true;
        QTest::newRow("symplectic-euler 0.05 rad a step") << "symplectic-euler" << 12.0 << false;
        QTest::newRow("splitting 4.2 rad a step") << "splitting" << 1000.0 << false;
        QTest::newRow("splitting-4 4.2 rad a step") << "splitting-4" << 1000.0 << false;
        QTest::newRow("euler, a ball at 4.2 rad a step") << "euler ball" << 1000.0 << false;
        QTest::newRow("rk4, a cube at 4.2 rad a step") << "rk4 cube" << 1000.0 << false;
    }
    void spinTooFastForTheIntegrator() {
        QFETCH(QString, integrator);
        QFETCH(double, spin);
        QFETCH(bool, stops);
        // A ball or a cube has three equal moments: no other axis to turn over to, no stop.
        const QString shape = integrator.section(' ', 1);
        integrator = integrator.section(' ', 0, 0);
        BodyDesc drill = shape == "ball"   ? sphereBody("drill", 0.2, 1.0)
                         : shape == "cube" ? boxBody("drill", Vec3(0.2, 0.2, 0.2), 1.0)
                                           : boxBody("drill", Vec3(0.5, 0.2, 0.1), 1.0);
        drill.angularVelocity = Vec3(0.01 * spin, 0.005 * spin, spin);
        SceneDesc scene = sceneOf({drill}, Vec3::Zero(), integrator.toStdString());
        scene.settings.dt = 1.0 / 240;
        scene.settings.duration = 0.5;
        World w(scene);
        const auto stop = run(w);
        QCOMPARE(bool(stop), stops);
        if (!stops) return;
        QCOMPARE(stop->body(), 0);
        QCOMPARE(stop->time(), 8.0 / 240);
        const QString what = stop->what();
        QVERIFY2(what.contains("body 'drill' (bodies[0]) spins at") && what.contains("more than " + integrator) &&
                     what.contains("use splitting"),
                 qPrintable(what));
        // With the guard off the run goes on, as the user asked.
        scene.settings.energyGuard = false;
        World off(scene);
        QVERIFY(!run(off));
    }

    // The likely cause of other kinds of blow-up.
    void likelyCauses() {
        // A kinematic paddle moving 0.5 m a step at a 0.1 m ball.
        BodyDesc paddle = boxBody("paddle", Vec3(0.5, 0.5, 0.05), 1.0);
        paddle.motion = Motion::Kinematic;
        paddle.mass.reset();
        paddle.velocity = Vec3(0, 0, 50);
        SceneDesc scene = sceneOf({sphereBody("ball", 0.1, 1.0), paddle});
        scene.settings.dt = 0.01;
        World w(scene);
        QCOMPARE(likelyCause(w.model(), w.state(), 0),
                 std::string("kinematic body 'paddle' moves 0.5 m per step (50 m/s), more than a tenth of "
                             "the size of body 'ball' (0.1 m): use a smaller step"));
        // Damping too strong for the step.
        BodyDesc damped = sphereBody("damped", 0.1, 1.0);
        damped.linearDamping = 300;
        SceneDesc d = sceneOf({damped}, Vec3(0, -9.81, 0), "rk4");
        d.settings.dt = 0.01;
        World dw(d);
        QCOMPARE(likelyCause(dw.model(), dw.state(), 0),
                 std::string("dt = 0.01 s is too large for its linear_damping of body 'damped' (300 1/s: "
                             "needs dt < 0.00927 s with rk4)"));
        // Nothing of the kind: the contact solver.
        SceneDesc plain = sceneOf({groundPlane(0.5, 0.5), sphereBody("ball", 0.1, 1.0)});
        World pw(plain);
        QCOMPARE(likelyCause(pw.model(), pw.state(), 1),
                 std::string("the contact solver (the contacts put energy in): try half the step (dt = "
                             "0.00417 s -> 0.00208 s) or twice the solver iterations (solver_iterations = 20 "
                             "-> 40)"));
    }
};

QTEST_MAIN(TestGuard)
#include "tst_guard.moc"
