// Mass properties: closed forms of the primitives, checked against exact polyhedral
// integration of finely tessellated meshes (a converged reference), and the polyhedral
// routine itself against solids whose answer is known in closed form.
#include "scene_builders.h"

#include <tumble/errors.h>
#include <tumble/mass.h>
#include <tumble/model.h>

#include <QtTest>

#include <numbers>

using namespace tumble;
using std::numbers::pi;

namespace {

// Closed surface of revolution about y: a profile of (radius, y) points from the bottom
// pole to the top pole, swept through `segments` angles. Triangles face outwards.
TriangleMesh revolve(const std::vector<std::pair<double, double>>& profile, int segments) {
    TriangleMesh m;
    const int rings = static_cast<int>(profile.size());
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const double a = 2.0 * pi * s / segments;
            m.vertices.emplace_back(profile[r].first * std::cos(a), profile[r].second,
                                    -profile[r].first * std::sin(a));
        }
    }
    auto id = [&](int r, int s) { return r * segments + (s % segments); };
    for (int r = 0; r + 1 < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            m.triangles.push_back({id(r, s), id(r, s + 1), id(r + 1, s + 1)});
            m.triangles.push_back({id(r, s), id(r + 1, s + 1), id(r + 1, s)});
        }
    }
    return m;  // the poles are rings of zero radius: degenerate triangles add nothing
}

TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi, bool inward = false) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) {
        m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    }
    // Outward-facing quads, counter-clockwise seen from outside.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        std::array<int, 3> t1{q[0], q[1], q[2]}, t2{q[0], q[2], q[3]};
        if (inward) {
            std::swap(t1[1], t1[2]);
            std::swap(t2[1], t2[2]);
        }
        m.triangles.push_back(t1);
        m.triangles.push_back(t2);
    }
    return m;
}

TriangleMesh merge(TriangleMesh a, const TriangleMesh& b) {
    const int offset = static_cast<int>(a.vertices.size());
    a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (auto t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return a;
}

bool near(const Mat3& a, const Mat3& b, double relTol) {
    return (a - b).cwiseAbs().maxCoeff() <= relTol * b.cwiseAbs().maxCoeff();
}

ShapeDesc shape(ShapeType t, double r = 0, double h = 0) {
    ShapeDesc s;
    s.type = t;
    s.radius = r;
    s.halfHeight = h;
    return s;
}

}  // namespace

class TestMassProperties : public QObject {
    Q_OBJECT
private slots:
    void sphereClosedForm() {
        const MassProperties mp = primitiveMassProperties(shape(ShapeType::Sphere, 0.3), 2.0);
        QCOMPARE(mp.inertia(0, 0), 0.4 * 2.0 * 0.09);
        QVERIFY(mp.inertia.isDiagonal());
        QCOMPARE(shapeVolume(shape(ShapeType::Sphere, 0.3)), 4.0 / 3.0 * pi * 0.027);
    }

    void boxClosedForm() {
        ShapeDesc s;
        s.type = ShapeType::Box;
        s.halfExtents = Vec3(0.5, 1.0, 1.5);  // full sides 1, 2, 3
        const MassProperties mp = primitiveMassProperties(s, 12.0);
        QCOMPARE(mp.inertia(0, 0), 12.0 / 12.0 * (4.0 + 9.0));
        QCOMPARE(mp.inertia(1, 1), 12.0 / 12.0 * (1.0 + 9.0));
        QCOMPARE(mp.inertia(2, 2), 12.0 / 12.0 * (1.0 + 4.0));
        QCOMPARE(shapeVolume(s), 6.0);
    }

    void cylinderClosedForm() {
        const MassProperties mp = primitiveMassProperties(shape(ShapeType::Cylinder, 0.5, 1.0), 3.0);
        QCOMPARE(mp.inertia(1, 1), 0.5 * 3.0 * 0.25);
        QCOMPARE(mp.inertia(0, 0), 3.0 * (3.0 * 0.25 + 4.0) / 12.0);
    }

    // The primitives against polyhedral integration of tessellations (error ~ 1/n²).
    void primitivesMatchTessellatedMeshes_data() {
        QTest::addColumn<int>("type");
        QTest::newRow("sphere") << int(ShapeType::Sphere);
        QTest::newRow("cylinder") << int(ShapeType::Cylinder);
        QTest::newRow("capsule") << int(ShapeType::Capsule);
    }
    void primitivesMatchTessellatedMeshes() {
        QFETCH(int, type);
        const double r = 0.4, h = 0.7, density = 500.0;
        const int n = 400;
        std::vector<std::pair<double, double>> profile;
        const auto t = static_cast<ShapeType>(type);
        if (t == ShapeType::Cylinder) {
            profile = {{0, -h}, {r, -h}, {r, h}, {0, h}};
        } else {
            const double half = t == ShapeType::Capsule ? h : 0.0;
            for (int k = 0; k <= n / 2; ++k) {  // bottom hemisphere
                const double a = -pi / 2 + pi / 2 * k / (n / 2);
                profile.emplace_back(r * std::cos(a), -half + r * std::sin(a));
            }
            for (int k = 0; k <= n / 2; ++k) {  // top hemisphere
                const double a = pi / 2 * k / (n / 2);
                profile.emplace_back(r * std::cos(a), half + r * std::sin(a));
            }
        }
        const TriangleMesh mesh = revolve(profile, n);
        double volume = 0;
        const MassProperties fromMesh = meshMassProperties(mesh, density, &volume);
        const ShapeDesc s = shape(t, r, h);
        QVERIFY(std::abs(volume - shapeVolume(s)) < 1e-3 * shapeVolume(s));
        const MassProperties closed = primitiveMassProperties(s, fromMesh.mass);
        QVERIFY2(near(fromMesh.inertia, closed.inertia, 1e-3), "closed form differs from the tessellation");
        QVERIFY(fromMesh.centerOfMass.norm() < 1e-9);
    }

    void cubeMesh() {
        double volume = 0;
        const MassProperties mp = meshMassProperties(boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), 3.0, &volume);
        QCOMPARE(volume, 1.0);
        QCOMPARE(mp.mass, 3.0);
        QVERIFY((mp.centerOfMass - Vec3(0.5, 0.5, 0.5)).norm() < 1e-15);
        QVERIFY(near(mp.inertia, Mat3::Identity() * 3.0 / 6.0, 1e-14));
    }

    // The corner tetrahedron (0, e1, e2, e3): V = 1/6, centroid 1/4, and about the
    // centroid Ixx = 1/80, Ixy = +1/480 (products of inertia enter with a minus sign).
    void cornerTetrahedron() {
        TriangleMesh m;
        m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
        m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        QVERIFY(isClosed(m));
        double volume = 0;
        const MassProperties mp = meshMassProperties(m, 1.0, &volume);
        QVERIFY(std::abs(volume - 1.0 / 6.0) < 1e-15);
        QVERIFY((mp.centerOfMass - Vec3::Constant(0.25)).norm() < 1e-15);
        Mat3 expected;
        expected << 1.0 / 80, 1.0 / 480, 1.0 / 480, 1.0 / 480, 1.0 / 80, 1.0 / 480, 1.0 / 480, 1.0 / 480, 1.0 / 80;
        QVERIFY(near(mp.inertia, expected, 1e-13));
    }

    // A rotated, translated box: the tensor turns with the body, I' = R I Rᵀ.
    void rotatedBoxMesh() {
        TriangleMesh m = boxMesh(Vec3(-0.5, -1, -1.5), Vec3(0.5, 1, 1.5));
        const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
        for (Vec3& v : m.vertices) v = R * v + Vec3(4, -2, 7);
        const MassProperties mp = meshMassProperties(m, 2.0);
        QVERIFY(std::abs(mp.mass - 12.0) < 1e-12);
        QVERIFY((mp.centerOfMass - Vec3(4, -2, 7)).norm() < 1e-12);
        const Mat3 body = Vec3(13.0 * 1.0, 10.0, 5.0).asDiagonal();  // m/12 (b² + c²), m = 12
        QVERIFY(near(mp.inertia, R * body * R.transpose(), 1e-12));
    }

    // A concave solid: a cube with a cubic cavity (inner faces pointing inwards).
    void hollowCube() {
        const TriangleMesh m = merge(boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1)),
                                     boxMesh(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5), true));
        QVERIFY(isClosed(m));
        double volume = 0;
        const MassProperties mp = meshMassProperties(m, 1.0, &volume);
        QCOMPARE(volume, 7.0);
        // Outer cube: m = 8, I = 8/6 · 4; inner: m = 1, I = 1/6 · 1.
        QVERIFY(std::abs(mp.inertia(0, 0) - (8.0 * 4.0 / 6.0 - 1.0 / 6.0)) < 1e-12);
        QVERIFY(std::abs(mp.inertia(0, 1)) < 1e-12);
    }

    void openMeshIsNotClosed() {
        TriangleMesh m = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
        m.triangles.pop_back();
        QVERIFY(!isClosed(m));
        TriangleMesh flipped = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
        std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
        QVERIFY(!isClosed(flipped));
    }

    void inertiaChecks_data() {
        QTest::addColumn<Mat3>("inertia");
        QTest::addColumn<QString>("problem");
        Mat3 ok = Vec3(1, 2, 2.5).asDiagonal();
        QTest::newRow("valid") << ok << "";
        Mat3 asym = ok;
        asym(0, 1) = 0.1;
        QTest::newRow("asymmetric") << asym << "must be symmetric";
        QTest::newRow("negative") << Mat3(Vec3(-1, 2, 2).asDiagonal()) << "must be positive definite";
        QTest::newRow("zero") << Mat3(Mat3::Zero()) << "must be positive definite";
        QTest::newRow("triangle") << Mat3(Vec3(1, 1, 3).asDiagonal())
                                  << "principal moments break the triangle inequality (no mass distribution has them)";
        QTest::newRow("thin rod is fine") << Mat3(Vec3(0.5, 0.5, 1).asDiagonal()) << "";
    }
    void inertiaChecks() {
        QFETCH(Mat3, inertia);
        QFETCH(QString, problem);
        QCOMPARE(QString::fromStdString(inertiaProblem(inertia)), problem);
    }

    void densityGivesMass() {
        BodyDesc b = test::sphereBody("s", 0.1, 1.0);
        b.mass.reset();
        b.density = 1000.0;
        const Model m = compile(test::sceneOf({b}));
        QVERIFY(std::abs(m.bodies[0].mass - 1000.0 * 4.0 / 3.0 * pi * 0.001) < 1e-12);
        QVERIFY(std::abs(m.bodies[0].inertia(2, 2) - 0.4 * m.bodies[0].mass * 0.01) < 1e-15);
    }

    // An explicit tensor and centre of mass replace the computed ones; the body frame
    // origin stays where the scene puts it and the centre of mass sits at R c from it.
    void overridesReplaceComputedValues() {
        BodyDesc b = test::boxBody("b", Vec3(1, 1, 1), 2.0);
        Mat3 I;
        I << 2, 0.1, 0, 0.1, 3, 0, 0, 0, 4;
        b.inertia = I;
        b.centerOfMass = Vec3(0.1, 0.2, 0.3);
        b.position = Vec3(1, 2, 3);
        b.orientation = Quat(Eigen::AngleAxisd(pi / 2, Vec3::UnitZ()));
        World w(test::sceneOf({b}));
        QCOMPARE(w.model().bodies[0].inertia, I);
        QVERIFY((w.state().bodies[0].x - Vec3(1 - 0.2, 2 + 0.1, 3 + 0.3)).norm() < 1e-15);
        QVERIFY((bodyFramePosition(w.model().bodies[0], w.state().bodies[0]) - Vec3(1, 2, 3)).norm() < 1e-15);
    }

    void meshBodiesAreRefusedUntilLoaded() {
        BodyDesc b = test::sphereBody("m", 1, 1);
        b.shape.type = ShapeType::Mesh;
        b.shape.file = "bunny.obj";
        try {
            compile(test::sceneOf({b}));
            QFAIL("a mesh body compiled without its mesh loaded");
        } catch (const SceneError& e) {
            QCOMPARE(QString::fromStdString(e.path()), QString("bodies[0].shape.file"));
        }
    }
};

QTEST_APPLESS_MAIN(TestMassProperties)
#include "tst_mass_properties.moc"
