// settings.impacts: "exact" cuts the step at each moment of impact (tst_response.cpp checks
// its bounces to 1e-6); "end-of-step" resolves an impact at the end of the step that finds
// the bodies touching, as the peers do. Checked here: the end-of-step bounce against its
// closed-form first-order error, energy never rising with either setting, and a fast body
// that would pass through a thin one still getting its moment. Only the public API is used.
#include "scene_builders.h"

#include <QtTest>

#include <algorithm>
#include <cmath>

using namespace tumble;
using namespace tumble::test;

namespace {

constexpr double kG = 9.81;

QString num(double v) {
    return QString::number(v, 'g', 17);
}

struct Bounce {
    double apex = 0.0;        // the bottom's height at the first apex after the bounce
    double highest = 0.0;     // the largest total energy seen, J
    double deepest = 0.0;     // the deepest the ball went below the ground, m
    long cuts = 0;            // moments of impact found within a step
};

// A ball of radius r dropped from h0 (its bottom) onto the ground, rk4 (exact in free fall),
// until just past its first apex.
Bounce dropBall(ImpactTiming timing, double e, double h, double h0 = 1.0) {
    const double r = 0.1;
    BodyDesc ball = material(sphereBody("ball", r, 1.0), e, 0.0);
    ball.position = Vec3(0, h0 + r, 0);
    SceneDesc scene = sceneOf({groundPlane(e, 0.0), ball}, Vec3(0, -kG, 0), "rk4");
    scene.settings.impacts = timing;
    World w(scene);
    Bounce b;
    bool rising = false;
    while (w.state().time < 3.0) {
        w.step(h);
        b.cuts += static_cast<long>(w.impacts().size());
        const double y = w.state().bodies[1].x.y(), vy = velocityOf(w, 1).y();
        b.highest = std::max(b.highest, energy(w.model(), w.state()).total());
        b.deepest = std::max(b.deepest, r - y);
        if (vy > 0.0) rising = true;
        if (rising && vy <= 0.0) {
            b.apex = y + vy * vy / (2.0 * kG) - r;  // the ballistic apex of this flight
            return b;
        }
    }
    return b;
}

// A static plate 1 cm thick about z = 0 and a 5 cm ball (e = 0.5 both) starting at z0 with
// speed v along z, no gravity, impacts at the end of the step.
World plateAndBall(double z0, double v) {
    BodyDesc plate = material(boxBody("plate", Vec3(1.0, 1.0, 0.005), 1.0), 0.5, 0.0);
    plate.motion = Motion::Static;
    plate.mass.reset();
    BodyDesc ball = material(sphereBody("ball", 0.05, 0.1), 0.5, 0.0);
    ball.position = Vec3(0, 0, z0);
    ball.velocity = Vec3(0, 0, v);
    SceneDesc scene = sceneOf({plate, ball}, Vec3::Zero());
    scene.settings.impacts = ImpactTiming::EndOfStep;
    return World(scene);
}

}  // namespace

class TestImpactTiming : public QObject {
    Q_OBJECT
private slots:
    // A ball bouncing with restitution e, impacts at the end of the step. It reaches the ground
    // s after some moment within the step (0 <= s < h), at speed v, and is found there
    // overlapping by d = v s + g s²/2 and falling at v + g s. The bounce must take its
    // restitution from the speed of the touch, v = sqrt(v_end² - 2 g d) (what the ball had
    // when it met the ground, as energy says): from v_end it would rise by e² d too high
    // after the overlap is pushed out, and an elastic ball (e = 1) would gain m g d at
    // every bounce. So: the apex lies between e² h0 - d_max and e² h0 (1e-9: rounding), the
    // energy never rises above the start, no step is cut, and the overlap stays below the
    // distance fallen in one step (v h + g h²/2).
    void endOfStepBounce_data() {
        QTest::addColumn<double>("e");
        QTest::addColumn<double>("h");
        for (double e : {1.0, 0.8, 0.5})
            for (double h : {1.0 / 30, 1.0 / 60, 1.0 / 240})
                QTest::addRow("e %g, dt 1/%.0f", e, 1.0 / h) << e << h;
    }
    void endOfStepBounce() {
        QFETCH(double, e);
        QFETCH(double, h);
        const double h0 = 1.0, v = std::sqrt(2.0 * kG * h0);
        const double dMax = v * h + 0.5 * kG * h * h;
        const Bounce b = dropBall(ImpactTiming::EndOfStep, e, h, h0);
        const double e0 = kG * (h0 + 0.1);  // m g y of the ball's centre at the start
        QVERIFY2(b.apex > 0.0, "no apex after the bounce within 3 s");
        QCOMPARE(b.cuts, 0L);
        QVERIFY2(b.deepest <= dMax * (1 + 1e-9),
                 qPrintable(QString("overlap %1 m, more than one step's fall %2 m").arg(b.deepest).arg(dMax)));
        const double expected = e * e * h0;
        QVERIFY2(b.apex <= expected + 1e-9 && b.apex >= expected - dMax,
                 qPrintable(QString("apex %1 m, expected %2 m less at most the overlap %3 m")
                                .arg(num(b.apex), num(expected))
                                .arg(dMax)));
        QVERIFY2(b.highest <= e0 * (1 + 1e-12),
                 qPrintable(QString("energy rose to %1 J above the start %2 J").arg(num(b.highest), num(e0))));
    }

    // The same drop with impacts at their moment: the apex to 1e-6 of e² h0 at every step
    // (the exact setting's promise, and what end-of-step gives up).
    void exactBounceForComparison_data() {
        QTest::addColumn<double>("h");
        for (double h : {1.0 / 30, 1.0 / 240}) QTest::addRow("dt 1/%.0f", 1.0 / h) << h;
    }
    void exactBounceForComparison() {
        QFETCH(double, h);
        const Bounce b = dropBall(ImpactTiming::Exact, 0.8, h);
        QVERIFY(b.cuts > 0);
        QVERIFY2(std::abs(b.apex - 0.64) < 1e-6 * 0.64, qPrintable(QString("apex %1 m").arg(num(b.apex))));
    }

    // A 5 cm ball at 200 m/s towards a static plate 1 cm thick: in one step of 1/60 s it
    // travels 3.3 m, so the end of the step finds it far beyond the plate, touching
    // nothing. End-of-step still cuts the step there, and the ball bounces back off the
    // plate (e = 0.5: 100 m/s back, the moment exact).
    void fastBodyThroughAThinPlateStillStops() {
        World w = plateAndBall(-1.0, 200.0);
        long cuts = 0;
        for (int i = 0; i < 6; ++i) {
            w.step(1.0 / 60);
            cuts += static_cast<long>(w.impacts().size());
        }
        QCOMPARE(cuts, 1L);
        const double z = w.state().bodies[1].x.z(), vz = velocityOf(w, 1).z();
        QVERIFY2(z < -0.05, qPrintable(QString("the ball is at z = %1 m: through the plate").arg(z)));
        QVERIFY2(std::abs(vz + 100.0) < 1e-9 * 100.0, qPrintable(QString("bounced back at %1 m/s").arg(num(vz))));
    }

    // The same ball at 4.8 m/s (8 cm a step at 1/60 s), starting 0.1 mm before the plate:
    // the end of its step finds it touching the plate with its centre past the plate's
    // middle, where the contact's normal points out of the far side and would push it
    // through. Its travel is more than half the plate's thickness, so it gets its moment:
    // it bounces back at e v.
    void ballPastAThinPlatesMiddleBouncesBack() {
        World w = plateAndBall(-0.0551, 4.8);
        for (int i = 0; i < 10; ++i) w.step(1.0 / 60);
        const double z = w.state().bodies[1].x.z(), vz = velocityOf(w, 1).z();
        QVERIFY2(z < -0.055, qPrintable(QString("the ball is at z = %1 m: through the plate").arg(z)));
        QVERIFY2(std::abs(vz + 2.4) < 1e-9 * 2.4, qPrintable(QString("bounced back at %1 m/s").arg(num(vz))));
    }

    // A pile of random boxes and spheres dropped onto the ground with end-of-step impacts
    // (restitution and friction 0..1): the total energy never rises above the start (1e-6
    // relative: rounding and the integrator's error in free flight). tst_response.cpp's
    // energyNeverRises is the same with exact impacts.
    void pileEnergyNeverRises_data() {
        QTest::addColumn<int>("seed");
        QTest::addColumn<double>("h");
        for (int seed : {1, 2, 3})
            for (double h : {1.0 / 60, 1.0 / 240}) QTest::addRow("seed %d, dt 1/%.0f", seed, 1.0 / h) << seed << h;
    }
    void pileEnergyNeverRises() {
        QFETCH(int, seed);
        QFETCH(double, h);
        const std::vector<BodyDesc> bodies = randomDropPile(std::uint64_t(seed));
        SceneDesc scene = sceneOf(bodies);
        scene.settings.impacts = ImpactTiming::EndOfStep;
        World w(scene);
        const double e0 = energy(w.model(), w.state()).total();
        while (w.state().time < 5.0) {
            w.step(h);
            const double e = energy(w.model(), w.state()).total();
            QVERIFY2(e <= e0 + 1e-6 * std::abs(e0), qPrintable(QString("energy %1 J at t = %2 s, above the start %3 J")
                                                                    .arg(num(e))
                                                                    .arg(w.state().time)
                                                                    .arg(num(e0))));
        }
        for (int i = 1; i < int(bodies.size()); ++i)
            QVERIFY2(w.state().bodies[i].x.y() > 0.0,
                     qPrintable(QString("body %1 ended at y = %2 m, below the ground").arg(i).arg(w.state().bodies[i].x.y())));
    }
};

QTEST_APPLESS_MAIN(TestImpactTiming)
#include "tst_impact_timing.moc"
