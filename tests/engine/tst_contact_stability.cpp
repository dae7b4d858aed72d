// Contacts at the steps people use (issue 16): stacks and piles stand at 1/60 s and 1/30 s,
// a light hit does not bring a pyramid down, and contacts never create energy. Every scene
// here is passive (no spring, motor, applied force or moving kinematic body), so the total
// mechanical energy (kinetic + gravity) may only fall: at every step it must stay within
// 1e-6 of its start above the lowest value it had before (what is left is the integrators'
// rounding), and the ledger's energy taken by contacts is never negative. Sleeping is off
// and the solver has its default iterations: nothing here is helped by a setting.
// About two minutes in Release; labelled `long`, so the sanitizer build (15-20 times
// slower) leaves it out: tst_response runs the same stages there.
#include "ledger_checks.h"
#include "scene_builders.h"
#include "test_meshes.h"
#include "test_random.h"

#include <tumble/io/scene_file.h>

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::test;

namespace {

SceneDesc sample(const char* name) {
    return io::readSceneFile(std::string(TUMBLE_SCENES_DIR) + "/" + name);
}

// Follows the energy of a run step by step: the largest rise above the lowest earlier value.
struct EnergyWatch {
    double start = 0.0, lowest = 0.0, rise = 0.0, riseAt = 0.0;
    explicit EnergyWatch(const World& w) : start(energy(w.model(), w.state()).total()), lowest(start) {}
    void step(const World& w) {
        const double e = energy(w.model(), w.state()).total();
        lowest = std::min(lowest, e);
        if (e - lowest > rise) rise = e - lowest, riseAt = w.state().time;
    }
    double relative() const { return rise / std::abs(start); }
};

QString describe(const EnergyWatch& e) {
    return QString("energy rose %1 J above its lowest earlier value at t = %2 s (%3 of the start %4 J)")
        .arg(e.rise)
        .arg(e.riseAt)
        .arg(e.relative())
        .arg(e.start);
}

// A 1 kg ball of radius 0.5 m held 0.5 m above the top of the scene's highest body.
void addTapBall(SceneDesc& s) {
    double top = 0.0;
    for (const BodyDesc& b : s.bodies)
        if (b.motion == Motion::Dynamic) top = std::max(top, b.position.y() + b.shape.halfExtents.y());
    BodyDesc ball = sphereBody("tap-ball", 0.5, 1.0);
    ball.position = Vec3(0, top + 1.0, 0);
    s.bodies.push_back(ball);
}

// The bowl the ball rolls in: radius R, friction 0.5 (restitution as BodyDesc's default).
BodyDesc bowlOf(double R) {
    BodyDesc b = meshBowl(R, 24, 32);
    b.friction = 0.5;
    return b;
}

// 200 boxes (4 layers of 10 x 5), a little turned and offset at random, dropped from up to
// 2.6 m so that they land on each other and settle into a pile.
SceneDesc pile() {
    Rng rng{7};
    std::vector<BodyDesc> bodies{groundPlane(0.2, 0.6)};
    for (int layer = 0; layer < 4; ++layer)
        for (int i = 0; i < 10; ++i)
            for (int k = 0; k < 5; ++k) {
                std::string name = "b";
                name += std::to_string(bodies.size());  // ("b" + std::string: a false gcc 12 warning)
                BodyDesc b = material(boxBody(name, Vec3(0.2, 0.15, 0.25), 2.0), 0.2, 0.6);
                b.position = Vec3(0.45 * i - 2.0 + rng.uniform(-0.05, 0.05) + 0.1 * layer, 0.3 + 0.65 * layer,
                                  0.55 * k - 1.1 + rng.uniform(-0.05, 0.05));
                b.orientation = Quat(Eigen::AngleAxisd(
                    rng.uniform(-0.3, 0.3), Vec3(rng.uniform(-1, 1), 1, rng.uniform(-1, 1)).normalized()));
                bodies.push_back(b);
            }
    SceneDesc s = sceneOf(bodies);
    s.settings.sleeping = false;
    return s;
}

}  // namespace

class TestContactStability : public QObject {
    Q_OBJECT
private slots:
    // 1. The sample stacks stand for 20 s at the large steps: no box moves more than 1 cm
    // from its start at 1/60 s, 2 cm at 1/30 s (checked every step), with the energy bound
    // of the header. "tapped": pyramid-15 with a 1 kg ball dropped onto its top from 0.5 m
    // (the ball itself bounces off and rolls away: it is not held to the bound).
    void stacksStand_data() {
        QTest::addColumn<QString>("scene");
        QTest::addColumn<bool>("tapped");
        QTest::addColumn<int>("rate");
        QTest::addColumn<double>("bound");
        for (const auto& [rate, bound] : {std::pair{60, 0.01}, std::pair{30, 0.02}}) {
            QTest::addRow("tower-20, 1/%d s", rate) << "tower-20.json" << false << rate << bound;
            QTest::addRow("pyramid-15, 1/%d s", rate) << "pyramid-15.json" << false << rate << bound;
            QTest::addRow("1 kg under 100 kg, 1/%d s", rate)
                << "mass-ratio-stack.json" << false << rate << bound;
            QTest::addRow("pyramid-15 tapped, 1/%d s", rate) << "pyramid-15.json" << true << rate << bound;
        }
    }
    void stacksStand() {
        QFETCH(QString, scene);
        QFETCH(bool, tapped);
        QFETCH(int, rate);
        QFETCH(double, bound);
        SceneDesc s = sample(qPrintable(scene));
        if (tapped) addTapBall(s);
        s.settings.sleeping = false;
        const double h = 1.0 / rate;
        s.settings.dt = h;
        World w(s);
        const State start = w.state();
        const int boxes = static_cast<int>(s.bodies.size()) - (tapped ? 1 : 0);
        EnergyWatch watch(w);
        double worst = 0.0;
        int worstBody = -1;
        bool ballLanded = !tapped;
        while (w.state().time < 20.0 - 1e-9) {
            w.step(h);
            watch.step(w);
            for (int i = 1; i < boxes; ++i) {
                const double d = (w.state().bodies[i].x - start.bodies[i].x).norm();
                if (d > worst) worst = d, worstBody = i;
            }
            if (worst >= bound)
                QFAIL(qPrintable(QString("at t = %1 s %2 moved %3 m from its start (bound %4 m)")
                                     .arg(w.state().time)
                                     .arg(QString::fromStdString(s.bodies[worstBody].name))
                                     .arg(worst)
                                     .arg(bound)));
            if (watch.relative() > 1e-6) QFAIL(qPrintable(describe(watch)));
            if (tapped && w.state().bodies.back().P.y() > 0.0) ballLanded = true;
        }
        qInfo("largest displacement %.3g m (%s), largest energy rise %.2e of E0", worst,
              worstBody < 0 ? "none" : s.bodies[worstBody].name.c_str(), watch.relative());
        QVERIFY2(ballLanded, "the ball never reached the pyramid");
        // (The contacts of a resting stack book nothing but the rounding of its bodies'
        // positions, 1e-15 of their weight times height a step: 2e-9 J of pyramid-15's 1e4 J
        // in 20 s. Before issue 44 they booked 0.05 J a second, and as much again in the
        // position correction.)
        const double rounding = 1e-15 * rate * 20.0 * weightTimesHeight(w);
        QVERIFY2(w.ledger().lostInContacts >= -rounding,
                 qPrintable(QString("the contacts put %1 J in").arg(-w.ledger().lostInContacts)));
    }

    // 2. Warm starting survives a box rocking on an edge: a box (1 x 0.5 x 0.5 m) stood on
    // one long bottom edge, tilted 20 degrees, falls back onto its face. While it pivots, the
    // two points of that edge are found every step and each starts from the impulse it had
    // the step before (a remembered point within 1 mm of where it was, carrying a normal
    // impulse); the box ends flat (within the slop) and at rest, having never gained energy.
    void warmStartSurvivesRocking_data() {
        QTest::addColumn<int>("rate");
        for (int rate : {30, 60, 240}) QTest::addRow("1/%d s", rate) << rate;
    }
    void warmStartSurvivesRocking() {
        QFETCH(int, rate);
        const double h = 1.0 / rate, tilt = 20.0 * std::numbers::pi / 180.0;
        const Vec3 half(0.5, 0.25, 0.25);
        BodyDesc box = material(boxBody("box", half, 1.0), 0.0, 0.8);
        box.orientation = Quat(Eigen::AngleAxisd(tilt, Vec3::UnitZ()));
        // The edge at (-0.5, -0.25) in the box's frame on the ground at x = 0.
        const Vec3 edge = box.orientation * Vec3(-half.x(), -half.y(), 0);
        box.position = -edge;
        SceneDesc s = sceneOf({groundPlane(0.0, 0.8), box});
        s.settings.dt = h;
        s.settings.sleeping = false;
        World w(s);
        EnergyWatch watch(w);
        std::vector<ContactMemory> last;
        int pivotSteps = 0;
        while (w.state().time < 3.0 - 1e-9) {
            w.step(h);
            watch.step(w);
            QVERIFY2(watch.relative() <= 1e-6, qPrintable(describe(watch)));
            const double angle = w.state().bodies[1].q.angularDistance(Quat::Identity());
            const std::vector<ContactMemory>& now = w.state().contacts;
            if (angle > 2.0 * std::numbers::pi / 180.0 && !last.empty()) {
                ++pivotSteps;
                QVERIFY2(now.size() >= 2,
                         qPrintable(QString("at t = %1 s (tilted %2 degrees) %3 points remembered")
                                        .arg(w.state().time)
                                        .arg(angle * 180 / std::numbers::pi)
                                        .arg(now.size())));
                for (const ContactMemory& c : now) {
                    double nearest = 1e9;
                    for (const ContactMemory& p : last)
                        nearest = std::min(nearest, (p.position - c.position).norm());
                    QVERIFY2(
                        nearest < 1e-3 && c.normalImpulse > 0.0,
                        qPrintable(QString("at t = %1 s a point of the pivot edge is %2 m from any of the "
                                           "last step's, impulse %3")
                                       .arg(w.state().time)
                                       .arg(nearest)
                                       .arg(c.normalImpulse)));
                }
            }
            last = now;
        }
        QVERIFY2(pivotSteps >= 3, qPrintable(QString("only %1 steps on the edge").arg(pivotSteps)));
        // Flat to within the overlap the solver leaves alone (0.005 of the box's size, 3 mm:
        // 3e-3 rad across its 1 m face), and at rest.
        const double slop = 0.005 * half.norm();
        const BodyState& b = w.state().bodies[1];
        QVERIFY2(b.q.angularDistance(Quat::Identity()) < slop / (2 * half.x()) &&
                     std::abs(b.x.y() - half.y()) < slop && b.P.norm() < 1e-3,
                 qPrintable(QString("the box ended tilted %1 rad at height %2 m, moving with %3 kg m/s")
                                .arg(b.q.angularDistance(Quat::Identity()))
                                .arg(b.x.y())
                                .arg(b.P.norm())));
    }

    // 3. Contacts never create energy, at every step people use: a box dropped onto a box
    // (landing on an edge), a box sliding into a wall, a ball rolling in a triangle-mesh
    // bowl, and 200 boxes dropped into a pile, left 10 s to settle (not checked: see below)
    // and then watched for a minute.
    // The pile is watched once it has settled: while 200 boxes land at once, more than a
    // step's 8 moments of impact are left to the end of the step, and the impulses there
    // can still raise the total by up to 1e-5 of the start in a step (see
    // docs/architecture.md); a settled pile, which the issue asks about (the soak test found
    // energy created there), is held to the bound like the rest.
    void contactsNeverAddEnergy_data() {
        QTest::addColumn<QString>("kind");
        QTest::addColumn<int>("rate");
        for (int rate : {30, 60, 120, 240})
            for (const char* kind : {"box on box", "into a wall", "mesh bowl", "settled pile"})
                QTest::addRow("%s, 1/%d s", kind, rate) << kind << rate;
    }
    void contactsNeverAddEnergy() {
        QFETCH(QString, kind);
        QFETCH(int, rate);
        SceneDesc s;
        double seconds = 10.0, settle = 0.0;  // s
        if (kind == "box on box") {
            BodyDesc lower = material(boxBody("lower", Vec3(0.5, 0.5, 0.5), 5.0), 0.3, 0.5);
            lower.position = Vec3(0, 0.5, 0);
            BodyDesc upper = material(boxBody("upper", Vec3(0.4, 0.2, 0.3), 2.0), 0.3, 0.5);
            upper.position = Vec3(0.1, 2.2, 0.05);
            upper.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 0, 1).normalized()));
            s = sceneOf({groundPlane(0.3, 0.5), lower, upper});
        } else if (kind == "into a wall") {
            BodyDesc wall = material(boxBody("wall", Vec3(0.1, 1.0, 2.0), 1.0), 0.2, 0.3);
            wall.motion = Motion::Static;
            wall.mass.reset();
            wall.position = Vec3(3.0, 1.0, 0);
            BodyDesc box = material(boxBody("box", Vec3(0.25, 0.25, 0.25), 1.0), 0.2, 0.3);
            box.position = Vec3(0, 0.25, 0);
            box.velocity = Vec3(6.0, 0, 0);
            s = sceneOf({groundPlane(0.2, 0.3), wall, box});
        } else if (kind == "mesh bowl") {
            const double R = 2.0, r = 0.25;
            BodyDesc ball = material(sphereBody("ball", r, 7.0), 0.0, 0.5);
            const double a = 50.0 * std::numbers::pi / 180.0;  // released 50 degrees up the side
            // 2 cm inside the sphere the facets approximate (they lie up to 9 mm inside it).
            const double d = R - r - 0.02;
            ball.position = Vec3(d * std::sin(a), R - d * std::cos(a), 0);
            s = sceneOf({bowlOf(R), ball});
        } else {
            s = pile();
            settle = 10.0;
            seconds = settle + 60.0;
        }
        s.settings.sleeping = false;
        const double h = 1.0 / rate;
        s.settings.dt = h;
        World w(s);
        while (w.state().time < settle - 1e-9) w.step(h);
        EnergyWatch watch(w);
        while (w.state().time < seconds - 1e-9) {
            w.step(h);
            watch.step(w);
            if (watch.relative() > 1e-6) QFAIL(qPrintable(describe(watch)));
        }
        for (int i : w.model().dynamicBodies)
            QVERIFY2(w.state().bodies[i].x.y() > 0.0,
                     qPrintable(
                         QString("%1 ended below the ground").arg(QString::fromStdString(s.bodies[i].name))));
        // (The contacts of a resting stack book nothing but the rounding of its bodies'
        // positions, 1e-15 of their weight times height a step: 2e-9 J of pyramid-15's 1e4 J
        // in 20 s. Before issue 44 they booked 0.05 J a second, and as much again in the
        // position correction.)
        const double rounding = 1e-15 * rate * 20.0 * weightTimesHeight(w);
        QVERIFY2(w.ledger().lostInContacts >= -rounding,
                 qPrintable(QString("the contacts put %1 J in").arg(-w.ledger().lostInContacts)));
        QVERIFY2(w.ledger().lostInContacts + w.ledger().lostInFriction > 0.0,
                 "the contacts took nothing out");
        qInfo("largest rise %.2e of E0, contacts took %.4g J, friction %.4g J", watch.relative(),
              w.ledger().lostInContacts, w.ledger().lostInFriction);
    }
};

QTEST_APPLESS_MAIN(TestContactStability)
#include "tst_contact_stability.moc"
