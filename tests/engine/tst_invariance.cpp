// One pose proves one pose (issue 44): the closed-form motions hold for bodies placed in
// any orientation, and a scene turned and shifted as a whole (gravity too) moves as the
// original does, turned and shifted. A failure names its seed and writes its scene.
#include "joint_checks.h"
#include "ledger_checks.h"
#include "sample_scenes.h"
#include "scene_builders.h"
#include "turned_world.h"

#include <tumble/integrators.h>
#include <tumble/io/scene_file.h>

#include <QtTest>

#include <cmath>
#include <string>

using namespace tumble;
using namespace tumble::test;

namespace {

// Runs `scene` for `frames` frames as simulate() would, with the steps it takes.
State runFrames(const SceneDesc& scene, int frames) {
    World w(scene);
    for (int k = 1; k <= frames; ++k) advanceFrame(w, k);
    return w.state();
}

// Scenes with every kind of joint, limit and motor, with gravity, each moving in all three
// dimensions (a motion in one plane would leave a turned world's other axes untried), each
// placed and set moving as its joints allow.
SceneDesc jointScene(const QString& name) {
    SceneDesc s = sceneOf({});
    s.settings.sleeping = false;
    auto add = [&](BodyDesc b, const Vec3& at, const Vec3& v = Vec3::Zero(), const Vec3& w = Vec3::Zero()) {
        b.position = at;
        b.velocity = v;
        b.angularVelocity = w;
        s.bodies.push_back(b);
    };
    if (name == "hinged rod and tumbling box") {  // issue 44: 0.27 m apart in 3 s before
        add(boxBody("rod", Vec3(0.05, 0.5, 0.05), 1.0), Vec3(0, 1.5, 0), Vec3(1, 0, 0.5), Vec3(0, 0, -2));
        JointDesc pin = joint("pin", JointType::Hinge, "rod", Vec3(0, 0.5, 0), "", Vec3(0, 2, 0));
        pin.axisA = Vec3(0.3, 0, 1).normalized();
        s.joints.push_back(pin);
        add(boxBody("box", Vec3(0.5, 0.2, 0.1), 2.0), Vec3(3, 2, 0), Vec3(1, 5, 0), Vec3(0.3, 6, 0.2));
    } else if (name == "ball pendulum") {
        add(boxBody("bob", Vec3(0.3, 0.1, 0.2), 1.5), Vec3(0.3, 1.9, 0), Vec3(0, 0, 1), Vec3(0, 0, 0.5));
        s.joints.push_back(joint("ball", JointType::Ball, "bob", Vec3(-0.3, 0.1, 0), "", Vec3(0, 2, 0)));
    } else if (name == "dumbbell on a distance joint") {
        add(sphereBody("a", 0.1, 1.0), Vec3(0, 2, 0), Vec3(1, 3, 0));
        add(sphereBody("b", 0.1, 2.0), Vec3(0.8, 2.3, 0.2), Vec3(-1, 3, 2));
        s.joints.push_back(joint("rod", JointType::Distance, "a", Vec3::Zero(), "b", Vec3::Zero()));
        s.joints.push_back(joint("hook", JointType::Rope, "a", Vec3::Zero(), "", Vec3(0, 3, 0), 1.5));
    } else if (name == "rope going slack") {
        add(boxBody("bob", Vec3(0.1, 0.1, 0.1), 1.0), Vec3(0.7, 1.5, 0.3), Vec3(2, 4, -1), Vec3(0, 3, 1));
        s.joints.push_back(joint("rope", JointType::Rope, "bob", Vec3(0.1, 0, 0), "", Vec3(0, 2, 0), 1.2));
    } else if (name == "limited door with a motor") {
        add(boxBody("door", Vec3(0.4, 1.0, 0.02), 10.0), Vec3(0.4, 1, 0), Vec3::Zero(), Vec3(0, 1, 0));
        JointDesc hinge = joint("hinge", JointType::Hinge, "door", Vec3(-0.4, 0, 0), "", Vec3(0, 1, 0));
        hinge.axisA = Vec3(0, 1, 0.2).normalized();
        hinge.limits = std::array<double, 2>{-0.6, 0.8};
        hinge.motor = JointDesc::Motor{2.0, 5.0};
        s.joints.push_back(hinge);
    } else if (name == "slider with a limit and a motor, swinging") {
        add(boxBody("arm", Vec3(0.5, 0.05, 0.05), 2.0), Vec3(0.5, 2, 0), Vec3(0, 0, 1), Vec3(0, -2, 0));
        s.joints.push_back(joint("shoulder", JointType::Ball, "arm", Vec3(-0.5, 0, 0), "", Vec3(0, 2, 0)));
        add(boxBody("block", Vec3(0.1, 0.1, 0.1), 1.0), Vec3(0.5, 2, 0), Vec3(0, 0, 1), Vec3(0, -2, 0));
        JointDesc rail = joint("rail", JointType::Slider, "block", Vec3::Zero(), "arm", Vec3::Zero());
        rail.axisA = Vec3::UnitX();
        rail.limits = std::array<double, 2>{-0.3, 0.4};
        rail.motor = JointDesc::Motor{0.5, 3.0};
        s.joints.push_back(rail);
    } else if (name == "welded pair tumbling") {
        // One rigid motion: v = (0, 4, 0) + ω × (x - c) about the pair's centre c = (0.25, 2, 0).
        add(boxBody("left", Vec3(0.5, 0.1, 0.2), 1.0), Vec3(-0.5, 2, 0), Vec3(0, 1.75, 0), Vec3(1, 0, 3));
        add(boxBody("right", Vec3(0.5, 0.2, 0.1), 3.0), Vec3(0.5, 2, 0), Vec3(0, 4.75, 0), Vec3(1, 0, 3));
        s.joints.push_back(
            joint("weld", JointType::Fixed, "left", Vec3(0.5, 0, 0), "right", Vec3(-0.5, 0, 0)));
    } else if (name == "double pendulum of capsules") {  // issue 45's, let go level; the elbow tilted
        BodyDesc c;
        c.shape.type = ShapeType::Capsule;
        c.shape.radius = 0.05;
        c.shape.halfHeight = 0.45;
        c.mass = 1.0;
        const Quat level(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));  // the capsule's axis y along x
        c.orientation = level;
        c.name = "upper";
        add(c, Vec3(0.5, 2, 0));
        c.name = "lower";
        add(c, Vec3(1.5, 2, 0));
        JointDesc top = joint("top", JointType::Hinge, "upper", Vec3(0, 0.5, 0), "", Vec3(0, 2, 0));
        top.axisA = level.conjugate() * Vec3::UnitZ();
        JointDesc elbow =
            joint("elbow", JointType::Hinge, "lower", Vec3(0, 0.5, 0), "upper", Vec3(0, -0.5, 0));
        elbow.axisA = level.conjugate() * Vec3(0, 0.2, 1).normalized();
        s.joints = {top, elbow};
    }
    return s;
}

// Whether anything in the scene drives its bodies (the ledger then does not close: their
// work is not booked): an applied force or torque, damping, a motor. (What moving kinematic
// and animated bodies do through contacts is booked: doneByKinematic.)
bool driven(const SceneDesc& s) {
    for (const BodyDesc& b : s.bodies) {
        if (b.linearDamping > 0 || b.angularDamping > 0) return true;
        for (const ForceDesc& f : b.forces)
            if (f.type != ForceType::Spring || f.damping > 0) return true;
    }
    for (const JointDesc& j : s.joints)
        if (j.motor || j.servo) return true;
    return false;
}

// A seeded scene of `n` bodies of every shape drifting into each other in empty space (no
// gravity, nothing static): elastic and frictionless, or with random materials and two
// pairs of them on rods.
SceneDesc randomCollisions(std::uint64_t seed, int n, bool elastic) {
    Rng rng{seed};
    SceneDesc s = sceneOf({}, Vec3::Zero());
    s.settings.sleeping = false;
    for (int i = 0; i < n; ++i) {
        BodyDesc b;
        b.name = "b" + std::to_string(i);
        const int kind = static_cast<int>(rng.uniform(0, 4));
        b.shape.type = kind == 0   ? ShapeType::Sphere
                       : kind == 1 ? ShapeType::Box
                       : kind == 2 ? ShapeType::Capsule
                                   : ShapeType::Cylinder;
        b.shape.radius = rng.uniform(0.1, 0.3);
        b.shape.halfHeight = rng.uniform(0.1, 0.3);
        b.shape.halfExtents = rng.vec(0.1, 0.3);
        b.mass = rng.uniform(0.5, 3.0);
        b.position = Vec3(i % 3, (i / 3) % 3, i / 9) * 0.9 + rng.vec(-0.05, 0.05);
        b.orientation = randomWorldPose(seed * 100 + i).R;
        b.velocity = rng.vec(-1.5, 1.5) - 1.5 * (b.position - Vec3::Constant(0.9));  // towards the middle
        b.angularVelocity = rng.vec(-4, 4);
        b.restitution = rng.uniform(0.0, 1.0);
        b.friction = rng.uniform(0.0, 1.0);
        if (elastic) b.friction = 0, b.restitution = 1;
        s.bodies.push_back(b);
    }
    for (int k = 0; k + 1 < n && k < 4 && !elastic; k += 2) {  // two pairs on distance rods
        JointDesc j;
        j.name = "rod" + std::to_string(k);
        j.type = JointType::Distance;
        j.bodyA = s.bodies[k].name;
        j.bodyB = s.bodies[k + 1].name;
        s.joints.push_back(j);
    }
    return s;
}

// The sanitizer build (TUMBLE_TEST_SHORT, set by dev.sh) runs 15-40 times slower: there
// each sweep keeps its first seed, and the joint scenes the default integrator alone.
bool shortRun() {
    return qEnvironmentVariableIsSet("TUMBLE_TEST_SHORT");
}

double kinetic(const World& w) {
    return energy(w.model(), w.state()).kinetic;
}

// The angle between two directions (well resolved near zero).
double angleOf(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

class TestInvariance : public QObject {
    Q_OBJECT
private slots:
    // A box (half extents 0.5, 0.2, 0.1; 2 kg; no gravity) placed in a random orientation
    // and spun at 30 rad/s about one of its principal axes, 3 s: the energy and |L| stay to
    // rounding whatever the pose, the axis and the step; about the two stable axes (the
    // largest and the smallest moment) the spin stays on its axis to rounding too. About
    // the middle axis rounding grows into a flip (e^(20 t): physics), but the energy holds.
    // On a1831fe 65 of these 72 rows failed, the energy off by 2.7e-8 to 147 %.
    void principalSpinInAnyPose_data() {
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<double>("h");
        QTest::addColumn<int>("axis");
        QTest::addColumn<int>("seed");
        for (const char* name : {"splitting", "splitting-4"})
            for (double h : {1.0 / 60, 1.0 / 1000})
                for (int axis = 0; axis < 3; ++axis)
                    for (int seed = 1; seed <= (shortRun() ? 1 : 6); ++seed)
                        QTest::addRow("%s h=%g axis %d seed %d", name, h, axis, seed)
                            << name << h << axis << seed;
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
    // and its energy 40.5 J (on a1831fe the spin jumped by up to 6.5 rad/s and the energy
    // by 5 %; the issue saw (0, 0, 30) become (-5.7, 2.6, 31.5) at 0.57 s).
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

    // Every sample scene, turned and shifted as a whole at random, moves as the original
    // does, turned and shifted: with the default integrator and RK4, over its first 2 s.
    // The samples are the closed-form scenes of docs/scene-format.md (bounce, slide, roll,
    // incline, projectile, the tumbling box, pendulums, cradles, the chain, stacks): their
    // own tests check the answer in one pose, and this one that any other pose gives the
    // same answer turned, so the closed form holds there within the same bound and the
    // gap. The gap is rounding (1e-7 allows for its growth over the run: the chain, the
    // tumbling box and the spring pendulum amplify it to 1e-9-1e-8 rad/s), except where a
    // tolerance decides an event: a mesh's impact moment is found to 1e-6 of its size
    // (mesh-shapes: the hull lands 1e-5 m and 1e-4 rad apart, then rests), and the
    // ragdoll's limbs meet the ground that way, after which its motion is chaotic: 0.5 s,
    // as its first limbs land (1e-10 there; by 1 s 2e-4 rad/s with GCC, 2e-3 with clang).
    // Before issue 44: the spring pendulum with RK4 0.14 rad apart (its stages' quaternions
    // were off unit length and turned the spring's arm by a pose-dependent rotation).
    void samplesTurnedMoveTurned_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<int>("seed");
        QTest::addColumn<QString>("integrator");
        for (const QString& f : sampleSceneFiles())
            for (int seed = 1; seed <= (shortRun() ? 1 : 2); ++seed)
                for (const char* name : {"", "rk4"})
                    QTest::addRow("%s seed %d %s", qPrintable(f), seed, *name ? name : "default")
                        << f << seed << QString(name);
    }
    void samplesTurnedMoveTurned() {
        QFETCH(QString, file);
        QFETCH(int, seed);
        QFETCH(QString, integrator);
        SceneDesc scene = io::readSceneFile(QDir(TUMBLE_SCENES_DIR).filePath(file).toStdString());
        if (!integrator.isEmpty()) scene.settings.integrator = integrator.toStdString();
        double seconds = 2.0, bound = 1e-7;
        if (file == "mesh-shapes.json") bound = 1e-3;
        // The mug's convex parts are hulls, met by GJK and EPA as mesh-shapes' are: 6e-6 m
        // apart after 2 s, the ball rolling in it 3e-3 rad/s.
        if (file == "mug-on-board.json") bound = 1e-2;
        // The chair falls over onto one corner of its back: 3e-14 m apart until 0.46 s, when
        // the solve of that one contact point (the same point, depth and feature in both
        // worlds) gives 0.35578 N s in one and 0.35609 in the other, and 2e-4 m apart after:
        // a threshold of the contact solve, not of the compound (its manifolds agree).
        if (file == "chair.json") bound = 1e-2;
        if (file == "ragdoll.json") seconds = 0.5, bound = 1e-5;
        // The ragdoll on the stairs (cones and twist limits): 2e-12 m apart until its first
        // limb lands at 0.417 s, 2.5e-8 m and 1.2e-5 rad/s by 0.5 s (rk4, seed 2: its limits
        // past, closed in the group's Newton steps since 2026-12-06, are taken there as the
        // rounding finds them past, by more than 1e-13 or not). The robot arm's servos
        // drive it alike in any pose (1e-13 m apart) until its hand meets the first block at
        // 0.65 s, a moment found to 1e-6 of the block's size: the pushed blocks are 0.06 m
        // apart by 2 s.
        if (file == "ragdoll-stairs.json") seconds = 0.5, bound = 3e-5;
        if (file == "robot-arm.json") seconds = 0.6;
        // The cart on its springs: 7e-13 m apart until its front wheels meet the first bump
        // at 1.125 s, a moment found to 1e-6 of a wheel's size (3e-6 m apart by 2 s).
        if (file == "suspension-cart.json") seconds = 1.1;
        // Bodies carried or struck by a moving animated body: the contact passes stop a
        // block by a share of its bodies' own speeds as 1-norms, which a turn of the world
        // changes (contact_rows.cpp), and the paddle's moment of impact is found to 1e-6 of
        // the domino's size: the dominoes 2e-4 m and 8e-3 rad/s apart as they tip, the
        // turntable's sliding boxes 5e-5 m and 1.3e-4 m/s, in 2 s.
        if (file == "paddle-dominoes.json") bound = 1e-2;
        if (file == "turntable.json") bound = 1e-3;
        // The stack on the lift: 0 m apart while the lift holds (to 1 s), then, two steps
        // after it starts, its top box 3e-3 m/s apart (1.5e-4 m by 2 s), whatever the
        // interpolation, with two boxes too, with sleeping off or impacts at the end of the
        // step, and with the quiet share off (it is not that). Not found yet (issue 50's
        // closing note): a known gap, bounded here.
        if (file == "lift.json") bound = 1e-3;
        // The pile of 200 chairs: its first layer lands level on the floor and bounces alike
        // in any pose (1e-15 m apart at 0.2 s). At 0.21 s the second layer lands on the
        // first's backs, 25 pairs meeting within one step at moments found to 1e-6 of a
        // chair's size; which are taken first at the cut is rounding's choice, and which
        // chairs tip which way with it (0.5 cm apart at 0.22 s, the same in a world only
        // shifted); from there the heap is chaotic. What holds in any pose after: its energy
        // ledger (tst_engine_compound pileOfChairsLedgerCloses, upright and turned).
        if (file == "chair-pile.json") seconds = 0.2;
        const WorldPose pose = randomWorldPose(seed);
        const SceneDesc turned = turnedScene(scene, pose);
        const int frames = static_cast<int>(
            std::lround(std::min(seconds, scene.settings.duration) * scene.settings.frameRate));
        const State a = turnedState(runFrames(scene, frames), pose);
        const State b = runFrames(turned, frames);
        const StateGap gap = stateGap(World(scene).model(), a, b);
        QVERIFY2(gap.worst() < bound, qPrintable(describe(gap) + "; the turned scene: " +
                                                 keepFailedScene(turned, file.toStdString(), seed)));
    }

    // Every kind of joint, limit and motor, in a world turned and shifted as a whole at
    // random: 3 s at 1/60 s (the joints' own step halving included) give the turned answer.
    // The joint suites check these joints against closed forms in one pose. Before issue 44
    // the hinged rod and the tumbling box of the issue ended 0.27 m apart with splitting.
    void jointsTurnedMoveTurned_data() {
        QTest::addColumn<QString>("scene");
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<int>("seed");
        for (const char* scene :
             {"hinged rod and tumbling box", "ball pendulum", "dumbbell on a distance joint",
              "rope going slack", "limited door with a motor", "slider with a limit and a motor, swinging",
              "welded pair tumbling", "double pendulum of capsules"})
            for (const char* integrator : {"splitting", "splitting-4", "rk4"})
                for (int seed = 3; seed <= (shortRun() ? 2 + (std::string(integrator) == "splitting") : 4); ++seed)
                    QTest::addRow("%s, %s, seed %d", scene, integrator, seed) << scene << integrator << seed;
    }
    void jointsTurnedMoveTurned() {
        QFETCH(QString, scene);
        QFETCH(QString, integrator);
        QFETCH(int, seed);
        SceneDesc original = jointScene(scene);
        original.settings.integrator = integrator.toStdString();
        const WorldPose pose = randomWorldPose(seed);
        const SceneDesc turned = turnedScene(original, pose);
        World a(original), b(turned);
        for (int k = 0; k < 180; ++k) a.step(1.0 / 60), b.step(1.0 / 60);
        const StateGap gap = stateGap(a.model(), turnedState(a.state(), pose), b.state());
        // A step whose joints did not hold is taken again in halves (World::stepJointed); a
        // step at that decision's threshold may be split in one world and not in the other,
        // rounding apart, and the two then differ by that step's error (the double pendulum
        // splits 2 of 3 steps at 1/60 s, and 472 against 473 left it 5e-5 m apart).
        const bool sameSplits = a.profile().jointSplits == b.profile().jointSplits;
        QVERIFY2(
            gap.worst() < (sameSplits ? 1e-7 : 1e-2),
            qPrintable(
                describe(gap) +
                QString("; %1 and %2 steps split").arg(a.profile().jointSplits).arg(b.profile().jointSplits) +
                "; the turned scene: " + keepFailedScene(turned, "joints", seed)));
    }

    // A flywheel (a cylinder, r 0.3 m, half height 0.05 m, 2 kg) on a hinge whose axis is its
    // own spin axis, in a random pose, gravity on: at 300 rad/s and 1/60 s (4.7 rad a step)
    // it keeps its spin to 1e-12 for 3 s (on a1831fe 4 of these 16 rows failed, the spin off
    // by up to 8.5 % of itself).
    void flywheelOnItsHingeKeepsItsSpin_data() {
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<double>("spin");
        QTest::addColumn<double>("h");
        QTest::addColumn<int>("seed");
        for (const char* integrator : {"splitting", "splitting-4"})
            for (double spin : {30.0, 300.0})
                for (double h : {1.0 / 60, 1.0 / 240})
                    for (int seed = 5; seed <= (shortRun() ? 5 : 6); ++seed)
                        QTest::addRow("%s %g rad/s h=%g seed %d", integrator, spin, h, seed)
                            << integrator << spin << h << seed;
    }
    void flywheelOnItsHingeKeepsItsSpin() {
        QFETCH(QString, integrator);
        QFETCH(double, spin);
        QFETCH(double, h);
        QFETCH(int, seed);
        const WorldPose pose = randomWorldPose(seed, 2.0);
        BodyDesc wheel;
        wheel.name = "wheel";
        wheel.shape.type = ShapeType::Cylinder;
        wheel.shape.radius = 0.3;
        wheel.shape.halfHeight = 0.05;
        wheel.mass = 2.0;
        wheel.position = pose.t;
        wheel.orientation = pose.R;
        const Vec3 axis = pose.R * Vec3::UnitY();  // the cylinder's own axis
        wheel.angularVelocity = spin * axis;
        SceneDesc scene = sceneOf({wheel}, Vec3(0, -9.81, 0), integrator.toStdString());
        JointDesc axle = joint("axle", JointType::Hinge, "wheel", Vec3::Zero(), "", pose.t);
        axle.axisA = Vec3::UnitY();
        scene.joints.push_back(axle);
        World w(scene);
        double worst = 0.0;
        for (long k = 0, n = std::lround(3.0 / h); k < n; ++k) {
            w.step(h);
            worst = std::max(worst, (omegaOf(w, 0) - spin * axis).norm() / spin);
        }
        QVERIFY2(worst < 1e-12, qPrintable(QString("spin off by %1 of itself").arg(worst)));
    }

    // The ledger tells the truth (issue 44). A scene at rest books nothing: tower-20,
    // pyramid-15 and a box held on a 30° slope by friction, sleeping off, 10 s at 1/30 s: every
    // entry within the rounding of the bodies' positions (contacts 1e-9 J of pyramid-15's
    // 1e4 J; before, contacts 6 416 J and correction as much for the tower, and the pyramid
    // with 5 passes booked −0.05 J to friction).
    void aSceneAtRestBooksNothing_data() {
        QTest::addColumn<QString>("scene");
        QTest::addColumn<int>("iterations");
        QTest::newRow("tower-20") << "tower-20.json" << 20;
        QTest::newRow("pyramid-15") << "pyramid-15.json" << 20;
        QTest::newRow("pyramid-15, 5 passes") << "pyramid-15.json" << 5;
        QTest::newRow("a box held on a slope") << "" << 20;
    }
    void aSceneAtRestBooksNothing() {
        QFETCH(QString, scene);
        QFETCH(int, iterations);
        SceneDesc s;
        if (scene.isEmpty()) {
            BodyDesc box = material(boxBody("box", Vec3(0.3, 0.2, 0.3), 1.0), 0.0, 0.7);
            box.position = Vec3(0, 0.2, 0);
            s = sceneOf({groundPlane(0.0, 0.7), box},
                        9.81 * Vec3(std::sin(M_PI / 6), -std::cos(M_PI / 6), 0));
        } else {
            s = io::readSceneFile(QDir(TUMBLE_SCENES_DIR).filePath(scene).toStdString());
        }
        s.settings.sleeping = false;
        s.settings.solverIterations = iterations;
        World w(s);
        const double start = energy(w.model(), w.state()).total();
        const long steps = 300;
        for (long k = 0; k < steps; ++k) w.step(1.0 / 30);
        const double rounding = 1e-15 * steps * weightTimesHeight(w);
        const EnergyLedger& l = w.ledger();
        const QString what = describeLedger(w, start) + QString(" (rounding %1 J)").arg(rounding, 0, 'g', 3);
        QVERIFY2(std::abs(l.lostInContacts) <= rounding && std::abs(l.lostInFriction) <= rounding,
                 qPrintable(what));
        QVERIFY2(l.positionCorrection == 0.0 && l.lostInJoints == 0.0, qPrintable(what));
    }

    // ... and where things move, the ledger's losses never go below zero and its parts add up
    // to the change of the scene's energy (and the work of kinematic and animated bodies):
    // every sample scene that nothing else drives, 3 s at
    // 1/30 and 1/60 s, checked every step: contacts and friction at least −rounding, the gap
    // within 1e-9 of the scene's energy scale (its weight times height and its largest
    // kinetic energy); with joints, within their integration error (1e-3).
    void theLedgerClosesAndNeverGoesNegative_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<int>("rate");
        for (const QString& f : sampleSceneFiles()) {
            // (The driven samples, the door's motor and the ragdoll's and spring's damping, do
            // work the ledger does not book.)
            if (driven(io::readSceneFile(QDir(TUMBLE_SCENES_DIR).filePath(f).toStdString()))) continue;
            for (int rate : {30, 60}) QTest::addRow("%s at 1/%d s", qPrintable(f), rate) << f << rate;
        }
    }
    void theLedgerClosesAndNeverGoesNegative() {
        QFETCH(QString, file);
        QFETCH(int, rate);
        SceneDesc s = io::readSceneFile(QDir(TUMBLE_SCENES_DIR).filePath(file).toStdString());
        s.settings.dt = 1.0 / rate;
        s.settings.frameRate = rate;
        World w(s);
        const double start = energy(w.model(), w.state()).total();
        double scale = weightTimesHeight(w), worstLoss = 0.0, worstJoints = 0.0;
        const bool carried =
            std::any_of(w.model().bodies.begin(), w.model().bodies.end(),
                        [](const BodyModel& b) { return b.motion == Motion::Kinematic && !b.standsStill(); });
        for (int k = 1; k <= 3 * rate; ++k) {
            advanceFrame(w, k);
            scale = std::max(scale, weightTimesHeight(w) + energy(w.model(), w.state()).kinetic);
            // Where joints and contacts meet in one impact (the cradle on strings), the sweeps'
            // rows pass energy between them: a contact pushes again what a string slowed, and
            // its row books that push as given. Their sum is the loss there.
            const EnergyLedger& l = w.ledger();
            const double contacts = s.joints.empty() ? l.lostInContacts : l.lostInContacts + l.lostInJoints;
            // Bodies carried by a moving kinematic or animated body: what their contacts take
            // in all (the work the carrier did is its own entry). Friction's share alone may
            // dip: it is taken against the carrier's motion over this step, the bodies' slip
            // against its motion over the last (a lift speeding up: -1e-3 J of 1700 J).
            if (carried)
                worstLoss = std::min(worstLoss, contacts + l.lostInFriction);
            else
                worstLoss = std::min({worstLoss, contacts, l.lostInFriction});
            worstJoints = std::min(worstJoints, l.lostInJoints);
        }
        const double rounding = 1e-15 * 3 * rate * scale;
        // Joints may give up to 1e-3 of their bodies' kinetic energy and weight in a step
        // before the step is taken again in halves (World::stepJointed): the chain's gave
        // 7e-3 J of 137 J for a while before they took 19-31 J (issue 45's losses).
        const double jointSlack = s.joints.empty() ? 0.0 : 1e-4 * scale;
        QVERIFY2(
            worstLoss >= -rounding - jointSlack && worstJoints >= -jointSlack,
            qPrintable(describeLedger(w, start) +
                       QString("; a loss reached %1 J, the joints' %2 J").arg(worstLoss).arg(worstJoints)));
        const double bound = s.joints.empty() ? 1e-9 * scale : 1e-3 * scale;
        QVERIFY2(std::abs(ledgerGap(w, start)) <= bound, qPrintable(describeLedger(w, start)));
    }

    // Seeded random scenes of 12 bodies of every shape colliding in empty space for 2 s:
    // nothing outside acts on them, so their momentum is kept (1e-10: the energy limit
    // scales velocities now and then), their energy never rises above the start, and the
    // ledger closes. Elastic and frictionless, they meet only in impacts, which keep the
    // angular momentum and the energy to rounding. With friction, inelastic contacts and
    // rods, bodies that stay in contact are re-placed from the step's start with their new
    // velocities while the solver's impulses acted at the arms of the free step's end: the
    // angular momentum drifts by h J × Δv at such a contact (up to 1.5e-4 of it here),
    // bounded at 1e-3 (a known limit, docs/architecture.md "Energy ledger").
    void randomCollisionsKeepWhatTheyMust_data() {
        QTest::addColumn<int>("seed");
        QTest::addColumn<bool>("elastic");
        for (bool elastic : {true, false})
            for (int seed = 1; seed <= (shortRun() ? 3 : 10); ++seed)
                QTest::addRow("%s, seed %d", elastic ? "elastic" : "any material", seed) << seed << elastic;
    }
    void randomCollisionsKeepWhatTheyMust() {
        QFETCH(int, seed);
        QFETCH(bool, elastic);
        const SceneDesc s = randomCollisions(seed, 12, elastic);
        World w(s);
        auto momenta = [&](Vec3& P, Vec3& L, double& scale) {
            P = L = Vec3::Zero();
            scale = 0.0;
            for (const BodyState& b : w.state().bodies) {
                P += b.P;
                L += b.x.cross(b.P) + b.L;
                scale += b.P.norm() * (1.0 + b.x.norm()) + b.L.norm();
            }
        };
        Vec3 P0, L0, P, L;
        double scale0, scale;
        momenta(P0, L0, scale0);
        const double start = energy(w.model(), w.state()).total();
        double worstP = 0, worstL = 0, rise = 0;
        for (int k = 0; k < 120; ++k) {
            w.step(1.0 / 60);
            momenta(P, L, scale);
            worstP = std::max(worstP, (P - P0).norm() / scale0);
            worstL = std::max(worstL, (L - L0).norm() / scale0);
            rise = std::max(rise, (energy(w.model(), w.state()).total() - start) / start);
        }
        const QString what =
            QString("momentum off by %1, angular momentum %2, energy rose %3 of the start; %4; the scene: %5")
                .arg(worstP, 0, 'g', 3)
                .arg(worstL, 0, 'g', 3)
                .arg(rise, 0, 'g', 3)
                .arg(describeLedger(w, start))
                .arg(keepFailedScene(s, elastic ? "elastic-collisions" : "random-collisions", seed));
        QVERIFY2(worstP < 1e-10 && worstL < (elastic ? 1e-12 : 1e-3), qPrintable(what));
        QVERIFY2(rise < 1e-12 && std::abs(ledgerGap(w, start)) < 1e-12 * start, qPrintable(what));
        if (elastic)
            QVERIFY2(std::abs(energy(w.model(), w.state()).total() - start) < 1e-12 * start,
                     qPrintable(what));
    }
};

QTEST_APPLESS_MAIN(TestInvariance)
#include "tst_invariance.moc"
