// An animated body's keys in the editor (issue 50 item 2): Insert Key makes a body animated
// and keys its pose, in time order, one undo step; moving an animated body at frame 0 moves
// its key at t = 0 or adds one; its pose is its path's at t = 0; a key edit redoes the run
// (the recorded path is the new one) and its undo puts the old run back; "use this frame
// as start" shifts the keys with the motion; the viewport draws each path through its keys.
#include "document/body_keys.h"
#include "document/document.h"
#include "timeline/timeline.h"
#include "viewport/viewport_overlays.h"

#include <tumble/model.h>

#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

constexpr int kWaitMs = 60000;

BodyDesc box(const std::string& name) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = Vec3(0.2, 0.2, 0.2);
    b.mass = 2.0;
    b.velocity = Vec3(1, 0, 0);
    b.position = Vec3(0, 1, 0);
    return b;
}

bool runToEnd(Timeline& t) {
    t.simulate();
    return QTest::qWaitFor([&] { return t.status() == Timeline::Status::Complete; }, kWaitMs);
}

// A 1 s scene: the ground, and a paddle keyed from (0, 1, 0) at t = 0 to (1, 1, 0) at 1 s.
SceneDesc paddleAlongX() {
    SceneDesc s = emptyScene();
    s.settings.duration = 1.0;
    BodyDesc b = box("paddle");
    insertKey(b, 0.0, Vec3(0, 1, 0), Quat::Identity());
    insertKey(b, 1.0, Vec3(1, 1, 0), Quat::Identity());
    s.bodies.push_back(b);
    return s;
}

// Where the run has body i at its last frame (the body frame's origin).
Vec3 lastPosition(const Timeline& t, int i) {
    State s;
    if (!t.frameState(t.frameCount() - 1, &s)) return Vec3::Constant(NAN);
    return bodyFramePosition(t.model()->bodies[size_t(i)], s.bodies[size_t(i)]);
}

}  // namespace

class TestBodyKeys : public QObject {
    Q_OBJECT

private slots:
    void insertKeyMakesABodyAnimatedInTimeOrder() {
        BodyDesc b = box("paddle");
        insertKey(b, 1.0, Vec3(1, 1, 0), Quat::Identity());
        QCOMPARE(b.motion, Motion::Animated);
        QVERIFY(!b.mass && !b.density && b.forces.empty() && b.velocity.isZero(0.0));
        insertKey(b, 0.0, Vec3(0, 1, 0), Quat::Identity());
        insertKey(b, 2.0, Vec3(2, 1, 0), Quat::Identity());
        insertKey(b, 1.0 + 1e-12, Vec3(5, 1, 0), Quat::Identity());  // the key at 1 s takes it
        QCOMPARE(int(b.keys.size()), 3);
        QCOMPARE(b.keys[0].time, 0.0);
        QCOMPARE(b.keys[1].position, Vec3(5, 1, 0));
        QCOMPARE(b.keys[2].time, 2.0);
        QVERIFY(moveKey(b, 0, 1.5));  // past the key at 1 s: in its place
        QCOMPARE(b.keys[1].time, 1.5);
        QCOMPARE(b.keys[1].position, Vec3(0, 1, 0));
        QVERIFY(!moveKey(b, 1, 2.0));  // onto another key: refused, nothing changed
        QCOMPARE(b.keys[1].time, 1.5);
        QVERIFY(moveKey(b, 1, 0.0));
        QVERIFY(removeKey(b, 1));
        QVERIFY(removeKey(b, 0));
        QVERIFY(!removeKey(b, 0));  // the last key stays
        SceneDesc s = emptyScene();
        s.bodies.push_back(b);
        QVERIFY(compile(s).bodies[1].path != nullptr);  // a body the engine takes
    }

    // At frame 0 (where bodies are edited) a move of an animated body is a key at t = 0:
    // the one there takes it, or one is added; one undo step; the shown pose is the path's.
    void movingAnAnimatedBodyKeysItAtZero() {
        Document doc;
        BodyDesc b = box("paddle");
        insertKey(b, 0.5, Vec3(0, 1, 0), Quat::Identity());
        insertKey(b, 1.5, Vec3(2, 1, 0), Quat::Identity());
        b.position = Vec3(7, 7, 7);  // not the path's: the document puts it on the path
        const int i = doc.addBody(b);
        QCOMPARE(doc.body(i).position, Vec3(0, 1, 0));  // held at its first key before 0.5 s
        const int steps = doc.undoStack()->count();
        BodyDesc moved = doc.body(i);
        moved.position = Vec3(0, 2, 0);
        doc.setBody(i, moved, "Move");
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        QCOMPARE(int(doc.body(i).keys.size()), 3);
        QCOMPARE(doc.body(i).keys[0].time, 0.0);
        QCOMPARE(doc.body(i).keys[0].position, Vec3(0, 2, 0));
        moved = doc.body(i);
        moved.position = Vec3(0, 3, 0);
        doc.setBody(i, moved, "Move");
        QCOMPARE(int(doc.body(i).keys.size()), 3);  // the key at 0 took it
        QCOMPARE(doc.body(i).keys[0].position, Vec3(0, 3, 0));
        doc.undoStack()->undo();
        doc.undoStack()->undo();
        QCOMPARE(int(doc.body(i).keys.size()), 2);
        QCOMPARE(doc.body(i).position, Vec3(0, 1, 0));
    }

    // A key edit makes the run stale and the new run follows the new key; undo brings the
    // old path back.
    void aKeyEditRedoesTheRun() {
        Document doc;
        doc.replaceScene(paddleAlongX(), "Scene", false);
        Timeline t(&doc);
        QVERIFY(runToEnd(t));
        const double end = double(t.frameCount() - 1) / t.frameRate();
        QVERIFY((lastPosition(t, 1) - Vec3(end, 1, 0)).norm() < 1e-12);
        BodyDesc edited = doc.body(1);
        edited.keys[1].position = Vec3(0, 1, 2);
        doc.setBody(1, edited, "Set key position");
        QVERIFY(t.isStale());
        QVERIFY(runToEnd(t));
        QVERIFY((lastPosition(t, 1) - Vec3(0, 1, 2 * end)).norm() < 1e-12);
        doc.undoStack()->undo();
        QVERIFY(runToEnd(t));
        QVERIFY((lastPosition(t, 1) - Vec3(end, 1, 0)).norm() < 1e-12);
    }

    // "Use this frame as the start" keeps the path: the keys move back by the frame's time.
    void useFrameAsStartShiftsTheKeys() {
        Document doc;
        doc.replaceScene(paddleAlongX(), "Scene", false);
        Timeline t(&doc);
        t.setAutoSimulate(false);
        QVERIFY(runToEnd(t));
        const int k = int(std::lround(0.5 * t.frameRate()));
        t.seek(k);
        QVERIFY(t.useCurrentFrameAsStart());
        const double shift = double(k) / t.frameRate();
        QVERIFY(std::abs(doc.body(1).keys[0].time + shift) < 1e-12 &&
                std::abs(doc.body(1).keys[1].time - (1.0 - shift)) < 1e-12);
        QVERIFY((doc.body(1).position - Vec3(shift, 1, 0)).norm() < 1e-12);
    }

    // The path drawn: a polyline from the first key to the last along the path (here the
    // straight line of a linear path, then its turn), a cross at each key; amber when
    // selected; nothing for a body that is not animated.
    void thePathIsDrawnThroughTheKeys() {
        SceneDesc s = emptyScene();
        BodyDesc b = box("paddle");
        insertKey(b, 0.0, Vec3(0, 1, 0), Quat::Identity());
        insertKey(b, 1.0, Vec3(1, 1, 0), Quat::Identity());
        insertKey(b, 2.0, Vec3(1, 2, 0), Quat::Identity());
        s.bodies.push_back(b);
        s.bodies.push_back(box("other"));
        const overlays::Lines plain = overlays::paths(s, {}), chosen = overlays::paths(s, {1});
        QCOMPARE(plain.items, 1);
        const std::vector<float>& v = plain.xyzrgb;
        QCOMPARE(int(v.size()), (2 * 24 + 3 * 3) * 2 * 6);  // 48 segments, three crosses of 3
        auto point = [&](size_t vertex) { return Vec3(v[vertex * 6], v[vertex * 6 + 1], v[vertex * 6 + 2]); };
        for (size_t n = 0; n < 48; ++n) {  // each segment's ends on the two legs
            for (size_t end : {0, 1}) {
                const Vec3 p = point(2 * n + end);
                const bool first = n < 24;
                QVERIFY2(first ? std::abs(p.y() - 1) < 1e-6 && p.x() > -1e-6 && p.x() < 1 + 1e-6
                               : std::abs(p.x() - 1) < 1e-6 && p.y() > 1 - 1e-6 && p.y() < 2 + 1e-6,
                         qPrintable(QString("segment %1: %2 %3").arg(n).arg(p.x()).arg(p.y())));
            }
        }
        QVERIFY((point(0) - Vec3(0, 1, 0)).norm() < 1e-6 && (point(95) - Vec3(1, 2, 0)).norm() < 1e-5);
        QVERIFY(chosen.xyzrgb[3] == 1.0f && plain.xyzrgb[3] != 1.0f);  // amber against grey
    }
};

QTEST_MAIN(TestBodyKeys)
#include "tst_body_keys.moc"
