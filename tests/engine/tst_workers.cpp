// World::setThreads: the stages whose items are independent run on a pool of threads, and
// the result must be the same bit for bit for any number of threads (a run recorded on one
// machine replays on another). Checked on a heap of 320 mixed bodies in a mesh bowl, with
// impacts at their moment (cuts, parked islands) and at the end of the step, and on the
// pool itself (every chunk once, errors carried back to the caller).
#include "common/workers.h"
#include "scene_builders.h"
#include "test_meshes.h"
#include "turned_world.h"

#include <QtTest>

#include <atomic>
#include <cmath>
#include <cstring>
#include <stdexcept>

using namespace tumble;
using namespace tumble::test;

namespace {

// A static mesh bowl of radius 4 (inside facing up) over a ground plane, and 320 boxes,
// spheres and convex rocks dropped into it from up to 3 m: more than the pool's chunk sizes
// of pairs and of bodies, so every parallel stage runs on several chunks.
SceneDesc heapInBowl(ImpactTiming timing) {
    const double R = 4.0;
    std::vector<BodyDesc> bodies{groundPlane(0.3, 0.5), meshBowl(R, 12, 16)};
    const auto rock = std::make_shared<const TriangleMesh>(uvSphere(0.2, 3, 5));
    Rng rng{11};
    for (int k = 0; k < 320; ++k) {
        BodyDesc body;
        if (k % 3 == 0) {
            body = boxBody("box", rng.vec(0.08, 0.2), rng.uniform(0.5, 3.0));
        } else if (k % 3 == 1) {
            body = sphereBody("ball", rng.uniform(0.08, 0.2), rng.uniform(0.5, 3.0));
        } else {
            body.name = "rock";
            body.shape.type = ShapeType::Mesh;
            body.shape.collision = MeshCollision::ConvexHull;
            body.shape.file = "rock (built by the test)";
            body.shape.meshData = rock;
            body.mass = rng.uniform(0.5, 3.0);
        }
        body.name += std::to_string(k);
        body.restitution = rng.uniform(0.0, 0.6);
        body.friction = rng.uniform(0.2, 0.8);
        // 8 x 8 columns 0.45 m apart, five layers 0.5 m apart from 0.4 m above the bowl
        // (clear of it whatever the turn), a little jittered: the bottom layer lands within
        // the first dozen steps.
        const int column = k % 64, layer = k / 64;
        const double x = 0.45 * (column % 8 - 3.5) + rng.uniform(-0.02, 0.02);
        const double z = 0.45 * (column / 8 - 3.5) + rng.uniform(-0.02, 0.02);
        const double floor = R - std::sqrt(R * R - x * x - z * z);
        body.position = Vec3(x, floor + 0.4 + 0.5 * layer, z);
        body.orientation = Quat(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
                               .normalized();
        body.velocity = rng.vec(-1.0, 1.0);
        body.angularVelocity = rng.vec(-3.0, 3.0);
        bodies.push_back(body);
    }
    SceneDesc s = sceneOf(std::move(bodies));
    s.settings.impacts = timing;
    return s;
}

// Every double of the state (positions, orientations, momenta, remembered impulses) and the
// contact points, appended as raw bytes: two runs agree bit for bit when these are equal.
QByteArray fingerprint(const World& w) {
    QByteArray out;
    auto add = [&](const double* p, int n) { out.append(reinterpret_cast<const char*>(p), n * sizeof(double)); };
    for (const BodyState& b : w.state().bodies) {
        add(b.x.data(), 3);
        add(b.q.coeffs().data(), 4);
        add(b.P.data(), 3);
        add(b.L.data(), 3);
    }
    for (const ContactMemory& m : w.state().contacts) {
        out.append(reinterpret_cast<const char*>(&m.bodyA), sizeof m.bodyA);
        out.append(reinterpret_cast<const char*>(&m.bodyB), sizeof m.bodyB);
        out.append(reinterpret_cast<const char*>(&m.feature), sizeof m.feature);
        add(&m.normalImpulse, 1);
        add(m.tangentImpulse.data(), 3);
    }
    for (const collision::Manifold& m : w.contacts()) {
        out.append(reinterpret_cast<const char*>(&m.bodyA), sizeof m.bodyA);
        out.append(reinterpret_cast<const char*>(&m.bodyB), sizeof m.bodyB);
        add(m.normal.data(), 3);
        for (int k = 0; k < m.count; ++k) {
            add(m.points[k].position.data(), 3);
            add(&m.points[k].depth, 1);
        }
    }
    return out;
}

// 60 stacks of three boxes in a 10 x 6 grid, 1.5 m apart, on the ground, each dropped 5 cm
// with a small push and spin of its own: 60 islands all the time (none touches another),
// each solved on its own, which the pool takes several at a time.
SceneDesc separateStacks() {
    std::vector<BodyDesc> bodies{groundPlane(0.2, 0.6)};
    Rng rng{23};
    for (int k = 0; k < 60; ++k)
        for (int level = 0; level < 3; ++level) {
            BodyDesc box = boxBody("box" + std::to_string(k) + "-" + std::to_string(level),
                                   Vec3(0.25, 0.15, 0.2), rng.uniform(0.5, 2.0));
            box.position = Vec3(1.5 * (k % 10), 0.2 + 0.32 * level, 1.5 * (k / 10));
            box.velocity = rng.vec(-0.2, 0.2);
            box.angularVelocity = rng.vec(-0.5, 0.5);
            box.restitution = rng.uniform(0.0, 0.4);
            box.friction = rng.uniform(0.3, 0.8);
            bodies.push_back(box);
        }
    SceneDesc s = sceneOf(std::move(bodies));
    s.settings.sleeping = false;
    return s;
}

// A square pyramid of 8 layers of 0.3 m boxes (204) on the ground, a ball rolled into its
// side: one island of some 1 200 blocks, which the solver splits in two regions solved side
// by side on the pool, then their boundary (block_regions.h).
SceneDesc ballIntoPyramid() {
    std::vector<BodyDesc> bodies{groundPlane(0.1, 0.6)};
    const int layers = 8;
    const double h = 0.15;
    for (int l = 0; l < layers; ++l) {
        const int n = layers - l;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < n; ++k) {
                BodyDesc box = boxBody("box" + std::to_string(bodies.size()), Vec3(h, h, h),
                                       1.0 + 0.1 * ((i + k + l) % 3));
                box.position = Vec3((2 * i - n + 1) * h, h + 2 * h * l, (2 * k - n + 1) * h);
                bodies.push_back(box);
            }
    }
    BodyDesc ball = sphereBody("ball", 0.2, 5.0);
    ball.position = Vec3(-2.0, 0.2, 0.1);
    ball.velocity = Vec3(4.0, 0.0, 0.0);
    bodies.push_back(ball);
    SceneDesc s = sceneOf(std::move(bodies));
    s.settings.sleeping = false;
    return s;
}

// The ledger's sums as raw bytes (the islands' shares are added in island order).
QByteArray ledgerBytes(const EnergyLedger& l) {
    QByteArray out;
    for (double v : {l.lostInContacts, l.lostInFriction, l.positionCorrection, l.lostInJoints, l.doneByKinematic})
        out.append(reinterpret_cast<const char*>(&v), sizeof v);
    return out;
}

struct Run {
    QByteArray end;
    long contactPoints = 0;
    long impactMoments = 0;
    long pooledRuns = 0;
    double lowest = 0.0;  // the lowest body centre at the end
};

Run runHeap(ImpactTiming timing, int threads, int steps) {
    World w(heapInBowl(timing));
    w.setThreads(threads);
    if (w.threads() != threads) throw std::logic_error("setThreads did not take");
    stepN(w, steps, 1.0 / 60.0);
    Run r;
    r.end = fingerprint(w);
    r.contactPoints = w.profile().contactPoints;
    r.impactMoments = w.profile().impactMoments;
    r.pooledRuns = w.profile().pooledRuns;
    r.lowest = 1e9;
    for (int i : w.model().dynamicBodies) r.lowest = std::min(r.lowest, w.state().bodies[i].x.y());
    return r;
}

}  // namespace

class TestWorkers : public QObject {
    Q_OBJECT
private slots:
    void everyChunkRunsOnce_data() {
        QTest::addColumn<int>("threads");
        for (int t : {1, 2, 4}) QTest::addRow("%d threads", t) << t;
    }
    void everyChunkRunsOnce() {
        QFETCH(int, threads);
        Workers pool(threads);
        QCOMPARE(pool.threads(), threads);
        for (int round = 0; round < 50; ++round) {  // many runs: the handshake between them
            const int chunks = 1 + round * 37 % 500;
            std::vector<std::atomic<int>> calls(chunks);
            pool.run(chunks, [&](int c) { calls[c].fetch_add(1); });
            for (int c = 0; c < chunks; ++c) QCOMPARE(calls[c].load(), 1);
        }
    }

    void anErrorInAChunkReachesTheCaller() {
        Workers pool(3);
        std::atomic<int> ran{0};
        bool caught = false;
        try {
            pool.run(40, [&](int c) {
                ran.fetch_add(1);
                if (c == 17) throw std::runtime_error("chunk 17 failed");
            });
        } catch (const std::runtime_error& e) {
            caught = std::string(e.what()) == "chunk 17 failed";
        }
        QVERIFY(caught);
        QCOMPARE(ran.load(), 40);  // the other chunks still ran: the stage's lists are whole
        // The pool is still usable afterwards.
        std::atomic<int> again{0};
        pool.run(10, [&](int) { again.fetch_add(1); });
        QCOMPARE(again.load(), 10);
    }

    void chunksCoverTheRangeInOrder() {
        Workers pool(2);
        for (int n : {1, 7, 256, 257, 1000}) {
            std::vector<int> owner(n, -1);
            forEachChunk(&pool, n, 64, [&](int begin, int end) {
                for (int i = begin; i < end; ++i) owner[i] = begin;
            });
            for (int i = 0; i < n; ++i) {
                QVERIFY(owner[i] >= 0 && owner[i] <= i);
                if (i > 0) QVERIFY(owner[i] >= owner[i - 1]);
            }
        }
    }

    // PoolGate (issue 53): a stage not yet timed stays on this thread; once timed at a per-item
    // cost a, n items go to the pool when a n (1 - 1/threads) exceeds 1.5 times its overhead d,
    // the pool's measured dispatch until pooled runs show theirs; every 16th run stays on this
    // thread to keep a current, and one in 64 goes to the pool to time d again when the saving
    // is over d / 4.
    void poolGateHandsThePoolOnlyWhatPays() {
        Workers pool(2);
        const double d = pool.dispatchSeconds();
        QVERIFY(d > 0.0);
        PoolGate gate;
        QVERIFY(!gate.worthIt(&pool, 1000000));  // not timed yet
        const double a = d / 100.0;              // an item costs a hundredth of a dispatch
        gate.record(&pool, 1000, 1000 * a, false);
        // The break-even: a n / 2 = 1.5 d, n = 300.
        int pooled = 0, calls = 0;
        for (int k = 0; k < 14; ++k, ++calls) pooled += gate.worthIt(&pool, 290) ? 1 : 0;
        QCOMPARE(pooled, 0);
        pooled = 0;
        for (int k = 0; k < 16; ++k) pooled += gate.worthIt(&pool, 320) ? 1 : 0;
        QCOMPARE(pooled, 15);  // one of the 16 timed on this thread
        // Pooled runs that cost 10 d beyond their share raise the bar to n = 3 000.
        for (int k = 0; k < 40; ++k) gate.record(&pool, 1000, 1000 * a / 2 + 10.0 * d, true);
        int more = 0;
        for (int k = 0; k < 64; ++k) more += gate.worthIt(&pool, 2500) ? 1 : 0;
        QCOMPARE(more, 1);  // one of 64 goes to time the overhead again
        more = 0;
        for (int k = 0; k < 16; ++k) more += gate.worthIt(&pool, 3500) ? 1 : 0;
        QCOMPARE(more, 15);
        // That probe is only made for runs whose saving is over a quarter of the overhead as
        // timed (and over the pool's own measure): not for 400 (2 d against 10 d).
        more = 0;
        for (int k = 0; k < 64; ++k) more += gate.worthIt(&pool, 400) ? 1 : 0;
        QCOMPARE(more, 0);
        // Pooled runs as cheap as the pool's measure bring the bar back down (a slow first
        // pooled run does not keep a stage on one thread for good).
        for (int k = 0; k < 40; ++k) gate.record(&pool, 1000, 1000 * a / 2 + d, true);
        more = 0;
        for (int k = 0; k < 16; ++k) more += gate.worthIt(&pool, 400) ? 1 : 0;
        QCOMPARE(more, 15);
    }

    void threadCountMustBePositive() {
        World w(heapInBowl(ImpactTiming::Exact));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, w.setThreads(0));
        QCOMPARE(w.threads(), 1);
        w.setThreads(3);
        QCOMPARE(w.threads(), 3);
        w.setThreads(1);
        QCOMPARE(w.threads(), 1);
    }

    // The state after the heap's first layer has landed in the bowl (hundreds of contacts
    // and moments of impact) is the same bit for bit on 1, 2 and 4 threads.
    void sameRunOnAnyNumberOfThreads_data() {
        QTest::addColumn<bool>("endOfStep");
        QTest::addRow("impacts exact") << false;
        QTest::addRow("impacts end-of-step") << true;
    }
    void sameRunOnAnyNumberOfThreads() {
        QFETCH(bool, endOfStep);
        const ImpactTiming timing = endOfStep ? ImpactTiming::EndOfStep : ImpactTiming::Exact;
        // Fewer steps in the sanitizer build, where a step costs thirty times as much.
#ifdef TUMBLE_TEST_SANITIZED
        const int steps = 16;
#else
        const int steps = 24;
#endif
        const Run one = runHeap(timing, 1, steps);
        // The run did what the test is about: bodies fell and landed on each other and the bowl.
        QVERIFY2(one.contactPoints > 40L * steps, qPrintable(QString::number(one.contactPoints)));
        if (timing == ImpactTiming::Exact) QVERIFY(one.impactMoments > 0);
        QVERIFY2(one.lowest > -0.01 && one.lowest < 0.9, qPrintable(QString::number(one.lowest)));
        qInfo("contact points %ld, moments %ld, lowest %.3f", one.contactPoints, one.impactMoments, one.lowest);
        for (int threads : {2, 4}) {
            const Run many = runHeap(timing, threads, steps);
            QCOMPARE(many.contactPoints, one.contactPoints);
            QCOMPARE(many.impactMoments, one.impactMoments);
            // The pool took some of the stages (else the comparison would prove nothing).
            QVERIFY2(many.pooledRuns > 0, qPrintable(QString("%1 threads: no stage went to the pool").arg(threads)));
            QVERIFY2(many.end == one.end, qPrintable(QString("%1 threads differ").arg(threads)));
        }
    }

    // The contact solver's islands on the pool (issue 53): 60 separate stacks, each an island,
    // give the same state, memory and ledger bit for bit on 1, 2 and 4 threads, in the world
    // as built and turned and shifted as a whole; the islands did go to the pool.
    void islandsOnThePoolSolveAsOnOneThread_data() {
        QTest::addColumn<bool>("turned");
        QTest::addRow("as built") << false;
        QTest::addRow("turned and shifted") << true;
    }
    void islandsOnThePoolSolveAsOnOneThread() {
        QFETCH(bool, turned);
        const SceneDesc scene = turned ? turnedScene(separateStacks(), randomWorldPose(5)) : separateStacks();
        auto run = [&](int threads) {
            World w(scene);
            w.setThreads(threads);
            stepN(w, 30, 1.0 / 60.0);
            return std::make_tuple(fingerprint(w), ledgerBytes(w.ledger()), w.profile().pooledIslandSolves,
                                   w.profile().contactPoints);
        };
        const auto [end, ledger, pooledOne, points] = run(1);
        QCOMPARE(pooledOne, 0L);
        QVERIFY2(points > 30L * 60 * 8, qPrintable(QString::number(points)));  // every stack stands on its points
        for (int threads : {2, 4}) {
            const auto [endMany, ledgerMany, pooled, pointsMany] = run(threads);
            QVERIFY2(pooled > 0, qPrintable(QString("%1 threads: no solve went to the pool").arg(threads)));
            QCOMPARE(pointsMany, points);
            QVERIFY2(endMany == end, qPrintable(QString("%1 threads: the state differs").arg(threads)));
            QVERIFY2(ledgerMany == ledger, qPrintable(QString("%1 threads: the ledger differs").arg(threads)));
        }
    }

    // A large island's two regions solved side by side on the pool: the same bits on one, two
    // and four threads, in the world as built and turned.
    void regionsOfAnIslandSolveAsOnOneThread_data() { islandsOnThePoolSolveAsOnOneThread_data(); }
    void regionsOfAnIslandSolveAsOnOneThread() {
        QFETCH(bool, turned);
        const WorldPose pose = turned ? randomWorldPose(9) : WorldPose{};
        const SceneDesc scene = turnedScene(ballIntoPyramid(), pose);
        auto run = [&](int threads) {
            World w(scene);
            w.setThreads(threads);
            stepN(w, 40, 1.0 / 60.0);
            return std::make_tuple(fingerprint(w), ledgerBytes(w.ledger()), w.profile().pooledRegions);
        };
        const auto [end, ledger, pooledOne] = run(1);
        QCOMPARE(pooledOne, 0L);
        for (int threads : {2, 4}) {
            const auto [endMany, ledgerMany, pooled] = run(threads);
            QVERIFY2(pooled > 0, qPrintable(QString("%1 threads: no pass went to the pool").arg(threads)));
            QVERIFY2(endMany == end, qPrintable(QString("%1 threads: the state differs").arg(threads)));
            QVERIFY2(ledgerMany == ledger, qPrintable(QString("%1 threads: the ledger differs").arg(threads)));
        }
    }
};

QTEST_APPLESS_MAIN(TestWorkers)
#include "tst_workers.moc"
