// The timeline dock as a user drives it: the slider scrubs, the buttons and the window's
// keys move the playhead, the labels say where and how far the run is, Cancel stops it and
// keeps the scene, "Use Frame as Start" is one undo step.
#include "document/document.h"
#include "window/main_window.h"
#include "timeline/timeline.h"
#include "timeline/scrub_slider.h"
#include "timeline/timeline_dock.h"
#include "viewport/viewport.h"

#include <QAction>
#include <QLabel>
#include <QMouseEvent>
#include <QProgressBar>
#include <QSettings>
#include <QSlider>
#include <QSpinBox>
#include <QUndoStack>
#include <QtTest>

#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::ui;

namespace {
constexpr int kWaitMs = 60000;

// Starts the run and waits for it to be done, the dock caught up.
bool runToEnd(Timeline& t) {
    t.simulate();
    const bool done = QTest::qWaitFor([&] { return t.status() == Timeline::Status::Complete; }, kWaitMs);
    QCoreApplication::processEvents();
    return done;
}
}

class TestTimelineDock : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName("tumble-tests");
    }

    // A rod pendulum let go level, its rod breaking at 1.5 m g (at 30 degrees below the
    // level, where the tension 3 m g sin(phi) reaches it): the slider is marked at the first
    // frame without the rod, its text names the joint and the moment, the status counts it.
    void aBrokenJointIsMarkedOnTheSlider() {
        SceneDesc s = emptyScene();
        s.settings.duration = 1.0;
        s.settings.frameRate = 30;
        BodyDesc bob;
        bob.name = "bob";
        bob.shape.type = ShapeType::Sphere;
        bob.shape.radius = 0.05;
        bob.mass = 1.0;
        bob.position = Vec3(1, 2, 0);
        s.bodies.push_back(bob);
        JointDesc rod;
        rod.name = "rod";
        rod.type = JointType::Distance;
        rod.bodyA = "bob";
        rod.anchorB = Vec3(0, 2, 0);
        rod.breakForce = 1.5 * 9.81;
        s.joints.push_back(rod);
        Document doc;
        doc.replaceScene(s, QString(), false);
        Timeline t(&doc);
        TimelineDock dock(&t);
        dock.show();
        QVERIFY(runToEnd(t));
        const auto breaks = t.jointBreaks();
        QCOMPARE(breaks.size(), size_t(1));
        State last;
        QVERIFY(t.frameState(t.framesDone() - 1, &last));
        QVERIFY(last.jointBroken(0));
        QCOMPARE(breaks[0].joint, 0);
        QCOMPARE(breaks[0].time, last.jointBrokenAt[0]);
        const int k = breaks[0].frame;
        QVERIFY(k / 30.0 >= breaks[0].time - 1e-12 && (k - 1) / 30.0 < breaks[0].time);
        State before, at;
        QVERIFY(t.frameState(k - 1, &before) && t.frameState(k, &at));
        QVERIFY(!before.jointBroken(0) && at.jointBroken(0));
        const auto& marks = dock.slider()->marks();
        QCOMPARE(marks.size(), size_t(1));
        QCOMPARE(marks[0].frame, k);
        QVERIFY2(marks[0].text.startsWith("joint rod broke at t = "), qPrintable(marks[0].text));
        QCOMPARE(dock.slider()->textNear(dock.slider()->xOf(k)), marks[0].text);
        QVERIFY(dock.slider()->textNear(dock.slider()->xOf(0)).isEmpty());
        QVERIFY2(dock.statusText().contains("1 joint(s) broke"), qPrintable(dock.statusText()));
        // It broke on its way down, about where the tension reached 1.5 m g: 30 degrees.
        const double phi = std::asin((2.0 - before.bodies[1].x.y()) / 1.0);
        QVERIFY2(phi < std::numbers::pi / 6 && phi > std::numbers::pi / 6 - 0.2, qPrintable(QString::number(phi)));
    }

    void sliderScrubsAndLabelsFollow() {
        Document doc;
        QString error;
        QVERIFY(doc.open(":/scenes/projectile.json", &error));
        Timeline t(&doc);
        TimelineDock dock(&t);
        dock.show();
        QVERIFY(runToEnd(t));
        const int last = t.frameCount() - 1;  // 2 s at 30 frames/s
        QCOMPARE(last, 60);
        QCOMPARE(dock.slider()->maximum(), last);
        auto* progress = dock.findChild<QProgressBar*>("progress");
        QCOMPARE(progress->value(), last + 1);
        QVERIFY2(dock.statusText().startsWith("Done"), qPrintable(dock.statusText()));

        dock.slider()->setValue(30);
        QCOMPARE(t.currentFrame(), 30);
        QCOMPARE(dock.positionText(), QString("t = 1.000 s   frame 30 / 60"));
        t.seek(45);
        QCOMPARE(dock.slider()->value(), 45);

        dock.stepBackAction()->trigger();
        QCOMPARE(t.currentFrame(), 44);
        dock.stepForwardAction()->trigger();
        dock.stepForwardAction()->trigger();
        QCOMPARE(t.currentFrame(), 46);
        dock.toStartAction()->trigger();
        QCOMPARE(t.currentFrame(), 0);
        QVERIFY(!dock.useFrameAction()->isEnabled());  // frame 0 is the start already
        dock.toEndAction()->trigger();
        QCOMPARE(t.currentFrame(), last);
        QVERIFY(dock.useFrameAction()->isEnabled());

        dock.playAction()->trigger();  // from the end: plays from the start
        QVERIFY(t.isPlaying());
        QCOMPARE(dock.playAction()->text(), QString("Pause"));
        dock.playAction()->trigger();
        QVERIFY(!t.isPlaying());
        QCOMPARE(dock.playAction()->text(), QString("Play"));
    }

    // Issue 21 item 9: a click on the track jumps to the frame under the pointer (not ten
    // frames towards it), and a drag from there scrubs on.
    void aClickOnTheTrackJumpsThere() {
        Document doc;
        QString error;
        QVERIFY(doc.open(":/scenes/projectile.json", &error));
        Timeline t(&doc);
        TimelineDock dock(&t);
        dock.resize(900, 120);
        dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&dock));
        QVERIFY(runToEnd(t));
        ScrubSlider* slider = dock.slider();
        t.seek(0);
        QCOMPARE(slider->value(), 0);
        const int y = slider->height() / 2;
        QTest::mouseClick(slider, Qt::LeftButton, Qt::NoModifier, QPoint(slider->xOf(45), y));
        QCOMPARE(t.currentFrame(), 45);
        QCOMPARE(slider->valueAt(slider->xOf(45)), 45);
        QTest::mouseClick(slider, Qt::LeftButton, Qt::NoModifier, QPoint(slider->xOf(12), y));
        QCOMPARE(t.currentFrame(), 12);
        // Press on the track, drag: the handle follows from the frame pressed.
        QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, QPoint(slider->xOf(30), y));
        QCOMPARE(t.currentFrame(), 30);
        QMouseEvent move(QEvent::MouseMove, QPointF(slider->xOf(50), y), slider->mapToGlobal(QPointF(slider->xOf(50), y)),
                         Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(slider, &move);
        QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, QPoint(slider->xOf(50), y));
        QCOMPARE(t.currentFrame(), 50);
    }

    // Issue 50 item 2: the selected animated body's keys are amber ticks under the groove;
    // Edit > Insert Key keys its pose at the playhead; a tick dragged moves its key, a right
    // click deletes it (the playhead stays); each is one undo step.
    void keysAreTicksToDragAndDelete() {
        MainWindow w;
        Document& doc = *w.document();
        BodyDesc paddle;
        paddle.name = "paddle";
        paddle.motion = Motion::Animated;
        paddle.shape.type = ShapeType::Box;
        paddle.shape.halfExtents = Vec3(0.1, 0.3, 0.3);
        paddle.keys = {{0.0, Vec3(0, 1, 0), Quat::Identity()}, {1.0, Vec3(1, 1, 0), Quat::Identity()}};
        const int i = doc.addBody(paddle);
        doc.setSelection({i});
        w.resize(1200, 800);
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        Timeline& t = *w.timeline();
        QVERIFY(runToEnd(t));
        ScrubSlider* slider = w.timelineDock()->slider();
        const double rate = t.frameRate();
        auto keyMarks = [&] {
            std::vector<int> frames;
            for (const ScrubSlider::Mark& m : slider->marks())
                if (m.key >= 0) frames.push_back(m.frame);
            return frames;
        };
        QCOMPARE(keyMarks(), std::vector<int>({0, int(std::lround(rate))}));
        // Insert Key at frame 30: the pose the run has there, between the two keys.
        t.seek(30);
        QAction* insert = w.findChild<QAction*>("insertKey");
        QVERIFY(insert);
        const int steps = doc.undoStack()->count();
        insert->trigger();
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        QCOMPARE(int(doc.body(i).keys.size()), 3);
        QVERIFY(std::abs(doc.body(i).keys[1].time - 30 / rate) < 1e-12);
        QVERIFY((doc.body(i).keys[1].position - Vec3(30 / rate, 1, 0)).norm() < 1e-9);
        QVERIFY(runToEnd(t));
        QCOMPARE(keyMarks().size(), size_t(3));
        // Drag the tick of the key at 1 s to frame 45: it is then the middle key's neighbour.
        t.seek(10);
        const int y = slider->height() - 2;
        const int from = slider->xOf(int(std::lround(rate))), to = slider->xOf(45);
        QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, QPoint(from, y));
        QMouseEvent move(QEvent::MouseMove, QPointF(to, y), slider->mapToGlobal(QPointF(to, y)), Qt::NoButton,
                         Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(slider, &move);
        QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, QPoint(to, y));
        QVERIFY(std::abs(doc.body(i).keys[2].time - 45 / rate) < 1e-12);
        QCOMPARE(doc.body(i).keys[2].position, Vec3(1, 1, 0));
        QCOMPARE(doc.undoStack()->count(), steps + 2);
        QVERIFY(runToEnd(t));
        t.seek(10);
        // A right click on the middle key's tick deletes it; the playhead stays.
        QTest::mouseClick(slider, Qt::RightButton, Qt::NoModifier, QPoint(slider->xOf(30), y));
        QCOMPARE(int(doc.body(i).keys.size()), 2);
        QCOMPARE(t.currentFrame(), 10);
        doc.undoStack()->undo();
        QCOMPARE(int(doc.body(i).keys.size()), 3);
    }

    void editMarksStaleInTheStatus() {
        Document doc;
        QString error;
        QVERIFY(doc.open(":/scenes/projectile.json", &error));
        Timeline t(&doc);
        TimelineDock dock(&t);
        t.setAutoSimulate(false);
        QVERIFY(runToEnd(t));
        BodyDesc b = doc.body(1);
        b.velocity.x() = 4.0;
        doc.setBody(1, b, "Velocity");
        QVERIFY2(dock.statusText().contains("stale"), qPrintable(dock.statusText()));
        t.toEnd();
        QVERIFY(!dock.useFrameAction()->isEnabled());  // a stale frame is not the edited scene's
        dock.simulateAction()->trigger();
        QVERIFY(QTest::qWaitFor([&] { return t.status() == Timeline::Status::Complete; }, kWaitMs));
        QVERIFY(!dock.statusText().contains("stale"));
    }

    // The engine's notes on the scene (here a joint that does not hold as placed) are counted
    // in the status and read in its tooltip.
    void notesOfTheRunAreShown() {
        Document doc;
        QString error;
        QVERIFY(doc.open(":/scenes/projectile.json", &error));
        JointDesc pin;
        pin.name = "pin";
        pin.bodyA = doc.body(1).name;
        pin.anchorB = doc.body(1).position + Vec3(0.5, 0, 0);
        doc.addJoint(pin);
        Timeline t(&doc);
        TimelineDock dock(&t);
        t.setAutoSimulate(false);
        QVERIFY(runToEnd(t));
        QVERIFY2(dock.statusText().contains("1 note(s): hover to read"), qPrintable(dock.statusText()));
        auto* status = dock.findChild<QLabel*>("status");
        QVERIFY(status);
        QCOMPARE(status->toolTip(), QString("joints[0] (pin): does not hold in the scene as written (off by 0.5 m); "
                                            "the first step pulls it together, giving its bodies that move's speed"));
    }

    // In the editor: the window's keys drive the playhead wherever the focus is, and
    // Cancel during a long run keeps the scene and its undo history.
    void windowKeysAndCancel() {
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        QString error;
        QVERIFY(w.openScene(":/scenes/projectile.json", &error));
        Timeline* t = w.timeline();
        QVERIFY(QTest::qWaitFor([&] { return t->status() == Timeline::Status::Complete; }, kWaitMs));
        w.activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(&w));
        QTest::keyClick(&w, Qt::Key_End, Qt::ControlModifier);  // (End alone: Drop to Surface)
        QCOMPARE(t->currentFrame(), t->frameCount() - 1);
        QTest::keyClick(&w, Qt::Key_Left);
        QCOMPARE(t->currentFrame(), t->frameCount() - 2);
        QTest::keyClick(&w, Qt::Key_Home);
        QCOMPARE(t->currentFrame(), 0);
        QTest::keyClick(&w, Qt::Key_Right);
        QCOMPARE(t->currentFrame(), 1);
        QTest::keyClick(&w, Qt::Key_Space);
        QVERIFY(t->isPlaying());
        QTest::keyClick(&w, Qt::Key_Space);
        QVERIFY(!t->isPlaying());
        // With the 3D view focused too (its own keys are the letters and Shift+arrows).
        w.viewport()->setFocus();
        QTest::keyClick(w.viewport()->renderWindow(), Qt::Key_Right);
        QCOMPARE(t->currentFrame(), 2);
        QTest::keyClick(w.viewport()->renderWindow(), Qt::Key_End, Qt::ControlModifier);
        QCOMPARE(t->currentFrame(), t->frameCount() - 1);

        // A long run: cancel keeps the frames made and the scene.
        SceneDesc s = w.document()->scene();
        s.settings.duration = 100000.0;
        s.settings.dt = 2e-5;  // 5e9 steps: long, under the 10^10 a scene may ask
        w.document()->setSettings(s.settings, "Long");
        const SceneDesc scene = w.document()->scene();
        const int undo = w.document()->undoStack()->count();
        QVERIFY(QTest::qWaitFor(
            [&] { return t->status() == Timeline::Status::Running && t->framesDone() > 2; }, kWaitMs));
        w.timelineDock()->cancelAction()->trigger();
        QVERIFY(QTest::qWaitFor([&] { return t->status() == Timeline::Status::Cancelled; }, kWaitMs));
        QVERIFY(w.document()->scene() == scene);
        QCOMPARE(w.document()->undoStack()->count(), undo);
        QVERIFY(w.timelineDock()->statusText().startsWith("Cancelled"));
    }

    void memoryCapField() {
        QSettings().remove("timeline/memoryCapMB");
        Document doc;
        Timeline t(&doc);
        TimelineDock dock(&t);
        auto* cap = dock.findChild<QSpinBox*>("memoryCap");
        QCOMPARE(cap->value(), 512);
        cap->setValue(64);
        QCOMPARE(t.memoryCap(), std::size_t(64) << 20);
        // Remembered for the next window.
        Timeline t2(&doc);
        TimelineDock dock2(&t2);
        QCOMPARE(t2.memoryCap(), std::size_t(64) << 20);
        QCOMPARE(dock2.findChild<QSpinBox*>("memoryCap")->value(), 64);
        cap->setValue(512);
    }
};

QTEST_MAIN(TestTimelineDock)
#include "tst_timeline_dock.moc"
