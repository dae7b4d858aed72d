// Triangle BVH against brute force over every triangle, on random triangle soups (slivers,
// degenerate and axis-aligned triangles, touching boxes) and on fine sphere meshes:
// - query visits exactly the triangles whose box overlaps the query box, once each;
// - raycast visits every triangle whose box the segment crosses (reference clipped in long
//   double, dividing rather than multiplying by an inverse), and nothing whose box, grown by
//   1e-9, it misses; on a sphere the nearest true hit lies between the inscribed and the
//   circumscribed radius;
// - queryPairs reports every pair whose boxes overlap once the other triangle is placed by
//   the pose, and nothing outside the box of its rotated box grown by 1e-9.
#include "collision/bvh.h"

#include "test_meshes.h"

#include <QtTest>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

using namespace tumble;
using namespace tumble::collision;

namespace {

using Mesh = TriangleMesh;

Aabb triangleBox(const Mesh& m, int t, const Pose& pose = Pose{}) {
    Aabb b;
    for (int v : m.triangles[t]) b.add(pose.toWorld(m.vertices[v]));
    return b;
}

Mesh sphere(double r, int rings, int segments) { return test::uvSphere(r, rings, segments); }

class Random {
public:
    explicit Random(unsigned seed) : rng_(seed) {}
    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
    Vec3 point(double a, double b) { return Vec3(uniform(a, b), uniform(a, b), uniform(a, b)); }
    Vec3 unit() {
        std::normal_distribution<double> g;
        Vec3 d(g(rng_), g(rng_), g(rng_));
        return d.normalized();
    }
    Mat3 rotation() {
        std::normal_distribution<double> g;
        return Quat(g(rng_), g(rng_), g(rng_), g(rng_)).normalized().toRotationMatrix();
    }

private:
    std::mt19937 rng_;
};

// Triangles of varied size in a cube of side 10; some on an integer grid (shared and
// touching box faces), some degenerate, some flat along an axis.
Mesh soup(Random& rnd, int n) {
    Mesh m;
    for (int t = 0; t < n; ++t) {
        const Vec3 c = rnd.point(0, 10);
        const double s = std::pow(10.0, rnd.uniform(-2, 0.3));
        const int base = static_cast<int>(m.vertices.size());
        for (int k = 0; k < 3; ++k) m.vertices.push_back(c + s * rnd.point(-1, 1));
        const int kind = rnd.integer(0, 9);
        if (kind == 0) m.vertices[base + 2] = m.vertices[base + 1];  // degenerate
        if (kind == 1) {                                             // flat along an axis
            const int axis = rnd.integer(0, 2);
            for (int k = 0; k < 3; ++k) m.vertices[base + k][axis] = c[axis];
        }
        if (kind == 2) {  // on the grid
            for (int k = 0; k < 3; ++k) m.vertices[base + k] = m.vertices[base + k].array().round();
        }
        m.triangles.push_back({base, base + 1, base + 2});
    }
    return m;
}

// Does the segment o + t d, t in [0, len], meet box b? Clipped in long double with
// divisions: an independent computation, more precise than the BVH's.
bool segmentMeetsBox(const Aabb& b, const Vec3& o, const Vec3& d, double len) {
    long double tmin = 0, tmax = len;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < b.min[a] || o[a] > b.max[a]) return false;
            continue;
        }
        long double t0 = (static_cast<long double>(b.min[a]) - o[a]) / d[a];
        long double t1 = (static_cast<long double>(b.max[a]) - o[a]) / d[a];
        if (t0 > t1) std::swap(t0, t1);
        tmin = std::max(tmin, t0);
        tmax = std::min(tmax, t1);
    }
    return tmin <= tmax;
}

// Möller-Trumbore: the parameter of the segment's crossing with triangle t, or -1.
double crossing(const Mesh& m, int t, const Vec3& o, const Vec3& d) {
    const Vec3& a = m.vertices[m.triangles[t][0]];
    const Vec3 e1 = m.vertices[m.triangles[t][1]] - a;
    const Vec3 e2 = m.vertices[m.triangles[t][2]] - a;
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) return -1;
    const Vec3 s = o - a;
    const double u = s.dot(p) / det;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (u < 0 || v < 0 || u + v > 1) return -1;
    return e2.dot(q) / det;
}

std::vector<int> sorted(std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
}

bool unique(const std::vector<int>& sortedList) {
    return std::adjacent_find(sortedList.begin(), sortedList.end()) == sortedList.end();
}

// Query boxes: random ones of every size, points, and boxes touching a triangle's box on a
// face or a corner exactly.
Aabb probe(Random& rnd, const Mesh& m, const Aabb& range) {
    const int kind = rnd.integer(0, 3);
    const int t = rnd.integer(0, static_cast<int>(m.triangles.size()) - 1);
    const Aabb tb = triangleBox(m, t);
    if (kind == 0) {
        const Vec3 c = tb.max;  // a point on the corner
        return {c, c};
    }
    if (kind == 1) {  // touching tb's +x face from outside
        Aabb b{tb.max, tb.max + rnd.point(0, 1)};
        b.min.y() = tb.min.y();
        b.min.z() = tb.min.z();
        return b;
    }
    const Vec3 c = range.min + (range.max - range.min).cwiseProduct(rnd.point(0, 1));
    const Vec3 h = (range.max - range.min).cwiseProduct(rnd.point(0, kind == 2 ? 0.02 : 0.3));
    return {c - h, c + h};
}

}  // namespace

class TestBvh : public QObject {
    Q_OBJECT

    void checkQueries(const Mesh& m, Random& rnd, int count) {
        const TriangleBvh bvh(m.vertices, m.triangles);
        const int n = static_cast<int>(m.triangles.size());
        QCOMPARE(bvh.triangleCount(), n);
        Aabb all;
        for (int t = 0; t < n; ++t) all.add(triangleBox(m, t));
        QCOMPARE(bvh.bounds().min, all.min);
        QCOMPARE(bvh.bounds().max, all.max);
        int nonEmpty = 0;
        for (int q = 0; q < count; ++q) {
            const Aabb box = probe(rnd, m, all.inflated(1.0));
            std::vector<int> found;
            bvh.query(box, [&](int t) { found.push_back(t); });
            std::vector<int> expected;
            for (int t = 0; t < n; ++t)
                if (triangleBox(m, t).overlaps(box)) expected.push_back(t);
            QCOMPARE(sorted(found), expected);
            nonEmpty += !expected.empty();
        }
        QVERIFY(nonEmpty > count / 3);  // the probes do find triangles
    }

    void checkRaycasts(const Mesh& m, Random& rnd, int count) {
        const TriangleBvh bvh(m.vertices, m.triangles);
        const int n = static_cast<int>(m.triangles.size());
        const Aabb range = bvh.bounds().inflated(1.0);
        const double scale = (range.max - range.min).maxCoeff();
        int hits = 0;
        for (int q = 0; q < count; ++q) {
            Vec3 o = range.min + (range.max - range.min).cwiseProduct(rnd.point(0, 1));
            Vec3 d = rnd.unit();
            if (q % 3 == 1) {  // along an axis, in the plane of some triangle box's face
                d = Vec3::Zero();
                d[rnd.integer(0, 2)] = rnd.integer(0, 1) ? 1.0 : -1.0;
                const Aabb tb = triangleBox(m, rnd.integer(0, n - 1));
                for (int a = 0; a < 3; ++a)
                    if (d[a] == 0) o[a] = rnd.integer(0, 1) ? tb.min[a] : tb.max[a];
            }
            if (q % 3 == 2) {  // aimed at a corner of a triangle's box: a grazing ray
                const Aabb tb = triangleBox(m, rnd.integer(0, n - 1));
                Vec3 corner;
                for (int a = 0; a < 3; ++a) corner[a] = rnd.integer(0, 1) ? tb.min[a] : tb.max[a];
                if (corner != o) d = (corner - o).normalized();
            }
            const double len = q % 4 == 0 ? std::numeric_limits<double>::infinity()
                                          : rnd.uniform(0, scale);
            std::vector<int> found;
            bvh.raycast(o, d, len, [&](int t) { found.push_back(t); });
            found = sorted(found);
            QVERIFY(unique(found));
            for (int t = 0; t < n; ++t) {
                const Aabb tb = triangleBox(m, t);
                const bool meets = segmentMeetsBox(tb, o, d, len);
                const bool listed = std::binary_search(found.begin(), found.end(), t);
                if (meets && !listed) QFAIL(qPrintable(QString("missed triangle %1 of ray %2").arg(t).arg(q)));
                if (listed && !segmentMeetsBox(tb.inflated(1e-9 * scale), o, d, len))
                    QFAIL(qPrintable(QString("triangle %1 far from ray %2").arg(t).arg(q)));
                hits += meets;
            }
        }
        if (n >= 100) QVERIFY(hits > count);  // the rays do cross triangle boxes
    }

    void checkPairs(const Mesh& a, const Mesh& b, const Pose& pose) {
        const TriangleBvh ba(a.vertices, a.triangles);
        const TriangleBvh bb(b.vertices, b.triangles);
        std::vector<std::pair<int, int>> found;
        ba.queryPairs(bb, pose, [&](int i, int j) { found.emplace_back(i, j); });
        std::sort(found.begin(), found.end());
        QVERIFY(std::adjacent_find(found.begin(), found.end()) == found.end());
        const Mat3 absR = pose.R.cwiseAbs();
        std::vector<Aabb> boxesA, placed, loose;
        for (int i = 0; i < static_cast<int>(a.triangles.size()); ++i) boxesA.push_back(triangleBox(a, i));
        for (int j = 0; j < static_cast<int>(b.triangles.size()); ++j) {
            placed.push_back(triangleBox(b, j, pose));
            const Aabb own = triangleBox(b, j);
            const Vec3 c = pose.toWorld(own.center());
            const Vec3 h = absR * (0.5 * own.extent());
            loose.push_back(Aabb{c - h, c + h}.inflated(1e-9));
        }
        std::size_t k = 0;
        int expected = 0;
        for (int i = 0; i < static_cast<int>(boxesA.size()); ++i) {
            for (int j = 0; j < static_cast<int>(placed.size()); ++j) {
                const bool listed = k < found.size() && found[k] == std::pair(i, j);
                if (listed) ++k;
                if (boxesA[i].overlaps(placed[j])) {
                    ++expected;
                    if (!listed) QFAIL(qPrintable(QString("missed pair %1 %2").arg(i).arg(j)));
                }
                if (listed && !boxesA[i].overlaps(loose[j]))
                    QFAIL(qPrintable(QString("pair %1 %2 too far apart").arg(i).arg(j)));
            }
        }
        QCOMPARE(k, found.size());
        QVERIFY(expected > 0);
    }

private slots:
    void emptyMesh() {
        const TriangleBvh bvh({Vec3::Zero()}, {});
        QVERIFY(bvh.bounds().empty());
        int visits = 0;
        bvh.query(Aabb{Vec3::Constant(-1), Vec3::Constant(1)}, [&](int) { ++visits; });
        bvh.raycast(Vec3::Zero(), Vec3(1, 0, 0), 1.0, [&](int) { ++visits; });
        bvh.queryPairs(bvh, Pose{}, [&](int, int) { ++visits; });
        QCOMPARE(visits, 0);
    }

    void badIndexThrows() {
        QVERIFY_THROWS_EXCEPTION(std::out_of_range, TriangleBvh({Vec3::Zero()}, {{0, 0, 1}}));
    }

    void queryIsExactOnSoups() {
        Random rnd(1);
        for (int n : {1, 3, 5, 17, 2000}) {
            const Mesh m = soup(rnd, n);
            checkQueries(m, rnd, n < 100 ? 50 : 300);
        }
    }

    void queryIsExactOnFineSphere() {
        Random rnd(2);
        checkQueries(sphere(1.0, 64, 128), rnd, 150);
    }

    void raycastIsConservativeOnSoups() {
        Random rnd(3);
        for (int n : {1, 5, 2000}) checkRaycasts(soup(rnd, n), rnd, n < 100 ? 40 : 200);
    }

    void raycastIsConservativeOnFineSphere() {
        Random rnd(4);
        checkRaycasts(sphere(2.0, 64, 128), rnd, 120);
    }

    void raycastFindsTheSphereSurface() {
        // From the centre every ray leaves the tessellated sphere between the radius of the
        // inscribed sphere (through the facets' nearest points) and r.
        using std::numbers::pi;
        const double r = 1.5;
        const int rings = 48, segments = 96;
        const Mesh m = sphere(r, rings, segments);
        const TriangleBvh bvh(m.vertices, m.triangles);
        const double inner = r * std::cos(pi / rings) * std::cos(pi / segments);
        Random rnd(5);
        for (int q = 0; q < 200; ++q) {
            const Vec3 d = rnd.unit();
            double nearest = std::numeric_limits<double>::infinity();
            int candidates = 0;
            bvh.raycast(Vec3::Zero(), d, 10.0, [&](int t) {
                ++candidates;
                const double s = crossing(m, t, Vec3::Zero(), d);
                if (s >= 0) nearest = std::min(nearest, s);
            });
            QVERIFY(nearest >= inner * (1 - 1e-12));
            QVERIFY(nearest <= r * (1 + 1e-12));
            QVERIFY(candidates < static_cast<int>(m.triangles.size()) / 50);  // it prunes
        }
    }

    void pairsAreConservativeOnSoups() {
        Random rnd(6);
        const Mesh a = soup(rnd, 800);
        const Mesh b = soup(rnd, 600);
        checkPairs(a, b, Pose{});
        checkPairs(a, a, Pose{});
        Pose shifted;
        shifted.p = Vec3(2.5, -1, 0.5);
        checkPairs(a, b, shifted);
        Pose quarter;  // a quarter turn about z: boxes map to boxes exactly (touching kept)
        quarter.R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
        quarter.p = Vec3(10, 0, 0);
        checkPairs(a, b, quarter);
        for (int k = 0; k < 3; ++k) {
            Pose p;
            p.R = rnd.rotation();
            p.p = Vec3(5, 5, 5) - p.R * Vec3(5, 5, 5) + rnd.point(-2, 2);
            checkPairs(a, b, p);
        }
    }

    void pairsSurviveRoundingOfThePose() {
        // B's triangles are points; A's are small triangles whose box has its max corner at
        // the point of B placed by the pose in long double and rounded. About one in eight
        // placed points is truly inside (at or below the corner on every axis): those pairs
        // must be reported although the pose's double arithmetic may land just outside.
        Random rnd(9);
        Mesh a, b;
        std::vector<std::array<long double, 3>> exact;
        for (int k = 0; k < 2000; ++k) {
            const Vec3 v = rnd.point(-10, 10);
            b.vertices.push_back(v);
            b.triangles.push_back({k, k, k});
        }
        Pose pose;
        pose.R = rnd.rotation();
        pose.p = rnd.point(-3, 3);
        for (int k = 0; k < 2000; ++k) {
            std::array<long double, 3> w;
            for (int i = 0; i < 3; ++i) {
                w[i] = pose.p[i];
                for (int j = 0; j < 3; ++j)
                    w[i] += static_cast<long double>(pose.R(i, j)) * b.vertices[k][j];
            }
            exact.push_back(w);
            const Vec3 r(static_cast<double>(w[0]), static_cast<double>(w[1]), static_cast<double>(w[2]));
            const int base = static_cast<int>(a.vertices.size());
            a.vertices.push_back(r);
            a.vertices.push_back(r - Vec3(1e-3, 1e-3, 0));
            a.vertices.push_back(r - Vec3(0, 1e-3, 1e-3));
            a.triangles.push_back({base, base + 1, base + 2});
        }
        const TriangleBvh ba(a.vertices, a.triangles);
        const TriangleBvh bb(b.vertices, b.triangles);
        std::set<std::pair<int, int>> found;
        ba.queryPairs(bb, pose, [&](int i, int j) { found.emplace(i, j); });
        int inside = 0;
        for (int k = 0; k < 2000; ++k) {
            bool in = true;
            for (int i = 0; i < 3; ++i) in = in && exact[k][i] <= a.vertices[3 * k][i];
            if (!in) continue;
            ++inside;
            QVERIFY(found.count({k, k}) == 1);
        }
        QVERIFY(inside > 100);
    }

    void pairsAreConservativeOnSpheres() {
        Random rnd(7);
        const Mesh s = sphere(1.0, 32, 64);
        const Mesh t = soup(rnd, 300);
        Pose p;
        p.R = rnd.rotation();
        p.p = Vec3(0.3, -0.2, 0.4);
        checkPairs(s, s, p);
        Pose q;
        q.R = rnd.rotation();
        q.p = -q.R * Vec3(5, 5, 5);  // the soup's centre on the sphere's
        checkPairs(s, t, q);
    }

    void buildIsDeterministic() {
        Random rnd(8);
        const Mesh m = soup(rnd, 1000);
        const TriangleBvh a(m.vertices, m.triangles);
        const TriangleBvh b(m.vertices, m.triangles);
        std::vector<int> fa, fb;
        const Aabb box{Vec3::Constant(2), Vec3::Constant(7)};
        a.query(box, [&](int t) { fa.push_back(t); });
        b.query(box, [&](int t) { fb.push_back(t); });
        QCOMPARE(fa, fb);
        QVERIFY(!fa.empty());
        QCOMPARE(a.nodeCount(), b.nodeCount());
    }
};

QTEST_APPLESS_MAIN(TestBvh)
#include "tst_bvh.moc"
