// Compound bodies (issue 49): one body of several shapes. Mass properties are the exact sum
// of the parts'; a compound moves as one rigid body (free tumbling, a throw), rests and tips
// on its parts as the statics say, and its parts carry their own materials. Each motion
// test also runs in a world turned and shifted as a whole. Only the public API is used.
#include "chair_pile.h"
#include "ledger_checks.h"
#include "scene_builders.h"
#include "turned_world.h"

#include <tumble/errors.h>
#include <tumble/io/scene_file.h>
#include <tumble/model.h>

#include <QDir>
#include <QtTest>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

using namespace tumble;
using namespace tumble::test;

namespace {

constexpr double kG = 9.81;

QString num(double v) {
    return QString::number(v, 'g', 17);
}

PartDesc part(ShapeType type, const Vec3& position, const Quat& orientation = Quat::Identity()) {
    PartDesc p;
    p.shape.type = type;
    p.position = position;
    p.orientation = orientation;
    return p;
}

PartDesc boxPart(const Vec3& half, const Vec3& position, const Quat& orientation = Quat::Identity()) {
    PartDesc p = part(ShapeType::Box, position, orientation);
    p.shape.halfExtents = half;
    return p;
}

PartDesc spherePart(double r, const Vec3& position) {
    PartDesc p = part(ShapeType::Sphere, position);
    p.shape.radius = r;
    return p;
}

BodyDesc compoundBody(const std::string& name, std::vector<PartDesc> parts) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Compound;
    b.shape.parts = std::move(parts);
    return b;
}

// The largest difference between two matrices, relative to the larger's largest entry.
double relativeGap(const Mat3& a, const Mat3& b) {
    return (a - b).cwiseAbs().maxCoeff() / std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
}

// A table: a top (1.2 x 0.1 x 0.8 m) on four legs (0.1 x 0.7 x 0.1 m) at x = ±0.5, z = ±0.3,
// its body frame on the floor under the middle; one density (500 kg/m³), friction `mu`.
BodyDesc table(double mu) {
    const Vec3 leg(0.05, 0.35, 0.05);
    BodyDesc t =
        compoundBody("table", {boxPart(Vec3(0.6, 0.05, 0.4), Vec3(0, 0.75, 0)),
                               boxPart(leg, Vec3(0.5, 0.35, 0.3)), boxPart(leg, Vec3(-0.5, 0.35, 0.3)),
                               boxPart(leg, Vec3(0.5, 0.35, -0.3)), boxPart(leg, Vec3(-0.5, 0.35, -0.3))});
    t.density = 500.0;
    t.restitution = 0.0;
    t.friction = mu;
    return t;
}

// The hammer: a handle (cylinder r 0.015 m, 0.3 m long, along y) with a head (box 0.1 x 0.03
// x 0.03 m) across its top end; density 7800 for the head, 700 for the handle.
BodyDesc hammer() {
    PartDesc handle = part(ShapeType::Cylinder, Vec3::Zero());
    handle.shape.radius = 0.015;
    handle.shape.halfHeight = 0.15;
    handle.density = 700.0;
    handle.name = "handle";
    PartDesc head = boxPart(Vec3(0.05, 0.015, 0.015), Vec3(0, 0.165, 0));
    head.density = 7800.0;
    head.name = "head";
    return compoundBody("hammer", {handle, head});
}

}  // namespace

class TestCompound : public QObject {
    Q_OBJECT
private slots:
    // Two boxes side by side are the box they make: mass, centre and inertia exactly (to
    // rounding), whether the halves are given straight or turned a quarter about z with
    // their extents swapped, and wherever the pair sits in the body frame (the centre of
    // mass follows it; the inertia about it does not change).
    void twoBoxesAreOneBox_data() {
        QTest::addColumn<bool>("turned");
        QTest::addColumn<Vec3>("offset");
        QTest::newRow("straight") << false << Vec3(0, 0, 0);
        QTest::newRow("turned halves") << true << Vec3(0, 0, 0);
        QTest::newRow("away from the origin") << false << Vec3(0.3, 1.0, -2.0);
        QTest::newRow("turned, away") << true << Vec3(-1.5, 0.25, 0.5);
    }
    void twoBoxesAreOneBox() {
        QFETCH(bool, turned);
        QFETCH(Vec3, offset);
        BodyDesc whole = boxBody("whole", Vec3(0.3, 0.4, 0.5), 1.0);
        whole.mass.reset();
        whole.density = 700.0;
        const Quat quarter(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));
        auto half = [&](double y) {
            return turned ? boxPart(Vec3(0.2, 0.3, 0.5), offset + Vec3(0, y, 0), quarter)
                          : boxPart(Vec3(0.3, 0.2, 0.5), offset + Vec3(0, y, 0));
        };
        BodyDesc pair = compoundBody("pair", {half(0.2), half(-0.2)});
        pair.density = 700.0;
        pair.position = Vec3(5, 5, 5);
        const Model m = compile(sceneOf({whole, pair}));
        const BodyModel &a = m.bodies[0], &b = m.bodies[1];
        QVERIFY2(std::abs(a.mass - b.mass) <= 1e-12 * a.mass, qPrintable(num(a.mass) + " " + num(b.mass)));
        QVERIFY2((b.centerOfMass - offset).norm() <= 1e-12,
                 qPrintable(num((b.centerOfMass - offset).norm())));
        QVERIFY2(relativeGap(a.inertia, b.inertia) <= 1e-12,
                 qPrintable(num(relativeGap(a.inertia, b.inertia))));
    }

    // Parts of their own density, the body's density, and a body's mass shared by volume:
    // the mass, centre and inertia in closed form (boxes: m (b² + c²) / 3 about the centre,
    // parallel axes to the common centre).
    void densitiesAndSharedMass() {
        const Vec3 h(0.1, 0.1, 0.1);  // cubes of 8e-3 m³
        auto cubeAt = [&](double x) { return boxPart(h, Vec3(x, 0, 0)); };
        BodyDesc b = compoundBody("bar", {cubeAt(-0.2), cubeAt(0.0), cubeAt(0.2)});
        b.shape.parts[0].density = 500.0;  // 4 kg of its own
        b.mass = 10.0;                     // 6 kg left for the two others: 3 kg each
        const Model m = compile(sceneOf({b}, Vec3::Zero()));
        const BodyModel& c = m.bodies[0];
        const double masses[3] = {4.0, 3.0, 3.0}, xs[3] = {-0.2, 0.0, 0.2};
        double cx = 0.0;
        for (int k = 0; k < 3; ++k) cx += masses[k] * xs[k] / 10.0;
        Mat3 I = Mat3::Zero();
        for (int k = 0; k < 3; ++k) {
            const double own = masses[k] * (0.01 + 0.01) / 3.0;  // m (b² + c²) / 3, half extents b = c = 0.1
            const double d = xs[k] - cx;
            I += Vec3(own, own + masses[k] * d * d, own + masses[k] * d * d).asDiagonal();
        }
        QCOMPARE(c.mass, 10.0);
        QVERIFY2((c.centerOfMass - Vec3(cx, 0, 0)).norm() < 1e-15, qPrintable(num(c.centerOfMass.x())));
        QVERIFY2(relativeGap(c.inertia, I) < 1e-12, qPrintable(num(relativeGap(c.inertia, I))));

        // Every part of its own density: the mass follows from them.
        BodyDesc own = compoundBody("own", {cubeAt(-0.2), cubeAt(0.2)});
        own.shape.parts[0].density = 1000.0;
        own.shape.parts[1].density = 250.0;
        const Model m2 = compile(sceneOf({own}, Vec3::Zero()));
        QVERIFY(std::abs(m2.bodies[0].mass - 10.0) < 1e-12);
        QVERIFY(std::abs(m2.bodies[0].centerOfMass.x() - (8.0 * -0.2 + 2.0 * 0.2) / 10.0) < 1e-15);
    }

    // What is refused, and the field each refusal names.
    void badCompoundsNameTheField_data() {
        QTest::addColumn<int>("which");
        QTest::addColumn<QString>("field");
        QTest::newRow("no parts") << 0 << "bodies[0].shape.parts";
        QTest::newRow("a plane part") << 1 << "bodies[0].shape.parts[1].shape.type";
        QTest::newRow("a nested compound") << 2 << "bodies[0].shape.parts[0].shape.type";
        QTest::newRow("a part with no mass to take") << 3 << "bodies[0].shape.parts[1].density";
        QTest::newRow("a mass with every part's density") << 4 << "bodies[0].mass";
        QTest::newRow("a mass below the parts' own") << 5 << "bodies[0].mass";
        QTest::newRow("a static body's part density") << 6 << "bodies[0].shape.parts[0].density";
        QTest::newRow("a bad part size") << 7 << "bodies[0].shape.parts[1].shape.half_extents[2]";
        QTest::newRow("a zero part orientation") << 8 << "bodies[0].shape.parts[0].orientation";
        QTest::newRow("a part restitution above 1") << 9 << "bodies[0].shape.parts[1].restitution";
    }
    void badCompoundsNameTheField() {
        QFETCH(int, which);
        QFETCH(QString, field);
        BodyDesc b = compoundBody(
            "c", {boxPart(Vec3(0.1, 0.1, 0.1), Vec3::Zero()), boxPart(Vec3(0.1, 0.1, 0.1), Vec3(0.2, 0, 0))});
        b.mass = 1.0;
        switch (which) {
            case 0: b.shape.parts.clear(); break;
            case 1: b.shape.parts[1].shape.type = ShapeType::Plane; break;
            case 2: b.shape.parts[0].shape.type = ShapeType::Compound; break;
            case 3:
                b.mass.reset();
                b.shape.parts[0].density = 100.0;
                break;
            case 4:
                b.shape.parts[0].density = 100.0;
                b.shape.parts[1].density = 100.0;
                break;
            case 5: b.shape.parts[0].density = 1000.0; break;  // 8 kg of its own > 1 kg
            case 6:
                b.mass.reset();
                b.motion = Motion::Static;
                b.shape.parts[0].density = 100.0;
                break;
            case 7: b.shape.parts[1].shape.halfExtents.z() = -1.0; break;
            case 8: b.shape.parts[0].orientation = Quat(0, 0, 0, 0); break;
            case 9: b.shape.parts[1].restitution = 1.5; break;
        }
        // validate() refuses each (the editor's panel checks an edit with it alone), and so
        // compile(), which starts with it.
        for (const bool full : {false, true}) {
            try {
                full ? void(compile(sceneOf({b}))) : validate(sceneOf({b}));
                QFAIL(full ? "compiled" : "validated");
            } catch (const SceneError& e) {
                QCOMPARE(QString::fromStdString(e.path()), field);
            }
        }
    }

    // A dumbbell (two balls on a handle) tumbling freely, spun about no principal axis: one
    // rigid body, so its momentum, angular momentum and energy stay as they were, and the
    // same run in a turned and shifted world is the turned run.
    void dumbbellTumblesAsOneBody_data() {
        QTest::addColumn<int>("seed");
        QTest::newRow("upright") << 0;
        QTest::newRow("turned 1") << 1;
        QTest::newRow("turned 2") << 2;
    }
    void dumbbellTumblesAsOneBody() {
        QFETCH(int, seed);
        PartDesc handle = part(ShapeType::Capsule, Vec3::Zero(),
                               Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ())));
        handle.shape.radius = 0.03;
        handle.shape.halfHeight = 0.25;
        BodyDesc d = compoundBody(
            "dumbbell", {spherePart(0.12, Vec3(-0.3, 0, 0)), spherePart(0.1, Vec3(0.3, 0, 0)), handle});
        d.density = 7800.0;
        d.velocity = Vec3(0.5, 1.0, -0.25);
        d.angularVelocity = Vec3(3.0, 1.0, -2.0);
        const SceneDesc upright = sceneOf({d}, Vec3::Zero());
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        World w(turnedScene(upright, pose)), reference(upright);
        const BodyState s0 = w.state().bodies[0];
        const double e0 = energy(w.model(), w.state()).total();
        for (int k = 0; k < 480; ++k) {
            w.step(1.0 / 240.0);
            reference.step(1.0 / 240.0);
        }
        const BodyState& s = w.state().bodies[0];
        QVERIFY2((s.L - s0.L).norm() <= 1e-12 * s0.L.norm(), qPrintable(num((s.L - s0.L).norm())));
        QVERIFY2((s.P - s0.P).norm() <= 1e-12 * s0.P.norm(), qPrintable(num((s.P - s0.P).norm())));
        const double e = energy(w.model(), w.state()).total();
        QVERIFY2(std::abs(e - e0) <= 1e-9 * e0, qPrintable(num(e) + " against " + num(e0)));
        const StateGap gap = stateGap(w.model(), w.state(), turnedState(reference.state(), pose));
        QVERIFY2(gap.worst() < 1e-9, qPrintable(describe(gap)));
    }

    // A hammer thrown spinning about its principal axis across the head: its centre of mass
    // flies the parabola of a point, and the head turns about that centre at the constant
    // rate, so the head's path is the parabola plus a circle (closed form at every frame).
    void hammerTurnsAboutItsCentreOfMass_data() { dumbbellTumblesAsOneBody_data(); }
    void hammerTurnsAboutItsCentreOfMass() {
        QFETCH(int, seed);
        BodyDesc h = hammer();
        const Vec3 v0(3.0, 4.0, 0.0);
        const double w0 = 12.0;
        h.velocity = v0;
        h.angularVelocity = Vec3(0, 0, w0);
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        SceneDesc scene = turnedScene(sceneOf({h}), pose);
        scene.settings.dt = 1.0 / 60.0;
        World w(scene);
        const BodyModel& m = w.model().bodies[0];
        const Vec3 c0 = pose.R.conjugate() * (w.state().bodies[0].x - pose.t);  // the scene's own axes
        const Vec3 head0 = Vec3(0, 0.165, 0) - m.centerOfMass;                  // from the centre, body frame
        // The head outweighs the handle: the centre is near it, on the handle's axis.
        QVERIFY(m.centerOfMass.y() > 0.1 && std::abs(m.centerOfMass.x()) < 1e-15);
        for (int k = 1; k <= 60; ++k) {
            w.step(1.0 / 60.0);
            const double t = k / 60.0;
            const BodyState& s = w.state().bodies[0];
            const Vec3 c = pose.R.conjugate() * (s.x - pose.t);
            const Vec3 cExpected = c0 + v0 * t + 0.5 * Vec3(0, -kG, 0) * t * t;
            const Vec3 head = pose.R.conjugate() * (s.q * (head0));
            const Vec3 headExpected = Eigen::AngleAxisd(w0 * t, Vec3::UnitZ()) * head0;
            QVERIFY2(
                (c - cExpected).norm() < 1e-9,
                qPrintable(
                    QString("t %1: the centre is %2 m off its parabola").arg(t).arg((c - cExpected).norm())));
            QVERIFY2((head - headExpected).norm() < 1e-9,
                     qPrintable(QString("t %1: the head is %2 m off its circle")
                                    .arg(t)
                                    .arg((head - headExpected).norm())));
        }
    }

    // A table resting on the floor stands on its four legs, each carrying a quarter of its
    // weight; the top touches nothing.
    void tableRestsOnFourLegs_data() { dumbbellTumblesAsOneBody_data(); }
    void tableRestsOnFourLegs() {
        QFETCH(int, seed);
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        SceneDesc scene = turnedScene(sceneOf({groundPlane(0.0, 0.8), table(0.8)}), pose);
        scene.settings.sleeping = false;
        World w(scene);
        const double h = 1.0 / 240.0;
        for (int k = 0; k < 240; ++k) w.step(h);
        const double weight = w.model().bodies[1].mass * kG;
        double legs[4] = {0, 0, 0, 0};
        for (const ContactMemory& c : w.state().contacts) {
            const Vec3 p = pose.R.conjugate() * (c.position - pose.t);  // the table's own axes
            QVERIFY2(p.y() < 1e-3, qPrintable(QString("a contact at height %1 m").arg(p.y())));
            const int leg = (p.x() > 0 ? 1 : 0) + (p.z() > 0 ? 2 : 0);
            QVERIFY2(std::abs(std::abs(p.x()) - 0.5) <= 0.05 + 1e-9 &&
                         std::abs(std::abs(p.z()) - 0.3) <= 0.05 + 1e-9,
                     qPrintable(QString("a contact at x %1, z %2: not under a leg").arg(p.x()).arg(p.z())));
            legs[leg] += c.normalImpulse / c.step;
        }
        for (int k = 0; k < 4; ++k)
            QVERIFY2(std::abs(legs[k] - weight / 4) < 1e-5 * weight,
                     qPrintable(QString("leg %1 carries %2 N, a quarter of the weight is %3 N")
                                    .arg(k)
                                    .arg(num(legs[k]), num(weight / 4))));
        const Vec3 v = velocityOf(w, 1);
        QVERIFY2(v.norm() < 1e-6, qPrintable(num(v.norm())));
    }

    // On a slope (gravity tilted by θ towards +x) with friction enough to hold it, the table
    // stands while its centre of mass is above the span of its legs, tan θ < 0.55 / h_c
    // (the feet's outer edges at x = ±0.55 m), and tips over the lower legs past it.
    void tableTipsAtItsLegsAngle_data() {
        QTest::addColumn<double>("margin");  // rad from the tipping angle
        QTest::addColumn<int>("seed");
        for (int seed : {0, 1}) {
            QTest::addRow("2 degrees below, pose %d", seed) << -2.0 << seed;
            QTest::addRow("2 degrees past, pose %d", seed) << 2.0 << seed;
        }
    }
    void tableTipsAtItsLegsAngle() {
        QFETCH(double, margin);
        QFETCH(int, seed);
        const BodyDesc t = table(1.5);
        // The centre's height, from the volumes (one density): top 0.096 m³ at 0.75 m, legs
        // 4 x 0.007 m³ at 0.35 m.
        const double hc = (0.096 * 0.75 + 0.028 * 0.35) / 0.124;
        const double critical = std::atan(0.55 / hc);
        const double theta = critical + margin * std::numbers::pi / 180.0;
        const Vec3 g = kG * Vec3(std::sin(theta), -std::cos(theta), 0);
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        SceneDesc scene = turnedScene(sceneOf({groundPlane(0.0, 1.5), t}, g), pose);
        World w(scene);
        QCOMPARE(w.model().bodies[1].centerOfMass.y(), hc);
        for (int k = 0; k < 480; ++k) w.step(1.0 / 240.0);
        const Quat q = pose.R.conjugate() * w.state().bodies[1].q;
        const double tilt = 2.0 * std::asin(std::min(1.0, q.vec().norm()));
        if (margin < 0)
            QVERIFY2(
                tilt < 1e-3,
                qPrintable(
                    QString("tilted %1 rad at %2 degrees").arg(tilt).arg(theta * 180 / std::numbers::pi)));
        else
            QVERIFY2(tilt > 0.5, qPrintable(QString("only tilted %1 rad at %2 degrees")
                                                .arg(tilt)
                                                .arg(theta * 180 / std::numbers::pi)));
    }

    // A part's own restitution: a compound whose only part is a ball (restitution 0.8 on a
    // body of 0) dropped on a dead floor bounces back to e² of its height; without its own
    // it takes the body's and stays down.
    void partRestitution_data() {
        QTest::addColumn<bool>("own");
        QTest::addColumn<int>("seed");
        for (int seed : {0, 1}) {
            QTest::addRow("the part's 0.8, pose %d", seed) << true << seed;
            QTest::addRow("the body's 0, pose %d", seed) << false << seed;
        }
    }
    void partRestitution() {
        QFETCH(bool, own);
        QFETCH(int, seed);
        BodyDesc b = compoundBody("ball", {spherePart(0.1, Vec3(0.5, -0.2, 0.3))});
        b.mass = 1.0;
        b.restitution = 0.0;
        if (own) b.shape.parts[0].restitution = 0.8;
        const double drop = 1.0;
        b.position = Vec3(-0.5, 0.1 + 0.2 + drop, -0.3);  // the ball's bottom `drop` above the floor
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        SceneDesc scene = turnedScene(sceneOf({groundPlane(0.0, 0.5), b}), pose);
        scene.settings.sleeping = false;
        World w(scene);
        double highest = -1.0;
        bool bounced = false;
        for (int k = 0; k < 480; ++k) {
            w.step(1.0 / 240.0);
            const double y = (pose.R.conjugate() * (w.state().bodies[1].x - pose.t)).y() - 0.1;
            const double vy = (pose.R.conjugate() * velocityOf(w, 1)).y();
            if (vy > 0) bounced = true;
            if (bounced) highest = std::max(highest, y);
        }
        const double expected = own ? 0.64 * drop : 0.0;
        // The apex between two steps: within the distance the ball moves near it in a step.
        QVERIFY2(std::abs(std::max(highest, 0.0) - expected) < 1e-3,
                 qPrintable(QString("bounced to %1 m, expected %2 m").arg(num(highest), num(expected))));
    }

    // A U-shaped bracket (a base and two arms) dropped arms down lands on its two arms:
    // it comes to rest with the base an arm's length above the floor (its hull would rest on
    // the floor whichever way; a one-box bracket too).
    void bracketLiesOnItsArms_data() { dumbbellTumblesAsOneBody_data(); }
    void bracketLiesOnItsArms() {
        QFETCH(int, seed);
        BodyDesc u = compoundBody("bracket", {boxPart(Vec3(0.3, 0.05, 0.1), Vec3(0, 0.35, 0)),
                                              boxPart(Vec3(0.05, 0.15, 0.1), Vec3(-0.25, 0.15, 0)),
                                              boxPart(Vec3(0.05, 0.15, 0.1), Vec3(0.25, 0.15, 0))});
        u.density = 2700.0;
        u.restitution = 0.0;
        u.position = Vec3(0, 0.2, 0);
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        World w(turnedScene(sceneOf({groundPlane(0.0, 0.6), u}), pose));
        for (int k = 0; k < 480; ++k) w.step(1.0 / 240.0);
        const BodyState& s = w.state().bodies[1];
        const Vec3 frame = pose.R.conjugate() * (bodyFramePosition(w.model().bodies[1], s) - pose.t);
        QVERIFY2(std::abs(frame.y()) < 2e-3, qPrintable(QString("the frame rests at %1 m").arg(frame.y())));
        QVERIFY2(velocityOf(w, 1).norm() < 1e-3, qPrintable(num(velocityOf(w, 1).norm())));
        // The contacts are under the arms only.
        for (const ContactMemory& c : w.state().contacts) {
            const Vec3 p = pose.R.conjugate() * (c.position - pose.t);
            QVERIFY2(std::abs(std::abs(p.x()) - 0.25) <= 0.05 + 1e-3, qPrintable(num(p.x())));
        }
    }

    // The cart sample (a compound deck on four cylinder wheels, each on a hinge), pushed
    // at 1 m/s on a level floor: nothing slows it but the solver's own error, so after 3 s
    // it still rolls at 1 m/s (to 2e-3: the wheels' contacts, new points on the rim every
    // step, and the axles' rows trade 1.4e-3 of the speed away at 1/60 s), level (the deck
    // 0.2 m up, to 2 mm: 1.15 mm lower, its wheels 0.65 mm into the floor as resting
    // contacts are, its axles sagging the rest under it), each wheel turning at v / r about
    // its axle. In a turned world too.
    void cartRollsOnItsHingedWheels_data() { dumbbellTumblesAsOneBody_data(); }
    void cartRollsOnItsHingedWheels() {
        QFETCH(int, seed);
        const SceneDesc cart = io::readSceneFile(QDir(TUMBLE_SCENES_DIR).filePath("cart.json").toStdString());
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        World w(turnedScene(cart, pose));
        while (w.state().time < 3.0 - 1e-9) w.step(1.0 / 60.0);
        const Vec3 v = pose.R.conjugate() * velocityOf(w, 1);
        QVERIFY2((v - Vec3(1, 0, 0)).norm() < 2e-3,
                 qPrintable(
                     QString("the deck moves at (%1, %2, %3) m/s").arg(num(v.x()), num(v.y()), num(v.z()))));
        const Vec3 at =
            pose.R.conjugate() * (bodyFramePosition(w.model().bodies[1], w.state().bodies[1]) - pose.t);
        QVERIFY2(std::abs(at.y() - 0.2) < 2e-3, qPrintable(QString("the deck is %1 m up").arg(num(at.y()))));
        for (int k = 2; k < 6; ++k) {
            // Rolling: ω = v / r about the axle, to 1 % (0.8 % at 1/60 s: a rolling wheel's
            // contact is new every step, and it rides 1.2 mm into the floor; 0.3 % at 1/240 s).
            const Vec3 omega = pose.R.conjugate() * omegaOf(w, k);
            const Vec3 vk = pose.R.conjugate() * velocityOf(w, k);
            const double mismatch = std::abs(omega.z() * 0.1 + vk.x()) / vk.x();
            QVERIFY2(mismatch < 1e-2 && std::hypot(omega.x(), omega.y()) < 1e-2,
                     qPrintable(QString("wheel %1 turns at (%2, %3, %4) rad/s at %5 m/s")
                                    .arg(k - 1)
                                    .arg(num(omega.x()), num(omega.y()), num(omega.z()), num(vk.x()))));
        }
    }

    // 200 chairs piling up (tumble-bench's chair-pile, the first second, impacts at the end
    // of the step): the ledger closes to rounding. (The energy limit booked as taken what
    // the bodies at points that no impulse reached kept: 16.4 J in the frame at 0.92 s.)
    void pileOfChairsLedgerCloses_data() {
        QTest::addColumn<int>("seed");
        QTest::newRow("upright") << 0;
        QTest::newRow("turned") << 4;
    }
    void pileOfChairsLedgerCloses() {
        QFETCH(int, seed);
        const SceneDesc s =
            chairPile(io::readSceneFile(QDir(TUMBLE_SCENES_DIR).filePath("chair.json").toStdString()), 200);
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        World w(turnedScene(s, pose));
        const double start = energy(w.model(), w.state()).total();
        for (int frame = 1; frame <= s.settings.frameRate; ++frame) advanceFrame(w, frame);
        QVERIFY2(std::abs(ledgerGap(w, start)) <= 1e-12 * weightTimesHeight(w) * 60,
                 qPrintable(describeLedger(w, start)));
    }

    // A ball dropped into a mug split into convex parts falls into its hole and rests on its
    // inner floor; with the mug's convex hull it rests on the rim's lid. The mug static, then
    // dynamic (its parts' mass from the mesh, exactly). Both in a turned world.
    void ballStaysInTheSplitMug_data() {
        QTest::addColumn<int>("collision");
        QTest::addColumn<bool>("dynamic");
        QTest::addColumn<int>("seed");
        for (int seed : {0, 1}) {
            QTest::addRow("convex parts, static, pose %d", seed)
                << int(MeshCollision::ConvexParts) << false << seed;
            QTest::addRow("convex parts, dynamic, pose %d", seed)
                << int(MeshCollision::ConvexParts) << true << seed;
            QTest::addRow("convex hull, pose %d", seed) << int(MeshCollision::ConvexHull) << false << seed;
        }
    }
    void ballStaysInTheSplitMug() {
        QFETCH(int, collision);
        QFETCH(bool, dynamic);
        QFETCH(int, seed);
        // Radius 0.4, height 1, a hole of radius 0.3 and depth 0.8: the inner floor at 0.2.
        static const auto mugMesh = std::make_shared<const TriangleMesh>(mug(0.4, 1.0, 0.3, 0.8, 32));
        BodyDesc cup;
        cup.name = "mug";
        cup.motion = dynamic ? Motion::Dynamic : Motion::Static;
        if (dynamic) cup.density = 1000.0;
        cup.shape.type = ShapeType::Mesh;
        cup.shape.file = "mug (built by the test)";
        cup.shape.meshData = mugMesh;
        cup.shape.collision = static_cast<MeshCollision>(collision);
        cup.restitution = 0.0;
        BodyDesc ball = material(sphereBody("ball", 0.1, 0.05), 0.0, 0.5);
        ball.position = Vec3(0.02, 1.5, -0.01);
        const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(static_cast<std::uint64_t>(seed));
        std::vector<BodyDesc> bodies = {groundPlane(0.0, 0.8), cup, ball};
        World w(turnedScene(sceneOf(bodies), pose));
        if (collision == int(MeshCollision::ConvexParts)) {
            const collision::Shape& c = w.model().bodies[1].collider;
            QCOMPARE(c.kind, collision::Kind::Compound);
            QVERIFY2(c.compound->parts.size() >= 4, qPrintable(QString::number(c.compound->parts.size())));
        }
        if (dynamic) {
            // The mass from the closed mesh (the parts' hulls only collide).
            const double volume = mugVolume(0.4, 1.0, 0.3, 0.8, 32);
            QVERIFY(std::abs(w.model().bodies[1].mass - 1000.0 * volume) < 1e-9 * 1000.0 * volume);
        }
        for (int k = 0; k < 480; ++k) w.step(1.0 / 240.0);
        const Vec3 p = pose.R.conjugate() * (w.state().bodies[2].x - pose.t);
        const Vec3 cupAt =
            pose.R.conjugate() * (bodyFramePosition(w.model().bodies[1], w.state().bodies[1]) - pose.t);
        const Vec3 rel = p - cupAt;
        if (collision == int(MeshCollision::ConvexParts)) {
            // On the inner floor, within the split's tolerance (1 % of the mug's diagonal).
            QVERIFY2(std::abs(rel.y() - 0.3) < 0.02 && std::hypot(rel.x(), rel.z()) < 0.2 + 0.02,
                     qPrintable(QString("the ball is at %1, %2, %3 from the mug")
                                    .arg(rel.x())
                                    .arg(rel.y())
                                    .arg(rel.z())));
        } else {
            QVERIFY2(std::abs(rel.y() - 1.1) < 1e-3,
                     qPrintable(QString("the ball rests at %1 m above the mug's base").arg(rel.y())));
        }
    }

    // A fast compound never passes through a thin wall: the dumbbell's small ball leads at
    // 40 m/s towards a 2 cm plate (8 cm a step at 1/60 s); the time of impact finds the part.
    void fastCompoundStopsAtThinWall() {
        BodyDesc d =
            compoundBody("dumbbell", {spherePart(0.05, Vec3(0.3, 0, 0)), spherePart(0.05, Vec3(-0.3, 0, 0))});
        d.mass = 1.0;
        d.restitution = 0.0;
        d.position = Vec3(-1.0, 0, 0);
        d.velocity = Vec3(40.0, 0, 0);
        BodyDesc wall = staticBoxBody("wall", Vec3(0.01, 1.0, 1.0), Vec3(1.0, 0, 0));
        SceneDesc scene = sceneOf({wall, d}, Vec3::Zero());
        scene.settings.dt = 1.0 / 60.0;
        scene.settings.frameRate = 60.0;
        World w(scene);
        for (int k = 0; k < 30; ++k) {
            w.step(1.0 / 60.0);
            const Vec3 front = w.state().bodies[1].x + w.state().bodies[1].q * Vec3(0.3, 0, 0);
            QVERIFY2(
                front.x() < 1.0 - 0.01 + 0.05 + 1e-3,
                qPrintable(QString("the leading ball reached x = %1 m at step %2").arg(front.x()).arg(k)));
        }
    }
};

QTEST_APPLESS_MAIN(TestCompound)
#include "tst_compound.moc"
