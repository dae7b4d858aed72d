// The viewport over a timeline: frame k draws every body at the recording's state k
// (scrubbing back and forth is exact), frame 0 the document; handles only at frame 0; a
// click picks a body where it is drawn; a recording with other bodies falls back to the
// document; each overlay counts what the frame has (contact points of a resting box, arrows
// of moving bodies, no force arrow for gravity alone, a trail point per frame, sleeping
// bodies) and nothing while off; the keyboard orbit is on Shift + arrows.
#include "document/document.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"
#include "viewport/viewport_overlays.h"
#include "viewport_test_util.h"

#include <tumble/model.h>

#include <QSignalSpy>
#include <QWindow>
#include <QMouseEvent>
#include <QUndoStack>
#include <QtTest>

#include <cmath>
#include <memory>
#include <set>

using namespace tumble;
using namespace tumble::ui;
using tumble::test::projected;

namespace {

constexpr int kWaitMs = 60000;
using O = Viewport::Overlay;

QVector3D toQt(const Vec3& v) {
    return QVector3D(float(v.x()), float(v.y()), float(v.z()));
}
Vec3 toVec(const QVector3D& v) {
    return Vec3(v.x(), v.y(), v.z());
}
QQuaternion toQt(const Quat& q) {
    const Quat n = q.normalized();
    return QQuaternion(float(n.w()), float(n.x()), float(n.y()), float(n.z()));
}

QMatrix4x4 pose(const Vec3& position, const Quat& orientation) {
    QMatrix4x4 m;
    m.translate(toQt(position));
    m.rotate(toQt(orientation));
    return m;
}

bool near(const QMatrix4x4& a, const QMatrix4x4& b, float tol = 1e-6f) {
    for (int i = 0; i < 16; ++i) {
        if (std::abs(a.constData()[i] - b.constData()[i]) > tol) return false;
    }
    return true;
}

// A sample scene simulated to the end, drawn by a viewport over the timeline.
struct Fixture {
    Document doc;
    std::unique_ptr<Timeline> timeline;
    std::unique_ptr<Viewport> view;
    bool ok = false;

    explicit Fixture(const QString& sample) {
        QString error;
        if (!doc.open(sample, &error)) {
            qWarning() << error;
            return;
        }
        timeline = std::make_unique<Timeline>(&doc);
        view = std::make_unique<Viewport>(&doc);
        view->resize(640, 480);
        view->show();
        view->setTimeline(timeline.get());
        timeline->simulate();
        ok = QTest::qWaitFor([&] { return timeline->status() == Timeline::Status::Complete; }, kWaitMs);
    }

    State frame(int k) const {
        State s;
        if (!timeline->frameState(k, &s)) qWarning() << "no frame" << k;
        return s;
    }
    const Model& model() const { return *timeline->model(); }

    // Every body drawn where frame k has it.
    bool drawsFrame(int k) const {
        const State s = frame(k);
        if (int(s.bodies.size()) != doc.bodyCount()) return false;
        for (int i = 0; i < doc.bodyCount(); ++i) {
            const BodyModel& b = model().bodies[size_t(i)];
            const BodyState& bs = s.bodies[size_t(i)];
            if (!near(view->drawnTransform(i), pose(bodyFramePosition(b, bs), bs.q))) return false;
        }
        return true;
    }
    bool drawsDocument() const {
        for (int i = 0; i < doc.bodyCount(); ++i) {
            if (!near(view->drawnTransform(i), pose(doc.body(i).position, doc.body(i).orientation)))
                return false;
        }
        return true;
    }
};

}  // namespace

class TestViewportPlayback : public QObject {
    Q_OBJECT
private slots:
    // Issue 21 (what to build, 5): Ctrl+drag on a body at the playhead pokes it: a force
    // over one frame from the playhead's time is added to the scene (one undo step), the
    // run is made again, and from that frame the body has taken the impulse: its momentum
    // changed by J exactly (in flight, nothing else differs), the pressed point's velocity
    // along the drag by drag / 0.5 s (to the frame's rotation), nothing before the frame.
    void ctrlDragPokesABodyAtThePlayhead() {
        Fixture f(":/scenes/projectile.json");
        QVERIFY(f.ok);
        const int k = 10, ball = 1;
        f.timeline->seek(k);
        const State before = f.frame(k), after = f.frame(k + 1), early = f.frame(k - 1);
        f.view->setCamera(toQt(before.bodies[ball].x), 3.0f, 0.0f, 0.0f);  // from +z, level
        QApplication::processEvents();
        const QPoint at = projected(*f.view, before.bodies[ball].x);
        const int steps = f.doc.undoStack()->count();
        QTest::mousePress(f.view->renderWindow(), Qt::LeftButton, Qt::ControlModifier, at);
        QMouseEvent move(QEvent::MouseMove, QPointF(at + QPoint(40, 0)), f.view->renderWindow()->mapToGlobal(QPointF(at + QPoint(40, 0))),
                         Qt::NoButton, Qt::LeftButton, Qt::ControlModifier);
        QApplication::sendEvent(f.view->renderWindow(), &move);
        QVERIFY(f.view->pokeArrowShown());  // while dragging: the arrow and its size
        QTest::mouseRelease(f.view->renderWindow(), Qt::LeftButton, Qt::ControlModifier, at + QPoint(80, 0));
        QVERIFY(!f.view->pokeArrowShown());
        QCOMPARE(f.doc.undoStack()->count(), steps + 1);
        const BodyDesc& b = f.doc.body(ball);
        QCOMPARE(b.forces.size(), size_t(1));
        const ForceDesc& poke = b.forces[0];
        QCOMPARE(*poke.start, before.time);
        QVERIFY(std::abs(*poke.end - (before.time + 1.0 / 30.0)) < 1e-12);
        QVERIFY(poke.vector.x() > 0.0 && std::abs(poke.vector.y()) < 1e-9 * poke.vector.norm());
        const Vec3 J = poke.vector / 30.0;
        QVERIFY(QTest::qWaitFor(
            [&] { return f.timeline->status() == Timeline::Status::Complete && !f.timeline->isStale(); }, kWaitMs));
        const State early2 = f.frame(k - 1), after2 = f.frame(k + 1);
        QCOMPARE(early2.bodies[ball].x, early.bodies[ball].x);  // nothing before the poke
        const Vec3 dP = after2.bodies[ball].P - after.bodies[ball].P;
        QVERIFY2((dP - J).norm() < 1e-9 * J.norm(), qPrintable(QString("%1 vs %2").arg(dP.x()).arg(J.x())));
        // The pressed point (on the ball's face towards the camera) took the push: the spin
        // about y changed, the ball's centre moved on along +x faster.
        QVERIFY(after2.bodies[ball].P.x() > after.bodies[ball].P.x());
        QVERIFY(std::abs(after2.bodies[ball].L.y() - after.bodies[ball].L.y()) > 0.0);
        f.doc.undoStack()->undo();
        QVERIFY(f.doc.body(ball).forces.empty());
    }

    void drawsTheFrameAtThePlayheadExactly() {
        Fixture f(":/scenes/tumbling-box.json");
        QVERIFY(f.ok);
        const int last = f.timeline->framesDone() - 1;
        QVERIFY(last > 100);
        QCOMPARE(f.view->shownFrame(), 0);
        QVERIFY(f.drawsDocument());
        // Scrub forward, back, to the end and to the start again.
        for (int k : {1, 10, 97, 40, 3, last, 60, 0, 25}) {
            f.timeline->seek(k);
            QCOMPARE(f.view->shownFrame(), k);
            if (k == 0) {
                QVERIFY(f.drawsDocument());
            } else {
                QVERIFY2(f.drawsFrame(k), qPrintable(QString("frame %1").arg(k)));
            }
        }
        // The box turns: frame 25 is not the document's pose.
        QVERIFY(!f.drawsDocument());
        // Stepping one frame at a time is exact too.
        for (int k = 26; k < 40; ++k) {
            f.timeline->stepForward();
            QVERIFY(f.drawsFrame(k));
        }
    }

    void handlesOnlyAtFrameZeroAndPickingWhereDrawn() {
        Fixture f(":/scenes/bouncing-ball.json");
        QVERIFY(f.ok);
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.view->setCamera(QVector3D(0, 0.6f, 0), 4.0f, 0.0f, 10.0f);
        f.doc.setSelection({1});
        QVERIFY(f.view->handlesVisible());
        // Frame 20 (t = 1/3 s): the ball has fallen about 0.55 m.
        f.timeline->seek(20);
        QVERIFY(!f.view->handlesVisible());
        const Vec3 start = f.doc.body(1).position;
        const Vec3 now = f.frame(20).bodies[1].x;
        QVERIFY(start.y() - now.y() > 0.5);
        f.doc.setSelection({});
        f.view->clickAt(projected(*f.view, now));
        QCOMPARE(f.doc.selection(), QList<int>{1});
        QVERIFY(f.view->bodyAt(projected(*f.view, start)) != 1);  // not where it started
        QVERIFY(!f.view->handlesVisible());                       // selected, still hidden
        f.timeline->seek(0);
        QVERIFY(f.view->handlesVisible());
        QCOMPARE(f.view->bodyAt(projected(*f.view, start)), 1);
        QVERIFY(f.view->bodyAt(projected(*f.view, now)) != 1);
    }

    // Issue 50 item 2: at a later frame an animated body's handles show where it is drawn;
    // a drag moves it there and its end keys that pose at the frame's time (one undo step);
    // the run is redone and passes through the key.
    void anAnimatedBodyIsKeyedByDraggingItAtAFrame() {
        Fixture f(":/scenes/lift.json");
        QVERIFY(f.ok);
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.view->setCamera(QVector3D(0, 1, 0), 8.0f, 20.0f, 15.0f);
        f.doc.setSelection({1});  // the lift
        f.timeline->seek(150);    // 2.5 s: on its way up
        QVERIFY(f.view->handlesVisible());
        const State s = f.frame(150);
        const Vec3 drawn = bodyFramePosition(f.model().bodies[1], s.bodies[1]);
        QVERIFY((toVec(f.view->handlesOrigin()) - drawn).norm() < 1e-5);
        // Drag the x arrow by about half its length.
        const double size = f.view->handlesSize();
        const QPoint from = projected(*f.view, drawn + Vec3(0.8 * size, 0, 0));
        const QPoint to = projected(*f.view, drawn + Vec3(1.3 * size, 0, 0));
        const int steps = f.doc.undoStack()->count();
        QWindow* w = f.view->renderWindow();
        QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
        for (int i = 1; i <= 4; ++i) QTest::mouseMove(w, from + (to - from) * i / 4);
        QCOMPARE(f.doc.undoStack()->count(), steps);  // nothing keyed while it moves
        QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, to);
        QCOMPARE(f.doc.undoStack()->count(), steps + 1);
        const BodyDesc& lift = f.doc.body(1);
        QCOMPARE(int(lift.keys.size()), 3);
        QVERIFY(std::abs(lift.keys[1].time - 2.5) < 1e-12);
        const Vec3 keyed = lift.keys[1].position;
        QVERIFY2(
            keyed.x() > 0.2 * size && std::abs(keyed.y() - drawn.y()) < 1e-9 && std::abs(keyed.z()) < 1e-9,
            qPrintable(QString("keyed at %1 %2 %3").arg(keyed.x()).arg(keyed.y()).arg(keyed.z())));
        // The new run passes through it.
        f.timeline->simulate();
        QVERIFY(QTest::qWaitFor([&] { return f.timeline->status() == Timeline::Status::Complete; }, kWaitMs));
        const State after = f.frame(150);
        QVERIFY((bodyFramePosition(f.model().bodies[1], after.bodies[1]) - keyed).norm() < 1e-9);
        f.doc.undoStack()->undo();
        QCOMPARE(int(f.doc.body(1).keys.size()), 2);
    }

    void aRecordingOfOtherBodiesFallsBackToTheDocument() {
        Fixture f(":/scenes/bouncing-ball.json");
        QVERIFY(f.ok);
        f.timeline->setAutoSimulate(false);
        f.timeline->seek(30);
        QVERIFY(f.drawsFrame(30));
        BodyDesc extra = f.doc.body(1);
        extra.name = "second";
        extra.position = Vec3(1, 2, 0);
        f.doc.addBody(extra);
        QVERIFY(f.timeline->isStale());
        QCOMPARE(f.view->shownFrame(), 0);
        QVERIFY(f.drawsDocument());
        f.view->setOverlay(O::Velocities, true);
        QCOMPARE(f.view->overlayItemCount(O::Velocities), 0);
        // Back to the recording's bodies: its frame is drawn again.
        f.doc.removeBodies({2});
        f.timeline->seek(31);
        QCOMPARE(f.view->shownFrame(), 31);
        QVERIFY(f.drawsFrame(31));
        QCOMPARE(f.view->overlayItemCount(O::Velocities), 1);
        // No timeline: the document.
        f.view->setTimeline(nullptr);
        QCOMPARE(f.view->shownFrame(), 0);
        QVERIFY(f.drawsDocument());
        QCOMPARE(f.view->overlayItemCount(O::Velocities), 0);
        // A timeline deleted under the viewport: the document too.
        f.view->setTimeline(f.timeline.get());
        QCOMPARE(f.view->shownFrame(), 31);
        f.timeline.reset();
        QCOMPARE(f.view->shownFrame(), 0);
        QVERIFY(f.drawsDocument());
        QCOMPARE(f.view->timeline(), nullptr);
    }

    void overlaysAreTogglesAndOffCountsNothing() {
        Fixture f(":/scenes/bouncing-ball.json");
        QVERIFY(f.ok);
        QSignalSpy changed(f.view.get(), &Viewport::overlayChanged);
        f.timeline->seek(10);
        for (int i = 0; i < Viewport::kOverlayCount; ++i) {
            const auto o = O(i);
            QCOMPARE(f.view->overlay(o), o == O::Joints);  // joints on at first, the rest off
            QCOMPARE(f.view->overlayItemCount(o), 0);      // (this scene has none)
            QVERIFY(!Viewport::overlayText(o).isEmpty());
            f.view->setOverlay(o, true);
            QVERIFY(f.view->overlay(o));
        }
        QCOMPARE(changed.count(), Viewport::kOverlayCount - 1);
        f.view->setOverlay(O::Trails, true);  // no change, no signal
        QCOMPARE(changed.count(), Viewport::kOverlayCount - 1);
        // The ball falls, not yet at the ground (t = 1/6 s): one velocity arrow, no spin,
        // gravity only (no force arrow), one centre of mass, no contact, awake.
        QCOMPARE(f.view->overlayItemCount(O::Velocities), 1);
        QCOMPARE(f.view->overlayItemCount(O::AngularVelocities), 0);
        QCOMPARE(f.view->overlayItemCount(O::Forces), 0);
        QCOMPARE(f.view->overlayItemCount(O::CentresOfMass), 1);
        QCOMPARE(f.view->overlayItemCount(O::Contacts), 0);
        QCOMPARE(f.view->overlayItemCount(O::Sleeping), 0);
        QCOMPARE(f.view->overlayItemCount(O::Trails), 1);
        // Frame 0: the ball at rest, no velocity yet.
        f.timeline->seek(0);
        QCOMPARE(f.view->overlayItemCount(O::Velocities), 0);
        QCOMPARE(f.view->overlayItemCount(O::CentresOfMass), 1);
        QCOMPARE(f.view->overlayItemCount(O::Trails), 0);  // a single point
        for (int i = 0; i < Viewport::kOverlayCount; ++i) f.view->setOverlay(O(i), false);
        f.timeline->seek(10);
        for (int i = 0; i < Viewport::kOverlayCount; ++i) QCOMPARE(f.view->overlayItemCount(O(i)), 0);
        QVERIFY(f.view->trailPoints(1).isEmpty());
        QCOMPARE(changed.count(), 2 * Viewport::kOverlayCount - 1);
        QCOMPARE(changed.last().at(1).toBool(), false);
    }

    // The cradle on strings: each of its ten joints drawn as a line from the ball's centre
    // to its point on the frame, while editing (from the document) and at a recorded frame
    // (from that frame's state: the first ball's strings follow it as it swings), and again
    // after an edit moves a ball; off, nothing.
    void jointsAreDrawnWhereTheirAnchorsAre() {
        Fixture f(":/scenes/newtons-cradle-strings.json");
        QVERIFY(f.ok);
        QCOMPARE(f.view->overlayItemCount(O::Joints), 10);
        // The lines themselves (what the overlay draws): the first from ball-1's centre.
        auto firstLine = [](const overlays::Lines& lines) {
            const auto& v = lines.xyzrgb;
            return std::pair{Vec3(v[0], v[1], v[2]), Vec3(v[6], v[7], v[8])};
        };
        const auto [a0, b0] = firstLine(overlays::joints(f.doc.scene()));
        QVERIFY((a0 - Vec3(-0.9, 1.1339745962155614, 0)).norm() < 1e-6);
        QVERIFY((b0 - Vec3(-0.4, 2, 0.5)).norm() < 1e-6);
        f.timeline->seek(15);  // a quarter of a second: ball-1 on its way down
        QCOMPARE(f.view->overlayItemCount(O::Joints), 10);
        const State s = f.frame(15);
        const auto [a1, b1] = firstLine(overlays::joints(f.model(), s));
        QVERIFY((a1 - s.bodies[1].x).norm() < 1e-6);  // the ball's centre (its centre of mass)
        QVERIFY((b1 - Vec3(-0.4, 2, 0.5)).norm() < 1e-6);
        QVERIFY((a1 - a0).norm() > 0.05);
        // Editing: the lines follow the document's bodies.
        f.timeline->seek(0);
        BodyDesc moved = f.doc.body(5);
        moved.position.z() = 0.2;
        f.doc.setBody(5, moved, "Move");
        QCOMPARE(f.view->overlayItemCount(O::Joints), 10);
        f.view->setOverlay(O::Joints, false);
        QCOMPARE(f.view->overlayItemCount(O::Joints), 0);
    }

    // The door's hinge: its axis drawn through anchor A along the world's y (the door's axis
    // as it stands), its limits as an arc about it, and the joint selected in the document
    // drawn in another colour.
    void aHingeShowsItsAxisAndTheSelectedJointStandsOut() {
        Fixture f(":/scenes/hinged-door.json");
        QVERIFY(f.ok);
        auto colours = [](const overlays::Lines& lines) {
            std::set<std::array<float, 3>> out;
            for (size_t k = 0; k + 5 < lines.xyzrgb.size(); k += 6)
                out.insert({lines.xyzrgb[k + 3], lines.xyzrgb[k + 4], lines.xyzrgb[k + 5]});
            return out;
        };
        const overlays::Lines plain = overlays::joints(f.doc.scene());
        QCOMPARE(plain.items, 1);
        // Segment 7 (after the line and the anchors' crosses) is the axis: vertical, through
        // anchor A (the line's first point); then the limits' arc [0, 1.5] rad about it: two
        // spokes 1.5 rad apart, square to the axis.
        const auto& v = plain.xyzrgb;
        auto point = [&](int segmentIndex, int end) {
            const size_t k = size_t(segmentIndex) * 12 + size_t(end) * 6;
            return Vec3(v[k], v[k + 1], v[k + 2]);
        };
        const Vec3 a = point(0, 0), p = point(7, 0), q = point(7, 1);
        QVERIFY(((p + q) / 2 - a).norm() < 1e-6);
        QVERIFY((q - p).normalized().cross(Vec3::UnitY()).norm() < 1e-6);
        const Vec3 s0 = point(8, 1) - point(8, 0), s1 = point(9, 1) - point(9, 0);
        QVERIFY((point(8, 0) - a).norm() < 1e-6 && (point(9, 0) - a).norm() < 1e-6);
        QVERIFY(std::abs(s0.y()) < 1e-6 && std::abs(s1.y()) < 1e-6);
        QVERIFY2(std::abs(std::acos(s0.normalized().dot(s1.normalized())) - 1.5) < 1e-5,
                 qPrintable(QString::number(std::acos(s0.normalized().dot(s1.normalized())))));
        // The door's angle now (0, as placed) is on the arc: its lower end points at the door.
        QVERIFY(s0.normalized().dot(Vec3(1, 0, 0)) > 0.999);
        // Played: the door has turned to its stop (1.5 rad at 2.5 s); the arc stays with the
        // post, where it was drawn while editing.
        f.timeline->seek(150);
        const overlays::Lines played = overlays::joints(f.model(), f.frame(150));
        const auto& w = played.xyzrgb;
        auto playedSpoke = [&](int segmentIndex) {
            const size_t k = size_t(segmentIndex) * 12;
            return Vec3(w[k + 6] - w[k], w[k + 7] - w[k + 1], w[k + 8] - w[k + 2]);
        };
        QVERIFY((playedSpoke(8).normalized() - s0.normalized()).norm() < 1e-3);
        QVERIFY((playedSpoke(9).normalized() - s1.normalized()).norm() < 1e-3);
        f.doc.selectJoint(0);
        const overlays::Lines picked = overlays::joints(f.doc.scene(), f.doc.selectedJoint());
        QCOMPARE(picked.xyzrgb.size(), plain.xyzrgb.size());
        QCOMPARE(colours(picked).size(), size_t(1));  // all of it in the selection's colour
        QVERIFY(colours(picked) != colours(plain));
        QCOMPARE(f.view->overlayItemCount(O::Joints), 1);
    }

    void trailsHaveAPointPerFrameUpToThePlayhead() {
        Fixture f(":/scenes/bouncing-ball.json");
        QVERIFY(f.ok);
        f.view->setOverlay(O::Trails, true);
        for (int k : {45, 12, 120, 1}) {
            f.timeline->seek(k);
            QCOMPARE(f.view->overlayItemCount(O::Trails), 1);  // the ball; not the ground
            QVERIFY(f.view->trailPoints(0).isEmpty());
            const QList<QVector3D> trail = f.view->trailPoints(1);
            QCOMPARE(trail.size(), k + 1);
            for (int j = 0; j <= k; ++j) {
                QVERIFY((trail[j] - toQt(f.frame(j).bodies[1].x)).length() < 1e-6f);
            }
        }
    }

    void longTrailsThinnedEvenlyKeepingTheEnds() {
        std::vector<Vec3> points;
        for (int i = 0; i < 10001; ++i) points.push_back(Vec3(i, 0, 0));
        const std::vector<Vec3> thin = overlays::thinned(points, 4096);
        QCOMPARE(int(thin.size()), 4096);
        QCOMPARE(thin.front().x(), 0.0);
        QCOMPARE(thin.back().x(), 10000.0);
        for (size_t k = 1; k < thin.size(); ++k) {
            const double gap = thin[k].x() - thin[k - 1].x();
            QVERIFY(gap == 2.0 || gap == 3.0);  // 10000 / 4095 = 2.44
        }
        QCOMPARE(int(overlays::thinned(points, 20000).size()), 10001);  // short enough
        QCOMPARE(overlays::trailCap(1), overlays::kMaxTrailPoints);
        QCOMPARE(overlays::trailCap(1000), 200);
        QCOMPARE(overlays::trailCap(100000), overlays::kMinTrailPoints);
    }

    void contactsOfABoxSlidingOnTheGround() {
        Fixture f(":/scenes/sliding-block.json");
        QVERIFY(f.ok);
        f.timeline->seek(30);
        QCOMPARE(f.view->overlayItemCount(O::Contacts), 0);  // off
        f.view->setOverlay(O::Contacts, true);
        // A face on the plane: the four corners.
        QCOMPARE(f.view->overlayItemCount(O::Contacts), 4);
        f.timeline->seek(5);
        QCOMPARE(f.view->overlayItemCount(O::Contacts), 4);
        // It slides: one velocity arrow, and friction is not an applied force.
        f.view->setOverlay(O::Velocities, true);
        f.view->setOverlay(O::Forces, true);
        QCOMPARE(f.view->overlayItemCount(O::Velocities), 1);
        QCOMPARE(f.view->overlayItemCount(O::Forces), 0);
        f.view->setOverlay(O::Contacts, false);
        QCOMPARE(f.view->overlayItemCount(O::Contacts), 0);
    }

    void overlayGeometryFollowsTheStatedScales() {
        // Six floats a vertex, two vertices a segment.
        auto vertexAt = [](const overlays::Lines& l, int v) {
            const float* p = l.xyzrgb.data() + 6 * v;
            return Vec3(p[0], p[1], p[2]);
        };
        Fixture f(":/scenes/sliding-block.json");
        QVERIFY(f.ok);
        const State s = f.frame(30);
        const BodyState& block = s.bodies[1];
        // Contacts: per point a cross (three segments) and the normal, up into the block.
        const overlays::Lines c = overlays::contacts(f.model(), s);
        QCOMPARE(c.items, 4);
        QCOMPARE(int(c.xyzrgb.size()), 4 * 4 * 2 * 6);
        for (int k = 0; k < 4; ++k) {
            const Vec3 p = vertexAt(c, 8 * k + 6), tip = vertexAt(c, 8 * k + 7);
            QVERIFY(std::abs(p.y()) < 1e-3);  // on the ground
            QVERIFY(std::abs(p.x() - block.x.x()) < 0.2 + 1e-3 &&
                    std::abs(p.z() - block.x.z()) < 0.15 + 1e-3);
            QVERIFY(tip.y() - p.y() > 0.1);  // up
            QVERIFY(std::abs(tip.x() - p.x()) < 1e-6 && std::abs(tip.z() - p.z()) < 1e-6);
        }
        // Velocity: from the centre of mass, the distance travelled in 0.1 s.
        const overlays::Lines v = overlays::velocities(f.model(), s);
        QCOMPARE(v.items, 1);
        const Vec3 velocity = block.P / 2.0;  // 2 kg
        QVERIFY((vertexAt(v, 0) - block.x).norm() < 1e-6);
        QVERIFY((vertexAt(v, 1) - (block.x + 0.1 * velocity)).norm() < 1e-6);

        // Force: the spring at frame 0 (at rest, no damping force), F/m times 0.05 s².
        Fixture g(":/scenes/spring-pendulum.json");
        QVERIFY(g.ok);
        const State s0 = g.frame(0);
        const BodyState& bob = s0.bodies[0];
        const Vec3 d = bob.x + bob.q * Vec3(-0.2, 0.1, 0) - Vec3(0, 2, 0);
        const Vec3 spring = -200.0 * (d.norm() - 1.5) * d.normalized();
        const overlays::Lines F = overlays::forces(g.model(), s0);
        QCOMPARE(F.items, 1);
        QVERIFY((vertexAt(F, 0) - bob.x).norm() < 1e-6);
        QVERIFY((vertexAt(F, 1) - (bob.x + 0.05 / 2.0 * spring)).norm() < 1e-5);
    }

    void springForceAndSpinArrows() {
        Fixture f(":/scenes/spring-pendulum.json");
        QVERIFY(f.ok);
        f.view->setOverlay(O::Forces, true);
        f.timeline->seek(20);
        QCOMPARE(f.view->overlayItemCount(O::Forces), 1);  // the spring
        Fixture g(":/scenes/tumbling-box.json");
        QVERIFY(g.ok);
        g.view->setOverlay(O::AngularVelocities, true);
        g.view->setOverlay(O::Forces, true);
        g.timeline->seek(50);
        QCOMPARE(g.view->overlayItemCount(O::AngularVelocities), 1);
        QCOMPARE(g.view->overlayItemCount(O::Forces), 0);  // no force at all
    }

    void sleepingBodiesTinted() {
        Fixture f(":/scenes/sleeping-wake.json");
        QVERIFY(f.ok);
        f.view->setOverlay(O::Sleeping, true);
        int asleep = 0, awake = 0;
        for (int k = 0; k < f.timeline->framesDone(); k += 7) {
            f.timeline->seek(k);
            const State s = f.frame(k);
            int expected = 0;
            for (int i = 0; i < int(s.bodies.size()); ++i) expected += s.isAsleep(i);
            QCOMPARE(f.view->overlayItemCount(O::Sleeping), expected);
            (expected > 0 ? asleep : awake) += 1;
        }
        QVERIFY(asleep > 0);  // the box falls asleep before the ball wakes it
        QVERIFY(awake > 0);
        f.view->setOverlay(O::Sleeping, false);
        QCOMPARE(f.view->overlayItemCount(O::Sleeping), 0);
    }

    void keyboardOrbitOnShiftArrows() {
        Document doc;
        Viewport view(&doc);
        view.resize(640, 480);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setCamera(QVector3D(0, 0, 0), 8.0f, 0.0f, 20.0f);
        QWindow* w = view.renderWindow();
        const QVector3D eye = view.cameraPosition();
        // Left, Right and Home are the timeline's: the camera stays.
        for (int key : {Qt::Key_Left, Qt::Key_Right, Qt::Key_Home}) {
            QTest::keyClick(w, Qt::Key(key));
            QCOMPARE(view.cameraPosition(), eye);
        }
        QTest::keyClick(w, Qt::Key_Left, Qt::ShiftModifier);
        QVERIFY((view.cameraPosition() - eye).length() > 0.5f);
        QTest::keyClick(w, Qt::Key_Right, Qt::ShiftModifier);
        QVERIFY((view.cameraPosition() - eye).length() < 1e-4f);
        QTest::keyClick(w, Qt::Key_Up, Qt::ShiftModifier);
        const QVector3D up = view.cameraPosition();
        QVERIFY(up.y() > eye.y());
        QTest::keyClick(w, Qt::Key_Up);  // plain Up too
        QVERIFY(view.cameraPosition().y() > up.y());
        QTest::keyClick(w, Qt::Key_Down, Qt::ShiftModifier);
        QVERIFY(std::abs(view.cameraPosition().y() - up.y()) < 1e-4f);
    }
};

QTEST_MAIN(TestViewportPlayback)
#include "tst_viewport_playback.moc"
