// Concave dynamic meshes: a U standing on a plane by its feet, an L pushed into another
// L's notch, two cube meshes crossed ridge over ridge with no vertex inside (Fig. 3), all
// with contacts known in closed form; and random pairs of cube meshes against the
// reference tests for detection and the placement of the points.
#include "collision/bvh.h"
#include "collision/mesh_pairs.h"
#include "collision/reference.h"

#include "test_random.h"

#include <QtTest>

#include <cstdint>
#include <numbers>

using namespace tumble;
using namespace tumble::collision;
namespace ref = tumble::collision::reference;

namespace {

using test::Rng;

// A closed prism: the polygon (counter-clockwise in xy) with its cap triangulation,
// extruded from z0 to z1, as a Mesh shape with its BVH.
Shape prism(const std::vector<std::array<double, 2>>& poly, const std::vector<std::array<int, 3>>& cap,
            double z0, double z1) {
    auto m = std::make_shared<MeshShape>();
    const int n = static_cast<int>(poly.size());
    for (const auto& q : poly) m->vertices.emplace_back(q[0], q[1], z0);
    for (const auto& q : poly) m->vertices.emplace_back(q[0], q[1], z1);
    for (const auto& t : cap) {
        m->triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
        m->triangles.push_back({t[0], t[2], t[1]});
    }
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        m->triangles.push_back({i, j, j + n});
        m->triangles.push_back({i, j + n, i + n});
    }
    m->closed = true;
    m->bvh = std::make_shared<const TriangleBvh>(m->vertices, m->triangles);
    Shape s;
    s.kind = Kind::Mesh;
    s.mesh = m;
    return s;
}

// The L: [0,2]x[0,1] and [0,1]x[0,2]; the notch [1,2]x[1,2] is outside.
Shape lPrism(double z0, double z1) {
    return prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
                 {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}}, z0, z1);
}

// An upside-down U: legs [0,1]x[0,1] and [2,3]x[0,1] under a bridge [0,3]x[1,2].
Shape uPrism() {
    return prism({{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 0}, {3, 0}, {3, 2}, {0, 2}},
                 {{0, 1, 2}, {0, 2, 7}, {7, 2, 3}, {7, 3, 6}, {3, 4, 5}, {3, 5, 6}}, 0.0, 1.0);
}

Shape cubeMesh(const Vec3& h) {
    return prism({{-h.x(), -h.y()}, {h.x(), -h.y()}, {h.x(), h.y()}, {-h.x(), h.y()}}, {{0, 1, 2}, {0, 2, 3}},
                 -h.z(), h.z());
}

double maxPlaneValue(const ref::Polyhedron& body, const Vec3& p) {
    double e = -1e300;
    for (const auto& f : body.faces) e = std::max(e, ref::planeValue(f.normal, -f.offset, p));
    return e;
}

}  // namespace

class TestMeshPairs : public QObject {
    Q_OBJECT
private slots:
    void uStandsOnAPlaneByItsFeet();
    void tiltedUTouchesWithOneFoot();
    void meshAbovePlaneNearContactsWithMargin();
    void lPushedIntoAnotherLsNotch();
    void cubeMeshesCrossedRidgeOverRidge();
    void separatedMeshesGiveNothing();
    void randomCubeMeshesAgreeWithReference();
};

void TestMeshPairs::uStandsOnAPlaneByItsFeet() {
    // The plane y = 0 given as the plane z = 0 turned onto y and moved along itself.
    const Shape plane = Shape::plane(Vec3(0, 0, 1), 0.0);
    const Pose pp{Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix(), Vec3(5, 0, -2)};
    QVERIFY((pp.directionToWorld(Vec3(0, 0, 1)) - Vec3(0, 1, 0)).norm() < 1e-15);
    const double delta = 0.02;
    ManifoldList out;
    collideMeshPlane(uPrism(), Pose{Mat3::Identity(), Vec3(0, -delta, 0)}, plane, pp, 0.0, out);
    QCOMPARE(out.size(), std::size_t(1));
    const Manifold& m = out[0];
    QVERIFY((m.normal - Vec3(0, 1, 0)).norm() < 1e-15);
    QCOMPARE(m.count, 4);
    // The eight foot corners are equally deep; the four kept are the outer corners, which
    // span the whole support (x = 0 and 3, z = 0 and 1).
    int corners = 0;
    for (int i = 0; i < m.count; ++i) {
        const ContactPoint& c = m.points[i];
        QVERIFY(std::abs(c.depth - delta) < 1e-14);
        QVERIFY(std::abs(c.position.y() + delta / 2) < 1e-14);
        const bool outerX = std::abs(c.position.x()) < 1e-14 || std::abs(c.position.x() - 3) < 1e-14;
        const bool endZ = std::abs(c.position.z()) < 1e-14 || std::abs(c.position.z() - 1) < 1e-14;
        corners += outerX && endZ;
    }
    QCOMPARE(corners, 4);
    QVERIFY(m.points[0].feature != m.points[1].feature);
}

void TestMeshPairs::tiltedUTouchesWithOneFoot() {
    // Turned by 0.1 rad about z around the origin and lowered by 0.15: the foot at x in
    // [2,3] stays up, the one at [0,1] goes down; each corner's depth is minus its height.
    const Shape u = uPrism();
    const Pose pm{Eigen::AngleAxisd(0.1, Vec3::UnitZ()).toRotationMatrix(), Vec3(0, -0.15, 0)};
    ManifoldList out;
    collideMeshPlane(u, pm, Shape::plane(Vec3(0, 1, 0), 0.0), Pose{}, 0.0, out);
    QCOMPARE(out.size(), std::size_t(1));
    int below = 0;
    for (const Vec3& v : u.mesh->vertices) below += pm.toWorld(v).y() < 0.0;
    QCOMPARE(below, 4);  // (0,0,z) and (1,0,z)
    QCOMPARE(out[0].count, 4);
    double deepest = 0.0;
    for (int i = 0; i < out[0].count; ++i) {
        const ContactPoint& c = out[0].points[i];
        // position = corner + n depth / 2, so the corner is at height -depth.
        const Vec3 corner = c.position - Vec3(0, c.depth / 2, 0);
        QVERIFY(std::abs(corner.y() + c.depth) < 1e-14);
        QVERIFY(corner.x() < 1.0);
        deepest = std::max(deepest, c.depth);
    }
    QVERIFY(std::abs(deepest - 0.15) < 1e-14);  // the corners at x = 0
    QVERIFY(std::abs(out[0].points[0].depth - 0.15) < 1e-14);
}

void TestMeshPairs::meshAbovePlaneNearContactsWithMargin() {
    const Shape u = uPrism();
    const Shape plane = Shape::plane(Vec3(0, 1, 0), 0.0);
    ManifoldList out;
    collideMeshPlane(u, Pose{Mat3::Identity(), Vec3(0, 0.03, 0)}, plane, Pose{}, 0.0, out);
    QVERIFY(out.empty());
    collideMeshPlane(u, Pose{Mat3::Identity(), Vec3(0, 0.03, 0)}, plane, Pose{}, 0.05, out);
    QCOMPARE(out.size(), std::size_t(1));
    QCOMPARE(out[0].count, 4);
    for (int i = 0; i < 4; ++i) QVERIFY(std::abs(out[0].points[i].depth + 0.03) < 1e-14);
    out.clear();
    collideMeshPlane(u, Pose{Mat3::Identity(), Vec3(0, 1e3, 0)}, plane, Pose{}, 0.05, out);
    QVERIFY(out.empty());
}

void TestMeshPairs::lPushedIntoAnotherLsNotch() {
    // B: the L, z in [0,1]. A: a thinner L (z in [0.25,0.75]) moved so that its corner
    // sits in B's notch and its left face is delta inside B's notch wall x = 1. Contacts:
    // A's two vertices (1-delta, 1.25, z) inside B; B's vertical edge at (1, 2) passes
    // through A (Fig. 3: no vertex of it inside), and so does the diagonal of B's notch
    // wall. All are delta deep, and A leaves along +x.
    const double delta = 0.1;
    const Shape b = lPrism(0.0, 1.0), a = lPrism(0.25, 0.75);
    const Pose pa{Mat3::Identity(), Vec3(1 - delta, 1.25, 0)};
    ManifoldList out;
    collideMeshMesh(a, pa, b, Pose{}, 0.0, out);
    QCOMPARE(out.size(), std::size_t(1));
    const Manifold& m = out[0];
    QVERIFY((m.normal - Vec3(1, 0, 0)).norm() < 1e-12);
    QVERIFY(m.count >= 3);
    bool edgeContact = false;
    for (int i = 0; i < m.count; ++i) {
        const ContactPoint& c = m.points[i];
        QVERIFY(std::abs(c.depth - delta) < 1e-12);
        QVERIFY(std::abs(c.position.x() - (1 - delta / 2)) < 1e-12);
        QVERIFY(c.position.y() > 1.25 - 1e-12 && c.position.y() < 2 + 1e-12);
        QVERIFY(c.position.z() > 0.25 - 1e-12 && c.position.z() < 0.75 + 1e-12);
        edgeContact |= std::abs(c.position.y() - 1.25) > 1e-9;  // not one of A's vertices
    }
    QVERIFY(edgeContact);
    // The same pair swapped: the normal turns, the depths stay.
    ManifoldList swapped;
    collideMeshMesh(b, Pose{}, a, pa, 0.0, swapped);
    QCOMPARE(swapped.size(), std::size_t(1));
    QVERIFY((swapped[0].normal + Vec3(1, 0, 0)).norm() < 1e-12);
    QVERIFY(std::abs(swapped[0].maxDepth() - delta) < 1e-12);
}

void TestMeshPairs::cubeMeshesCrossedRidgeOverRidge() {
    // Two cubes (half 1) as triangle meshes: B turned 45° about x (ridge along x on top at
    // z = sqrt 2), A turned 45° about y (ridge along y below), A's ridge delta below B's.
    // No vertex is inside either; the edge of each passes through the other, and the
    // separating axis of the two ridges is z, depth delta, at (0, 0, sqrt2 - delta/2).
    const double s2 = std::sqrt(2.0), delta = 0.1;
    const Shape cube = cubeMesh(Vec3::Ones());
    const Pose pb{Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()};
    const Pose pa{Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()).toRotationMatrix(),
                  Vec3(0, 0, 2 * s2 - delta)};
    ManifoldList out;
    collideMeshMesh(cube, pa, cube, pb, 0.0, out);
    QCOMPARE(out.size(), std::size_t(1));
    QVERIFY((out[0].normal - Vec3(0, 0, 1)).norm() < 1e-12);
    QVERIFY(out[0].count >= 1);
    for (int i = 0; i < out[0].count; ++i) {
        QVERIFY(std::abs(out[0].points[i].depth - delta) < 1e-12);
        QVERIFY((out[0].points[i].position - Vec3(0, 0, s2 - delta / 2)).norm() < 1e-12);
    }
    // Raised past touching: nothing; with a margin, the near vertices are not within it.
    out.clear();
    collideMeshMesh(cube, Pose{pa.R, pa.p + Vec3(0, 0, 2 * delta)}, cube, pb, 0.0, out);
    QVERIFY(out.empty());
}

void TestMeshPairs::separatedMeshesGiveNothing() {
    const Shape a = lPrism(0, 1), b = lPrism(0, 1);
    ManifoldList out;
    // Side by side with a gap of 0.05 between B's x = 2 face and A's x = 0 face.
    collideMeshMesh(a, Pose{Mat3::Identity(), Vec3(2.05, 0, 0)}, b, Pose{}, 0.0, out);
    QVERIFY(out.empty());
    // With a margin of 0.1, A's vertices on that face are near contacts at -0.05.
    collideMeshMesh(a, Pose{Mat3::Identity(), Vec3(2.05, 0, 0)}, b, Pose{}, 0.1, out);
    QVERIFY(!out.empty());
    for (const auto& m : out) {
        QVERIFY((m.normal - Vec3(1, 0, 0)).norm() < 1e-12);
        for (int i = 0; i < m.count; ++i) QVERIFY(std::abs(m.points[i].depth + 0.05) < 1e-12);
    }
}

void TestMeshPairs::randomCubeMeshesAgreeWithReference() {
    // Random poses of two boxes as triangle meshes. Where the reference tests (on the
    // boxes) find penetration deeper than 1e-6 by the separating axes, the mesh pair finds
    // some overlap; where the boxes are apart by more than 1e-6, it finds nothing. Every
    // point it reports is inside both boxes to within half its depth (a point is midway
    // between the surfaces), and the vertex contacts are exactly as deep as the reference's.
    Rng rng{21};
    int penetrating = 0, separated = 0;
    for (int k = 0; k < 1500; ++k) {
        const Vec3 ha = rng.vec(0.2, 0.8), hb = rng.vec(0.2, 0.8);
        const Shape a = cubeMesh(ha), b = cubeMesh(hb);
        const Pose pa{rng.rotation(), rng.vec(-1.3, 1.3)}, pb{rng.rotation(), Vec3::Zero()};
        const ref::RefContacts rc = ref::referenceContacts(Shape::box(ha), pa, Shape::box(hb), pb);
        ManifoldList out;
        collideMeshMesh(a, pa, b, pb, 0.0, out);
        if (rc.depth < -1e-6) {
            QVERIFY(out.empty());
            ++separated;
            continue;
        }
        if (rc.depth < 1e-6) continue;
        ++penetrating;
        QVERIFY(!out.empty());
        double refVertexDepth = 0.0;
        for (const auto& p : rc.points)
            if (p.kind == ref::RefPoint::Kind::VertexOfAInB || p.kind == ref::RefPoint::Kind::VertexOfBInA)
                refVertexDepth = std::max(refVertexDepth, p.depth);
        const ref::Polyhedron A = ref::worldPolyhedron(Shape::box(ha), pa),
                              B = ref::worldPolyhedron(Shape::box(hb), pb);
        double deepest = 0.0;
        for (const auto& m : out) {
            QVERIFY(std::abs(m.normal.norm() - 1.0) < 1e-12);
            for (int i = 0; i < m.count; ++i) {
                const ContactPoint& c = m.points[i];
                QVERIFY(c.depth >= 0.0);
                QVERIFY(maxPlaneValue(A, c.position) < c.depth / 2 + 1e-9);
                QVERIFY(maxPlaneValue(B, c.position) < c.depth / 2 + 1e-9);
                deepest = std::max(deepest, c.depth);
            }
        }
        // The deepest vertex is always kept (each manifold keeps its deepest point).
        QVERIFY(deepest >= refVertexDepth - 1e-12);
    }
    QVERIFY(penetrating > 300);
    QVERIFY(separated > 100);
}

QTEST_APPLESS_MAIN(TestMeshPairs)
#include "tst_mesh_pairs.moc"
