// Time of impact: closed-form first-contact times for fast spheres, a box turning onto a
// plane and meshes; a thin fast spinning plate that a discrete check would let through;
// misses. The answer s must never be after the true first contact, and the shapes must be
// within the tolerance there.
#include "collision/bvh.h"
#include "collision/gjk.h"
#include "collision/toi.h"

#include <QtTest>

#include <cmath>
#include <memory>
#include <numbers>

using namespace tumble;
using namespace tumble::collision;

namespace {

Quat about(const Vec3& axis, double angle) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

Sweep still(const Vec3& c, const Quat& q = Quat::Identity()) {
    Sweep s;
    s.c0 = s.c1 = c;
    s.q0 = s.q1 = q;
    return s;
}

Sweep moving(const Vec3& c0, const Vec3& c1, const Quat& q0 = Quat::Identity(),
             const Quat& q1 = Quat::Identity()) {
    Sweep s;
    s.c0 = c0;
    s.c1 = c1;
    s.q0 = q0;
    s.q1 = q1;
    return s;
}

Shape meshShape(std::vector<Vec3> v, std::vector<std::array<int, 3>> t) {
    auto m = std::make_shared<MeshShape>();
    m->vertices = std::move(v);
    m->triangles = std::move(t);
    m->bvh = std::make_shared<TriangleBvh>(m->vertices, m->triangles);
    Shape s;
    s.kind = Kind::Mesh;
    s.mesh = m;
    return s;
}

// A closed cube mesh, side 2h, centred on the origin, faces outwards.
Shape cubeMesh(double h) {
    std::vector<Vec3> v;
    for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    return meshShape(v, {{0, 2, 3},
                         {0, 3, 1},
                         {4, 5, 7},
                         {4, 7, 6},
                         {0, 1, 5},
                         {0, 5, 4},
                         {2, 6, 7},
                         {2, 7, 3},
                         {0, 4, 6},
                         {0, 6, 2},
                         {1, 3, 7},
                         {1, 7, 5}});
}

// A flat square of two triangles in y = 0, side 2h, faces up.
Shape groundMesh(double h) {
    return meshShape({Vec3(-h, 0, -h), Vec3(-h, 0, h), Vec3(h, 0, h), Vec3(h, 0, -h)},
                     {{0, 1, 2}, {0, 2, 3}});
}

// A flat square ground in y = 0 from -h to h in x and z, of n x n cells of two triangles
// each, faces up.
Shape gridGround(double h, int n) {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> t;
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k) v.emplace_back(-h + 2 * h * i / n, 0.0, -h + 2 * h * k / n);
    auto at = [n](int i, int k) { return i * (n + 1) + k; };
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            t.push_back({at(i, k), at(i, k + 1), at(i + 1, k + 1)});
            t.push_back({at(i, k), at(i + 1, k + 1), at(i + 1, k)});
        }
    return meshShape(v, t);
}

double distanceAt(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb, double s) {
    return gjkDistance(proxyOf(a, sa.at(s)), proxyOf(b, sb.at(s))).distance;
}

}  // namespace

class TestToi : public QObject {
    Q_OBJECT

private slots:
    void sweepPose() {
        Sweep s = moving(Vec3(1, 2, 3), Vec3(3, 2, 1), Quat::Identity(), about(Vec3::UnitZ(), 1.0));
        s.localCenter = Vec3(0.5, 0, 0);
        const Pose p = s.at(0.5);
        QVERIFY((p.R - about(Vec3::UnitZ(), 0.5).toRotationMatrix()).norm() < 1e-15);
        QVERIFY((p.toWorld(s.localCenter) - Vec3(2, 2, 2)).norm() < 1e-15);
    }

    void fastSphereThinPlate() {
        // A 1 cm sphere at 200 m/s against a 1 cm plate, one step of 1/240 s, at three scales.
        for (double k : {1e-3, 1.0, 1e3}) {
            const double r = 0.01 * k, v = 200.0 * k, dt = 1.0 / 240, tol = 1e-4 * k;
            const Shape ball = Shape::sphere(r), plate = Shape::box(Vec3(0.005, 1, 1) * k);
            const Sweep sa = moving(Vec3(-0.5, 0.1, 0) * k, Vec3(-0.5 * k + v * dt, 0.1 * k, 0));
            const Sweep sb = still(Vec3(0.3, 0, 0) * k);
            const double exact = ((0.295 - 0.01 + 0.5) * k) / (v * dt);
            const auto hit = timeOfImpact(ball, sa, plate, sb, tol);
            QVERIFY(hit.has_value());
            QVERIFY(hit->s <= exact);
            QVERIFY((exact - hit->s) * v * dt <= tol);
            QVERIFY((hit->normal - Vec3(-1, 0, 0)).norm() < 1e-9);
            QVERIFY(std::abs(hit->point.x() - 0.295 * k) <= tol);
            // The other order: the same time, the normal reversed.
            const auto back = timeOfImpact(plate, sb, ball, sa, tol);
            QVERIFY(back && std::abs(back->s - hit->s) < 1e-12 && (back->normal + hit->normal).norm() < 1e-9);
        }
    }

    void spinningThinPlateDoesNotTunnel() {
        // 1 m x 1 cm x 1 m turning at 50 rad/s about z and falling at 50 m/s onto a 1 cm
        // plate. It is clear of the plate at both ends of the step (flat-ish above, flat-ish
        // below): a discrete test sees nothing.
        const double dt = 1.0 / 240, w = 50.0, v = 50.0, tol = 1e-4;
        const Shape blade = Shape::box(Vec3(0.5, 0.005, 0.5)), plate = Shape::box(Vec3(2, 0.005, 2));
        const Sweep sa = moving(Vec3(0.1, 0.1, 0), Vec3(0.1, 0.1 - v * dt, 0),
                                about(Vec3::UnitZ(), -0.5 * w * dt), about(Vec3::UnitZ(), 0.5 * w * dt));
        const Sweep sb = still(Vec3::Zero());
        QVERIFY(distanceAt(blade, sa, plate, sb, 0.0) > 0.0);
        QVERIFY(distanceAt(blade, sa, plate, sb, 1.0) > 0.0);
        const auto hit = timeOfImpact(blade, sa, plate, sb, tol);
        QVERIFY(hit.has_value());
        const double d = distanceAt(blade, sa, plate, sb, hit->s);
        QVERIFY(d > 0.0 && d <= tol);
        for (int i = 0; i < 2000; ++i) QVERIFY(distanceAt(blade, sa, plate, sb, hit->s * i / 2000.0) > 0.0);
        QVERIFY(hit->normal.y() > 0.99);
        // The same with the blade turning about the other horizontal axis.
        const Sweep sc = moving(Vec3(0.1, 0.1, 0), Vec3(0.1, 0.1 - v * dt, 0),
                                about(Vec3::UnitX(), -0.5 * w * dt), about(Vec3::UnitX(), 0.5 * w * dt));
        const auto hit2 = timeOfImpact(blade, sc, plate, sb, tol);
        QVERIFY(hit2.has_value());
        QVERIFY(distanceAt(blade, sc, plate, sb, hit2->s) <= tol);
        for (int i = 0; i < 2000; ++i) QVERIFY(distanceAt(blade, sc, plate, sb, hit2->s * i / 2000.0) > 0.0);
    }

    void sphereOnPlane() {
        // Centre from y = 2 to y = -3 over the step, radius 0.5: touches at s = 1.5 / 5.
        const Shape ball = Shape::sphere(0.5), ground = Shape::plane(Vec3(0, 1, 0), 0.0);
        const Sweep sa = moving(Vec3(3, 2, 1), Vec3(3, -3, 1)), sg = still(Vec3::Zero());
        const double tol = 1e-6;
        const auto hit = timeOfImpact(ball, sa, ground, sg, tol);
        QVERIFY(hit && hit->s <= 0.3 && (0.3 - hit->s) * 5 <= tol);
        QVERIFY((hit->normal - Vec3(0, 1, 0)).norm() < 1e-15);
        QVERIFY((hit->point - Vec3(3, 0, 1)).norm() <= tol);
        const auto flip = timeOfImpact(ground, sg, ball, sa, tol);
        QVERIFY(flip && flip->s == hit->s && (flip->normal - Vec3(0, -1, 0)).norm() < 1e-15);
        // A plane with an offset and a tilted normal, placed by its pose.
        const Vec3 n = Vec3(1, 2, 2) / 3.0;
        const Shape tilted = Shape::plane(n, 1.0);
        const Sweep sp = still(Vec3(0, 0, 1), Quat::Identity());  // the plane n·x = 1 + n·(0,0,1)
        const Vec3 start = n * 5.0, end = n * -1.0 + Vec3(0, 0, 1);
        const auto h2 = timeOfImpact(ball, moving(start, end), tilted, sp, tol);
        // Signed distance of the centre: 5 - (1 + 2/3) at s = 0, linear to n·end - 5/3.
        const double d0 = 5.0 - 5.0 / 3.0, d1 = n.dot(end) - 5.0 / 3.0;
        const double exact = (d0 - 0.5) / (d0 - d1);
        QVERIFY(h2 && h2->s <= exact && (exact - h2->s) * (d0 - d1) <= tol);
    }

    void boxTurningOntoPlane() {
        // A 2 x 0.2 x 0.2 box, centre held 0.5 above the ground, turning 1 rad about z over the
        // step: its lowest corner reaches the ground when sin(t) + 0.1 cos(t) = 0.5.
        const Shape bar = Shape::box(Vec3(1, 0.1, 0.1)), ground = Shape::plane(Vec3(0, 1, 0), 0.0);
        const Sweep sa =
            moving(Vec3(0, 0.5, 0), Vec3(0, 0.5, 0), Quat::Identity(), about(Vec3::UnitZ(), 1.0));
        const double phi = std::atan2(0.1, 1.0), exact = std::asin(0.5 / std::hypot(1.0, 0.1)) - phi;
        const double tol = 1e-6;
        const auto hit = timeOfImpact(bar, sa, ground, still(Vec3::Zero()), tol);
        QVERIFY(hit.has_value());
        QVERIFY(hit->s <= exact);
        // The corner's height falls at rate cos(t) - 0.1 sin(t) > 0.8 per radian here.
        QVERIFY((exact - hit->s) * 0.8 <= tol);
        // Against a box of ground instead of the plane: the same time.
        const auto boxHit = timeOfImpact(bar, sa, Shape::box(Vec3(5, 1, 5)), still(Vec3(0, -1, 0)), tol);
        QVERIFY(boxHit && boxHit->s <= exact && (exact - boxHit->s) * 0.8 <= tol);
    }

    void misses() {
        const Shape ball = Shape::sphere(0.01), plate = Shape::box(Vec3(0.005, 1, 1));
        // Passing beside the plate, and moving away from it.
        QVERIFY(!timeOfImpact(ball, moving(Vec3(-0.5, 1.2, 0), Vec3(0.5, 1.2, 0)), plate, still(Vec3::Zero()),
                              1e-4));
        QVERIFY(!timeOfImpact(ball, moving(Vec3(-0.5, 0, 0), Vec3(-0.9, 0, 0)), plate, still(Vec3::Zero()),
                              1e-4));
        // Stopping short.
        QVERIFY(!timeOfImpact(ball, moving(Vec3(-0.5, 0, 0), Vec3(-0.1, 0, 0)), plate, still(Vec3::Zero()),
                              1e-4));
        QVERIFY(!timeOfImpact(ball, moving(Vec3(0, 1, 0), Vec3(0, 0.6, 0)), Shape::plane(Vec3(0, 1, 0), 0.0),
                              still(Vec3::Zero()), 1e-4));
        // Already touching: s = 0.
        const auto now = timeOfImpact(ball, moving(Vec3(-0.015, 0, 0), Vec3(-0.5, 0, 0)), plate,
                                      still(Vec3::Zero()), 1e-4);
        QVERIFY(now && now->s == 0.0);
        // Two planes never meet.
        QVERIFY(!timeOfImpact(Shape::plane(Vec3(0, 1, 0), 0), still(Vec3::Zero()),
                              Shape::plane(Vec3(0, 1, 0), 1), still(Vec3::Zero()), 1e-4));
    }

    void meshes() {
        const double tol = 1e-6;
        // A sphere falling through a two-triangle ground, and the ground meeting the sphere.
        const Shape ground = groundMesh(5.0), ball = Shape::sphere(0.25);
        const Sweep falling = moving(Vec3(1, 3, -2), Vec3(1, -2, -2));
        auto hit = timeOfImpact(ball, falling, ground, still(Vec3::Zero()), tol);
        QVERIFY(hit && hit->s <= 0.55 && (0.55 - hit->s) * 5 <= tol);
        QVERIFY((hit->normal - Vec3(0, 1, 0)).norm() < 1e-9);
        hit = timeOfImpact(ground, still(Vec3::Zero()), ball, falling, tol);
        QVERIFY(hit && hit->s <= 0.55 && (0.55 - hit->s) * 5 <= tol &&
                (hit->normal - Vec3(0, -1, 0)).norm() < 1e-9);
        // A cube mesh (half side 0.5) falling onto a plane, turned 45 degrees about z: its
        // lowest edge is sqrt(0.5) below the centre. Centre from 3 to -1: touches at
        // s = (3 - sqrt(0.5)) / 4.
        const Shape cube = cubeMesh(0.5);
        const Quat q = about(Vec3::UnitZ(), std::numbers::pi / 4);
        const Sweep drop = moving(Vec3(0, 3, 0), Vec3(0, -1, 0), q, q);
        const double exact = (3 - std::sqrt(0.5)) / 4;
        hit = timeOfImpact(cube, drop, Shape::plane(Vec3(0, 1, 0), 0.0), still(Vec3::Zero()), tol);
        QVERIFY(hit && hit->s <= exact && (exact - hit->s) * 4 <= tol);
        // ... onto the ground mesh: the same time (mesh against mesh, triangle pairs).
        hit = timeOfImpact(cube, drop, ground, still(Vec3::Zero()), tol);
        QVERIFY(hit && hit->s <= exact && (exact - hit->s) * 4 <= tol);
        QVERIFY(hit->normal.y() > 0.999);
        // ... and a box falling the same way onto the moving ground (the ground rising to meet
        // it at 1 per step: relative speed 5).
        hit = timeOfImpact(Shape::box(Vec3(0.5, 0.5, 0.5)), drop, ground, moving(Vec3::Zero(), Vec3(0, 1, 0)),
                           tol);
        const double exact2 = (3 - std::sqrt(0.5)) / 5;
        QVERIFY(hit && hit->s <= exact2 && (exact2 - hit->s) * 5 <= tol);
        // The ground turning about its own normal is the same surface: the same time, by
        // the turning bounds (the sphere stays over the ground).
        const Sweep spinning =
            moving(Vec3::Zero(), Vec3::Zero(), Quat::Identity(), about(Vec3::UnitY(), 1.0));
        hit = timeOfImpact(ball, falling, ground, spinning, tol);
        QVERIFY(hit && hit->s <= 0.55 && (0.55 - hit->s) * 5 <= tol);
        hit = timeOfImpact(ball, falling, Shape::plane(Vec3(0, 1, 0), 0.0), spinning, tol);
        QVERIFY(hit && hit->s <= 0.55 && (0.55 - hit->s) * 5 <= tol);
        // A miss: the sphere falls beside the ground.
        QVERIFY(!timeOfImpact(ball, moving(Vec3(6, 3, 0), Vec3(6, -2, 0)), ground, still(Vec3::Zero()), tol));
    }

    void turningBodiesOverALargeMesh() {
        // The turning bar of boxTurningOntoPlane, far from the centre of a ground of 12 800
        // small triangles (the triangles a turning body can reach are looked up around its
        // own path, not around the mesh's centre): the same closed-form time, whether the
        // ground stands still or slides along its own plane, and for the bar as a mesh too.
        const Shape bar = Shape::box(Vec3(1, 0.1, 0.1)), ground = gridGround(10.0, 80);
        const double phi = std::atan2(0.1, 1.0), exact = std::asin(0.5 / std::hypot(1.0, 0.1)) - phi;
        const double tol = 1e-6;
        const Vec3 at(7.3, 0.5, -6.1);
        const Sweep sa = moving(at, at, Quat::Identity(), about(Vec3::UnitZ(), 1.0));
        for (const Sweep& sg : {still(Vec3::Zero()), moving(Vec3::Zero(), Vec3(0.4, 0, -0.3))}) {
            const auto hit = timeOfImpact(bar, sa, ground, sg, tol);
            QVERIFY(hit.has_value());
            QVERIFY(hit->s <= exact && (exact - hit->s) * 0.8 <= tol);
            QVERIFY(hit->normal.y() > 0.999);
        }
        // A cube mesh turning 1 rad about x as it falls onto the ground off its centre, its
        // centre of mass 0.2 from its frame's origin: the same time as against the plane.
        Shape cube = cubeMesh(0.5);
        Sweep drop = moving(Vec3(-8.2, 2.5, 4.4), Vec3(-8.2, -0.5, 4.4), Quat::Identity(),
                            about(Vec3::UnitX(), 1.0));
        drop.localCenter = Vec3(0.2, 0, 0);
        const auto onPlane = timeOfImpact(cube, drop, Shape::plane(Vec3(0, 1, 0), 0.0), still(Vec3::Zero()), tol);
        const auto onMesh = timeOfImpact(cube, drop, ground, still(Vec3::Zero()), tol);
        QVERIFY(onPlane && onMesh);
        QVERIFY2(std::abs(onPlane->s - onMesh->s) * 3 <= 2 * tol,
                 qPrintable(QString("plane %1, mesh %2").arg(onPlane->s).arg(onMesh->s)));
    }
};

QTEST_APPLESS_MAIN(TestToi)
#include "tst_toi.moc"
