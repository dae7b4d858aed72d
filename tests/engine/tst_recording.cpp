// The recording behind the timeline: re-simulation from any recorded frame repeats the run
// bit for bit, the memory cap thins to keyframes and every frame stays reachable, and the
// per-frame summary holds the closed-form energy.
#include "scene_builders.h"

#include <tumble/io/scene_file.h>
#include <tumble/recording.h>

#include <QtTest>

#include <cstring>

using namespace tumble;
using namespace tumble::test;

namespace {

// Every field of two states equal to the bit (not only the hashed x, q, P, L).
bool sameBits(const State& a, const State& b) {
    if (hashState(a) != hashState(b)) return false;
    if (a.restTime != b.restTime || a.asleep != b.asleep || a.touching != b.touching ||
        a.touchingKnown != b.touchingKnown || a.contacts.size() != b.contacts.size())
        return false;
    for (std::size_t i = 0; i < a.contacts.size(); ++i) {
        const ContactMemory& x = a.contacts[i];
        const ContactMemory& y = b.contacts[i];
        if (x.bodyA != y.bodyA || x.bodyB != y.bodyB || x.feature != y.feature || x.position != y.position ||
            x.normalImpulse != y.normalImpulse || x.tangentImpulse != y.tangentImpulse ||
            x.twistImpulse != y.twistImpulse || x.step != y.step)
            return false;
    }
    return true;
}

std::vector<State> runAll(const SceneDesc& scene) {
    World w(scene);
    std::vector<State> frames;
    simulate(w, [&](int, const State& s) { frames.push_back(s); });
    return frames;
}

SceneDesc sample(const char* name, double duration) {
    SceneDesc scene = io::readSceneFile(std::string(TUMBLE_SCENES_DIR) + "/" + name);
    scene.settings.duration = duration;
    return scene;
}

}  // namespace

class TestRecording : public QObject {
    Q_OBJECT
private slots:
    // From any frame of a run with impacts, resting contact, friction and sleeping, a fresh
    // World set to that frame's state steps to exactly the recorded later frames.
    void resimulationIsBitForBit_data() {
        QTest::addColumn<QString>("scene");
        QTest::newRow("pyramid (contacts, no sleeping)") << "pyramid-15.json";
        QTest::newRow("sleeping-wake (islands fall asleep and wake)") << "sleeping-wake.json";
        QTest::newRow("bouncing-ball (impacts)") << "bouncing-ball.json";
        QTest::newRow("spring-pendulum (forces)") << "spring-pendulum.json";
        QTest::newRow("newtons-cradle (impact chains)") << "newtons-cradle.json";
        QTest::newRow("tower-20 (stack)") << "tower-20.json";
        QTest::newRow("tilted-box-impact") << "tilted-box-impact.json";
        QTest::newRow("rolling-sphere (friction)") << "rolling-sphere.json";
    }
    void resimulationIsBitForBit() {
        QFETCH(QString, scene);
        const SceneDesc desc = sample(scene.toUtf8().constData(), 3.0);
        const std::vector<State> frames = runAll(desc);
        QVERIFY(frames.size() > 60);
        World again(desc);
        // One frame on from every frame...
        for (int from = 0; from + 1 < int(frames.size()); ++from) {
            again.setState(frames[static_cast<std::size_t>(from)]);
            advanceFrame(again, from + 1);
            if (!sameBits(again.state(), frames[static_cast<std::size_t>(from + 1)]))
                QFAIL(qPrintable(QString("frame %1 from frame %2 differs").arg(from + 1).arg(from)));
        }
        // ... and many frames on from a few.
        for (int from : {1, 7, 30, int(frames.size()) / 2}) {
            again.setState(frames[static_cast<std::size_t>(from)]);
            for (int k = from + 1; k < std::min(int(frames.size()), from + 25); ++k) {
                advanceFrame(again, k);
                if (!sameBits(again.state(), frames[static_cast<std::size_t>(k)]))
                    QFAIL(qPrintable(QString("from frame %1, frame %2 differs").arg(from).arg(k)));
            }
        }
    }

    // The pyramid sits in resting contact from its first frame: the pairs touching at the
    // end of a step travel with the state.
    void stateCarriesTouchingPairs() {
        const std::vector<State> frames = runAll(sample("pyramid-15.json", 0.1));
        QVERIFY(!frames[0].touchingKnown);
        QVERIFY(frames[1].touchingKnown);
        QVERIFY(frames[1].touching.size() > 100);
        QVERIFY(std::is_sorted(frames[1].touching.begin(), frames[1].touching.end()));
    }

    // Under a cap that holds a tenth of the run the recording keeps keyframes at multiples
    // of a power of two, stays under the cap, and hands back every frame exactly.
    void capThinsToKeyframesAndEveryFrameIsReachable() {
        const SceneDesc desc = sample("sleeping-wake.json", 4.0);
        const std::vector<State> frames = runAll(desc);
        const int n = int(frames.size());
        const std::size_t cap = stateBytes(frames.back()) * std::size_t(n) / 10;
        World w(desc);
        Recording rec(cap);
        rec.reset(n);
        for (const State& s : frames) rec.append(s, summarize(w.model(), s, 0));
        QVERIFY(rec.complete());
        QVERIFY2(rec.bytes() <= cap, qPrintable(QString("%1 > %2").arg(rec.bytes()).arg(cap)));
        const int K = rec.keyframeInterval();
        QVERIFY(K >= 8);
        QCOMPARE(K & (K - 1), 0);
        for (int k = 0; k < n; ++k) QCOMPARE(rec.stored(k) != nullptr, k % K == 0);
        // Scrub forward, backward and at random: all exact.
        std::vector<int> order;
        for (int k = 0; k < n; ++k) order.push_back(k);
        for (int k = n - 1; k >= 0; k -= 3) order.push_back(k);
        for (int k : {n - 1, 3, n / 2, 1, n / 3}) order.push_back(k);
        for (int k : order) {
            const State* s = rec.state(k, w);
            QVERIFY(s);
            if (!sameBits(*s, frames[static_cast<std::size_t>(k)]))
                QFAIL(qPrintable(QString("frame %1").arg(k)));
        }
        QVERIFY(rec.state(n, w) == nullptr);
    }

    // Lowering the cap of a finished recording thins it at once.
    void loweringTheCapThins() {
        const SceneDesc desc = sample("bouncing-ball.json", 2.0);
        const std::vector<State> frames = runAll(desc);
        World w(desc);
        Recording rec;
        rec.reset(int(frames.size()));
        for (const State& s : frames) rec.append(s, summarize(w.model(), s, 0));
        QCOMPARE(rec.keyframeInterval(), 1);
        QCOMPARE(rec.storedCount(), int(frames.size()));
        rec.setCapBytes(rec.bytes() / 5);
        QVERIFY(rec.keyframeInterval() >= 8);
        QVERIFY(rec.bytes() <= rec.capBytes());
        QVERIFY(sameBits(*rec.state(int(frames.size()) - 2, w), frames[frames.size() - 2]));
    }

    // Free fall from rest: kinetic ½ m g² t², potential m g y(t) falls by as much, momentum m g t.
    void summaryOfFreeFall() {
        SceneDesc scene = sceneOf({sphereBody("s", 0.1, 2.0)});
        scene.settings.duration = 1.0;
        World w(scene);
        const double g = 9.81, m = 2.0;
        const double y0 = w.state().bodies[0].x.y();
        const double p0 = summarize(w.model(), w.state(), 0).potential;
        int frames = 0;
        simulate(w, [&](int, const State& s) {
            const FrameSummary f = summarize(w.model(), s, 0);
            const double t = s.time;
            QVERIFY(std::abs(f.kinetic - 0.5 * m * g * g * t * t) < 1e-9);
            QVERIFY(std::abs(f.potential - (p0 + m * g * (s.bodies[0].x.y() - y0))) < 1e-9);
            QVERIFY(std::abs(f.potential - (p0 - 0.5 * m * g * g * t * t)) < 1e-9);
            QVERIFY(std::abs(f.momentum - m * g * t) < 1e-9);
            ++frames;
        });
        QCOMPARE(frames, frameCount(scene.settings));
    }
};

QTEST_APPLESS_MAIN(TestRecording)
#include "tst_recording.moc"
