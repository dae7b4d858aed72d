// The general convex narrowphase (collideConvex) and convex against a triangle mesh
// (collideConvexMesh): manifolds checked against the corners, rims and depths that the
// geometry fixes in closed form.
#include <tumble/convex_hull.h>
#include "collision/bvh.h"
#include "collision/convex.h"
#include "collision/gjk.h"
#include "collision/narrowphase.h"
#include "test_random.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <set>

using namespace tumble;
using namespace tumble::collision;

namespace {

Pose pose(const Vec3& p, const Quat& q = Quat::Identity()) {
    Pose r;
    r.R = q.normalized().toRotationMatrix();
    r.p = p;
    return r;
}

Quat about(const Vec3& axis, double angle) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

Shape hullOf(const std::vector<Vec3>& points) {
    Shape s;
    s.kind = Kind::Hull;
    s.hull = std::make_shared<ConvexHull>(mesh::convexHull(points));
    return s;
}

// A triangular prism, its top face the plane y = top, wide enough to hold a unit box.
Shape prism(double top) {
    return hullOf({Vec3(-4, top, -3), Vec3(4, top, -3), Vec3(0, top, 5), Vec3(-4, top - 2, -3),
                   Vec3(4, top - 2, -3), Vec3(0, top - 2, 5)});
}

Shape meshShape(std::vector<Vec3> v, std::vector<std::array<int, 3>> t, bool withBvh = true) {
    auto m = std::make_shared<MeshShape>();
    m->vertices = std::move(v);
    m->triangles = std::move(t);
    if (withBvh) m->bvh = std::make_shared<TriangleBvh>(m->vertices, m->triangles);
    Shape s;
    s.kind = Kind::Mesh;
    s.mesh = m;
    return s;
}

// A flat strip of 2n triangles in y = 0, x in [0, n], z in [-2, 2], faces up.
Shape groundStrip(int n, bool withBvh = true) {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> t;
    for (int i = 0; i <= n; ++i) {
        v.emplace_back(i, 0, -2);
        v.emplace_back(i, 0, 2);
    }
    for (int i = 0; i < n; ++i) {
        const int a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
        t.push_back({a, b, d});  // counter-clockwise seen from +y
        t.push_back({a, d, c});
    }
    return meshShape(v, t, withBvh);
}

// The cube [0,1]³ as a closed mesh, outward normals.
Shape unitCubeMesh() {
    const std::vector<Vec3> v{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                              Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
    const std::vector<std::array<int, 3>> t{{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                            {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
                                            {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    return meshShape(v, t);
}

// Every expected point is matched by a contact point within tol, and the depths agree.
bool hasPoints(const Manifold& m, const std::vector<Vec3>& expected, double depth, double tol) {
    if (m.count != static_cast<int>(expected.size())) return false;
    for (const Vec3& e : expected) {
        bool found = false;
        for (int i = 0; i < m.count; ++i)
            found = found ||
                    ((m.points[i].position - e).norm() < tol && std::abs(m.points[i].depth - depth) < tol);
        if (!found) return false;
    }
    return true;
}

std::set<std::uint32_t> ids(const Manifold& m) {
    std::set<std::uint32_t> s;
    for (int i = 0; i < m.count; ++i) s.insert(m.points[i].feature);
    return s;
}

}  // namespace

class TestConvex : public QObject {
    Q_OBJECT

private slots:
    // collision::thickness, the narrowest width of each kind of solid (end-of-step impacts
    // look for a moment only when bodies moved more than theirs together): closed forms,
    // and a hull's from its faces (a box's hull, a tetrahedron's height over its base).
    void thicknessOfEachShape() {
        QCOMPARE(thickness(Shape::sphere(0.3)), 0.6);
        QCOMPARE(thickness(Shape::box(Vec3(0.5, 0.2, 0.7))), 0.4);
        QCOMPARE(thickness(Shape::capsule(0.1, 2.0)), 0.2);
        QCOMPARE(thickness(Shape::cylinder(0.4, 0.1)), 0.2);
        QVERIFY(std::isinf(thickness(Shape::plane(Vec3(0, 1, 0), 0.0))));
        Shape box;
        box.kind = Kind::Hull;
        box.hull = std::make_shared<ConvexHull>(mesh::boxHull(Vec3(0.5, 0.2, 0.7)));
        QVERIFY(std::abs(thickness(box) - 0.4) < 1e-12);
        // The regular tetrahedron of edge 2√2 (alternate corners of the cube ±1) is 2 wide
        // between opposite edges, narrower than its height over a face (4/√3).
        Shape tetra;
        tetra.kind = Kind::Hull;
        tetra.hull = std::make_shared<ConvexHull>(
            mesh::convexHull({Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)}));
        QVERIFY2(std::abs(thickness(tetra) - 2.0) < 1e-12, qPrintable(QString::number(thickness(tetra), 'g', 17)));
        // The octahedron with semi-axes 1, 2, 3 is narrowest across opposite faces, whose
        // planes x + y/2 + z/3 = ±1 are 2 / |(1, 1/2, 1/3)| apart; no direction is narrower
        // (20 000 directions tried), and the nearest tried are within 3 %.
        Shape octa;
        octa.kind = Kind::Hull;
        octa.hull = std::make_shared<ConvexHull>(mesh::convexHull(
            {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 2, 0), Vec3(0, -2, 0), Vec3(0, 0, 3), Vec3(0, 0, -3)}));
        const double width = 2.0 / Vec3(1, 0.5, 1.0 / 3.0).norm();
        QVERIFY2(std::abs(thickness(octa) - width) < 1e-12, qPrintable(QString::number(thickness(octa), 'g', 17)));
        test::Rng rng{5};
        double narrowest = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 20000; ++k) {
            const Vec3 n = rng.direction();
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (const Vec3& v : octa.hull->vertices) {
                lo = std::min(lo, n.dot(v));
                hi = std::max(hi, n.dot(v));
            }
            narrowest = std::min(narrowest, hi - lo);
        }
        QVERIFY(narrowest >= width - 1e-12);
        QVERIFY2(narrowest <= 1.03 * width, qPrintable(QString::number(narrowest / width)));
        Shape mesh;
        mesh.kind = Kind::Mesh;
        QCOMPARE(thickness(mesh), 0.0);
    }

    void boxOnBoxFaceToFace() {
        const Shape top = Shape::box(Vec3(0.5, 0.5, 0.5)), floor = Shape::box(Vec3(2, 1, 2));
        const double yaw = 0.4;
        const Pose pa = pose(Vec3(0.1, 1.49, 0.2), about(Vec3::UnitY(), yaw));
        ManifoldList out;
        collideConvex(top, pa, floor, pose(Vec3::Zero()), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        const Manifold& m = out[0];
        QVERIFY((m.normal - Vec3(0, 1, 0)).norm() < 1e-12);
        std::vector<Vec3> corners;
        for (double sx : {-0.5, 0.5})
            for (double sz : {-0.5, 0.5})
                corners.push_back(pa.toWorld(Vec3(sx, -0.5, sz)) + Vec3(0, 0.005, 0));
        QVERIFY(hasPoints(m, corners, 0.01, 1e-12));
        QCOMPARE(ids(m).size(), size_t(4));
        // Nudged sideways the same features touch: the same ids.
        ManifoldList moved;
        collideConvex(top, pose(pa.p + Vec3(1e-3, 0, -1e-3), about(Vec3::UnitY(), yaw)), floor,
                      pose(Vec3::Zero()), 0.0, moved);
        QCOMPARE(moved.size(), size_t(1));
        QVERIFY(ids(moved[0]) == ids(m));
    }

    void boxTiltedOnEdge() {
        // Turned 30 degrees about z: one bottom edge 0.01 deep, the rest well above.
        const double a = std::numbers::pi / 6;
        const Pose pa = pose(Vec3::Zero(), about(Vec3::UnitZ(), a));
        const Vec3 lowest = pa.toWorld(Vec3(-0.5, -0.5, 0));  // lowest corner (x<0 side goes down)
        Pose placed = pa;
        placed.p.y() = 1.0 - 0.01 - lowest.y();
        ManifoldList out;
        collideConvex(Shape::box(Vec3(0.5, 0.5, 0.5)), placed, Shape::box(Vec3(2, 1, 2)), pose(Vec3::Zero()),
                      0.001, out);
        QCOMPARE(out.size(), size_t(1));
        std::vector<Vec3> edge{placed.toWorld(Vec3(-0.5, -0.5, -0.5)) + Vec3(0, 0.005, 0),
                               placed.toWorld(Vec3(-0.5, -0.5, 0.5)) + Vec3(0, 0.005, 0)};
        QVERIFY(hasPoints(out[0], edge, 0.01, 1e-12));
    }

    void boxOnHullFace() {
        const Pose pa = pose(Vec3(0.3, 1.0 + 0.5 - 0.02, -0.4), about(Vec3::UnitY(), 1.1));
        ManifoldList out;
        collideConvex(Shape::box(Vec3(0.5, 0.5, 0.5)), pa, prism(1.0), pose(Vec3::Zero()), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY((out[0].normal - Vec3(0, 1, 0)).norm() < 1e-12);
        std::vector<Vec3> corners;
        for (double sx : {-0.5, 0.5})
            for (double sz : {-0.5, 0.5})
                corners.push_back(pa.toWorld(Vec3(sx, -0.5, sz)) + Vec3(0, 0.01, 0));
        QVERIFY(hasPoints(out[0], corners, 0.02, 1e-12));
        // The hull as A, the box as B: same contact, normal reversed.
        out.clear();
        collideConvex(prism(1.0), pose(Vec3::Zero()), Shape::box(Vec3(0.5, 0.5, 0.5)), pa, 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY((out[0].normal - Vec3(0, -1, 0)).norm() < 1e-12);
        QVERIFY(hasPoints(out[0], corners, 0.02, 1e-12));
    }

    void hullOnHull() {
        // A tetrahedron standing on a face (y = 0 in its frame) on the prism, 0.05 deep,
        // placed far from the origin: three points at its base corners.
        const Shape tet = hullOf({Vec3(-0.5, 0, -0.4), Vec3(0.5, 0, -0.4), Vec3(0, 0, 0.6), Vec3(0, 0.8, 0)});
        const Vec3 far(1000, -2000, 500);
        const Pose pa = pose(far + Vec3(0.5, 1.0 - 0.05, 0.5), about(Vec3::UnitY(), 0.3));
        ManifoldList out;
        collideConvex(tet, pa, prism(1.0), pose(far), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY((out[0].normal - Vec3(0, 1, 0)).norm() < 1e-12);
        std::vector<Vec3> corners;
        for (const Vec3& c : {Vec3(-0.5, 0, -0.4), Vec3(0.5, 0, -0.4), Vec3(0, 0, 0.6)})
            corners.push_back(pa.toWorld(c) + Vec3(0, 0.025, 0));
        QVERIFY(hasPoints(out[0], corners, 0.05, 1e-9));
    }

    void cylinderOnItsCap() {
        // Standing on a box: four points on the rim, all at the depth.
        const Pose pc = pose(Vec3(0.2, 1.0 + 1.5 - 0.01, -0.1), about(Vec3::UnitY(), 0.25));
        ManifoldList out;
        collideConvex(Shape::cylinder(0.6, 1.5), pc, Shape::box(Vec3(2, 1, 2)), pose(Vec3::Zero()), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        const Manifold& m = out[0];
        QCOMPARE(m.count, 4);
        QVERIFY((m.normal - Vec3(0, 1, 0)).norm() < 1e-9);
        double area = 0.0;
        for (int i = 0; i < 4; ++i) {
            const Vec3 p = m.points[i].position;
            QVERIFY(std::abs(std::hypot(p.x() - pc.p.x(), p.z() - pc.p.z()) - 0.6) < 1e-9);
            QVERIFY(std::abs(p.y() - 0.995) < 1e-9);
            QVERIFY(std::abs(m.points[i].depth - 0.01) < 1e-9);
        }
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                area = std::max(area, (m.points[i].position - m.points[j].position).norm());
        QVERIFY(area > 1.1);  // spread over the rim, not bunched
        // A small box on the cylinder's cap: its four corners.
        const Pose pb = pose(pc.p + Vec3(0.1, 1.5 + 0.2 - 0.03, 0), about(Vec3::UnitY(), 0.7));
        out.clear();
        collideConvex(Shape::box(Vec3(0.2, 0.2, 0.2)), pb, Shape::cylinder(0.6, 1.5), pc, 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        std::vector<Vec3> corners;
        for (double sx : {-0.2, 0.2})
            for (double sz : {-0.2, 0.2})
                corners.push_back(pb.toWorld(Vec3(sx, -0.2, sz)) + Vec3(0, 0.015, 0));
        QVERIFY(hasPoints(out[0], corners, 0.03, 1e-9));
    }

    void cylinderOnItsRim() {
        // Tipped 20 degrees: only the lowest rim point is within the margin.
        const Quat tilt = about(Vec3::UnitZ(), 20 * std::numbers::pi / 180);
        Pose pc = pose(Vec3::Zero(), tilt);
        const Vec3 lowest = pc.toWorld(Vec3(-0.6, -1.5, 0));
        QVERIFY(lowest.y() < pc.toWorld(Vec3(0.6, -1.5, 0)).y());
        pc.p = Vec3(0, 1.0 - 0.01 - lowest.y(), 0);
        ManifoldList out;
        collideConvex(Shape::cylinder(0.6, 1.5), pc, Shape::box(Vec3(2, 1, 2)), pose(Vec3::Zero()), 0.001,
                      out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY(hasPoints(out[0], {pc.toWorld(Vec3(-0.6, -1.5, 0)) + Vec3(0, 0.005, 0)}, 0.01, 1e-9));
    }

    void lyingRoundShapes() {
        // A cylinder on its side and a capsule, each lying along x on a box: two points, at
        // the ends of the line of contact.
        const Quat alongX = about(Vec3::UnitZ(), std::numbers::pi / 2);
        ManifoldList out;
        collideConvex(Shape::cylinder(0.3, 0.8), pose(Vec3(0, 1.0 + 0.3 - 0.02, 0.1), alongX),
                      Shape::box(Vec3(2, 1, 2)), pose(Vec3::Zero()), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY(hasPoints(out[0], {Vec3(-0.8, 0.99, 0.1), Vec3(0.8, 0.99, 0.1)}, 0.02, 1e-9));
        out.clear();
        collideConvex(Shape::capsule(0.3, 0.8), pose(Vec3(0, 1.0 + 0.3 - 0.02, 0.1), alongX), prism(1.0),
                      pose(Vec3::Zero()), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY(hasPoints(out[0], {Vec3(-0.8, 0.99, 0.1), Vec3(0.8, 0.99, 0.1)}, 0.02, 1e-9));
        // Two cylinders lying side by side, parallel: the overlap of their lines. EPA on two
        // curved cores stops at a support gain of 1e-10 of their size, so the normal is
        // good to about the square root of that.
        out.clear();
        collideConvex(Shape::cylinder(0.3, 0.8), pose(Vec3(0.5, 0.6 - 0.01, 0), alongX),
                      Shape::cylinder(0.3, 0.8), pose(Vec3(0, 0, 0), alongX), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY((out[0].normal - Vec3(0, 1, 0)).norm() < 1e-4);
        QVERIFY(hasPoints(out[0], {Vec3(-0.3, 0.295, 0), Vec3(0.8, 0.295, 0)}, 0.01, 1e-4));
    }

    void singlePointsAndMargin() {
        // A sphere on a hull face: one point; the depth and position in closed form.
        ManifoldList out;
        collideConvex(Shape::sphere(0.5), pose(Vec3(0.2, 1.45, 0.1)), prism(1.0), pose(Vec3::Zero()), 0.0,
                      out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY(hasPoints(out[0], {Vec3(0.2, 0.975, 0.1)}, 0.05, 1e-12));
        // Apart by 0.02: nothing with a margin of 0.01, a near contact with 0.05.
        out.clear();
        const Pose above = pose(Vec3(0.1, 1.0 + 0.5 + 0.02, 0.2));
        collideConvex(Shape::box(Vec3(0.5, 0.5, 0.5)), above, prism(1.0), pose(Vec3::Zero()), 0.01, out);
        QVERIFY(out.empty());
        collideConvex(Shape::box(Vec3(0.5, 0.5, 0.5)), above, prism(1.0), pose(Vec3::Zero()), 0.05, out);
        QCOMPARE(out.size(), size_t(1));
        QCOMPARE(out[0].count, 4);
        for (int i = 0; i < 4; ++i) QVERIFY(std::abs(out[0].points[i].depth + 0.02) < 1e-12);
    }

    void boxOnMeshAcrossTheDiagonal() {
        // The box covers the shared diagonal of two triangles: one manifold, its 4 corners.
        for (bool withBvh : {true, false}) {
            const Pose pa = pose(Vec3(0.5, 0.5 - 0.01, 0.3), about(Vec3::UnitY(), 0.2));
            ManifoldList out;
            collideConvexMesh(Shape::box(Vec3(0.3, 0.5, 0.3)), pa, groundStrip(1, withBvh),
                              pose(Vec3::Zero()), 0.0, out);
            QCOMPARE(out.size(), size_t(1));
            QVERIFY((out[0].normal - Vec3(0, 1, 0)).norm() < 1e-12);
            std::vector<Vec3> corners;
            for (double sx : {-0.3, 0.3})
                for (double sz : {-0.3, 0.3})
                    corners.push_back(pa.toWorld(Vec3(sx, -0.5, sz)) + Vec3(0, 0.005, 0));
            QVERIFY(hasPoints(out[0], corners, 0.01, 1e-12));
        }
    }

    void noGhostAtInternalEdge() {
        // A box sunk 0.05 into a flat strip, reaching 0.002 past the edge x = 2 onto the next
        // triangle pair. Alone, that sliver's shortest way out is sideways across the edge...
        const Shape box = Shape::box(Vec3(0.4, 0.4, 0.4));
        const Pose pa = pose(Vec3(2.0 - 0.4 + 0.002, 0.4 - 0.05, 0.3));
        const ConvexProxy sliver = triangleProxy(Vec3(2, 0, -2), Vec3(2, 0, 2), Vec3(3, 0, 2));
        const Penetration raw = penetration(proxyOf(box, pa), sliver, 0.0);
        QVERIFY(raw.hit && raw.normal.y() < 0.5);
        // ... but on the mesh every contact pushes up.
        ManifoldList out;
        collideConvexMesh(box, pa, groundStrip(4), pose(Vec3::Zero()), 0.0, out);
        QVERIFY(!out.empty());
        for (const Manifold& m : out) {
            QVERIFY((m.normal - Vec3(0, 1, 0)).norm() < 1e-12);
            for (int i = 0; i < m.count; ++i) QVERIFY(std::abs(m.points[i].depth - 0.05) < 1e-12);
        }
        QCOMPARE(out.size(), size_t(1));
        QCOMPARE(out[0].count, 4);
    }

    void outerEdgeKeepsItsNormal() {
        // A unit cube as a closed mesh; a sphere against its top edge x = 1 from outside and
        // above: the normal points from the edge to the centre, not up.
        const Shape cube = unitCubeMesh();
        const Vec3 dir = Vec3(1, 1, 0).normalized();
        const Vec3 centre = Vec3(1, 1, 0.5) + (0.3 - 0.01) * dir;
        ManifoldList out;
        collideConvexMesh(Shape::sphere(0.3), pose(centre), cube, pose(Vec3(0, 0, 0)), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY((out[0].normal - dir).norm() < 1e-9);
        QVERIFY(std::abs(out[0].maxDepth() - 0.01) < 1e-9);
        // A sphere resting on the top face: up, one point.
        out.clear();
        collideConvexMesh(Shape::sphere(0.3), pose(Vec3(0.4, 1.29, 0.6)), cube, pose(Vec3::Zero()), 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY(hasPoints(out[0], {Vec3(0.4, 0.995, 0.6)}, 0.01, 1e-12));
        QVERIFY((out[0].normal - Vec3(0, 1, 0)).norm() < 1e-12);
    }

    void boxTippingOverARimIsNotLifted() {
        // A plank (half 0.6 x 0.1 x 0.2) over the top edge x = 1, y = 1 of a table (the unit
        // cube as a mesh), turned 0.3 rad about z so that its right end hangs down past the
        // rim; the rim is 0.01 (vertically) into its bottom face, and its lowest corners are
        // 0.024 below the top's plane, 0.044 out in the air. The centre is over the table,
        // and the plank crosses the top's plane just inside the rim (x = 0.997): the contact
        // is the rim's, along the plank's bottom normal and 0.0096 deep, never the top's
        // normal with the corners' 0.024 (the face path needs the lowest point over the
        // face too).
        const double th = 0.3, hx = 0.6, hy = 0.1, cx = 0.5, d = 0.01;
        const double s = (1.0 - cx + hy * std::sin(th)) / std::cos(th);  // the bottom's point at the rim
        const double cy = 1.0 - d + hy * std::cos(th) + s * std::sin(th);
        const Pose pa = pose(Vec3(cx, cy, 0.5), about(Vec3::UnitZ(), -th));
        const Vec3 bottomNormal(std::sin(th), std::cos(th), 0.0);  // out of the table, into the plank
        ManifoldList out;
        collideConvexMesh(Shape::box(Vec3(hx, hy, 0.2)), pa, unitCubeMesh(), pose(Vec3::Zero()), 0.0, out);
        QVERIFY(!out.empty());
        for (const Manifold& m : out) {
            QVERIFY2(m.normal.dot(bottomNormal) > 1.0 - 1e-9, "the rim pushes along the plank's bottom normal");
            for (int i = 0; i < m.count; ++i)
                QVERIFY(m.points[i].depth > 0.0 && m.points[i].depth <= d * std::cos(th) + 1e-9);
        }
    }

    void posedMesh() {
        // The ground strip turned and moved: results move with it.
        const Pose pm = pose(Vec3(5, -2, 7), about(Vec3(1, 2, 3), 0.8));
        const Pose local = pose(Vec3(0.5, 0.5 - 0.01, 0.3), about(Vec3::UnitY(), 0.2));
        Pose pa;
        pa.R = pm.R * local.R;
        pa.p = pm.toWorld(local.p);
        ManifoldList out;
        collideConvexMesh(Shape::box(Vec3(0.3, 0.5, 0.3)), pa, groundStrip(1), pm, 0.0, out);
        QCOMPARE(out.size(), size_t(1));
        QVERIFY((out[0].normal - pm.R.col(1)).norm() < 1e-12);
        std::vector<Vec3> corners;
        for (double sx : {-0.3, 0.3})
            for (double sz : {-0.3, 0.3})
                corners.push_back(pa.toWorld(Vec3(sx, -0.5, sz)) + 0.005 * pm.R.col(1));
        QVERIFY(hasPoints(out[0], corners, 0.01, 1e-12));
    }

    void randomConvexNearATriangle() {
        // The shortcuts of collideConvexMesh (the triangle's plane, the planes through its
        // edges square to it, the face path) must find contact exactly where GJK does: a
        // box, capsule, cylinder or hull at random poses about one triangle, most of them
        // within reach of it, gives a manifold exactly when the penetration query hits.
        std::mt19937 rng(77);
        std::uniform_real_distribution<double> size(0.1, 0.6), u(-1.0, 1.0);
        std::normal_distribution<double> g;
        const Shape tri = meshShape({Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0.5, 0, 1.5)}, {{0, 2, 1}});
        const ConvexProxy T = triangleProxy(Vec3(0, 0, 0), Vec3(0.5, 0, 1.5), Vec3(2, 0, 0));
        const double margin = 0.05;
        int hits = 0, misses = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            Shape sa;
            switch (trial % 4) {
                case 0: sa = Shape::box(Vec3(size(rng), size(rng), size(rng))); break;
                case 1: sa = Shape::capsule(size(rng), size(rng)); break;
                case 2: sa = Shape::cylinder(size(rng), size(rng)); break;
                default: {
                    std::vector<Vec3> pts;
                    for (int i = 0; i < 10; ++i) pts.emplace_back(size(rng) * u(rng), size(rng) * u(rng), size(rng) * u(rng));
                    sa = hullOf(pts);
                }
            }
            const Pose pa = pose(Vec3(1.0 + 1.6 * u(rng), 0.5 * u(rng), 0.75 + 1.4 * u(rng)),
                                 Quat(g(rng), g(rng), g(rng), g(rng)));
            ManifoldList out;
            collideConvexMesh(sa, pa, tri, pose(Vec3::Zero()), margin, out);
            const bool hit = penetration(proxyOf(sa, pa), T, margin).hit;
            QVERIFY2(out.empty() != hit, qPrintable(QString("trial %1: gjk %2").arg(trial).arg(hit)));
            hit ? ++hits : ++misses;
        }
        QVERIFY(hits > 500 && misses > 500);
    }

    void apartAlongProvesWhatGjkFinds() {
        // Hull and cylinder pairs at random poses: whenever a direction shows them apart by
        // more than the margin, the narrowphase finds nothing there (the detect stage skips
        // GJK on that proof); and a pair the narrowphase finds apart gives a direction that
        // proves it, up to the hair apartAlong leaves for rounding.
        test::Rng rng{2026};
        const double margin = 0.02;
        int proofs = 0, apartPairs = 0, told = 0;
        for (int trial = 0; trial < 2000; ++trial) {
            auto shape = [&](int kind) {
                if (kind == 0) return Shape::cylinder(rng.uniform(0.1, 0.5), rng.uniform(0.1, 0.5));
                std::vector<Vec3> pts;
                for (int i = 0; i < 8; ++i) pts.push_back(rng.vec(-0.5, 0.5));
                return hullOf(pts);
            };
            const Shape a = shape(trial % 3 == 0 ? 0 : 1), b = shape(trial % 5 == 0 ? 0 : 1);
            Pose pa, pb;
            pa.R = rng.rotation();
            pa.p = rng.vec(-0.8, 0.8);
            pb.R = rng.rotation();
            pb.p = rng.vec(-0.8, 0.8);
            const double distance = gjkDistance(proxyOf(a, pa), proxyOf(b, pb)).distance;
            for (int d = 0; d < 4; ++d) {
                const Vec3 n = d == 0 ? Vec3((pa.p - pb.p).normalized()) : rng.direction();
                if (!apartAlong(a, pa, b, pb, n, margin)) continue;
                ++proofs;
                ManifoldList out;
                collideConvex(a, pa, b, pb, margin, out);
                QVERIFY2(out.empty() && distance > margin,
                         qPrintable(QString("trial %1: apart along n, yet %2 manifolds, distance %3")
                                        .arg(trial).arg(out.size()).arg(distance)));
            }
            ManifoldList out;
            Vec3 apart = Vec3::Zero();
            collide(a, pa, b, pb, margin, out, apart);
            QCOMPARE(out.empty(), distance > margin);
            if (!out.empty() || distance < margin + 1e-6) continue;
            ++apartPairs;
            QVERIFY(std::abs(apart.norm() - 1.0) < 1e-12);
            if (apartAlong(a, pa, b, pb, apart, margin)) ++told;
        }
        qInfo("%d proofs; %d of %d pairs apart proved by their own direction", proofs, told, apartPairs);
        QVERIFY(proofs > 500 && apartPairs > 200);
        QCOMPARE(told, apartPairs);
    }

    void randomPairsInvariants() {
        // Every kind against every kind at random poses (a third of them with parallel
        // frames, where faces meet faces): a manifold exactly when the penetration query
        // hits, 1 to 4 finite points within the margin, and the deepest of them as deep as
        // the penetration (more only where a face normal within half a degree was used).
        std::mt19937 rng(4242);
        std::uniform_real_distribution<double> size(0.2, 1.2), u(-1.0, 1.0);
        std::normal_distribution<double> g;
        auto randomShape = [&](int kind) {
            switch (kind) {
                case 0: return Shape::sphere(size(rng));
                case 1: return Shape::box(Vec3(size(rng), size(rng), size(rng)));
                case 2: return Shape::capsule(size(rng), size(rng));
                case 3: return Shape::cylinder(size(rng), size(rng));
                default: {
                    std::vector<Vec3> pts;
                    for (int i = 0; i < 12; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
                    return hullOf(pts);
                }
            }
        };
        const double margin = 0.05;
        int hits = 0, multi = 0;
        for (int trial = 0; trial < 1500; ++trial) {
            const Shape sa = randomShape(trial % 5), sb = randomShape((trial / 5) % 5);
            Pose pa = pose(Vec3(u(rng), u(rng), u(rng)) * 1.5, Quat(g(rng), g(rng), g(rng), g(rng)));
            const Pose pb = pose(Vec3(u(rng), u(rng), u(rng)) * 1.5, Quat(g(rng), g(rng), g(rng), g(rng)));
            if (trial % 3 == 0) pa.R = pb.R;
            ManifoldList out;
            collideConvex(sa, pa, sb, pb, margin, out);
            const Penetration p = penetration(proxyOf(sa, pa), proxyOf(sb, pb), margin);
            QCOMPARE(out.size(), size_t(p.hit ? 1 : 0));
            if (!p.hit) continue;
            ++hits;
            const Manifold& m = out[0];
            multi += m.count > 1;
            QVERIFY(std::abs(m.normal.norm() - 1.0) < 1e-12 && m.normal.dot(p.normal) > 0.9999);
            QVERIFY(m.count >= 1 && m.count <= 4);
            for (int i = 0; i < m.count; ++i)
                QVERIFY(m.points[i].position.allFinite() && m.points[i].depth > -margin);
            QVERIFY2(m.maxDepth() >= p.depth - 1e-6 && m.maxDepth() <= p.depth + 0.02,
                     qPrintable(QString("trial %1: %2 vs %3").arg(trial).arg(m.maxDepth()).arg(p.depth)));
        }
        QVERIFY(hits > 400 && multi > 100);
    }
};

QTEST_APPLESS_MAIN(TestConvex)
#include "tst_convex.moc"
