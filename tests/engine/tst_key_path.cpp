// Issue 50 item 1 (groundwork): a keyed path's pose, velocity and angular velocity. Closed
// forms for the linear path; for the smooth one, the keys met exactly, the velocities equal
// to the pose's own rates of change, continuous across the keys and zero at the ends; every
// path with its keys turned and shifted is the path turned and shifted.
#include <QtTest>

#include <tumble/key_path.h>
#include "turned_world.h"

#include <numbers>

using namespace tumble;
using namespace tumble::test;

namespace {

Quat turnAbout(const Vec3& axis, double angle) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

std::vector<BodyKey> someKeys() {
    return {{0.5, Vec3(0, 1, 0), Quat::Identity()},
            {1.0, Vec3(1, 1.5, -0.5), turnAbout(Vec3(0, 1, 0), 0.8)},
            {2.2, Vec3(1.5, 0.7, 0.3), turnAbout(Vec3(1, 2, -1), 2.1)},
            {2.5, Vec3(0.2, 0.9, 1.1), turnAbout(Vec3(-1, 0.3, 0.4), -1.2)},
            {4.0, Vec3(-1, 1, 0), turnAbout(Vec3(0, 0, 1), 2.9)}};
}

// The world angular velocity of a turning orientation, from its poses a little before and after.
Vec3 rateOfTurn(const KeyPath& path, double t, double e) {
    const Quat q = path.at(t + e).orientation * path.at(t - e).orientation.conjugate();
    const Eigen::AngleAxisd aa(q.w() < 0 ? Quat(-q.coeffs()) : q);
    return aa.axis() * aa.angle() / (2 * e);
}

}  // namespace

class TestKeyPath : public QObject {
    Q_OBJECT

private slots:
    // Two keys 2 s apart: 2 m along x and a quarter turn about z at constant rates; held
    // before and after, at rest. At a key the velocity is the one of the segment starting
    // there (the stepper lands on keys and steps on from them).
    void linearIsConstantRates() {
        const KeyPath path({{1.0, Vec3::Zero(), Quat::Identity()},
                            {3.0, Vec3(2, 0, 0), turnAbout(Vec3::UnitZ(), std::numbers::pi / 2)}},
                           KeyInterpolation::Linear);
        const PathPoint mid = path.at(2.0);
        QVERIFY((mid.position - Vec3(1, 0, 0)).norm() < 1e-15);
        QVERIFY((mid.velocity - Vec3(1, 0, 0)).norm() < 1e-15);
        QVERIFY(mid.orientation.angularDistance(turnAbout(Vec3::UnitZ(), std::numbers::pi / 4)) < 1e-15);
        QVERIFY((mid.angularVelocity - Vec3(0, 0, std::numbers::pi / 4)).norm() < 1e-15);
        for (double t : {0.0, 3.0, 5.0}) {
            const PathPoint held = path.at(t);
            QVERIFY(held.velocity.isZero(0.0) && held.angularVelocity.isZero(0.0));
        }
        QVERIFY((path.at(1.0).velocity - Vec3(1, 0, 0)).norm() < 1e-15);
        QVERIFY(path.at(1.0).position.isZero(0.0));
        // The fastest point a metre out: 1 m/s and π/4 rad/s.
        QVERIFY(std::abs(path.fastest(1.0) - (1.0 + std::numbers::pi / 4)) < 1e-12);
        QVERIFY((path.at(5.0).position - Vec3(2, 0, 0)).norm() < 1e-15);
    }

    // Both kinds meet every key exactly.
    void theKeysAreMet_data() {
        QTest::addColumn<int>("kind");
        QTest::newRow("linear") << int(KeyInterpolation::Linear);
        QTest::newRow("smooth") << int(KeyInterpolation::Smooth);
    }
    void theKeysAreMet() {
        QFETCH(int, kind);
        const KeyPath path(someKeys(), KeyInterpolation(kind));
        for (const BodyKey& k : someKeys()) {
            const PathPoint p = path.at(k.time);
            QVERIFY2((p.position - k.position).norm() < 1e-14, qPrintable(QString::number(k.time)));
            QVERIFY2(p.orientation.angularDistance(k.orientation) < 1e-14,
                     qPrintable(QString::number(k.time)));
        }
    }

    // Smooth: the velocity and angular velocity are the pose's own rates of change (central
    // differences, 1e-6 s), continuous across every key, zero at the first and the last.
    void smoothRatesAreTheDerivativesAndContinuous() {
        const KeyPath path(someKeys(), KeyInterpolation::Smooth);
        const double e = 1e-6;
        for (double t = 0.52; t < 3.99; t += 0.0731) {
            const PathPoint p = path.at(t);
            const Vec3 v = (path.at(t + e).position - path.at(t - e).position) / (2 * e);
            QVERIFY2((p.velocity - v).norm() < 1e-6,
                     qPrintable(QString("t %1: %2").arg(t).arg((p.velocity - v).norm())));
            const Vec3 w = rateOfTurn(path, t, e);
            QVERIFY2((p.angularVelocity - w).norm() < 1e-6,
                     qPrintable(QString("t %1: %2").arg(t).arg((p.angularVelocity - w).norm())));
        }
        for (const BodyKey& k : someKeys()) {
            const PathPoint before = path.at(k.time - 1e-9), after = path.at(k.time + 1e-9);
            QVERIFY2((before.velocity - after.velocity).norm() < 1e-6, qPrintable(QString::number(k.time)));
            QVERIFY2((before.angularVelocity - after.angularVelocity).norm() < 1e-6,
                     qPrintable(QString::number(k.time)));
        }
        QVERIFY(path.at(0.5 + 1e-9).velocity.norm() < 1e-6 &&
                path.at(0.5 + 1e-9).angularVelocity.norm() < 1e-6);
        QVERIFY(path.at(4.0 - 1e-9).velocity.norm() < 1e-6 &&
                path.at(4.0 - 1e-9).angularVelocity.norm() < 1e-6);
    }

    // Keys turned and shifted as a whole give the path turned and shifted.
    void aTurnedPathIsThePathTurned_data() { theKeysAreMet_data(); }
    void aTurnedPathIsThePathTurned() {
        QFETCH(int, kind);
        const WorldPose pose = randomWorldPose(11);
        std::vector<BodyKey> turned = someKeys();
        for (BodyKey& k : turned) {
            k.position = pose.point(k.position);
            k.orientation = pose.orientation(k.orientation);
        }
        const KeyPath path(someKeys(), KeyInterpolation(kind)), moved(turned, KeyInterpolation(kind));
        for (double t = 0.3; t < 4.2; t += 0.117) {
            const PathPoint a = path.at(t), b = moved.at(t);
            QVERIFY((pose.point(a.position) - b.position).norm() < 1e-12);
            QVERIFY(pose.orientation(a.orientation).angularDistance(b.orientation) < 1e-12);
            QVERIFY((pose.direction(a.velocity) - b.velocity).norm() < 1e-12);
            QVERIFY((pose.direction(a.angularVelocity) - b.angularVelocity).norm() < 1e-12);
        }
    }

    // An orientation given as -q is the same orientation: the path does not turn.
    void theShortWayRound() {
        const Quat q = turnAbout(Vec3(1, 1, 0), 0.4);
        const KeyPath path({{0, Vec3::Zero(), q}, {1, Vec3::Zero(), Quat(-q.coeffs())}},
                           KeyInterpolation::Linear);
        QVERIFY(path.at(0.5).angularVelocity.norm() < 1e-15);
        QVERIFY(path.at(0.5).orientation.angularDistance(q) < 1e-15);
    }
};

QTEST_GUILESS_MAIN(TestKeyPath)
#include "tst_key_path.moc"
