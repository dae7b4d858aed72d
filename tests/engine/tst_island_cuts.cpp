// Only the islands with an impact are cut, each at its own moments (World::park,
// World::startGroups), and a pair searched without an impact keeps that answer within the step
// (DetectScratch::noImpact): islands far apart, or bouncing in different steps, move bit for
// bit (or to rounding) as each would in a world of its own. Only the public API is used.
#include "scene_builders.h"

#include <QtTest>
#include "turned_world.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

using namespace tumble;
using namespace tumble::test;

namespace {

// Runs `together` (the ground, then island k's `each` bodies at 1 + k each) and each island
// alone (the ground, then its bodies) for `steps` steps of dt, side by side: the largest
// distance of an island's bodies (position, momentum, angular momentum) from their run
// alone, and the steps in which two of the lone runs were cut.
struct AloneRuns {
    double worst = 0.0;
    int shared = 0;
};
AloneRuns asIfAlone(World& together, std::vector<World>& alone, int each, int steps, double dt) {
    AloneRuns r;
    for (int n = 0; n < steps; ++n) {
        together.step(dt);
        int cut = 0;
        for (size_t k = 0; k < alone.size(); ++k) {
            const long cuts = alone[k].profile().impactMoments;
            alone[k].step(dt);
            cut += alone[k].profile().impactMoments > cuts;
            for (int j = 0; j < each; ++j) {
                const BodyState& a = together.state().bodies[1 + static_cast<int>(k) * each + j];
                const BodyState& b = alone[k].state().bodies[1 + j];
                r.worst = std::max({r.worst, (a.x - b.x).norm(), (a.P - b.P).norm(), (a.L - b.L).norm()});
            }
        }
        r.shared += cut > 1;
    }
    return r;
}

// The islands (bodies of the same count each) on `ground` in one world and each alone, sleeping
// off, all turned and shifted by `pose`, run side by side (asIfAlone); `together` gets the
// world's profile.
AloneRuns islandsAsIfAlone(const std::vector<std::vector<BodyDesc>>& islands, const BodyDesc& ground,
                           const WorldPose& pose, int steps, double dt, Profile* together = nullptr) {
    auto world = [&](std::vector<const std::vector<BodyDesc>*> parts) {
        SceneDesc s = sceneOf({ground});
        for (const auto* part : parts) s.bodies.insert(s.bodies.end(), part->begin(), part->end());
        s.settings.sleeping = false;
        return World(turnedScene(s, pose));
    };
    std::vector<const std::vector<BodyDesc>*> all;
    for (const auto& island : islands) all.push_back(&island);
    World both = world(all);
    std::vector<World> alone;
    for (const auto& island : islands) alone.push_back(world({&island}));
    const AloneRuns r = asIfAlone(both, alone, static_cast<int>(islands.front().size()), steps, dt);
    if (together) *together = both.profile();
    return r;
}

// Ball k of a row 3 m apart along x (radius r, 1 kg, restitution e), its bottom `height`
// above the ground: far enough from the others never to share an island.
BodyDesc rowBall(int k, double height, double r, double e) {
    BodyDesc b = material(sphereBody("ball" + std::to_string(k), r, 1.0), e, 0.5);
    b.position = Vec3(3.0 * k, height + r, 0);
    return b;
}

}  // namespace

class TestIslandCuts : public QObject {
    Q_OBJECT

private slots:
    // An impact cuts the step of its island only (issue 17): three balls bouncing far apart
    // move as each would alone (to the impact tolerance, 1e-6 of the radius: where two
    // bounce in one step, both are cut at both moments), and a ball not bouncing in a step
    // is integrated once in it.
    void islandsBounceAsIfAlone() {
        const double r = 0.1, e = 0.8, dt = 1.0 / 60.0;
        const double heights[3] = {1.2, 2.1, 2.9};
        auto ballAt = [&](int k) { return rowBall(k, heights[k], r, e); };
        SceneDesc all = sceneOf({groundPlane(e, 0.5), ballAt(0), ballAt(1), ballAt(2)});
        all.settings.sleeping = false;
        World together(all);
        std::vector<World> alone;
        for (int k = 0; k < 3; ++k) {
            SceneDesc one = sceneOf({groundPlane(e, 0.5), ballAt(k)});
            one.settings.sleeping = false;
            alone.emplace_back(one);
        }
        const int steps = 90;  // 1.5 s: each ball bounces 1 to 3 times
        const auto [worst, shared] = asIfAlone(together, alone, 1, steps, dt);
        QVERIFY2(shared == 0, "precondition: no two balls bounce in the same step");
        QVERIFY2(worst == 0.0, qPrintable(QString("a ball moved %1 (m or kg m/s) away from its run alone").arg(worst)));
        long aloneCuts = 0, aloneIntegrations = 0;
        for (const World& w : alone) {
            aloneCuts += w.profile().impactMoments;
            aloneIntegrations += w.profile().awakeBodySteps - steps;  // more than once a step
        }
        const Profile& p = together.profile();
        // (One moment a bounce: the three first ones and the lowest ball's second. While the
        // time of impact swept the chord of a step, not the fall's parabola, the chord met
        // the ground early and each bounce took three cuts to reach it: 12.)
        QVERIFY2(aloneCuts >= 4, "precondition: the balls bounce");
        QCOMPARE(p.islandRestarts, 0L);
        QVERIFY(p.parkedBodySteps > 0);
        // Integrations beyond one per ball and step: only the cut ball's, as alone (cutting
        // every body at every moment would be 3 x the moments).
        QCOMPARE(p.awakeBodySteps - 3L * steps, aloneIntegrations);
    }

    // Islands bouncing in the same step are each cut at their own moments only (group mode,
    // World::startGroups): two balls far apart whose bounces fall in the same steps move bit
    // for bit as each alone, in the world and in three turned and shifted ones.
    void islandsBouncingInOneStepMoveAsIfAlone() {
        const double r = 0.1, e = 0.8, dt = 1.0 / 60.0;
        const double heights[3] = {1.2, 1.21, 1.23};
        auto ballAt = [&](int k) { return rowBall(k, heights[k], r, e); };
        for (std::uint64_t seed : {0, 1, 2, 3}) {
            const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(seed);
            Profile p;
            const auto [worst, shared] =
                islandsAsIfAlone({{ballAt(0)}, {ballAt(1)}, {ballAt(2)}}, groundPlane(e, 0.5), pose, 90, dt, &p);
            QVERIFY2(shared >= 2, "precondition: balls bounce in the same steps");
            QCOMPARE(p.islandRestarts, 0L);
            QVERIFY2(worst == 0.0, qPrintable(QString("seed %1: a ball moved %2 (m or kg m/s) away from its run alone")
                                                  .arg(seed)
                                                  .arg(worst)));
        }
    }

    // The same with resting contacts: two stacks of three boxes far apart, a box dropped on
    // each, landing in the same step; each stack moves bit for bit as alone.
    void stacksHitInOneStepMoveAsIfAlone() {
        const double dt = 1.0 / 60.0;
        const double drops[2] = {0.8, 0.81};
        auto stack = [&](int k) {
            std::vector<BodyDesc> out;
            for (int j = 0; j < 4; ++j) {
                BodyDesc b = material(boxBody("s" + std::to_string(k) + "-" + std::to_string(j), Vec3(0.2, 0.1, 0.2), 1.0),
                                      0.3, 0.6);
                b.position = Vec3(4.0 * k + 0.03 * j, 0.1 + 0.2 * j + (j == 3 ? drops[k] : 0.0), 0.01 * j);
                out.push_back(b);
            }
            return out;
        };
        for (std::uint64_t seed : {0, 1, 2, 3}) {
            const WorldPose pose = seed == 0 ? WorldPose{} : randomWorldPose(seed);
            const auto [worst, shared] = islandsAsIfAlone({stack(0), stack(1)}, groundPlane(0.3, 0.6), pose, 60, dt);
            QVERIFY2(shared >= 1, "precondition: both stacks are hit in one step");
            QVERIFY2(worst == 0.0, qPrintable(QString("seed %1: a stack moved %2 away from its run alone")
                                                  .arg(seed)
                                                  .arg(worst)));
        }
    }

    // A pair searched without an impact keeps that answer over the rest of the step while
    // neither body's path changed (DetectScratch::noImpact): three balls falling side by side
    // in one island, bouncing in different steps; at each bounce's cut the other two fly on
    // untouched, and their pair is not searched again. Each ball moves as it does alone, to
    // rounding (the cut integrates the others' step in two pieces), in the world and in three
    // turned and shifted ones.
    void aSearchWithoutImpactHoldsWhileThePathsDoNot() {
        const double r = 0.1, e = 0.8, dt = 1.0 / 60.0;
        const double heights[3] = {1.2, 1.3, 1.4};
        auto ballAt = [&](int k) {
            BodyDesc b = material(sphereBody("ball" + std::to_string(k), r, 1.0), e, 0.5);
            // 4 cm apart on a diagonal, their boxes overlapping: one island, never touching.
            b.position = Vec3(0.17 * k, heights[k] + r, 0.17 * k);
            return b;
        };
        // The turned worlds keep the balls' offsets diagonal to the world's axes, so that
        // their boxes still overlap (one island): a quarter turn about gravity, a half turn
        // about the diagonal (gravity up), a third of a turn about (1, 1, 1) (x to y to z).
        const WorldPose poses[4] = {
            {},
            {Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY())), Vec3(5, -3, 2)},
            {Quat(Eigen::AngleAxisd(std::numbers::pi, Vec3(1, 0, 1).normalized())), Vec3(-7, 4, 1)},
            {Quat(Eigen::AngleAxisd(2 * std::numbers::pi / 3, Vec3(1, 1, 1).normalized())), Vec3(3, 8, -6)}};
        for (int seed = 0; seed < 4; ++seed) {
            Profile p;
            const auto [worst, shared] =
                islandsAsIfAlone({{ballAt(0)}, {ballAt(1)}, {ballAt(2)}}, groundPlane(e, 0.5), poses[seed], 90, dt, &p);
            QVERIFY2(shared == 0, "precondition: the balls bounce in different steps");
            QVERIFY2(p.impactMoments >= 6, "precondition: the balls bounce");
            QVERIFY2(p.impactSearchesKept > 0, qPrintable(QString("pose %1: no search was kept across a cut (%2 searched)").arg(seed).arg(p.impactSearches)));
            QVERIFY2(worst < 1e-12, qPrintable(QString("pose %1: a ball moved %2 (m or kg m/s) away from its run alone")
                                                   .arg(seed)
                                                   .arg(worst)));
        }
    }

};

QTEST_APPLESS_MAIN(TestIslandCuts)
#include "tst_island_cuts.moc"
