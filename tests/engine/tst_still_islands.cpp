// Islands at their fixed point (engine/src/islands/still_islands.h): a world that takes the still
// islands' answer as known must agree bit for bit with one that solves every island every
// step (World::skipStillIslands(false)), in piles that come to rest, are hit again, rest
// on a slope under friction, are pushed by a force that starts late, change step length
// or sleep; and it must actually skip (the profile's count), or the comparison proves
// nothing.
#include "scene_builders.h"

#include <QtTest>

#include <algorithm>
#include <cstring>
#include <tuple>

using namespace tumble;
using namespace tumble::test;

namespace {

// The remembered contact impulses as a sorted list: the same set in any order.
std::vector<std::tuple<int, int, std::uint32_t, double, double>> memoryOf(const State& s) {
    std::vector<std::tuple<int, int, std::uint32_t, double, double>> out;
    for (const ContactMemory& c : s.contacts)
        out.emplace_back(c.bodyA, c.bodyB, c.feature, c.normalImpulse, c.tangentImpulse.norm());
    std::sort(out.begin(), out.end());
    return out;
}

struct Run {
    World skipping, solving;
    explicit Run(const SceneDesc& scene) : skipping(scene), solving(scene) { solving.skipStillIslands(false); }
    // Steps both; false (with a message) at the first step their states differ.
    bool step(double h, int n) {
        for (int k = 0; k < n; ++k) {
            skipping.step(h);
            solving.step(h);
            if (hashState(skipping.state()) != hashState(solving.state())) {
                qWarning("states differ after the step to t = %.6f", skipping.state().time);
                return false;
            }
        }
        return true;
    }
    long bodySteps() const { return skipping.profile().awakeBodySteps; }
    long skipped() const { return skipping.profile().stillBodySteps; }
};

// The bodies with sleeping off: every body is stepped, and only the still islands skip.
SceneDesc awake(std::vector<BodyDesc> bodies) {
    SceneDesc scene = sceneOf(std::move(bodies));
    scene.settings.sleeping = false;
    return scene;
}

void compareEnds(const Run& r) {
    qInfo("%ld of %ld body-steps skipped", r.skipped(), r.bodySteps());
    QCOMPARE(r.solving.profile().stillBodySteps, 0L);
    QVERIFY(memoryOf(r.skipping.state()) == memoryOf(r.solving.state()));
    // The ledger books the skipped blocks' friction as last computed: the same, summed in
    // another order.
    const EnergyLedger &a = r.skipping.ledger(), &b = r.solving.ledger();
    const double scale = std::abs(b.lostInContacts) + std::abs(b.lostInFriction) + 1.0;
    QVERIFY(std::abs(a.lostInContacts - b.lostInContacts) <= 1e-12 * scale);
    QVERIFY(std::abs(a.lostInFriction - b.lostInFriction) <= 1e-12 * scale);
    QVERIFY(std::abs(a.positionCorrection - b.positionCorrection) <= 1e-12 * scale);
}

}  // namespace

class TestStillIslands : public QObject {
    Q_OBJECT

private slots:
    void restingHeapIsSkippedAndUnchanged_data() {
        QTest::addColumn<double>("h");
        QTest::addColumn<int>("rocks");
        QTest::addColumn<int>("seed");
        QTest::newRow("16 rocks, 1/60 s") << 1.0 / 60 << 16 << 31;
        QTest::newRow("16 rocks, 1/30 s") << 1.0 / 30 << 16 << 31;
        QTest::newRow("16 rocks, 1/240 s") << 1.0 / 240 << 16 << 5;
        QTest::newRow("32 rocks, 1/60 s") << 1.0 / 60 << 32 << 99;
    }
    void restingHeapIsSkippedAndUnchanged() {
        // Rocks fall in a heap and settle; a ball dropped from 20 m hits the heap at about
        // 2 s and sets it moving again; it settles again. (8 s: at 1/30 s the heap comes to
        // rest late, and how late is chaos: 14 % of 5 s skipped before issue 44, 8 % after,
        // 12 % of 8 s.)
        QFETCH(double, h);
        QFETCH(int, rocks);
        QFETCH(int, seed);
        std::vector<BodyDesc> bodies = rockHeap(rocks, static_cast<std::uint64_t>(seed), true);
        BodyDesc ball = sphereBody("ball", 0.3, 5.0);
        ball.position = Vec3(-0.3, 21.0, 0.4);
        bodies.push_back(ball);
        const SceneDesc scene = awake(bodies);
        Run r(scene);
        QVERIFY(r.step(h, static_cast<int>(std::lround(8.0 / h))));
        compareEnds(r);
        QVERIFY(r.skipped() > r.bodySteps() / 10);
    }

    void boxesOnASlopeHeldByFriction() {
        // Boxes resting on a 20 degree ramp (μ 0.8 holds them: tan 20° = 0.36), two stacked:
        // their friction impulses are remembered and taken as they were.
        BodyDesc ramp = boxBody("ramp", Vec3(3, 0.2, 1), 1.0);
        ramp.motion = Motion::Static;
        ramp.mass.reset();
        const Quat tilt(Eigen::AngleAxisd(20.0 * M_PI / 180, Vec3::UnitZ()));
        ramp.orientation = tilt;
        ramp.friction = 0.8;
        std::vector<BodyDesc> bodies{ramp};
        for (int i = 0; i < 3; ++i) {
            BodyDesc b = material(boxBody("box" + std::to_string(i), Vec3(0.2, 0.2, 0.2), 1.0 + i), 0.0, 0.8);
            const double along = -1.5 + 1.2 * i;
            b.position = tilt * Vec3(along, 0.2 + 0.2 + 1e-4, 0);
            b.orientation = tilt;
            bodies.push_back(b);
        }
        BodyDesc top = material(boxBody("top", Vec3(0.15, 0.15, 0.15), 0.5), 0.0, 0.8);
        top.position = tilt * Vec3(-1.5, 0.2 + 0.4 + 0.15 + 2e-4, 0);
        top.orientation = tilt;
        bodies.push_back(top);
        const SceneDesc scene = awake(bodies);
        Run r(scene);
        QVERIFY(r.step(1.0 / 60, 240));
        compareEnds(r);
        QVERIFY(r.skipped() > r.bodySteps() / 4);
        // They rest: the skipping cannot have hidden a slide.
        for (int i = 1; i <= 4; ++i) QVERIFY(r.skipping.state().bodies[i].P.norm() == 0.0);
    }

    void aForceThatStartsLateWakesItsIsland() {
        // A stack of three boxes at rest; at 1.5 s a sideways push starts on the top one. The
        // pushed body is never taken as still; the ones under it are until it moves.
        std::vector<BodyDesc> bodies{groundPlane(0.0, 0.5)};
        for (int i = 0; i < 3; ++i) {
            BodyDesc b = material(boxBody("box" + std::to_string(i), Vec3(0.3, 0.3, 0.3), 1.0), 0.0, 0.5);
            b.position = Vec3(0, 0.3 + 0.6 * i, 0);
            bodies.push_back(b);
        }
        ForceDesc push;
        push.vector = Vec3(20, 0, 0);
        push.start = 1.5;
        bodies.back().forces.push_back(push);
        const SceneDesc scene = awake(bodies);
        Run r(scene);
        QVERIFY(r.step(1.0 / 60, 180));
        compareEnds(r);
        QVERIFY(r.skipped() > 0);
        QVERIFY(r.skipping.state().bodies[3].x.x() > 0.1);  // the push did move the top box
    }

    void anotherStepLengthSolvesAgain() {
        // The heap at 1/60 s, then at 1/90 s, then at 1/60 s again: what was still at one
        // step is solved again at the other, and skipped again once still at it.
        const SceneDesc scene = awake(rockHeap(8, 7, true));
        Run r(scene);
        QVERIFY(r.step(1.0 / 60, 150));
        const long before = r.skipped();
        QVERIFY(r.step(1.0 / 90, 1));
        QCOMPARE(r.skipped(), before);  // the first step at a new length solves everything
        QVERIFY(r.step(1.0 / 90, 60));
        QVERIFY(r.step(1.0 / 60, 60));
        compareEnds(r);
        QVERIFY(r.skipped() > before);
    }

    void withSleepingOn() {
        // Bodies at rest before they fall asleep are skipped too; sleep comes as it would.
        std::vector<BodyDesc> bodies = randomDropPile(5);
        SceneDesc scene = sceneOf(bodies);
        scene.settings.sleeping = true;
        Run r(scene);
        QVERIFY(r.step(1.0 / 60, 400));
        compareEnds(r);
        QVERIFY(r.skipping.state().asleep == r.solving.state().asleep);
    }

    void rocksInATriangleMeshBowl() {
        // Rocks settle in a bowl made of triangles: several manifolds a pair (one per group
        // of triangle normals), the mesh path of the narrowphase.
        std::vector<BodyDesc> bodies = rockHeap(12, 17, true);
        bodies[0] = meshBowl(2.0, 8, 16);
        for (size_t i = 1; i < bodies.size(); ++i) bodies[i].position += Vec3(0.3, 0.2, -0.3);
        const SceneDesc scene = awake(bodies);
        Run r(scene);
        QVERIFY(r.step(1.0 / 60, 300));
        compareEnds(r);
        // Few of these rocks come to an exact fixed point (at 6-9 s about one body a step
        // is skipped), so the share depends on how the heap happened to land: 663 of 4 610
        // body-steps with the shock pass's friction always remembered, 180 of 4 717 since
        // it is remembered only on a support at rest (shock_propagation.cpp). (One rock
        // starts under the bowl's rim and falls away.)
        QVERIFY(r.skipped() > r.bodySteps() / 40);
    }

    void aMovingPlatformBesideARestingPile() {
        // A kinematic platform slides under two boxes (it carries them: never still) beside
        // a stack on the ground (still once settled, and then skipped).
        BodyDesc platform = material(boxBody("platform", Vec3(1, 0.1, 1), 1.0), 0.0, 0.6);
        platform.motion = Motion::Kinematic;
        platform.mass.reset();
        platform.position = Vec3(-4, 0.1, 0);
        platform.velocity = Vec3(0.5, 0, 0);
        std::vector<BodyDesc> bodies{groundPlane(0.0, 0.6), platform};
        for (int i = 0; i < 2; ++i) {
            BodyDesc b = material(boxBody("carried" + std::to_string(i), Vec3(0.2, 0.2, 0.2), 1.0), 0.0, 0.6);
            b.position = Vec3(-4.4 + 0.8 * i, 0.4, 0);
            bodies.push_back(b);
        }
        for (int i = 0; i < 3; ++i) {
            BodyDesc b = material(boxBody("stack" + std::to_string(i), Vec3(0.3, 0.3, 0.3), 2.0), 0.0, 0.6);
            b.position = Vec3(3, 0.3 + 0.6 * i, 0);
            bodies.push_back(b);
        }
        const SceneDesc scene = awake(bodies);
        Run r(scene);
        QVERIFY(r.step(1.0 / 60, 240));
        compareEnds(r);
        QVERIFY(r.skipped() > 3 * 100);  // the stack, for most of the run
        QVERIFY(r.skipping.state().bodies[2].x.x() > -4.4 + 1.5);  // carried along
    }

    void aStateSetFromOutsideSolvesEverything() {
        // setState forgets what was found still: the next step solves every island, and a
        // world given its own state before every step agrees with one that was not.
        const SceneDesc scene = awake(rockHeap(8, 11, true));
        World kept(scene), fresh(scene);
        QCOMPARE(firstDifferenceFromFresh(kept, fresh, 200, 1.0 / 60), -1.0);
        QCOMPARE(fresh.profile().stillBodySteps, 0L);
        QVERIFY(kept.profile().stillBodySteps > 0);
    }
};

QTEST_APPLESS_MAIN(TestStillIslands)
#include "tst_still_islands.moc"
