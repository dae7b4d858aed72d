// The viewport's handles and collision wireframes: a drag on an axis handle moves the
// selection along that axis by the distance between the mouse rays' nearest points on the
// axis, a drag on a ring turns it by the angle between the rays' hits on the ring's plane,
// both snapped on request, each drag one undo step, Escape cancels one and leaves no step;
// planes stay where they are; the collision shapes appear and disappear as line entities.
#include "document/document.h"
#include "document/joint_presets.h"
#include "viewport/viewport.h"
#include "viewport/viewport_handles.h"
#include "viewport_test_util.h"
#include "viewport/viewport_wire.h"

#include <tumble/mass.h>

#include <QSignalSpy>
#include <QUndoStack>
#include <QWindow>
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <memory>

using namespace tumble;
using namespace tumble::ui;
using tumble::test::body;
using tumble::test::projected;

namespace {

Vec3 toVec(const QVector3D& v) {
    return Vec3(v.x(), v.y(), v.z());
}

// What the drag from `from` to `to` along `axis` through `origin` must move by.
double axisDistance(const Viewport& v, const QPoint& from, const QPoint& to, const Vec3& origin,
                    const Vec3& axis) {
    QVector3D o0, d0, o1, d1;
    v.rayAt(from, &o0, &d0);
    v.rayAt(to, &o1, &d1);
    return *handles::axisParameter(toVec(o1), toVec(d1), origin, axis) -
           *handles::axisParameter(toVec(o0), toVec(d0), origin, axis);
}

// What the drag from `from` to `to` on the ring about `axis` through `origin` must turn by.
double ringAngle(const Viewport& v, const QPoint& from, const QPoint& to, const Vec3& origin,
                 const Vec3& axis) {
    QVector3D o0, d0, o1, d1;
    v.rayAt(from, &o0, &d0);
    v.rayAt(to, &o1, &d1);
    const Vec3 a = *handles::planeHit(toVec(o0), toVec(d0), origin, axis) - origin;
    const Vec3 b = *handles::planeHit(toVec(o1), toVec(d1), origin, axis) - origin;
    return handles::signedAngle(a, b, axis);
}

void drag(Viewport& v, const QPoint& from, const QPoint& to, Qt::KeyboardModifiers releaseModifiers = {}) {
    QWindow* w = v.renderWindow();
    QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
    for (int i = 1; i <= 4; ++i) QTest::mouseMove(w, from + (to - from) * i / 4);
    QTest::mouseRelease(w, Qt::LeftButton, releaseModifiers, to);
}

// The ground (0), a ball (1) at (0, 1, 0) and a crate (2) at (2, 0.5, 0), seen from the
// front, a little to the right and above, so no axis is seen end-on.
struct Fixture {
    Document doc;
    std::unique_ptr<Viewport> view;
    explicit Fixture(float pitch = 20.0f) {
        doc.addBody(body("ball", ShapeType::Sphere, Vec3(0, 1, 0)));
        doc.addBody(body("crate", ShapeType::Box, Vec3(2, 0.5, 0)));
        doc.undoStack()->clear();
        view = std::make_unique<Viewport>(&doc);
        view->resize(800, 600);
        view->show();
        view->setCamera(QVector3D(1, 0.75f, 0), 9.0f, 20.0f, pitch);
    }
    Vec3 origin() const { return toVec(view->handlesOrigin()); }
    double size() const { return view->handlesSize(); }
};

constexpr double kPi = 3.14159265358979323846;

}  // namespace

class TestViewportHandles : public QObject {
    Q_OBJECT
private slots:
    // ---- The math, against closed forms.

    void axisParameterIsTheNearestPointOnTheAxis() {
        // A ray straight down the z axis at x = 3 crosses the x axis at s = 3.
        QCOMPARE(*handles::axisParameter(Vec3(3, 5, 10), Vec3(0, -0.5, -1), Vec3::Zero(), Vec3::UnitX()),
                 3.0);
        // Through an origin at (1, 0, 0): s counts from there.
        QCOMPARE(*handles::axisParameter(Vec3(3, 5, 10), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3::UnitX()), 2.0);
        // A ray along the axis has no nearest point.
        QVERIFY(!handles::axisParameter(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3::Zero(), Vec3::UnitX()));
    }

    void planeHitAndSignedAngle() {
        const auto hit = handles::planeHit(Vec3(2, 5, 1), Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3::UnitY());
        QVERIFY(hit && (*hit - Vec3(2, 1, 1)).norm() < 1e-15);
        QVERIFY(!handles::planeHit(Vec3(2, 5, 1), Vec3(0, 1, 0), Vec3(0, 1, 0), Vec3::UnitY()));  // away
        // A right-handed quarter turn about +y takes +x to -z.
        QVERIFY(std::abs(handles::signedAngle(Vec3(1, 0, 0), Vec3(0, 0, -1), Vec3::UnitY()) - kPi / 2) <
                1e-15);
        QVERIFY(std::abs(handles::signedAngle(Vec3(1, 7, 0), Vec3(0, -3, 2), Vec3::UnitY()) + kPi / 2) <
                1e-15);
        QCOMPARE(handles::snap(1.26, 0.1), 1.3);
        QCOMPARE(handles::snap(-0.04, 0.1), 0.0);
        QCOMPARE(handles::snap(0.37, 0.0), 0.37);
        // A turn of a body beside the pivot carries it round.
        const BodyDesc b =
            handles::rotated(body("b", ShapeType::Box, Vec3(1, 0, 0)), Vec3::Zero(), Vec3::UnitY(), kPi / 2);
        QVERIFY((b.position - Vec3(0, 0, -1)).norm() < 1e-15);
    }

    // ---- Dragging.

    void theModeKeysSwitchTheHandles() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        QSignalSpy spy(f.view.get(), &Viewport::transformModeChanged);
        QCOMPARE(f.view->transformMode(), Viewport::TransformMode::Move);
        QTest::keyClick(f.view->renderWindow(), Qt::Key_E);
        QCOMPARE(f.view->transformMode(), Viewport::TransformMode::Rotate);
        QTest::keyClick(f.view->renderWindow(), Qt::Key_W);
        QCOMPARE(f.view->transformMode(), Viewport::TransformMode::Move);
        QCOMPARE(spy.count(), 2);
        // No handles without a selection, nor for a plane alone.
        QVERIFY(!f.view->handlesVisible());
        f.doc.setSelection({0});
        QVERIFY(!f.view->handlesVisible());
        f.doc.setSelection({1});
        QVERIFY(f.view->handlesVisible());
        QCOMPARE(f.origin(), Vec3(0, 1, 0));
    }

    void aDragOnTheXHandleMovesAlongXOnlyInOneUndoStep() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({1});
        const Vec3 o = f.origin();
        const double L = f.size();
        const QPoint from = projected(*f.view, o + 0.6 * L * Vec3::UnitX());
        const QPoint to = projected(*f.view, o + (0.6 * L + 1.23) * Vec3::UnitX());
        QCOMPARE(f.view->handleAt(from), 0);
        const double expected = axisDistance(*f.view, from, to, o, Vec3::UnitX());
        QVERIFY2(std::abs(expected - 1.23) < 0.03, qPrintable(QString::number(expected)));  // a pixel's worth

        drag(*f.view, from, to);
        const BodyDesc& b = f.doc.body(1);
        QVERIFY(std::abs(b.position.x() - expected) < 1e-9);
        QCOMPARE(b.position.y(), 1.0);
        QCOMPARE(b.position.z(), 0.0);
        QVERIFY(b.orientation.isApprox(Quat::Identity(), 0.0));
        QCOMPARE(f.doc.selection(), QList<int>({1}));  // a handle drag is no click
        QCOMPARE(f.doc.undoStack()->count(), 1);
        // The handles followed the body.
        QVERIFY((f.origin() - b.position).norm() < 1e-6);  // in floats
        f.doc.undoStack()->undo();
        QCOMPARE(f.doc.body(1).position, Vec3(0, 1, 0));
        QCOMPARE(f.doc.body(2).position, Vec3(2, 0.5, 0));

        // A second drag is a second step.
        f.doc.undoStack()->redo();
        drag(*f.view, projected(*f.view, f.origin() + 0.6 * L * Vec3::UnitX()),
             projected(*f.view, f.origin() + (0.6 * L - 0.5) * Vec3::UnitX()));
        QCOMPARE(f.doc.undoStack()->count(), 2);
        QVERIFY(std::abs(f.doc.body(1).position.x() - (expected - 0.5)) < 0.03);
    }

    void snappingRoundsTheMoveToTheStep() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({1});
        const Vec3 o = f.origin();
        const double L = f.size();
        const QPoint from = projected(*f.view, o + 0.6 * L * Vec3::UnitX());
        const QPoint to = projected(*f.view, o + (0.6 * L + 1.23) * Vec3::UnitX());
        const double expected = axisDistance(*f.view, from, to, o, Vec3::UnitX());
        QVERIFY(std::abs(expected - 1.2) > 1e-3);  // so snapping shows

        f.view->setSnapping(true);
        QCOMPARE(f.view->translationSnap(), 0.1);
        drag(*f.view, from, to);
        QVERIFY(std::abs(f.doc.body(1).position.x() - 1.2) < 1e-12);
        f.doc.undoStack()->undo();

        // Ctrl at the end of the drag snaps too, to a step of 0.25 m.
        f.view->setSnapping(false);
        f.view->setTranslationSnap(0.25);
        drag(*f.view, from, to, Qt::ControlModifier);
        QVERIFY(std::abs(f.doc.body(1).position.x() - 1.25) < 1e-12);
        QCOMPARE(f.doc.body(1).position.y(), 1.0);
    }

    void aRingDragTurnsAboutYOnlyByTheDraggedAngle() {
        Fixture f(50.0f);  // from higher up, the y ring is a wide ellipse
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({2});
        f.view->renderWindow()->requestActivate();
        QTest::keyClick(f.view->renderWindow(), Qt::Key_E);
        QCOMPARE(f.view->transformMode(), Viewport::TransformMode::Rotate);
        const Vec3 o = f.origin();
        const double L = f.size();
        // On the y ring: from its point towards +z to 0.65 rad further, towards +x.
        auto onRing = [&](double phi) {
            return o + L * (std::cos(phi) * Vec3::UnitZ() + std::sin(phi) * Vec3::UnitX());
        };
        const QPoint from = projected(*f.view, onRing(0.0));
        const QPoint to = projected(*f.view, onRing(0.65));
        QCOMPARE(f.view->handleAt(from), 1);
        const double expected = ringAngle(*f.view, from, to, o, Vec3::UnitY());
        QVERIFY2(std::abs(expected - 0.65) < 0.03, qPrintable(QString::number(expected)));

        drag(*f.view, from, to);
        const BodyDesc& b = f.doc.body(2);
        QCOMPARE(b.position, Vec3(2, 0.5, 0));  // turned about its own centre
        QVERIFY(std::abs(b.orientation.x()) < 1e-12);
        QVERIFY(std::abs(b.orientation.z()) < 1e-12);
        QVERIFY(std::abs(2.0 * std::atan2(b.orientation.y(), b.orientation.w()) - expected) < 1e-9);
        QCOMPARE(f.doc.undoStack()->count(), 1);
        f.doc.undoStack()->undo();
        QVERIFY(f.doc.body(2).orientation.isApprox(Quat::Identity(), 0.0));

        // Snapped: to the nearest 15°, here 30°.
        f.view->setSnapping(true);
        QCOMPARE(f.view->rotationSnapDegrees(), 15.0);
        drag(*f.view, from, to);
        const Quat q = f.doc.body(2).orientation;
        QVERIFY(std::abs(2.0 * std::atan2(q.y(), q.w()) - kPi / 6) < 1e-12);
        QVERIFY(std::abs(q.x()) < 1e-15 && std::abs(q.z()) < 1e-15);
    }

    // A selected joint's handles stand on its anchor: a drag on x moves the joined point (both
    // anchors, each in its own body's frame, so the joint still holds as placed) in one step;
    // in rotate mode a ring turns a hinge's axis; a joint without an axis has no rings.
    void aJointsHandlesMoveItsAnchorAndTurnItsAxis() {
        Fixture f(50.0f);
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        BodyDesc crate = f.doc.body(2);
        crate.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()));
        f.doc.setBody(2, crate, "turn");
        JointDesc hinge;
        hinge.name = "hinge";
        hinge.type = JointType::Hinge;
        hinge.bodyA = "crate";
        hinge.bodyB = "ball";
        hinge.anchorA = crate.orientation.conjugate() * (Vec3(1, 0.75, 0) - crate.position);
        hinge.anchorB = Vec3(1, 0.75, 0) - Vec3(0, 1, 0);
        hinge.axisA = crate.orientation.conjugate() * Vec3::UnitY();
        f.doc.addJoint(hinge);
        f.doc.undoStack()->clear();
        QCOMPARE(f.doc.selectedJoint(), 0);
        QVERIFY(f.view->handlesVisible());
        QVERIFY((f.origin() - Vec3(1, 0.75, 0)).norm() < 1e-6);
        const double L = f.size();
        const Vec3 o = f.origin();
        const QPoint from = projected(*f.view, o + 0.6 * L * Vec3::UnitX());
        const QPoint to = projected(*f.view, o + (0.6 * L + 0.4) * Vec3::UnitX());
        QCOMPARE(f.view->handleAt(from), 0);
        const double expected = axisDistance(*f.view, from, to, o, Vec3::UnitX());
        drag(*f.view, from, to);
        QCOMPARE(f.doc.undoStack()->count(), 1);
        const JointDesc& j = f.doc.joint(0);
        const Vec3 worldA = crate.position + crate.orientation * j.anchorA;
        const Vec3 worldB = Vec3(0, 1, 0) + j.anchorB;
        QVERIFY((worldA - Vec3(1 + expected, 0.75, 0)).norm() < 1e-9);
        QVERIFY((worldB - worldA).norm() < 1e-12);  // still one point
        QVERIFY((f.origin() - worldA).norm() < 1e-5);  // the handles followed
        QCOMPARE(*j.axisA, *hinge.axisA);  // a move does not turn

        // Rotate: the z ring turns the axis about z by the dragged angle.
        f.view->setTransformMode(Viewport::TransformMode::Rotate);
        QVERIFY(f.view->handlesVisible());
        const Vec3 p = f.origin();
        auto onRing = [&](double phi) { return p + L * (std::cos(phi) * Vec3::UnitX() + std::sin(phi) * Vec3::UnitY()); };
        const QPoint a = projected(*f.view, onRing(0.3)), b = projected(*f.view, onRing(0.8));
        QCOMPARE(f.view->handleAt(a), 2);
        const double angle = ringAngle(*f.view, a, b, p, Vec3::UnitZ());
        drag(*f.view, a, b);
        const Vec3 axis = crate.orientation * *f.doc.joint(0).axisA;
        // (The expected angle is from the handles' origin as the viewport reports it, in floats.)
        QVERIFY((axis - Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())) * Vec3::UnitY()).norm() < 1e-6);
        QVERIFY(angle > 0.3);
        QCOMPARE(f.doc.undoStack()->count(), 2);
        f.doc.undoStack()->undo();
        QCOMPARE(*f.doc.joint(0).axisA, *hinge.axisA);

        // A click on the joint's anchor selects it, one on the crate away from it the crate;
        // with the Joints overlay off the anchor is the bodies' again.
        f.doc.setSelection({});
        const QPoint anchor = projected(*f.view, worldAnchorA(f.doc.scene(), f.doc.joint(0)));
        QCOMPARE(f.view->jointAt(anchor), 0);
        f.view->clickAt(anchor);
        QCOMPARE(f.doc.selectedJoint(), 0);
        f.view->clickAt(projected(*f.view, crate.position + Vec3(0.3, 0.3, 0)));
        QCOMPARE(f.doc.selectedJoint(), -1);
        QCOMPARE(f.doc.selection(), QList<int>({2}));
        f.view->setOverlay(Viewport::Overlay::Joints, false);
        QCOMPARE(f.view->jointAt(anchor), -1);
        f.view->setOverlay(Viewport::Overlay::Joints, true);
        f.doc.selectJoint(0);

        // A ball joint has nothing to turn: no rings; in move mode its handles are back.
        JointDesc ball = f.doc.joint(0);
        ball.type = JointType::Ball;
        ball.axisA.reset();
        f.doc.setJoint(0, ball, "ball");
        QVERIFY(!f.view->handlesVisible());
        f.view->setTransformMode(Viewport::TransformMode::Move);
        QVERIFY(f.view->handlesVisible());
        // The math: a rod's ends are apart, and only A's moves.
        JointDesc rod = ball;
        rod.type = JointType::Distance;
        const JointDesc moved = handles::movedAnchor(f.doc.scene(), rod, Vec3::UnitZ(), 0.5);
        QCOMPARE(moved.anchorB, rod.anchorB);
        QVERIFY((worldAnchorA(f.doc.scene(), moved) - worldAnchorA(f.doc.scene(), rod) -
                 Vec3(0, 0, 0.5)).norm() < 1e-12);
    }

    // A ball joint's limit grips, against closed forms: a cone's half-angle is the hit's
    // angle from n in the plane of n and the grip's direction (a round cone stays round, an
    // elliptical one changes one half-angle); a twist bound the hit's angle about n from e1,
    // snapped to the step, kept within the other bound.
    void ballLimitGripMath() {
        const BallLimitFrame f{Vec3::Zero(), Vec3::UnitY(), Vec3::UnitX(), 1.0};
        JointDesc j;
        j.type = JointType::Ball;
        j.swingLimit = std::array<double, 2>{0.5, 0.5};
        j.twistLimits = std::array<double, 2>{-0.3, 0.4};
        const double angle = std::atan2(0.8, 0.6);
        JointDesc out = handles::draggedBallLimit(f, j, 0, Vec3(0.8, 0.6, 5), Vec3(0, 0, -1), 0.0);
        QVERIFY(std::abs((*out.swingLimit)[0] - angle) < 1e-12 && (*out.swingLimit)[1] == (*out.swingLimit)[0]);
        j.swingLimit = std::array<double, 2>{0.5, 0.7};  // towards e2 = n × e1 = −z
        out = handles::draggedBallLimit(f, j, 1, Vec3(5, 0.6, -0.8), Vec3(-1, 0, 0), 0.0);
        QVERIFY(std::abs((*out.swingLimit)[1] - angle) < 1e-12);
        QCOMPARE((*out.swingLimit)[0], 0.5);
        out = handles::draggedBallLimit(f, j, 2, Vec3(0.6, 5, 0.8), Vec3(0, -1, 0), 0.0);
        QVERIFY(std::abs((*out.twistLimits)[0] + angle) < 1e-12);  // (0.6, 0, 0.8): −53° about y from x
        out = handles::draggedBallLimit(f, j, 2, Vec3(0.6, 5, 0.8), Vec3(0, -1, 0), kPi / 12);
        QVERIFY(std::abs((*out.twistLimits)[0] + kPi / 3) < 1e-12);
        out = handles::draggedBallLimit(f, j, 3, Vec3(0.6, 5, 0.8), Vec3(0, -1, 0), 0.0);
        QCOMPARE((*out.twistLimits)[1], -0.3);  // not below the lower bound
        // The grips stand where the limits are drawn.
        const Vec3 rim = *ballLimitGrip(f, j, 0);
        QVERIFY((rim - Vec3(std::sin(0.5), std::cos(0.5), 0)).norm() < 1e-12);
    }

    // A selected ball joint's cone and twist are set by dragging their grips in the
    // viewport, one undo step a drag.
    void aBallJointsLimitsAreDraggedByTheirGrips() {
        Fixture f(50.0f);
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        JointDesc j;
        j.name = "neck";
        j.type = JointType::Ball;
        j.bodyA = "ball";
        j.anchorB = Vec3(0, 1, 0);
        j.axisA = Vec3::UnitY();
        j.swingLimit = std::array<double, 2>{0.5, 0.5};
        j.twistLimits = std::array<double, 2>{-0.5, 0.5};
        f.doc.addJoint(j);
        f.doc.undoStack()->clear();
        QCOMPARE(f.doc.selectedJoint(), 0);
        const BallLimitFrame frame = *ballLimitFrame(f.doc.scene(), f.doc.joint(0));
        const QPoint from = projected(*f.view, *ballLimitGrip(frame, j, 0));
        QCOMPARE(f.view->handleAt(from), 3);
        const QPoint to = projected(*f.view, frame.anchor + frame.size * (std::cos(0.8) * frame.n +
                                                                         std::sin(0.8) * frame.e1));
        QVector3D o, d;
        f.view->rayAt(to, &o, &d);
        const double expected = (*handles::draggedBallLimit(frame, j, 0, toVec(o), toVec(d), 0.0).swingLimit)[0];
        drag(*f.view, from, to);
        QCOMPARE(f.doc.undoStack()->count(), 1);
        QCOMPARE((*f.doc.joint(0).swingLimit)[0], expected);
        QCOMPARE((*f.doc.joint(0).swingLimit)[1], expected);  // round, still
        QVERIFY(std::abs(expected - 0.8) < 0.02);
        // The upper twist bound, from 0.5 to 1.2 rad about n.
        const JointDesc now = f.doc.joint(0);
        const Vec3 e2 = frame.n.cross(frame.e1);
        const QPoint twistFrom = projected(*f.view, *ballLimitGrip(frame, now, 3));
        QCOMPARE(f.view->handleAt(twistFrom), 6);
        const QPoint twistTo = projected(*f.view, frame.anchor + frame.size / 3 * (std::cos(1.2) * frame.e1 +
                                                                                  std::sin(1.2) * e2));
        drag(*f.view, twistFrom, twistTo);
        QCOMPARE(f.doc.undoStack()->count(), 2);
        QVERIFY(std::abs((*f.doc.joint(0).twistLimits)[1] - 1.2) < 0.03);
        QCOMPARE((*f.doc.joint(0).twistLimits)[0], -0.5);
        f.doc.undoStack()->undo();
        QCOMPARE((*f.doc.joint(0).twistLimits)[1], 0.5);
    }

    void aMultiSelectionDragMovesEveryBodyInOneUndoStepButNotThePlane() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({0, 1, 2});
        const Vec3 o = f.origin();
        QVERIFY((o - Vec3(1, 0.75, 0)).norm() < 1e-6);  // the mean of the two, the plane left out
        const double L = f.size();
        const QPoint from = projected(*f.view, o + 0.6 * L * Vec3::UnitX());
        const QPoint to = projected(*f.view, o + (0.6 * L - 0.8) * Vec3::UnitX());
        QCOMPARE(f.view->handleAt(from), 0);
        const double expected = axisDistance(*f.view, from, to, o, Vec3::UnitX());
        const BodyDesc ground = f.doc.body(0);

        drag(*f.view, from, to);  // four moves and a release: five edits, one step
        QVERIFY(std::abs(f.doc.body(1).position.x() - expected) < 1e-9);
        QVERIFY(std::abs(f.doc.body(2).position.x() - (2.0 + expected)) < 1e-9);
        QCOMPARE(f.doc.body(1).position.y(), 1.0);
        QCOMPARE(f.doc.body(2).position.y(), 0.5);
        QVERIFY(f.doc.body(0) == ground);
        QCOMPARE(f.doc.undoStack()->count(), 1);
        f.doc.undoStack()->undo();
        QCOMPARE(f.doc.body(1).position, Vec3(0, 1, 0));
        QCOMPARE(f.doc.body(2).position, Vec3(2, 0.5, 0));
        f.doc.undoStack()->redo();
        QVERIFY(std::abs(f.doc.body(2).position.x() - (2.0 + expected)) < 1e-9);
    }

    void escapeDuringADragPutsTheBodiesBackAndLeavesNoStep() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        QWindow* w = f.view->renderWindow();
        f.doc.setSelection({1});
        const double L = f.size();
        // A first, finished drag: one step, kept.
        drag(*f.view, projected(*f.view, f.origin() + 0.6 * L * Vec3::UnitX()),
             projected(*f.view, f.origin() + (0.6 * L + 0.7) * Vec3::UnitX()));
        QCOMPARE(f.doc.undoStack()->count(), 1);
        const BodyDesc afterFirst = f.doc.body(1);
        QVERIFY(afterFirst.position.x() > 0.5);

        // A second drag, cancelled half way: the body is back where the first one left it.
        const Vec3 o = f.origin();
        const QPoint from = projected(*f.view, o + 0.6 * L * Vec3::UnitX());
        const QPoint to = projected(*f.view, o + (0.6 * L - 1.5) * Vec3::UnitX());
        QCOMPARE(f.view->handleAt(from), 0);
        QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
        QTest::mouseMove(w, (from + to) / 2);
        QTest::mouseMove(w, to);
        QVERIFY(f.doc.body(1).position.x() < afterFirst.position.x() - 1.0);  // it was moving
        QCOMPARE(f.doc.undoStack()->count(), 2);
        QTest::keyClick(w, Qt::Key_Escape);
        QVERIFY(f.doc.body(1) == afterFirst);
        QCOMPARE(f.doc.undoStack()->count(), 1);  // no undo step
        QVERIFY(!f.doc.undoStack()->canRedo());   // and no redo step
        QCOMPARE(f.doc.undoStack()->undoText(), f.doc.undoStack()->text(0));
        // The rest of the gesture does nothing: no move, no click.
        QTest::mouseMove(w, from);
        QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, from);
        QVERIFY(f.doc.body(1) == afterFirst);
        QCOMPARE(f.doc.selection(), QList<int>({1}));
        QCOMPARE(f.doc.undoStack()->count(), 1);
        // The first drag still undoes to the start.
        f.doc.undoStack()->undo();
        QCOMPARE(f.doc.body(1).position, Vec3(0, 1, 0));
        QVERIFY(f.doc.undoStack()->isClean());
    }

    void escapeCancelsAMultiSelectionDragAndAnUnmovedOne() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        QWindow* w = f.view->renderWindow();
        f.doc.setSelection({1, 2});
        const BodyDesc ball = f.doc.body(1), crate = f.doc.body(2);
        const Vec3 o = f.origin();
        const double L = f.size();
        const QPoint from = projected(*f.view, o + 0.6 * L * Vec3::UnitX());
        const QPoint to = projected(*f.view, o + (0.6 * L + 1.0) * Vec3::UnitX());
        QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
        for (int i = 1; i <= 3; ++i) QTest::mouseMove(w, from + (to - from) * i / 3);
        QVERIFY(f.doc.body(2).position.x() > 2.5);
        QCOMPARE(f.doc.undoStack()->count(), 1);  // the macro so far
        QTest::keyClick(w, Qt::Key_Escape);
        QVERIFY(f.doc.body(1) == ball);
        QVERIFY(f.doc.body(2) == crate);
        QCOMPARE(f.doc.undoStack()->count(), 0);
        QVERIFY(f.doc.undoStack()->isClean());
        QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, to);
        QCOMPARE(f.doc.undoStack()->count(), 0);

        // Pressed on a handle and not moved: Escape leaves the stack as it was.
        f.doc.setSelection({1});
        const QPoint grip = projected(*f.view, f.origin() + 0.6 * L * Vec3::UnitX());
        QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, grip);
        QTest::keyClick(w, Qt::Key_Escape);
        QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, grip);
        QVERIFY(f.doc.body(1) == ball);
        QCOMPARE(f.doc.undoStack()->count(), 0);
        // With no drag, Escape is left to others (it does not reach the handles).
        f.doc.addBody(body("extra", ShapeType::Box, Vec3(-2, 0.5, 0)));
        QTest::keyClick(w, Qt::Key_Escape);
        QCOMPARE(f.doc.undoStack()->count(), 1);  // the add stays
    }

    // ---- Collision shapes.

    void collisionWiresOutlineTheShapes() {
        ShapeDesc box;
        box.type = ShapeType::Box;
        box.halfExtents = Vec3(1, 2, 3);
        const auto edges = collisionWire(box);
        QCOMPARE(edges.size(), size_t(24));  // 12 edges
        for (const Vec3& p : edges) QCOMPARE(p.cwiseAbs(), Vec3(1, 2, 3));
        // A mesh: the edges of its hull, which leaves out a point inside it.
        auto mesh = std::make_shared<TriangleMesh>();
        mesh->vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0.1, 0.1, 0.1)};
        mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 1, 2}};
        ShapeDesc m;
        m.type = ShapeType::Mesh;
        m.meshData = mesh;
        const auto hull = collisionWire(m);
        QCOMPARE(hull.size(), size_t(12));  // a tetrahedron's 6 edges
        QVERIFY(
            std::none_of(hull.begin(), hull.end(), [](const Vec3& p) { return p == Vec3(0.1, 0.1, 0.1); }));
        m.collision = MeshCollision::Triangles;
        QCOMPARE(collisionWire(m).size(), size_t(2 * 8));  // the triangles' 8 distinct edges
        ShapeDesc plane;
        plane.type = ShapeType::Plane;
        QVERIFY(collisionWire(plane).empty());
    }

    // Each piece of a collision (a compound's part) is told apart, for its own colour; the
    // first sixteen colours are far apart from each other.
    void collisionWirePiecesAreToldApart() {
        ShapeDesc c;
        c.type = ShapeType::Compound;
        c.parts.resize(2);
        for (PartDesc& p : c.parts) p.shape.type = ShapeType::Box;
        c.parts[1].position = Vec3(3, 0, 0);
        std::vector<int> pieces;
        const auto wire = collisionWire(c, &pieces);
        QCOMPARE(wire.size(), size_t(48));
        QCOMPARE(pieces.size(), size_t(24));
        QVERIFY(std::all_of(pieces.begin(), pieces.begin() + 12, [](int k) { return k == 0; }));
        QVERIFY(std::all_of(pieces.begin() + 12, pieces.end(), [](int k) { return k == 1; }));
        for (int a = 0; a < 16; ++a)
            for (int b = a + 1; b < 16; ++b) {
                const auto x = pieceColour(a), y = pieceColour(b);
                const double d = std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
                QVERIFY2(d > 0.05, qPrintable(QString("pieces %1 and %2: %3").arg(a).arg(b).arg(d)));
            }
    }

    void theWireframeToggleAddsAndRemovesLineEntities() {
        auto tetra = std::make_shared<TriangleMesh>();
        tetra->vertices = {Vec3(0.6, -0.4, 0.6), Vec3(-0.6, -0.4, 0.6), Vec3(0, -0.4, -0.7), Vec3(0, 0.7, 0)};
        tetra->triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
        Document doc;  // the ground is body 0
        doc.addBody(body("sphere", ShapeType::Sphere, Vec3(-3, 0.5, 0)));
        BodyDesc box = body("box", ShapeType::Box, Vec3(-1.5, 0.5, 0));
        box.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitY()));
        doc.addBody(box);
        BodyDesc capsule = body("capsule", ShapeType::Capsule, Vec3(0, 1.0, 0));
        capsule.shape.radius = 0.4;
        doc.addBody(capsule);
        BodyDesc mesh = body("mesh", ShapeType::Mesh, Vec3(3, 0.4, 0));
        mesh.shape.file = "tetra.obj";
        mesh.shape.meshData = tetra;
        doc.addBody(mesh);
        Viewport view(&doc);
        view.resize(960, 640);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setCamera(QVector3D(0, 0.5f, 0), 9.0f, 20.0f, 25.0f);
        QSignalSpy spy(&view, &Viewport::showCollisionShapesChanged);

        QCOMPARE(view.collisionShapeCount(), 0);
        view.setShowCollisionShapes(true);
        QVERIFY(view.showCollisionShapes());
        QCOMPARE(view.collisionShapeCount(), 4);  // every body but the ground plane
        QCOMPARE(spy.count(), 1);
        doc.addBody(body("cylinder", ShapeType::Cylinder, Vec3(1.5, 0.5, 0)));
        QCOMPARE(view.collisionShapeCount(), 5);
        BodyDesc bigger = doc.body(1);
        bigger.shape.radius = 0.7;  // a new shape: a new outline, still one
        doc.setBody(1, bigger, "Radius");
        QCOMPARE(view.collisionShapeCount(), 5);
        doc.removeBodies({2});
        QCOMPARE(view.collisionShapeCount(), 4);
        doc.undoStack()->undo();
        QCOMPARE(view.collisionShapeCount(), 5);

        // Under TUMBLE_VIEWPORT_SHOW_MS the view stays up that long, rotate handles on the
        // capsule, for a screenshot.
        doc.setSelection({3});
        view.setTransformMode(Viewport::TransformMode::Rotate);
        const int ms = qEnvironmentVariableIntValue("TUMBLE_VIEWPORT_SHOW_MS");
        if (ms > 0) QTest::qWait(ms);

        view.setShowCollisionShapes(false);
        QCOMPARE(view.collisionShapeCount(), 0);
        QCOMPARE(spy.count(), 2);
        view.setShowCollisionShapes(false);
        QCOMPARE(spy.count(), 2);  // no change, no signal
    }
};

QTEST_MAIN(TestViewportHandles)
#include "tst_viewport_handles.moc"
