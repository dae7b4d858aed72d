// Mesh processing: welding and cleaning, convex hulls (qhull) with merged faces, and mesh
// bodies compiled from meshes built in code. Answers are exact (counts, a cube's and a
// tetrahedron's mass properties) or geometric invariants (containment, Euler's formula).
#include "scene_builders.h"

#include <tumble/convex_hull.h>
#include "mesh/mesh_body.h"
#include "mesh/mesh_clean.h"

#include <tumble/errors.h>
#include <tumble/mass.h>
#include <tumble/model.h>

#include <QtTest>

#include <map>
#include <memory>
#include <random>
#include <set>

using namespace tumble;
using collision::ConvexHull;

namespace {

// The box [lo, hi] as 12 triangles facing outwards. `split`: every triangle has its own
// three vertices, as STL files store them.
TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi, bool split = false) {
    TriangleMesh m;
    for (int k = 0; k < 8; ++k)
        m.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
    }
    if (!split) return m;
    TriangleMesh s;
    for (const auto& t : m.triangles) {
        const int base = static_cast<int>(s.vertices.size());
        for (int v : t) s.vertices.push_back(m.vertices[v]);
        s.triangles.push_back({base, base + 1, base + 2});
    }
    return s;
}

// Checks the conventions of collision::ConvexHull; returns an empty string when all hold.
QString hullProblem(const ConvexHull& h, double eps) {
    const int n = static_cast<int>(h.vertices.size());
    std::map<std::pair<int, int>, int> directed;
    for (size_t f = 0; f < h.faces.size(); ++f) {
        const auto& face = h.faces[f];
        if (face.first < 0 || face.count < 0 || face.first + face.count > static_cast<int>(h.faceVertices.size()))
            return QString("face %1: its vertices are outside faceVertices").arg(f);
        const std::span<const int> vs = h.verticesOf(face);
        if (vs.size() < 3) return QString("face %1 has fewer than 3 vertices").arg(f);
        if (std::abs(face.normal.norm() - 1.0) > 1e-12) return QString("face %1: normal not unit").arg(f);
        Vec3 newell = Vec3::Zero();
        for (size_t k = 0; k < vs.size(); ++k) {
            const int a = vs[k], b = vs[(k + 1) % vs.size()];
            if (a < 0 || a >= n) return QString("face %1: bad index").arg(f);
            if (std::abs(face.normal.dot(h.vertices[a]) - face.offset) > eps)
                return QString("face %1: vertex off its plane").arg(f);
            newell += h.vertices[a].cross(h.vertices[b]);
            ++directed[{a, b}];
        }
        if (!(newell.dot(face.normal) > 0.0))
            return QString("face %1: not counter-clockwise seen from outside").arg(f);
        if (!(face.normal.dot(h.interiorPoint) < face.offset - eps))
            return QString("face %1: interior point not inside").arg(f);
        for (const Vec3& v : h.vertices) {
            if (face.normal.dot(v) > face.offset + eps)
                return QString("face %1: a vertex is outside it").arg(f);
        }
    }
    // A closed polytope: every directed edge once, and its reverse once.
    for (const auto& [e, count] : directed) {
        if (count != 1 || !directed.contains({e.second, e.first})) return "the faces do not close up";
    }
    if (h.edges.size() * 2 != directed.size()) return "edges are not the faces' undirected edges";
    for (const auto& e : h.edges) {
        if (!directed.contains({e[0], e[1]})) return "an edge belongs to no face";
    }
    const long euler = static_cast<long>(h.vertices.size()) - static_cast<long>(h.edges.size()) +
                       static_cast<long>(h.faces.size());
    if (euler != 2) return QString("V - E + F = %1").arg(euler);
    return {};
}

BodyDesc meshBody(const TriangleMesh& m, MeshCollision collision = MeshCollision::ConvexHull) {
    BodyDesc b;
    b.name = "rock";
    b.shape.type = ShapeType::Mesh;
    b.shape.file = "rock.obj";
    b.shape.collision = collision;
    b.shape.meshData = std::make_shared<const TriangleMesh>(m);
    return b;
}

QString sceneErrorPath(const SceneDesc& scene) {
    try {
        compile(scene);
    } catch (const SceneError& e) {
        return QString::fromStdString(e.path() + " | " + e.message());
    }
    return "compiled";
}

}  // namespace

class TestMeshProcessing : public QObject {
    Q_OBJECT
private slots:
    void boxHullIsABox() {
        const ConvexHull h = mesh::boxHull(Vec3(0.5, 1, 1.5));
        QCOMPARE(h.vertices.size(), size_t(8));
        QCOMPARE(h.faces.size(), size_t(6));
        QCOMPARE(h.edges.size(), size_t(12));
        for (const auto& f : h.faces) {
            QCOMPARE(h.verticesOf(f).size(), size_t(4));
            QCOMPARE(f.offset, f.normal.cwiseAbs().dot(Vec3(0.5, 1, 1.5)));
        }
        QVERIFY(h.interiorPoint == Vec3::Zero());
        const QString problem = hullProblem(h, 1e-15);
        QVERIFY2(problem.isEmpty(), qPrintable(problem));
    }

    // Coplanar facets are merged: 8 corners and points inside give 6 quads.
    void cubeWithInteriorPoints() {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(-0.999, 0.999);
        std::vector<Vec3> points;
        for (int k = 0; k < 200; ++k) points.emplace_back(2 * u(rng), 3 * u(rng), 4 * u(rng));
        for (int k = 0; k < 8; ++k)
            points.insert(points.begin() + 25 * k, Vec3(k & 1 ? 2 : -2, k & 2 ? 3 : -3, k & 4 ? 4 : -4));
        const ConvexHull h = mesh::convexHull(points);
        QCOMPARE(h.vertices.size(), size_t(8));
        QCOMPARE(h.faces.size(), size_t(6));
        QCOMPARE(h.edges.size(), size_t(12));
        for (const auto& f : h.faces) {
            QCOMPARE(h.verticesOf(f).size(), size_t(4));
            // Outward axis normals: the face's centre lies along its normal from the middle.
            QVERIFY(std::abs(f.normal.cwiseAbs().maxCoeff() - 1.0) < 1e-12);
            Vec3 c = Vec3::Zero();
            for (int v : h.verticesOf(f)) c += h.vertices[v];
            QVERIFY(f.normal.dot(c) > 0.0);
        }
        for (const Vec3& v : h.vertices) QCOMPARE(v.cwiseAbs(), Vec3(2, 3, 4));
        const QString problem = hullProblem(h, 1e-12);
        QVERIFY2(problem.isEmpty(), qPrintable(problem));
        // The solid is the box: 4 × 6 × 8.
        double volume = 0;
        meshMassProperties(mesh::hullSurface(h), 1.0, &volume);
        QVERIFY(std::abs(volume - 192.0) < 1e-12);
    }

    void randomCloudHullContainsEveryPoint() {
        std::mt19937 rng(11);
        std::normal_distribution<double> g(0.0, 1.0);
        std::vector<Vec3> points;
        for (int k = 0; k < 500; ++k) points.emplace_back(g(rng), 0.5 * g(rng), 2.0 * g(rng) + 10.0);
        const ConvexHull h = mesh::convexHull(points);
        const QString problem = hullProblem(h, 1e-12);
        QVERIFY2(problem.isEmpty(), qPrintable(problem));
        QVERIFY(h.vertices.size() >= 4 && h.vertices.size() < points.size());
        for (const Vec3& p : points) {
            for (const auto& f : h.faces) QVERIFY(f.normal.dot(p) <= f.offset + 1e-12);
        }
        // Every hull vertex is an input point.
        for (const Vec3& v : h.vertices) QVERIFY(std::find(points.begin(), points.end(), v) != points.end());
        // Every input point outside the hull of the others must be a vertex: check the
        // extreme point along a few directions.
        for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(1, 2, 3).normalized()}) {
            const auto far =
                std::max_element(points.begin(), points.end(),
                                 [&](const Vec3& a, const Vec3& b) { return a.dot(d) < b.dot(d); });
            QVERIFY(std::find(h.vertices.begin(), h.vertices.end(), *far) != h.vertices.end());
        }
    }

    void tetrahedronHull() {
        const ConvexHull h = mesh::convexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        QCOMPARE(h.vertices.size(), size_t(4));
        QCOMPARE(h.faces.size(), size_t(4));
        QCOMPARE(h.edges.size(), size_t(6));
        const QString problem = hullProblem(h, 1e-15);
        QVERIFY2(problem.isEmpty(), qPrintable(problem));
        QVERIFY((h.interiorPoint - Vec3::Constant(0.25)).norm() < 1e-15);
    }

    void degenerateHullInput_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<QString>("expected");
        QTest::newRow("three points") << "three"
                                      << "at least 4 points";
        QTest::newRow("square") << "square"
                                << "one plane";
        QTest::newRow("tilted disc") << "disc"
                                     << "one plane";
        QTest::newRow("segment") << "segment"
                                 << "one line";
        QTest::newRow("one point") << "same"
                                   << "coincide";
        QTest::newRow("nan") << "nan"
                             << "not finite";
    }

    void degenerateHullInput() {
        QFETCH(QString, name);
        QFETCH(QString, expected);
        std::vector<Vec3> p;
        if (name == "three") p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        if (name == "square") p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
        if (name == "disc") {
            const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
            for (int k = 0; k < 50; ++k) p.push_back(R * Vec3(std::cos(k), std::sin(k), 0) + Vec3(5, 6, 7));
        }
        if (name == "segment")
            for (int k = 0; k < 10; ++k) p.push_back(Vec3(1, 2, 3) * k);
        if (name == "same") p.assign(6, Vec3(1, 2, 3));
        if (name == "nan") p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, std::nan(""))};
        try {
            mesh::convexHull(p);
            QFAIL("no error");
        } catch (const mesh::HullError& e) {
            QVERIFY2(QString(e.what()).contains(expected), e.what());
        }
    }

    // A cube stored as STL stores it (36 vertices) is open until welded; copies that
    // differ by less than the tolerance weld too, copies further apart do not.
    void weldingClosesASplitCube() {
        TriangleMesh split = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1), true);
        QCOMPARE(split.vertices.size(), size_t(36));
        QVERIFY(!isClosed(split));
        mesh::CleanStats stats;
        TriangleMesh welded = mesh::cleanMesh(split, &stats);
        QCOMPARE(welded.vertices.size(), size_t(8));
        QCOMPARE(welded.triangles.size(), size_t(12));
        QCOMPARE(stats.weldedVertices, 28);
        QVERIFY(isClosed(welded));

        QCOMPARE(mesh::weldTolerance(split.vertices), mesh::kWeldRelative * std::sqrt(3.0));
        for (size_t v = 0; v < split.vertices.size(); ++v) split.vertices[v].x() += (v % 3) * 1e-8;
        QVERIFY(isClosed(mesh::cleanMesh(split)));
        for (size_t v = 0; v < split.vertices.size(); ++v) split.vertices[v].x() += (v % 3) * 1e-3;
        QVERIFY(!isClosed(mesh::cleanMesh(split)));
    }

    void degenerateAndRepeatedTrianglesAreDropped() {
        TriangleMesh m = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
        m.vertices.push_back(Vec3(0.5, 0, 0));   // 8: on the edge 0-1
        m.vertices.push_back(Vec3(7, 7, 7));     // 9: used by nothing
        m.vertices.push_back(Vec3(0, 0, 1e-9));  // 10: welds into vertex 0
        m.triangles.push_back({0, 8, 1});        // collinear: no area
        m.triangles.push_back({3, 3, 5});        // two corners the same
        m.triangles.push_back({10, 4, 6});       // becomes {0, 4, 6}, a repeat of the first
        m.triangles.push_back({4, 6, 0});        // the same turned: a repeat
        mesh::CleanStats stats;
        const TriangleMesh c = mesh::cleanMesh(m, &stats);
        QCOMPARE(stats.degenerateTriangles, 2);
        QCOMPARE(stats.duplicateTriangles, 2);
        QCOMPARE(stats.weldedVertices, 1);
        QCOMPARE(stats.unusedVertices, 2);  // the edge point and the stray point
        QCOMPARE(c.triangles.size(), size_t(12));
        QCOMPARE(c.vertices.size(), size_t(8));
        QVERIFY(isClosed(c));
        double volume = 0;
        meshMassProperties(c, 1.0, &volume);
        QCOMPARE(volume, 1.0);
    }

    void badInputIsRefused() {
        TriangleMesh m = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
        m.triangles.push_back({0, 1, 8});
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, mesh::cleanMesh(m));
        m.triangles.pop_back();
        m.vertices[2].y() = std::numeric_limits<double>::infinity();
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, mesh::cleanMesh(m));
    }

    void insideOutClosedMeshIsTurned() {
        TriangleMesh m = boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
        for (auto& t : m.triangles) std::swap(t[0], t[1]);
        const mesh::PreparedMesh p = mesh::prepareMesh(m, false, true);
        QVERIFY(p.closed && p.turnedOutward && !p.massFromHull && !p.hull);
        QCOMPARE(p.volume, 6.0);
    }

    void openMeshMassComesFromTheHull() {
        TriangleMesh m = boxMesh(Vec3(-1, -1, -1), Vec3(1, 1, 1));
        m.triangles.resize(10);  // the +z face is gone
        const mesh::PreparedMesh p = mesh::prepareMesh(m, false, true);
        QVERIFY(!p.closed && p.massFromHull && p.hull);
        QVERIFY(std::abs(p.volume - 8.0) < 1e-12);
        QVERIFY(p.unitDensity.centerOfMass.norm() < 1e-12);
        QVERIFY(std::abs(p.unitDensity.inertia(2, 2) - 8.0 / 3.0 * 2.0) < 1e-12);  // m (a² + b²) / 3
    }

    // A closed cube off the origin: the centre of mass is computed, not assumed at the origin.
    void compiledMeshBody() {
        BodyDesc b = meshBody(boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3)));
        b.density = 2.0;
        b.position = Vec3(10, 0, 0);
        const SceneDesc scene = test::sceneOf({b});
        const Model m = compile(scene);
        const BodyModel& body = m.bodies[0];
        QCOMPARE(body.mass, 12.0);
        QVERIFY((body.centerOfMass - Vec3(0.5, 1, 1.5)).norm() < 1e-14);
        const Vec3 expected = 12.0 / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4);
        QVERIFY((body.inertia - Mat3(expected.asDiagonal())).cwiseAbs().maxCoeff() < 1e-12);
        QCOMPARE(body.collider.kind, collision::Kind::Hull);
        QCOMPARE(body.collider.hull->faces.size(), size_t(6));
        QCOMPARE(m.notes.size(), size_t(1));
        QCOMPARE(QString::fromStdString(m.notes[0]),
                 QString("bodies[0] (rock): the mesh is closed; mass properties come from its surface"));
        const State s = initialState(m, scene);
        QVERIFY((s.bodies[0].x - Vec3(10.5, 1, 1.5)).norm() < 1e-14);

        // The same mass given directly, and collision as triangles.
        b.density.reset();
        b.mass = 6.0;
        b.shape.collision = MeshCollision::Triangles;
        const Model m2 = compile(test::sceneOf({b}));
        QCOMPARE(m2.bodies[0].mass, 6.0);
        QVERIFY((m2.bodies[0].inertia - Mat3((0.5 * expected).asDiagonal())).cwiseAbs().maxCoeff() < 1e-12);
        QCOMPARE(m2.bodies[0].collider.kind, collision::Kind::Mesh);
        QVERIFY(m2.bodies[0].collider.mesh->closed);
        QVERIFY(m2.bodies[0].collider.mesh->bvh);
        QCOMPARE(m2.bodies[0].collider.mesh->triangles.size(), size_t(12));
    }

    void openMeshBodyNotesTheHull() {
        TriangleMesh open = boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1));
        open.triangles.pop_back();
        BodyDesc b = meshBody(open);
        b.density = 3.0;
        const Model m = compile(test::sceneOf({b}));
        QVERIFY(std::abs(m.bodies[0].mass - 3.0) < 1e-12);
        QVERIFY((m.bodies[0].centerOfMass - Vec3::Constant(0.5)).norm() < 1e-12);
        QCOMPARE(
            QString::fromStdString(m.notes.at(0)),
            QString("bodies[0] (rock): the mesh is not closed; mass properties come from its convex hull"));
    }

    void meshNeverLoadedIsRefused() {
        BodyDesc b = meshBody(boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)));
        b.shape.meshData.reset();
        b.mass = 1.0;
        QVERIFY(sceneErrorPath(test::sceneOf({b}))
                    .startsWith("bodies[0].shape.file | the mesh 'rock.obj' was never loaded"));
        b.motion = Motion::Static;
        b.mass.reset();
        QVERIFY(sceneErrorPath(test::sceneOf({b})).startsWith("bodies[0].shape.file | "));
    }

    void flatMeshNeedsNoVolumeOnlyWhenNothingIsComputed() {
        TriangleMesh sheet;
        sheet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(0, 0, 1)};
        sheet.triangles = {{0, 2, 1}, {0, 3, 2}};
        BodyDesc b = meshBody(sheet);
        b.density = 100.0;
        QVERIFY(sceneErrorPath(test::sceneOf({b}))
                    .startsWith("bodies[0].density | rock.obj: the mesh encloses no volume"));
        b.density.reset();
        b.mass = 1.0;
        QVERIFY(sceneErrorPath(test::sceneOf({b}))
                    .startsWith("bodies[0].shape.file | rock.obj: the mesh encloses no "
                                "volume (all points lie on one plane"));
        QVERIFY(sceneErrorPath(test::sceneOf({b})).contains("give center_of_mass and inertia"));
        b.inertia = Mat3(Vec3(1, 2, 1).asDiagonal());
        b.centerOfMass = Vec3(0.5, 0, 0.5);
        QVERIFY(sceneErrorPath(test::sceneOf({b}))
                    .startsWith("bodies[0].shape.file | rock.obj: has no convex hull"));
        b.shape.collision = MeshCollision::Triangles;
        QCOMPARE(sceneErrorPath(test::sceneOf({b})), QString("compiled"));
        // A closed but flat surface (both sides of the sheet) has no volume either.
        sheet.triangles.push_back({0, 1, 2});
        sheet.triangles.push_back({0, 2, 3});
        BodyDesc both = meshBody(sheet, MeshCollision::Triangles);
        both.density = 1.0;
        QVERIFY(sceneErrorPath(test::sceneOf({both})).startsWith("bodies[0].density | "));
        // A static flat mesh is fine as triangles.
        BodyDesc ground = meshBody(sheet, MeshCollision::Triangles);
        ground.motion = Motion::Static;
        QCOMPARE(sceneErrorPath(test::sceneOf({ground})), QString("compiled"));
    }

    void meshWithOnlyDegenerateTrianglesIsRefused() {
        TriangleMesh m;
        m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
        m.triangles = {{0, 1, 2}};
        BodyDesc b = meshBody(m);
        b.motion = Motion::Static;
        QVERIFY(sceneErrorPath(test::sceneOf({b})).contains("has no triangles with an area"));
        m.triangles = {{0, 1, 5}};
        b.shape.meshData = std::make_shared<const TriangleMesh>(m);
        QVERIFY(sceneErrorPath(test::sceneOf({b}))
                    .startsWith("bodies[0].shape.file | rock.obj: triangle 0 uses vertex 5"));
    }

    // meshData is derived from file and scale: scenes compare by what the file holds.
    void shapeEqualityIgnoresLoadedData() {
        BodyDesc a = meshBody(boxMesh(Vec3(0, 0, 0), Vec3(1, 1, 1)));
        BodyDesc b = a;
        b.shape.meshData.reset();
        QVERIFY(a.shape == b.shape);
        b.shape.scale = Vec3(1, 1, 2);
        QVERIFY(!(a.shape == b.shape));
        b = a;
        b.shape.collision = MeshCollision::Triangles;
        QVERIFY(!(a.shape == b.shape));
    }
};

QTEST_APPLESS_MAIN(TestMeshProcessing)
#include "tst_mesh_processing.moc"
