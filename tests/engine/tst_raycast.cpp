// Ray casts: closed-form hits (distance, point, outward normal) for every shape kind, misses,
// rotated poses, rays that start inside (RayStart::Surface leaves through the far wall,
// RayStart::Solid hits at 0), the nearest of several bodies with ties to the lower index,
// the model's poses (the body frame, not the centre of mass), the scene variant, and a mesh
// searched through its BVH against brute force on random rays.
#include "collision/bvh.h"

#include <tumble/mass.h>
#include <tumble/model.h>
#include <tumble/raycast.h>

#include "test_meshes.h"

#include <QtTest>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

using namespace tumble;
using namespace tumble::collision;

namespace {

constexpr double kTol = 1e-12;

bool near(double a, double b, double tol = kTol) {
    return std::abs(a - b) <= tol * std::max(1.0, std::abs(b));
}
bool near(const Vec3& a, const Vec3& b, double tol = kTol) {
    return (a - b).norm() <= tol * std::max(1.0, b.norm());
}

Quat about(const Vec3& axis, double angle) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

Pose at(const Vec3& p, const Quat& q = Quat::Identity()) {
    Pose pose;
    pose.R = q.toRotationMatrix();
    pose.p = p;
    return pose;
}

QString str(const Vec3& v) {
    return QString("(%1, %2, %3)").arg(v.x(), 0, 'g', 17).arg(v.y(), 0, 'g', 17).arg(v.z(), 0, 'g', 17);
}

// What is wrong with a hit against the closed form; empty when nothing is.
QString hitProblem(const std::optional<RayHit>& h, double distance, const Vec3& point, const Vec3& normal) {
    if (!h) return "no hit";
    QString p;
    if (!near(h->distance, distance)) p += QString("distance %1 ").arg(h->distance, 0, 'g', 17);
    if (!near(h->point, point)) p += "point " + str(h->point) + " ";
    if (!near(h->normal, normal)) p += "normal " + str(h->normal);
    return p;
}

#define CHECK_HIT(hit, dist, pt, nrm)                                    \
    do {                                                                 \
        const QString problem_ = hitProblem((hit), (dist), (pt), (nrm)); \
        QVERIFY2(problem_.isEmpty(), qPrintable(problem_));              \
    } while (0)

// The unit cube [-1, 1]³ + offset, closed, counter-clockwise from outside.
std::shared_ptr<TriangleMesh> cubeMesh(const Vec3& offset = Vec3::Zero()) {
    auto m = std::make_shared<TriangleMesh>();
    for (int i = 0; i < 8; ++i)
        m->vertices.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1) + offset);
    m->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

Shape meshShape(const TriangleMesh& t, bool withBvh) {
    auto m = std::make_shared<MeshShape>();
    m->vertices = t.vertices;
    m->triangles = t.triangles;
    m->closed = isClosed(t);
    if (withBvh) m->bvh = std::make_shared<const TriangleBvh>(m->vertices, m->triangles);
    Shape s;
    s.kind = Kind::Mesh;
    s.mesh = m;
    return s;
}

using test::uvSphere;

// The octahedron |x| + |y| + |z| <= 1 as a hull (faces only: all the ray cast reads).
ConvexHull octahedron() {
    ConvexHull h;
    for (int i = 0; i < 8; ++i) {
        ConvexHull::Face f;
        f.normal = Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1) / std::sqrt(3.0);
        f.offset = 1.0 / std::sqrt(3.0);
        h.faces.push_back(f);
    }
    return h;
}

Shape hullShape(const ConvexHull& h) {
    Shape s;
    s.kind = Kind::Hull;
    s.hull = std::make_shared<const ConvexHull>(h);
    return s;
}

BodyDesc staticBody(const std::string& name, const ShapeDesc& shape, const Vec3& position,
                    const Quat& q = Quat::Identity()) {
    BodyDesc b;
    b.name = name;
    b.motion = Motion::Static;
    b.shape = shape;
    b.position = position;
    b.orientation = q;
    return b;
}

ShapeDesc sphereDesc(double r) {
    ShapeDesc s;
    s.type = ShapeType::Sphere;
    s.radius = r;
    return s;
}

ShapeDesc boxDesc(const Vec3& h) {
    ShapeDesc s;
    s.type = ShapeType::Box;
    s.halfExtents = h;
    return s;
}

}  // namespace

class TestRaycast : public QObject {
    Q_OBJECT

private slots:
    // A compound is hit on its nearest part, which the hit names, in the scene as described
    // and in the compiled model (turned, placed away from the origin): a table seen from
    // above is hit on its top, from below between its legs on the top's underside, and on a
    // leg from the side.
    void compoundHitsItsNearestPart() {
        BodyDesc t;
        t.name = "table";
        t.shape.type = ShapeType::Compound;
        auto box = [](const Vec3& half, const Vec3& at) {
            PartDesc p;
            p.shape.type = ShapeType::Box;
            p.shape.halfExtents = half;
            p.position = at;
            return p;
        };
        t.shape.parts = {box(Vec3(0.6, 0.05, 0.4), Vec3(0, 0.75, 0)),
                         box(Vec3(0.05, 0.35, 0.05), Vec3(0.5, 0.35, 0.3)),
                         box(Vec3(0.05, 0.35, 0.05), Vec3(-0.5, 0.35, 0.3))};
        t.mass = 10.0;
        const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
        t.orientation = q;
        t.position = Vec3(3, -2, 5);
        SceneDesc scene;
        scene.bodies = {t};
        const Model model = compile(scene);
        const State state = initialState(model, scene);
        auto world = [&](const Vec3& p) { return Vec3(q * p + t.position); };
        struct Ray {
            Vec3 from, direction;
            int part;
            double distance;
        };
        const Ray rays[] = {
            {Vec3(0.5, 2.0, 0.3), Vec3(0, -1, 0), 0, 2.0 - 0.8},    // down onto the top over a leg
            {Vec3(0, -1.0, 0), Vec3(0, 1, 0), 0, 1.0 + 0.7},        // up between the legs: the underside
            {Vec3(2.0, 0.35, 0.3), Vec3(-1, 0, 0), 1, 2.0 - 0.55},  // from the side: the near leg
        };
        for (const Ray& r : rays) {
            const Vec3 o = world(r.from), d = q * r.direction;
            for (const auto& hit : {rayCastScene(scene, o, d), rayCast(model, state, o, d)}) {
                QVERIFY(hit);
                QCOMPARE(hit->part, r.part);
                QVERIFY2(std::abs(hit->distance - r.distance) < 1e-12,
                         qPrintable(QString::number(hit->distance, 'g', 17)));
            }
        }
    }

    void sphere() {
        const Shape s = Shape::sphere(2.0);
        const Pose p = at(Vec3(1, 2, 3));
        CHECK_HIT(rayShape(s, p, Vec3(1, 2, 13), Vec3(0, 0, -1)), 8.0, Vec3(1, 2, 5), Vec3(0, 0, 1));
        // Off-centre by 1: the chord gives 10 - sqrt(r² - 1), the normal (1, 0, sqrt3) / 2.
        CHECK_HIT(rayShape(s, p, Vec3(2, 2, 13), Vec3(0, 0, -1)), 10.0 - std::sqrt(3.0),
                  Vec3(2, 2, 3 + std::sqrt(3.0)), Vec3(0.5, 0, std::sqrt(3.0) / 2));
        // A direction that is not unit: the distance is still in metres.
        CHECK_HIT(rayShape(s, p, Vec3(1, 2, 13), Vec3(0, 0, -5)), 8.0, Vec3(1, 2, 5), Vec3(0, 0, 1));
        QVERIFY(!rayShape(s, p, Vec3(3.5, 2, 13), Vec3(0, 0, -1)));  // beside it
        QVERIFY(!rayShape(s, p, Vec3(1, 2, 13), Vec3(0, 0, 1)));     // pointing away
        QVERIFY(!rayShape(s, p, Vec3(1, 2, 13), Vec3::Zero()));      // no direction
    }

    void box() {
        const Shape s = Shape::box(Vec3(1, 2, 3));
        CHECK_HIT(rayShape(s, Pose{}, Vec3(10, 0.5, -1), Vec3(-1, 0, 0)), 9.0, Vec3(1, 0.5, -1),
                  Vec3(1, 0, 0));
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0.5, -10, 0.5), Vec3(0, 1, 0)), 8.0, Vec3(0.5, -2, 0.5),
                  Vec3(0, -1, 0));
        // Diagonal past the corner region: enters through x = 1 at t = 4 sqrt2.
        CHECK_HIT(rayShape(s, Pose{}, Vec3(5, 0, 5.5), Vec3(-1, 0, -1)), 4.0 * std::sqrt(2.0),
                  Vec3(1, 0, 1.5), Vec3(1, 0, 0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(10, 2.5, 0), Vec3(-1, 0, 0)));
        // Turned 45° about z, the unit cube is the diamond |x| + |y| <= sqrt2 across z.
        const Shape cube = Shape::box(Vec3(1, 1, 1));
        const Pose turned = at(Vec3(0, 0, 7), about(Vec3::UnitZ(), std::numbers::pi / 4));
        CHECK_HIT(rayShape(cube, turned, Vec3(10, 0.5, 7.2), Vec3(-1, 0, 0)), 10.0 - (std::sqrt(2.0) - 0.5),
                  Vec3(std::sqrt(2.0) - 0.5, 0.5, 7.2), Vec3(1, 1, 0).normalized());
    }

    void capsule() {
        const Shape s = Shape::capsule(0.5, 1.0);
        CHECK_HIT(rayShape(s, Pose{}, Vec3(5, 0.7, 0), Vec3(-1, 0, 0)), 4.5, Vec3(0.5, 0.7, 0),
                  Vec3(1, 0, 0));
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0, 10, 0), Vec3(0, -1, 0)), 8.5, Vec3(0, 1.5, 0), Vec3(0, 1, 0));
        // The cap off-axis at x = 0.3: y = 1 + sqrt(0.25 - 0.09) = 1.4, normal (0.3, 0.4, 0) / 0.5.
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0.3, 10, 0), Vec3(0, -1, 0)), 8.6, Vec3(0.3, 1.4, 0),
                  Vec3(0.6, 0.8, 0));
        // Through the bottom cap region from the side, y = -1.3: x = 0.4.
        CHECK_HIT(rayShape(s, Pose{}, Vec3(5, -1.3, 0), Vec3(-1, 0, 0)), 4.6, Vec3(0.4, -1.3, 0),
                  Vec3(0.8, -0.6, 0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(5, 1.6, 0), Vec3(-1, 0, 0)));
        QVERIFY(!rayShape(s, Pose{}, Vec3(0.6, 10, 0), Vec3(0, -1, 0)));
        // Turned 90° about z, the capsule lies along x; from above at x = 1.3 the end cap.
        const Pose lying = at(Vec3(0, 0, 0), about(Vec3::UnitZ(), std::numbers::pi / 2));
        CHECK_HIT(rayShape(s, lying, Vec3(1.3, 10, 0), Vec3(0, -1, 0)), 9.6, Vec3(1.3, 0.4, 0),
                  Vec3(0.6, 0.8, 0));
        CHECK_HIT(rayShape(s, lying, Vec3(-0.2, 10, 0.3), Vec3(0, -1, 0)), 9.6, Vec3(-0.2, 0.4, 0.3),
                  Vec3(0, 0.8, 0.6));
    }

    void cylinder() {
        const Shape s = Shape::cylinder(0.5, 1.0);
        CHECK_HIT(rayShape(s, Pose{}, Vec3(5, 0.9, 0), Vec3(-1, 0, 0)), 4.5, Vec3(0.5, 0.9, 0),
                  Vec3(1, 0, 0));
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0.3, 10, 0), Vec3(0, -1, 0)), 9.0, Vec3(0.3, 1, 0), Vec3(0, 1, 0));
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0, -10, 0.4), Vec3(0, 1, 0)), 9.0, Vec3(0, -1, 0.4),
                  Vec3(0, -1, 0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(5, 1.1, 0), Vec3(-1, 0, 0)));  // a capsule would hit here
        QVERIFY(!rayShape(s, Pose{}, Vec3(0.6, 10, 0), Vec3(0, -1, 0)));
        // Tipped 90° about x, the axis runs along z: from +z the flat cap.
        const Pose tipped = at(Vec3(0, 0, 0), about(Vec3::UnitX(), std::numbers::pi / 2));
        CHECK_HIT(rayShape(s, tipped, Vec3(0.2, 0.1, 10), Vec3(0, 0, -1)), 9.0, Vec3(0.2, 0.1, 1),
                  Vec3(0, 0, 1));
    }

    void plane() {
        const Shape s = Shape::plane(Vec3(0, 1, 0), 1.0);
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0, 5, 0), Vec3(0, -1, 0)), 4.0, Vec3(0, 1, 0), Vec3(0, 1, 0));
        // From below (Surface): the plane is met where the ray crosses it; the normal stays outward.
        CHECK_HIT(rayShape(s, Pose{}, Vec3(2, -5, 0), Vec3(0, 1, 0)), 6.0, Vec3(2, 1, 0), Vec3(0, 1, 0));
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0, 4, 0), Vec3(1, -1, 0)), 3.0 * std::sqrt(2.0), Vec3(3, 1, 0),
                  Vec3(0, 1, 0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(0, 5, 0), Vec3(1, 0, 0)));   // parallel
        QVERIFY(!rayShape(s, Pose{}, Vec3(0, 5, 0), Vec3(0, 1, 0)));   // up into the sky
        QVERIFY(!rayShape(s, Pose{}, Vec3(0, -5, 0), Vec3(1, 0, 0)));  // parallel, underground
        // A ground plane turned 90° about z: its normal is -x, the plane x = -1.
        const Pose turned = at(Vec3::Zero(), about(Vec3::UnitZ(), std::numbers::pi / 2));
        CHECK_HIT(rayShape(s, turned, Vec3(-7, 3, 0), Vec3(1, 0, 0)), 6.0, Vec3(-1, 3, 0), Vec3(-1, 0, 0));
    }

    void hull() {
        const Shape s = hullShape(octahedron());
        // From +z at (0.2, 0.1): the face x + y + z = 1 at z = 0.7.
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0.2, 0.1, 10), Vec3(0, 0, -1)), 9.3, Vec3(0.2, 0.1, 0.7),
                  Vec3(1, 1, 1) / std::sqrt(3.0));
        CHECK_HIT(rayShape(s, at(Vec3(0, 5, 0)), Vec3(-0.2, 5.1, -10), Vec3(0, 0, 1)), 9.3,
                  Vec3(-0.2, 5.1, -0.7), Vec3(-1, 1, -1) / std::sqrt(3.0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(0.6, 0.6, 10), Vec3(0, 0, -1)));  // beside the tip
        // Turned 45° about z, the face normals (±1, ±1, ·) land on the axes' planes: from +x, the
        // faces with normal (sqrt2, 0, ±1)/sqrt3 and, along z = 0.1, x = (1 - 0.1)/sqrt2.
        const Pose turned = at(Vec3::Zero(), about(Vec3::UnitZ(), std::numbers::pi / 4));
        CHECK_HIT(rayShape(s, turned, Vec3(10, 0, 0.1), Vec3(-1, 0, 0)), 10.0 - 0.9 / std::sqrt(2.0),
                  Vec3(0.9 / std::sqrt(2.0), 0, 0.1), Vec3(std::sqrt(2.0), 0, 1) / std::sqrt(3.0));
    }

    void meshTriangles() {
        const auto cube = cubeMesh();
        const Shape s = meshShape(*cube, true);
        CHECK_HIT(rayShape(s, Pose{}, Vec3(0.2, 0.1, 9), Vec3(0, 0, -1)), 8.0, Vec3(0.2, 0.1, 1),
                  Vec3(0, 0, 1));
        CHECK_HIT(rayShape(s, at(Vec3(0, 0, 3)), Vec3(-9, 0.3, 3.2), Vec3(1, 0, 0)), 8.0, Vec3(-1, 0.3, 3.2),
                  Vec3(-1, 0, 0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(1.2, 0.1, 9), Vec3(0, 0, -1)));
        // One triangle, either face; the normal follows the winding, not the ray.
        const std::vector<Vec3> v = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
        CHECK_HIT(rayTriangles(v, {{0, 1, 2}}, Pose{}, Vec3(0.5, 0.5, 3), Vec3(0, 0, -1)), 3.0,
                  Vec3(0.5, 0.5, 0), Vec3(0, 0, 1));
        CHECK_HIT(rayTriangles(v, {{0, 1, 2}}, Pose{}, Vec3(0.5, 0.5, -3), Vec3(0, 0, 1)), 3.0,
                  Vec3(0.5, 0.5, 0), Vec3(0, 0, 1));
        QVERIFY(!rayTriangles(v, {{0, 1, 2}}, Pose{}, Vec3(1.5, 1.5, 3), Vec3(0, 0, -1)));
        QVERIFY(
            !rayTriangles(v, {{0, 1, 7}}, Pose{}, Vec3(0.5, 0.5, 3), Vec3(0, 0, -1)));  // bad index: skipped
    }

    // A ray onto the edge where two faces meet hits both at the same distance: the lower
    // triangle index wins (7, of the y = 1 face, before 11, of the x = 1 face), BVH or not.
    void meshTiesGoToTheLowerTriangle() {
        const auto cube = cubeMesh();
        for (bool bvh : {false, true}) {
            const Shape s = meshShape(*cube, bvh);
            CHECK_HIT(rayShape(s, Pose{}, Vec3(5, 5, 0.3), Vec3(-1, -1, 0)), 4.0 * std::sqrt(2.0),
                      Vec3(1, 1, 0.3), Vec3(0, 1, 0));
        }
    }

    // A ray from inside: Surface leaves through the far wall (the outward normal points along
    // the ray); Solid hits at the origin, normal -direction.
    void rayStartingInside_data() {
        QTest::addColumn<int>("shape");
        QTest::addColumn<double>("exit");
        // Each from (0.1, 0, 0) along +x, except where noted.
        QTest::newRow("sphere") << 0 << 1.9;
        QTest::newRow("box") << 1 << 0.9;
        QTest::newRow("capsule") << 2 << 0.4;
        QTest::newRow("cylinder") << 3 << 0.4;
        QTest::newRow("hull") << 4 << 0.0;  // along (1,1,1): see below
        QTest::newRow("mesh") << 5 << 0.9;
        QTest::newRow("plane") << 6 << 2.1;
    }
    void rayStartingInside() {
        QFETCH(int, shape);
        QFETCH(double, exit);
        const auto cube = cubeMesh();
        const Shape shapes[] = {Shape::sphere(2.0),
                                Shape::box(Vec3(1, 1, 1)),
                                Shape::capsule(0.5, 1.0),
                                Shape::cylinder(0.5, 1.0),
                                hullShape(octahedron()),
                                meshShape(*cube, false),
                                Shape::plane(Vec3(1, 0, 0), 2.2)};
        const Shape& s = shapes[shape];
        Vec3 origin(0.1, 0, 0);
        Vec3 dir(1, 0, 0);
        if (shape == 4) {  // the octahedron: from (0.1,0.1,0.1) along (1,1,1), out at sum = 1
            origin = Vec3(0.1, 0.1, 0.1);
            dir = Vec3(1, 1, 1);
            exit = 0.7 / std::sqrt(3.0);
        }
        const Vec3 u = dir.normalized();
        // Every exit here is through a face whose outward normal is the direction.
        CHECK_HIT(rayShape(s, Pose{}, origin, dir), exit, origin + exit * u, u);
        CHECK_HIT(rayShape(s, Pose{}, origin, dir, kRayUnbounded, RayStart::Solid), 0.0, origin, -u);
        if (shape == 6) return;  // behind a plane is inside it, however far back
        // Moved away (outside), Solid and Surface agree on the entry.
        const Vec3 outside = origin - 10 * u;
        const auto a = rayShape(s, Pose{}, outside, dir, kRayUnbounded, RayStart::Surface);
        const auto b = rayShape(s, Pose{}, outside, dir, kRayUnbounded, RayStart::Solid);
        QVERIFY(a && b);
        QCOMPARE(a->distance, b->distance);
        QVERIFY(a->distance > 0.0 && a->distance < 10.0);
    }

    void aMeshThatIsNotClosedHasNoInside() {
        auto open = cubeMesh();
        open->triangles.resize(10);  // drop the +x face
        const Shape s = meshShape(*open, false);
        QVERIFY(!s.mesh->closed);
        // Out through the -x face's back, whatever RayStart says.
        const auto h = rayShape(s, Pose{}, Vec3(0.1, 0, 0), Vec3(-1, 0, 0), kRayUnbounded, RayStart::Solid);
        CHECK_HIT(h, 1.1, Vec3(-1, 0, 0), Vec3(-1, 0, 0));
        QVERIFY(!rayShape(s, Pose{}, Vec3(0.1, 0, 0), Vec3(1, 0, 0), kRayUnbounded, RayStart::Solid));
    }

    void maxDistanceBoundsTheHit() {
        const Shape s = Shape::sphere(1.0);
        QVERIFY(rayShape(s, Pose{}, Vec3(0, 0, 5), Vec3(0, 0, -1), 4.0));  // exactly at the bound
        QVERIFY(!rayShape(s, Pose{}, Vec3(0, 0, 5), Vec3(0, 0, -1), 3.999));
        QVERIFY(!rayShape(s, Pose{}, Vec3(0, 0, 5), Vec3(0, 0, -1), -1.0));
    }

    void sceneNearestBodyAndTies() {
        SceneDesc scene;
        scene.bodies.push_back(staticBody("far", sphereDesc(2.0), Vec3(0, 0, -10)));
        scene.bodies.push_back(staticBody("near", boxDesc(Vec3(1, 1, 1)), Vec3(0, 0, 0)));
        scene.bodies.push_back(staticBody("twin", boxDesc(Vec3(1, 1, 1)), Vec3(0, 0, 0)));
        ShapeDesc ground;
        ground.type = ShapeType::Plane;
        ground.normal = Vec3(0, 1, 0);
        ground.distance = -5.0;
        scene.bodies.push_back(staticBody("ground", ground, Vec3::Zero()));
        auto h = rayCastScene(scene, Vec3(0.3, 0.2, 10), Vec3(0, 0, -1));
        QVERIFY(h);
        QCOMPARE(h->body, 1);  // the twins tie at 9: the lower index
        CHECK_HIT(h, 9.0, Vec3(0.3, 0.2, 1), Vec3(0, 0, 1));
        // Beside the boxes, the far sphere.
        h = rayCastScene(scene, Vec3(0, 1.5, 10), Vec3(0, 0, -1));
        QVERIFY(h);
        QCOMPARE(h->body, 0);
        // Down: the ground under everything; with maxDistance short of it, nothing.
        h = rayCastScene(scene, Vec3(3, 10, 0), Vec3(0, -1, 0));
        QVERIFY(h);
        QCOMPARE(h->body, 3);
        QCOMPARE(h->distance, 15.0);
        QVERIFY(!rayCastScene(scene, Vec3(3, 10, 0), Vec3(0, -1, 0), 14.0));
        // The order of the scene decides ties, not the order of distances found.
        std::swap(scene.bodies[1], scene.bodies[2]);
        h = rayCastScene(scene, Vec3(0.3, 0.2, 10), Vec3(0, 0, -1));
        QVERIFY(h);
        QCOMPARE(h->body, 1);
        QCOMPARE(scene.bodies[1].name, std::string("twin"));
    }

    void sceneMeshesUseTheirTriangles() {
        SceneDesc scene;
        ShapeDesc mesh;
        mesh.type = ShapeType::Mesh;
        mesh.collision = MeshCollision::ConvexHull;  // picked on the triangles all the same
        mesh.meshData = cubeMesh();
        scene.bodies.push_back(
            staticBody("cube", mesh, Vec3(0, 0, 2), about(Vec3::UnitZ(), std::numbers::pi / 4)));
        ShapeDesc unloaded;
        unloaded.type = ShapeType::Mesh;
        scene.bodies.push_back(staticBody("unloaded", unloaded, Vec3(0, 0, 0)));
        // Turned 45° about z: the face with outward normal (1, 1, 0)/sqrt2 at |x| + |y| = sqrt2.
        const auto h = rayCastScene(scene, Vec3(10, 0.5, 2.5), Vec3(-1, 0, 0));
        CHECK_HIT(h, 10.0 - (std::sqrt(2.0) - 0.5), Vec3(std::sqrt(2.0) - 0.5, 0.5, 2.5),
                  Vec3(1, 1, 0).normalized());
        QCOMPARE(h->body, 0);
        // Closed, so the solid query knows the inside.
        CHECK_HIT(rayCastScene(scene, Vec3(0, 0, 2), Vec3(0, 0, 1), kRayUnbounded, RayStart::Solid), 0.0,
                  Vec3(0, 0, 2), Vec3(0, 0, -1));
        QVERIFY(!rayCastScene(scene, Vec3(0, 5, -3), Vec3(0, 0, 1)));
    }

    // The model's poses put the body frame where bodyFramePosition says, not the centre of
    // mass: a cube mesh off its frame origin has its centre of mass at (2, 0, 0).
    void modelUsesTheBodyFrame() {
        for (MeshCollision mode : {MeshCollision::Triangles, MeshCollision::ConvexHull}) {
            SceneDesc scene;
            BodyDesc b;
            b.name = "offset";
            b.shape.type = ShapeType::Mesh;
            b.shape.collision = mode;
            b.shape.file = "offset-cube.obj";  // never read: meshData is given
            b.shape.meshData = cubeMesh(Vec3(2, 0, 0));
            b.density = 1000.0;
            b.position = Vec3(0, 1, 0);
            scene.bodies.push_back(b);
            scene.bodies.push_back(staticBody("ball", sphereDesc(0.5), Vec3(-5, 1, 0)));
            const Model model = compile(scene);
            State state = initialState(model, scene);
            QVERIFY(near(model.bodies[0].centerOfMass, Vec3(2, 0, 0), 1e-9));
            auto h = rayCast(model, state, Vec3(10, 1.2, 0.3), Vec3(-1, 0, 0));
            CHECK_HIT(h, 7.0, Vec3(3, 1.2, 0.3), Vec3(1, 0, 0));
            QCOMPARE(h->body, 0);
            // The same as the scene variant.
            const auto s = rayCastScene(scene, Vec3(10, 1.2, 0.3), Vec3(-1, 0, 0));
            QVERIFY(s && s->body == 0 && near(s->distance, h->distance));
            // Half a turn about y through the centre of mass (2, 1, 0): the frame moves to
            // (4, 1, 0) and the cube, turned about its own centre, is met at x = 3 again.
            state.bodies[0].q = about(Vec3::UnitY(), std::numbers::pi);
            h = rayCast(model, state, Vec3(10, 1.2, 0.3), Vec3(-1, 0, 0));
            CHECK_HIT(h, 7.0, Vec3(3, 1.2, 0.3), Vec3(1, 0, 0));
            // Move it away along z: the ray goes on to the ball.
            state.bodies[0].x += Vec3(0, 0, 5);
            h = rayCast(model, state, Vec3(10, 1.2, 0.0), Vec3(-1, 0, 0));
            QVERIFY(h);
            QCOMPARE(h->body, 1);
            QVERIFY(near(h->distance, 15.0 - std::sqrt(0.25 - 0.04), 1e-12));
        }
    }

    // Through the BVH or triangle by triangle, the same hit, bit for bit; on a fine sphere the
    // hit lies between the inscribed and the circumscribed sphere.
    void meshBvhAgreesWithBruteForce() {
        const TriangleMesh sphere = uvSphere(1.0, 40, 64);
        const Shape withBvh = meshShape(sphere, true);
        const Shape brute = meshShape(sphere, false);
        QVERIFY(withBvh.mesh->closed);
        std::mt19937_64 rng(12);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const Pose pose = at(Vec3(0.5, -0.2, 0.1), about(Vec3(1, 2, 3), 0.9));
        int hits = 0, inside = 0;
        for (int k = 0; k < 2000; ++k) {
            const Vec3 origin = pose.p + 3.0 * Vec3(u(rng), u(rng), u(rng));
            // Half the rays aim near the sphere, half anywhere.
            const Vec3 dir = k % 2 ? Vec3(u(rng), u(rng), u(rng))
                                   : Vec3(pose.p + 0.8 * Vec3(u(rng), u(rng), u(rng)) - origin);
            const RayStart start = k % 3 == 0 ? RayStart::Solid : RayStart::Surface;
            const auto a = rayShape(withBvh, pose, origin, dir, kRayUnbounded, start);
            const auto b = rayShape(brute, pose, origin, dir, kRayUnbounded, start);
            QCOMPARE(a.has_value(), b.has_value());
            if (!a) continue;
            ++hits;
            QCOMPARE(a->distance, b->distance);
            QCOMPARE(a->point, b->point);
            QCOMPARE(a->normal, b->normal);
            const double r = (a->point - pose.p).norm();
            if (a->distance == 0.0 && start == RayStart::Solid) {
                ++inside;
                QVERIFY(r < 1.0 + 1e-12);
            } else {
                QVERIFY2(r <= 1.0 + 1e-12 &&
                             r >= std::cos(std::numbers::pi / 40) * std::cos(std::numbers::pi / 64) - 1e-12,
                         qPrintable(QString::number(r)));
            }
        }
        QVERIFY(hits > 500);
        QVERIFY(inside > 5);
    }
};

QTEST_APPLESS_MAIN(TestRaycast)
#include "tst_raycast.moc"
