// The dedicated narrowphase routines against closed-form contacts: depth, normal (out of B
// towards A) and points, for every pair with a routine of its own, in both argument orders.
#include "collision/narrowphase.h"

#include <QtTest>

#include <algorithm>
#include <cmath>

using namespace tumble;
using namespace tumble::collision;

namespace {

constexpr double kTol = 1e-12;

Pose at(const Vec3& p, const Quat& q = Quat::Identity()) { return {q.toRotationMatrix(), p}; }

Quat about(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

ManifoldList run(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin = 0.0) {
    ManifoldList out;
    collide(a, pa, b, pb, margin, out);
    return out;
}

bool near(const Vec3& x, const Vec3& y, double tol = 1e-9) { return (x - y).norm() <= tol; }

// True when the manifold holds a point at `p` (within tol) with depth `depth`.
bool hasPoint(const Manifold& m, const Vec3& p, double depth, double tol = 1e-9) {
    for (int i = 0; i < m.count; ++i) {
        if (near(m.points[i].position, p, tol) && std::abs(m.points[i].depth - depth) <= tol) return true;
    }
    return false;
}

const Shape kGround = Shape::plane(Vec3::UnitY(), 0.0);

}  // namespace

class TestNarrowphase : public QObject {
    Q_OBJECT
private slots:
    void sphereOnPlaneAtDepth() {
        const double r = 0.5, d = 0.01;
        const auto m = run(Shape::sphere(r), at(Vec3(1, r - d, 2)), kGround, at(Vec3::Zero()));
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 1);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), kTol));
        QVERIFY(std::abs(m[0].points[0].depth - d) < kTol);
        QVERIFY(near(m[0].points[0].position, Vec3(1, -d / 2, 2), kTol));
        // Swapped: the normal flips, nothing else changes.
        const auto s = run(kGround, at(Vec3::Zero()), Shape::sphere(r), at(Vec3(1, r - d, 2)));
        QCOMPARE(s.size(), size_t(1));
        QVERIFY(near(s[0].normal, -Vec3::UnitY(), kTol));
        QVERIFY(std::abs(s[0].points[0].depth - d) < kTol);
    }

    void tiltedOffsetPlane() {
        // Plane body rotated and moved: normal n = R n_local, offset through its own frame.
        const Shape plane = Shape::plane(Vec3::UnitY(), 0.25);
        const Pose pose = at(Vec3(0, 1, 0), about(Vec3::UnitZ(), 0.3));
        Vec3 n;
        double offset;
        worldPlane(plane, pose, n, offset);
        const Vec3 expectedN = about(Vec3::UnitZ(), 0.3) * Vec3::UnitY();
        QVERIFY(near(n, expectedN, kTol));
        QVERIFY(std::abs(offset - (expectedN.dot(Vec3(0, 1, 0)) + 0.25)) < kTol);
        const Vec3 centre = n * (offset + 0.4);  // sphere of radius 0.5 sunk 0.1
        const auto m = run(Shape::sphere(0.5), at(centre), plane, pose);
        QCOMPARE(m.size(), size_t(1));
        QVERIFY(std::abs(m[0].points[0].depth - 0.1) < 1e-12);
    }

    void marginReportsNearContacts() {
        const auto none = run(Shape::sphere(0.5), at(Vec3(0, 0.52, 0)), kGround, at(Vec3::Zero()), 0.01);
        QVERIFY(none.empty());
        const auto near = run(Shape::sphere(0.5), at(Vec3(0, 0.505, 0)), kGround, at(Vec3::Zero()), 0.01);
        QCOMPARE(near.size(), size_t(1));
        QVERIFY(std::abs(near[0].points[0].depth + 0.005) < kTol);
    }

    void sphereSphere() {
        const auto m = run(Shape::sphere(1.0), at(Vec3(0, 0, 0)), Shape::sphere(0.5), at(Vec3(1.2, 0, 0)));
        QCOMPARE(m.size(), size_t(1));
        QVERIFY(near(m[0].normal, Vec3(-1, 0, 0), kTol));  // out of B (at +x) towards A
        QVERIFY(std::abs(m[0].points[0].depth - 0.3) < kTol);
        QVERIFY(near(m[0].points[0].position, Vec3(0.85, 0, 0), kTol));  // between 0.7 and 1.0
        QVERIFY(run(Shape::sphere(1.0), at(Vec3::Zero()), Shape::sphere(0.5), at(Vec3(1.51, 0, 0))).empty());
    }

    void sphereBoxRegions_data() {
        QTest::addColumn<Vec3>("centre");  // box frame; the box is rotated in the test
        QTest::addColumn<Vec3>("normal");  // box frame
        QTest::addColumn<double>("depth");
        const double r = 0.3;
        QTest::newRow("face") << Vec3(0, 0.7, 0.1) << Vec3(0, 1, 0) << (r - 0.2);
        QTest::newRow("face, sunk") << Vec3(0.2, 0.45, 0) << Vec3(0, 1, 0) << (r + 0.05);
        const double e = 0.1 / std::sqrt(2.0);
        QTest::newRow("edge") << Vec3(1 + e, 0.5 + e, 0) << Vec3(1, 1, 0).normalized() << (r - 0.1);
        QTest::newRow("corner") << Vec3(1.1, 0.6, 0.7) << Vec3(1, 1, 1).normalized() << (r - std::sqrt(0.03));
        QTest::newRow("centre inside, nearest face z") << Vec3(0.1, 0.1, -0.55) << Vec3(0, 0, -1) << (r + 0.05);
    }

    void sphereBoxRegions() {
        QFETCH(Vec3, centre);
        QFETCH(Vec3, normal);
        QFETCH(double, depth);
        const Vec3 h(1.0, 0.5, 0.6);
        const Pose box = at(Vec3(3, -1, 2), about(Vec3(1, 2, 3), 0.7));
        const auto m = run(Shape::sphere(0.3), at(box.toWorld(centre)), Shape::box(h), box);
        QCOMPARE(m.size(), size_t(1));
        QVERIFY(near(m[0].normal, box.R * normal, 1e-12));
        QVERIFY(std::abs(m[0].points[0].depth - depth) < 1e-12);
        // The point is midway between the sphere's surface and the box's.
        const Vec3 surfaceA = box.toWorld(centre) - m[0].normal * 0.3;
        QVERIFY(near(m[0].points[0].position, surfaceA + m[0].normal * (depth / 2), 1e-12));
        // And the other way round.
        const auto s = run(Shape::box(h), box, Shape::sphere(0.3), at(box.toWorld(centre)));
        QCOMPARE(s.size(), size_t(1));
        QVERIFY(near(s[0].normal, -(box.R * normal), 1e-12));
    }

    void boxRestingOnFaceGivesFourCorners() {
        const Vec3 h(0.5, 0.25, 0.75);
        const double d = 0.002;
        const Quat spin = about(Vec3::UnitY(), 0.4);
        const Pose pose = at(Vec3(2, h.y() - d, -1), spin);
        const auto m = run(Shape::box(h), pose, kGround, at(Vec3::Zero()));
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 4);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), kTol));
        for (int sx : {-1, 1}) {
            for (int sz : {-1, 1}) {
                const Vec3 corner = pose.toWorld(Vec3(sx * h.x(), -h.y(), sz * h.z()));
                QVERIFY(hasPoint(m[0], Vec3(corner.x(), -d / 2, corner.z()), d, 1e-12));
            }
        }
    }

    void boxOnBoxFaceToFace() {
        // A small box sunk 0.01 into the top face of a large one: its four bottom corners.
        const Shape big = Shape::box(Vec3(2, 0.5, 2));
        const Shape small = Shape::box(Vec3(0.3, 0.2, 0.4));
        const Pose below = at(Vec3(0, 0, 0));
        const Pose above = at(Vec3(0.5, 0.5 + 0.2 - 0.01, -0.3), about(Vec3::UnitY(), 0.5));
        const auto m = run(small, above, big, below);
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 4);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), 1e-12));
        for (int sx : {-1, 1}) {
            for (int sz : {-1, 1}) {
                const Vec3 c = above.toWorld(Vec3(sx * 0.3, -0.2, sz * 0.4));
                QVERIFY(hasPoint(m[0], Vec3(c.x(), 0.5 - 0.005, c.z()), 0.01, 1e-12));
            }
        }
        // Reversed roles: the big box on top of the small one (same contact, normal down).
        const auto r = run(big, below, small, above);
        QCOMPARE(r.size(), size_t(1));
        QVERIFY(near(r[0].normal, -Vec3::UnitY(), 1e-12));
        QCOMPARE(r[0].count, 4);
        QVERIFY(std::abs(r[0].maxDepth() - 0.01) < 1e-12);
    }

    void boxOnBoxRotatedClipsToFourOfEight() {
        // Two equal boxes, the top one turned 45°: the overlap is an octagon; four of its
        // eight corners are kept and they span a large part of it.
        const Shape b = Shape::box(Vec3(0.5, 0.5, 0.5));
        const auto m = run(b, at(Vec3(0, 0.99, 0), about(Vec3::UnitY(), M_PI / 4)), b, at(Vec3::Zero()));
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 4);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), 1e-12));
        const double octagonRadius = std::sqrt(0.25 + std::pow(std::sqrt(0.5) - 0.5, 2));
        for (int i = 0; i < 4; ++i) {
            const Vec3 p = m[0].points[i].position;
            QVERIFY(std::abs(p.y() - 0.495) < 1e-12);
            QVERIFY(std::abs(m[0].points[i].depth - 0.01) < 1e-12);
            QVERIFY(std::abs(Vec3(p.x(), 0, p.z()).norm() - octagonRadius) < 1e-9);  // a corner of the octagon
        }
    }

    void boxEdgeOnBoxEdge() {
        // Box A turned 45° about z, box B turned 45° about x and placed below: the lowest
        // edge of A (along z) crosses the highest edge of B (along x). No vertex is inside.
        const Shape b = Shape::box(Vec3(0.5, 0.5, 0.5));
        const double reach = std::sqrt(0.5);  // centre to edge of a 45° box
        const double depth = 0.02;
        const Pose a = at(Vec3(0, 2 * reach - depth, 0), about(Vec3::UnitZ(), M_PI / 4));
        const Pose bPose = at(Vec3::Zero(), about(Vec3::UnitX(), M_PI / 4));
        const auto m = run(b, a, b, bPose);
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 1);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), 1e-12));
        QVERIFY(std::abs(m[0].points[0].depth - depth) < 1e-12);
        QVERIFY(near(m[0].points[0].position, Vec3(0, reach - depth / 2, 0), 1e-12));
    }

    void separatedBoxesGiveNothing() {
        const Shape b = Shape::box(Vec3(0.5, 0.5, 0.5));
        QVERIFY(run(b, at(Vec3(1.001, 0, 0)), b, at(Vec3::Zero())).empty());
        // Separated only along an edge axis: two 45° boxes whose edges pass each other.
        const double reach = std::sqrt(0.5);
        QVERIFY(run(b, at(Vec3(0, 2 * reach + 0.001, 0), about(Vec3::UnitZ(), M_PI / 4)), b,
                    at(Vec3::Zero(), about(Vec3::UnitX(), M_PI / 4))).empty());
    }

    void capsulesParallelGiveTwoPoints() {
        const Shape c = Shape::capsule(0.2, 1.0);
        const Quat lying = about(Vec3::UnitZ(), M_PI / 2);  // axis along x
        // B from x = -1..1, A shifted 0.5 along x and sitting 0.39 above: depth 0.01.
        const auto m = run(c, at(Vec3(0.5, 0.39, 0), lying), c, at(Vec3::Zero(), lying));
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 2);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), 1e-12));
        QVERIFY(hasPoint(m[0], Vec3(-0.5, 0.195, 0), 0.01, 1e-12));
        QVERIFY(hasPoint(m[0], Vec3(1.0, 0.195, 0), 0.01, 1e-12));
    }

    void capsulesCrossedGiveOnePoint() {
        const Shape c = Shape::capsule(0.2, 1.0);
        const auto m = run(c, at(Vec3(0.1, 0.38, 0.2), about(Vec3::UnitZ(), M_PI / 2)), c,
                           at(Vec3::Zero(), about(Vec3::UnitX(), M_PI / 2)));
        QCOMPARE(m.size(), size_t(1));
        QCOMPARE(m[0].count, 1);
        QVERIFY(near(m[0].normal, Vec3::UnitY(), 1e-12));
        QVERIFY(std::abs(m[0].points[0].depth - 0.02) < 1e-12);
        QVERIFY(near(m[0].points[0].position, Vec3(0, 0.19, 0.2), 1e-12));
    }

    void sphereOnCapsuleSide() {
        const auto m = run(Shape::sphere(0.5), at(Vec3(0.3, 0.6, 0)), Shape::capsule(0.2, 1.0),
                           at(Vec3::Zero(), about(Vec3::UnitZ(), M_PI / 2)));
        QCOMPARE(m.size(), size_t(1));
        QVERIFY(near(m[0].normal, Vec3::UnitY(), 1e-12));
        QVERIFY(std::abs(m[0].points[0].depth - 0.1) < 1e-12);
    }

    void capsuleLyingOnPlaneAndOnBox() {
        const Shape c = Shape::capsule(0.2, 1.0);
        const Pose lying = at(Vec3(0, 0.19, 0), about(Vec3::UnitZ(), M_PI / 2));
        const auto p = run(c, lying, kGround, at(Vec3::Zero()));
        QCOMPARE(p.size(), size_t(1));
        QCOMPARE(p[0].count, 2);
        QVERIFY(hasPoint(p[0], Vec3(-1, -0.005, 0), 0.01, 1e-12));
        QVERIFY(hasPoint(p[0], Vec3(1, -0.005, 0), 0.01, 1e-12));
        // On a box top at y = 0: same contacts.
        const auto b = run(c, lying, Shape::box(Vec3(3, 0.5, 3)), at(Vec3(0, -0.5, 0)));
        QCOMPARE(b.size(), size_t(1));
        QCOMPARE(b[0].count, 2);
        QVERIFY(near(b[0].normal, Vec3::UnitY(), 1e-9));
        QVERIFY(hasPoint(b[0], Vec3(-1, -0.005, 0), 0.01, 1e-9));
        QVERIFY(hasPoint(b[0], Vec3(1, -0.005, 0), 0.01, 1e-9));
        // Standing on its end on the box: one point below the axis.
        const auto s = run(c, at(Vec3(0.3, 1.19, 0)), Shape::box(Vec3(3, 0.5, 3)), at(Vec3(0, -0.5, 0)));
        QCOMPARE(s.size(), size_t(1));
        QCOMPARE(s[0].count, 1);
        QVERIFY(hasPoint(s[0], Vec3(0.3, -0.005, 0), 0.01, 1e-9));
    }

    void cylinderOnPlane() {
        const Shape c = Shape::cylinder(0.3, 0.5);
        // Standing: four points on the bottom rim.
        const auto s = run(c, at(Vec3(1, 0.49, 0)), kGround, at(Vec3::Zero()));
        QCOMPARE(s.size(), size_t(1));
        QCOMPARE(s[0].count, 4);
        for (int i = 0; i < 4; ++i) {
            const Vec3 p = s[0].points[i].position;
            QVERIFY(std::abs(p.y() + 0.005) < 1e-12);
            QVERIFY(std::abs(Vec3(p.x() - 1, 0, p.z()).norm() - 0.3) < 1e-12);
            QVERIFY(std::abs(s[0].points[i].depth - 0.01) < 1e-12);
        }
        // Lying: the lowest line, one point at each cap.
        const auto l = run(c, at(Vec3(0, 0.29, 0), about(Vec3::UnitZ(), M_PI / 2)), kGround, at(Vec3::Zero()));
        QCOMPARE(l.size(), size_t(1));
        QCOMPARE(l[0].count, 2);
        QVERIFY(hasPoint(l[0], Vec3(-0.5, -0.005, 0), 0.01, 1e-12));
        QVERIFY(hasPoint(l[0], Vec3(0.5, -0.005, 0), 0.01, 1e-12));
        // Tilted by 30°: the lowest rim point, r sin30 + h cos30 below the centre.
        const double tilt = M_PI / 6;
        const double low = 0.3 * std::sin(tilt) + 0.5 * std::cos(tilt);
        const auto t = run(c, at(Vec3(0, low - 0.01, 0), about(Vec3::UnitZ(), tilt)), kGround, at(Vec3::Zero()));
        QCOMPARE(t.size(), size_t(1));
        QCOMPARE(t[0].count, 1);
        QVERIFY(std::abs(t[0].points[0].depth - 0.01) < 1e-12);
    }
};

QTEST_APPLESS_MAIN(TestNarrowphase)
#include "tst_narrowphase.moc"
