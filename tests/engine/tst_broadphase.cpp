// Broadphase: on many random scenes and through histories of updates (small motion,
// teleports, bodies falling asleep and waking, changing counts), the pairs must be exactly
// the brute-force set, sorted, without duplicates and without a static-static pair. The
// brute force itself is checked on a hand-made scene, and the dynamic tree's invariants
// under random insertions and removals.
#include "collision/broadphase.h"
#include "common/workers.h"

#include <QtTest>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

using namespace tumble;
using namespace tumble::collision;

namespace {

using Pairs = std::vector<std::pair<int, int>>;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct SceneKind {
    int n;
    bool clustered;
    bool grid;          // corners on an integer grid: exact touching (min == max) is common
    double staticShare;
    int unbounded;      // planes and half-spaces among the bodies
};

struct Scene {
    std::vector<Aabb> bounds;
    std::vector<std::uint8_t> moving;
};

class Generator {
public:
    explicit Generator(unsigned seed) : rng_(seed) {}

    double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
    int integer(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
    bool chance(double p) { return uniform(0.0, 1.0) < p; }

    Aabb randomBox(const SceneKind& k, double side, const std::vector<Vec3>& clusters) {
        Vec3 c;
        if (k.clustered) {
            const Vec3& centre = clusters[integer(0, static_cast<int>(clusters.size()) - 1)];
            std::normal_distribution<double> g(0.0, 0.05 * side);
            c = centre + Vec3(g(rng_), g(rng_), g(rng_));
        } else {
            c = Vec3(uniform(0, side), uniform(0, side), uniform(0, side));
        }
        // Mostly unit-sized, some points, some flat, some large.
        Vec3 h(uniform(0.1, 1.0), uniform(0.1, 1.0), uniform(0.1, 1.0));
        const double r = uniform(0.0, 1.0);
        if (r < 0.05) h.setZero();
        else if (r < 0.1) h[integer(0, 2)] = 0.0;
        else if (r < 0.13) h *= 10.0;
        Aabb b{c - h, c + h};
        if (k.grid) {
            b.min = b.min.array().floor();
            b.max = b.max.array().ceil();
            if (r < 0.05) b.max = b.min;  // a point on the grid
        }
        return b;
    }

    Aabb unboundedBox() {
        Aabb b{Vec3::Constant(-kInf), Vec3::Constant(kInf)};
        const int r = integer(0, 2);
        if (r == 1) b.max.y() = uniform(-1.0, 5.0);  // a half-space below some height
        if (r == 2) b.min.x() = uniform(-1.0, 5.0);
        return b;
    }

    Scene scene(const SceneKind& k) {
        const double side = 2.0 * std::cbrt(std::max(1, k.n));  // about 8 volume per body
        std::vector<Vec3> clusters;
        for (int c = 0; c < 4; ++c)
            clusters.emplace_back(uniform(0, side), uniform(0, side), uniform(0, side));
        Scene s;
        for (int i = 0; i < k.n; ++i) {
            s.bounds.push_back(randomBox(k, side, clusters));
            s.moving.push_back(chance(k.staticShare) ? 0 : 1);
        }
        for (int u = 0; u < k.unbounded && k.n > 0; ++u) {
            const int i = integer(0, k.n - 1);
            s.bounds[i] = unboundedBox();
        }
        if (k.n > 3) s.bounds[integer(0, k.n - 1)] = Aabb{};  // an empty box pairs with nothing
        return s;
    }

    void step(Scene& s, const SceneKind& k, double size) {
        for (std::size_t i = 0; i < s.bounds.size(); ++i) {
            if (!s.moving[i]) continue;
            Aabb& b = s.bounds[i];
            if (!b.min.allFinite() || !b.max.allFinite() || b.empty()) continue;
            Vec3 d(uniform(-size, size), uniform(-size, size), uniform(-size, size));
            if (chance(0.01)) d *= 1000.0;  // teleported far away
            if (k.grid) d = d.array().round();
            b.min += d;
            b.max += d;
        }
    }

private:
    std::mt19937 rng_;
};

bool sortedUnique(const Pairs& p) {
    for (std::size_t k = 0; k < p.size(); ++k) {
        if (p[k].first >= p[k].second) return false;
        if (k > 0 && !(p[k - 1] < p[k])) return false;
    }
    return true;
}

bool noStaticPair(const Pairs& p, const std::vector<std::uint8_t>& moving) {
    for (const auto& [i, j] : p)
        if (!moving[i] && !moving[j]) return false;
    return true;
}

}  // namespace

class TestBroadphase : public QObject {
    Q_OBJECT

private slots:
    void bruteForceOnHandScene() {
        // 0 and 1 touch on a face; 2 overlaps 1 only; 3 is static and overlaps 0; 4 is a
        // static plane (infinite box); 5 is static and overlaps 3 (never reported).
        const std::vector<Aabb> b = {
            {Vec3(0, 0, 0), Vec3(1, 1, 1)},   {Vec3(1, 0, 0), Vec3(2, 1, 1)},
            {Vec3(1.5, 0.5, 0.5), Vec3(3, 3, 3)}, {Vec3(-0.5, -0.5, -0.5), Vec3(0.1, 0.1, 0.1)},
            {Vec3::Constant(-kInf), Vec3::Constant(kInf)},
            {Vec3(-1, -1, -1), Vec3(-0.2, -0.2, -0.2)}};
        const std::vector<std::uint8_t> moving = {1, 1, 1, 0, 0, 0};
        const Pairs expected = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 4}};
        QCOMPARE(bruteForcePairs(b, moving), expected);
        Broadphase bp;
        bp.update(b, moving);
        QCOMPARE(bp.pairs(), expected);
    }

    void mismatchedSizesThrow() {
        Broadphase bp;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, bp.update({Aabb{}}, {}));
    }

    void randomScenesMatchBruteForce_data() {
        QTest::addColumn<int>("n");
        QTest::addColumn<bool>("clustered");
        QTest::addColumn<bool>("grid");
        QTest::addColumn<double>("staticShare");
        QTest::addColumn<int>("unbounded");
        QTest::newRow("empty") << 0 << false << false << 0.0 << 0;
        QTest::newRow("one") << 1 << false << false << 0.0 << 0;
        QTest::newRow("few") << 5 << true << false << 0.4 << 1;
        QTest::newRow("spread") << 400 << false << false << 0.3 << 0;
        QTest::newRow("clustered") << 400 << true << false << 0.3 << 2;
        QTest::newRow("grid touching") << 400 << false << true << 0.3 << 1;
        QTest::newRow("grid clustered") << 300 << true << true << 0.5 << 3;
        QTest::newRow("all static") << 200 << true << false << 1.0 << 2;
        QTest::newRow("all moving") << 1000 << false << false << 0.0 << 1;
        QTest::newRow("mostly static") << 1000 << true << false << 0.9 << 2;
    }

    void randomScenesMatchBruteForce() {
        QFETCH(int, n);
        QFETCH(bool, clustered);
        QFETCH(bool, grid);
        QFETCH(double, staticShare);
        QFETCH(int, unbounded);
        const SceneKind kind{n, clustered, grid, staticShare, unbounded};
        for (unsigned seed = 1; seed <= (n >= 1000 ? 2u : 3u); ++seed) {
            Generator gen(seed * 7919u + static_cast<unsigned>(n));
            Scene s = gen.scene(kind);
            Broadphase bp;
            for (int step = 0; step < 25; ++step) {
                bp.update(s.bounds, s.moving);
                const Pairs expected = bruteForcePairs(s.bounds, s.moving);
                QCOMPARE(bp.pairs(), expected);
                QVERIFY(sortedUnique(bp.pairs()));
                QVERIFY(noStaticPair(bp.pairs(), s.moving));
                QVERIFY(bp.movingTree().valid());
                QVERIFY(bp.staticTree().valid());
                gen.step(s, kind, grid ? 1.0 : 0.05);
                // The editor moves a static body now and then.
                if (n > 0 && step % 7 == 3) {
                    for (int k = 0; k < std::max(1, n / 50); ++k) {
                        const int i = gen.integer(0, n - 1);
                        Aabb& b = s.bounds[i];
                        if (s.moving[i] || b.empty() || !b.min.allFinite() || !b.max.allFinite()) continue;
                        const Vec3 d = Vec3(gen.uniform(-3, 3), gen.uniform(-3, 3), gen.uniform(-3, 3)).array().round();
                        b.min += d;
                        b.max += d;
                    }
                }
                // Bodies fall asleep and wake up now and then.
                if (n > 0 && step % 5 == 4) {
                    for (int k = 0; k < std::max(1, n / 20); ++k) {
                        const int i = gen.integer(0, n - 1);
                        s.moving[i] = s.moving[i] ? 0 : 1;
                    }
                }
            }
        }
    }

    void parkedBodiesStayInTheMovingTree() {
        // World parks the islands without an impact for the rest of a step (not moving)
        // and moves them again in the next: while their boxes stay put nothing is
        // re-inserted, and the pairs are the brute force's throughout (two parked bodies
        // make no pair, a parked and a moving one do). Standing still for long, a body
        // joins the static tree after all.
        Generator gen(5);
        const SceneKind kind{400, true, false, 0.2, 0};
        Scene s = gen.scene(kind);
        Broadphase bp;
        for (int step = 0; step < 3; ++step) {
            bp.update(s.bounds, s.moving);
            gen.step(s, kind, 0.05);
        }
        // Standing still for two updates: the fat boxes stretched along the last moves
        // (a body teleported far) have shrunk back.
        bp.update(s.bounds, s.moving);
        bp.update(s.bounds, s.moving);
        std::vector<std::uint8_t> parked = s.moving;
        int count = 0;  // parked bodies with a box (the generator leaves some empty)
        for (size_t i = 0; i < parked.size(); ++i) {
            if (!parked[i] || i % 3 == 0) continue;
            parked[i] = 0;
            const Aabb& b = s.bounds[i];
            count += !b.empty() && b.min.allFinite() && b.max.allFinite();
        }
        QVERIFY(count > 100);
        for (int round = 0; round < 3; ++round) {
            for (int look = 0; look < 3; ++look) {  // the cuts of one step: the parked bodies still
                bp.update(s.bounds, parked);
                QCOMPARE(bp.pairs(), bruteForcePairs(s.bounds, parked));
                QCOMPARE(bp.reinserted(), 0);
            }
            bp.update(s.bounds, s.moving);  // the next step: moving again, from where they stood
            QCOMPARE(bp.pairs(), bruteForcePairs(s.bounds, s.moving));
            QCOMPARE(bp.reinserted(), 0);
        }
        int joined = 0;
        for (int look = 0; look < 20; ++look) {
            bp.update(s.bounds, parked);
            QCOMPARE(bp.pairs(), bruteForcePairs(s.bounds, parked));
            joined += bp.reinserted();
            QVERIFY(bp.movingTree().valid() && bp.staticTree().valid());
        }
        QCOMPARE(joined, count);
    }

    void spinningBodiesInPlaceAreReinsertedOnce() {
        // Boxes turning about their middles where they stand (free-10000): their boxes change
        // shape every update. Once seen turning, a body's fat box takes in every turn, so it
        // is re-inserted once, not every few updates; the pairs are the brute force's
        // throughout (neighbours close enough to touch at some turns).
        const int side = 12;
        std::vector<Eigen::Matrix3d> turn(side * side);
        std::vector<Vec3> centre(side * side), half{Vec3(0.5, 0.3, 0.2)};
        std::vector<Eigen::Matrix3d> R(side * side, Eigen::Matrix3d::Identity());
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int i = 0; i < side * side; ++i) {
            centre[i] = Vec3(1.1 * (i % side), 0.0, 1.1 * (i / side));
            const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
            turn[i] = Eigen::AngleAxisd(0.05 + 0.05 * std::abs(u(rng)), axis).toRotationMatrix();
        }
        auto boxesNow = [&] {
            std::vector<Aabb> out(side * side);
            for (int i = 0; i < side * side; ++i) {
                const Vec3 reach = R[i].cwiseAbs() * half[0];
                out[i] = {centre[i] - reach, centre[i] + reach};
            }
            return out;
        };
        const std::vector<std::uint8_t> moving(side * side, 1);
        Broadphase bp;
        int reinserted = 0, pairs = 0;
        for (int update = 0; update < 200; ++update) {
            const std::vector<Aabb> boxes = boxesNow();
            bp.update(boxes, moving);
            QCOMPARE(bp.pairs(), bruteForcePairs(boxes, moving));
            if (update > 0) reinserted += bp.reinserted();
            pairs += static_cast<int>(bp.pairs().size());
            for (int i = 0; i < side * side; ++i) R[i] = turn[i] * R[i];
        }
        QVERIFY2(pairs > 0, "no neighbours ever touched: the comparison proves little");
        // At most once each after the first (144 here; without the turning cube, 2 204).
        QVERIFY2(reinserted <= side * side, qPrintable(QString::number(reinserted)));
    }

    void expectedPairsArePresent() {
        // A guard on the brute force as reference: a non-trivial number of pairs of every
        // sort appears in a dense scene, so the comparisons above are not vacuous.
        Generator gen(42);
        const Scene s = gen.scene({600, true, true, 0.4, 2});
        int movingMoving = 0, movingStatic = 0;
        for (const auto& [i, j] : bruteForcePairs(s.bounds, s.moving))
            (s.moving[i] && s.moving[j] ? movingMoving : movingStatic)++;
        QVERIFY(movingMoving > 100);
        QVERIFY(movingStatic > 100);
    }

    void changingBodyCountStartsAfresh() {
        Generator gen(5);
        const SceneKind kind{300, false, false, 0.2, 1};
        Broadphase bp;
        for (int round = 0; round < 6; ++round) {
            const SceneKind k{kind.n + 37 * round * (round % 2 ? -1 : 1), false, round % 2 == 1, 0.2, 1};
            const Scene s = gen.scene(k);
            bp.update(s.bounds, s.moving);
            QCOMPARE(bp.pairs(), bruteForcePairs(s.bounds, s.moving));
        }
    }

    void historyDoesNotChangeTheResult() {
        // Two broadphases reach the same final scene along different paths.
        Generator gen(11);
        const SceneKind kind{500, true, false, 0.3, 1};
        Scene s = gen.scene(kind);
        Broadphase a;
        for (int step = 0; step < 20; ++step) {
            a.update(s.bounds, s.moving);
            gen.step(s, kind, 0.2);
        }
        Broadphase b;
        b.update(s.bounds, s.moving);
        a.update(s.bounds, s.moving);
        QCOMPARE(a.pairs(), b.pairs());
        QVERIFY(!a.pairs().empty());
    }

    void infiniteBoxesPairWithEveryMovingBody() {
        // A static plane pairs with every moving body wherever it is, and with no static one.
        Generator gen(3);
        Scene s = gen.scene({200, false, false, 0.5, 0});
        s.bounds[0] = {Vec3::Constant(-kInf), Vec3::Constant(kInf)};
        s.moving[0] = 0;
        s.bounds[1] = Aabb{};
        s.moving[1] = 1;
        s.bounds[2].min = Vec3::Constant(1e300);
        s.bounds[2].max = Vec3::Constant(1e300);
        s.moving[2] = 1;
        Broadphase bp;
        bp.update(s.bounds, s.moving);
        std::vector<int> partners;
        for (const auto& [i, j] : bp.pairs())
            if (i == 0) partners.push_back(j);
        std::vector<int> expected;
        for (int j = 2; j < 200; ++j)
            if (s.moving[j] && !s.bounds[j].empty()) expected.push_back(j);
        QCOMPARE(partners, expected);
    }

    void aHalfSpacePairsOnlyWithTheBoxesReachingIt() {
        // A static plane given its half-space (a tilted ground) pairs with exactly the moving
        // boxes that have a corner on its solid side or on it, checked corner by corner; the
        // other pairs are those of the plain update.
        Generator gen(5);
        Scene s = gen.scene({300, false, false, 0.3, 0});
        s.bounds[0] = {Vec3::Constant(-kInf), Vec3::Constant(kInf)};
        s.moving[0] = 0;
        std::vector<HalfSpace> half(s.bounds.size());
        half[0] = {Vec3(0.3, 1.0, -0.2).normalized(), 4.0, true};
        Broadphase plain, culled;
        plain.update(s.bounds, s.moving);
        culled.update(s.bounds, s.moving, half);
        Pairs expected;
        int reaching = 0, far = 0;
        for (const auto& [i, j] : plain.pairs()) {
            if (i != 0) {
                expected.emplace_back(i, j);
                continue;
            }
            const Aabb& b = s.bounds[j];
            bool reaches = false;
            for (int c = 0; c < 8; ++c) {
                const Vec3 corner(c & 1 ? b.max.x() : b.min.x(), c & 2 ? b.max.y() : b.min.y(),
                                  c & 4 ? b.max.z() : b.min.z());
                reaches = reaches || half[0].normal.dot(corner) <= half[0].offset;
            }
            (reaches ? reaching : far) += 1;
            if (reaches) expected.emplace_back(i, j);
        }
        std::sort(expected.begin(), expected.end());
        QVERIFY(reaching > 10 && far > 10);  // the scene straddles the plane
        QCOMPARE(culled.pairs(), expected);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                                 culled.update(s.bounds, s.moving, std::vector<HalfSpace>(3)));
    }

    // A tree large enough to be rebuilt on two threads (4 096 leaves or more) is the same tree
    // as on one: every query visits the same leaves in the same order, and its own pairs come
    // in the same order (the broadphase's pairs, and so the whole step, bit for bit).
    void aPoolRebuildsTheSameTree() {
        constexpr int kBodies = 6000;
        Generator gen(23);
        const SceneKind kind{kBodies, true, false, 0.0, 0};
        const std::vector<Vec3> clusters = {Vec3(5, 5, 5), Vec3(30, 8, 12), Vec3(12, 40, 3)};
        Workers pool(2);
        AabbTree one, two;
        one.reset(kBodies);
        two.reset(kBodies);
        for (int i = 0; i < kBodies; ++i) {
            const Aabb b = gen.randomBox(kind, 45.0, clusters);
            one.add(i, b);
            two.add(i, b);
        }
        const long runs = pool.runs();
        one.rebuild();
        two.rebuild(&pool);
        QVERIFY2(pool.runs() > runs, "precondition: the rebuild used the pool");
        QVERIFY(one.valid() && two.valid());
        for (int q = 0; q < 50; ++q) {
            const Aabb probe = gen.randomBox(kind, 45.0, clusters);
            std::vector<int> a, b;
            one.query(probe, [&](int body) { a.push_back(body); });
            two.query(probe, [&](int body) { b.push_back(body); });
            QCOMPARE(a, b);
        }
        Pairs a, b;
        one.selfPairs([&](int x, int y) { a.emplace_back(x, y); });
        two.selfPairs([&](int x, int y) { b.emplace_back(x, y); });
        QVERIFY(!a.empty());
        QCOMPARE(a, b);
    }

    void treeQueriesMatchBruteForceUnderChurn() {
        // Random insertions, additions and removals in two trees; every query, the tree
        // against itself and against the other, exactly as brute force over the stored boxes,
        // before and after rebuilds.
        constexpr int kBodies = 1500;
        Generator gen(17);
        const SceneKind kind{kBodies, false, true, 0.0, 0};
        const std::vector<Vec3> noClusters;
        AabbTree trees[2];
        std::vector<Aabb> box[2];
        for (int t = 0; t < 2; ++t) {
            trees[t].reset(kBodies);
            box[t].assign(kBodies, Aabb{});
        }
        auto check = [&]() {
            for (int t = 0; t < 2; ++t) QVERIFY(trees[t].valid());
            for (int q = 0; q < 50; ++q) {
                const Aabb probe = gen.randomBox(kind, 22.0, noClusters);
                std::vector<int> found;
                trees[0].query(probe, [&](int body) { found.push_back(body); });
                std::sort(found.begin(), found.end());
                std::vector<int> expected;
                for (int i = 0; i < kBodies; ++i)
                    if (trees[0].contains(i) && box[0][i].overlaps(probe)) expected.push_back(i);
                QCOMPARE(found, expected);
            }
            Pairs self, cross, selfExpected, crossExpected;
            trees[0].selfPairs([&](int a, int b) { self.emplace_back(std::min(a, b), std::max(a, b)); });
            trees[0].pairsWith(trees[1], [&](int a, int b) { cross.emplace_back(a, b); });
            std::sort(self.begin(), self.end());
            std::sort(cross.begin(), cross.end());
            for (int i = 0; i < kBodies; ++i) {
                if (!trees[0].contains(i)) continue;
                for (int j = i + 1; j < kBodies; ++j)
                    if (trees[0].contains(j) && box[0][i].overlaps(box[0][j])) selfExpected.emplace_back(i, j);
                for (int j = 0; j < kBodies; ++j)
                    if (trees[1].contains(j) && box[0][i].overlaps(box[1][j])) crossExpected.emplace_back(i, j);
            }
            QCOMPARE(self, selfExpected);
            QCOMPARE(cross, crossExpected);
            QVERIFY(!self.empty() && !cross.empty());
        };
        for (int round = 0; round < 6; ++round) {
            for (int k = 0; k < 3000; ++k) {
                const int t = gen.integer(0, 1);
                const int i = gen.integer(0, kBodies - 1);
                if (trees[t].contains(i)) {
                    trees[t].remove(i);
                } else {
                    box[t][i] = gen.randomBox(kind, 22.0, noClusters);
                    if (round == 0 || gen.chance(0.1)) {
                        trees[t].add(i, box[t][i]);  // seen after the rebuild below
                    } else {
                        trees[t].insert(i, box[t][i]);
                    }
                }
            }
            if (round % 2 == 0) {
                for (AabbTree& tree : trees) {
                    tree.rebuild();
                    QVERIFY(!tree.needsRebuild());
                    QVERIFY(tree.height() <= static_cast<int>(std::bit_width(static_cast<unsigned>(tree.leafCount()))) + 1);
                }
            }
            if (round % 2 == 1) {
                // Unlinked leaves wait for a rebuild; the others are all seen.
                for (AabbTree& tree : trees) QVERIFY(tree.needsRebuild());
                for (AabbTree& tree : trees) tree.rebuild();
            }
            check();
            if (QTest::currentTestFailed()) return;
        }
    }
};

QTEST_APPLESS_MAIN(TestBroadphase)
#include "tst_broadphase.moc"
