// Issue 49 item 3: a mesh modelled as open shells (the assimp spider: its legs left open where
// they meet the body, ten edges wound against their neighbours) still bounds a solid once its
// triangles wind alike and its holes are filled (mesh/mesh_holes.h); its pieces come apart
// for the split. Volumes against closed forms, in a turned and shifted pose as well.
#include <QtTest>

#include "mesh/mesh_holes.h"

#include "test_meshes.h"

#include <numbers>

using namespace tumble;
using namespace tumble::mesh;
using namespace tumble::test;

namespace {

// An open tube: n sides of radius r about y from 0 to h, no ends.
TriangleMesh tube(double r, double h, int n) {
    TriangleMesh m;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n;
        m.vertices.emplace_back(r * std::cos(a), 0, -r * std::sin(a));
        m.vertices.emplace_back(r * std::cos(a), h, -r * std::sin(a));
    }
    for (int k = 0; k < n; ++k) {
        const int j = (k + 1) % n;
        m.triangles.push_back({2 * k, 2 * j, 2 * j + 1});
        m.triangles.push_back({2 * k, 2 * j + 1, 2 * k + 1});
    }
    return m;
}

TriangleMesh posed(TriangleMesh m, bool turn) {
    const Quat q(Eigen::AngleAxisd(0.9, Vec3(2, -1, 0.5).normalized()));
    if (turn)
        for (Vec3& v : m.vertices) v = q * v + Vec3(4.5, -2.0, 7.25);
    return m;
}

}  // namespace

class TestMeshHoles : public QObject {
    Q_OBJECT

private slots:
    void poses_data() {
        QTest::addColumn<bool>("turn");
        QTest::newRow("upright") << false;
        QTest::newRow("turned and shifted") << true;
    }

    // A box without one face, or without one triangle: the hole gets a flat fan and the
    // box its whole volume back.
    void aBoxLeftOpenIsClosedWithItsVolume_data() { poses_data(); }
    void aBoxLeftOpenIsClosedWithItsVolume() {
        QFETCH(bool, turn);
        for (int missing : {1, 2}) {
            TriangleMesh open = boxMesh(Vec3(1.0, 0.5, 0.25));
            open.triangles.resize(open.triangles.size() - missing);
            HoleFilling f;
            const TriangleMesh filled = fillHoles(posed(open, turn), &f);
            QVERIFY(f.closed);
            QVERIFY(isClosed(filled));
            QCOMPARE(f.holes, 1);
            QCOMPARE(f.shells, 1);
            QCOMPARE(f.openShells, 1);
            QVERIFY2(std::abs(signedVolume(filled) - 1.0) < 1e-12,
                     qPrintable(QString::number(signedVolume(filled))));
        }
    }

    // A tube open at both ends: two flat fans, the prism's volume (n/2 r^2 sin(2 pi/n) h).
    void aTubeGetsBothEnds_data() { poses_data(); }
    void aTubeGetsBothEnds() {
        QFETCH(bool, turn);
        const int n = 12;
        const double r = 0.3, h = 1.7;
        HoleFilling f;
        const TriangleMesh filled = fillHoles(posed(tube(r, h, n), turn), &f);
        QVERIFY(f.closed);
        QCOMPARE(f.holes, 2);
        const double prism = 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n) * h;
        QVERIFY2(std::abs(signedVolume(filled) - prism) < 1e-12 * prism,
                 qPrintable(QString::number(signedVolume(filled))));
    }

    // Triangles wound against their neighbours are turned back; a shell facing inwards is
    // turned outwards on its own, beside one that faces out.
    void windingsAreMadeAlike_data() { poses_data(); }
    void windingsAreMadeAlike() {
        QFETCH(bool, turn);
        TriangleMesh m = boxMesh(Vec3(1, 1, 1));
        std::swap(m.triangles[5][1], m.triangles[5][2]);
        std::swap(m.triangles[9][1], m.triangles[9][2]);
        QVERIFY(!isClosed(m));
        TriangleMesh inward = boxMesh(Vec3(0.5, 0.5, 0.5), Vec3(5, 0, 0));
        for (auto& t : inward.triangles) std::swap(t[1], t[2]);
        for (const auto& t : inward.triangles) m.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
        m.vertices.insert(m.vertices.end(), inward.vertices.begin(), inward.vertices.end());
        HoleFilling f;
        const TriangleMesh fixed = fillHoles(posed(m, turn), &f);
        QVERIFY(f.closed);
        QCOMPARE(f.turned, 2);
        QCOMPARE(f.holes, 0);
        QCOMPARE(f.shells, 2);
        QVERIFY2(std::abs(signedVolume(fixed) - 9.0) < 1e-12,
                 qPrintable(QString::number(signedVolume(fixed))));
    }

    // A fin on an edge two triangles already share cannot be closed, and the message says so.
    void aFinCannotBeClosed() {
        TriangleMesh m = boxMesh(Vec3(1, 1, 1));
        m.vertices.push_back(Vec3(3, 3, 3));
        m.triangles.push_back({m.triangles[0][0], m.triangles[0][1], 8});
        HoleFilling f;
        fillHoles(m, &f);
        QVERIFY(!f.closed);
        const QString why = QString::fromStdString(notClosedForParts(f));
        QVERIFY2(why.contains("not closed") && why.contains("convex-hull"), qPrintable(why));
    }

    // Pieces that share no vertex come apart, each with its own vertices, in order.
    void piecesComeApart() {
        TriangleMesh m = boxMesh(Vec3(1, 1, 1));
        const TriangleMesh second = boxMesh(Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0, 0));  // overlapping
        for (const auto& t : second.triangles) m.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
        m.vertices.insert(m.vertices.end(), second.vertices.begin(), second.vertices.end());
        const std::vector<TriangleMesh> shells = shellsOf(m);
        QCOMPARE(int(shells.size()), 2);
        for (const TriangleMesh& s : shells) {
            QCOMPARE(int(s.vertices.size()), 8);
            QCOMPARE(int(s.triangles.size()), 12);
            QVERIFY(isClosed(s));
        }
        QCOMPARE(signedVolume(shells[0]), 8.0);
        QCOMPARE(signedVolume(shells[1]), 1.0);
    }
};

QTEST_GUILESS_MAIN(TestMeshHoles)
#include "tst_mesh_holes.moc"
