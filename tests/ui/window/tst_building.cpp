// Building a scene quickly (issue 52), through the real window: Add sets a body down on the
// surface under the view's centre and adds in a row stack up; End drops the selection along
// gravity onto what is below (not while a text field has the focus; Ctrl+End is the
// timeline's); Copy and Paste put the copies beside the originals; Array and Make Stack /
// Pyramid / Wall fill their dialogs and add their bodies; each is one undo step. The
// viewport's keys (F, A, W, E, the standard views) work from every dock, but not in a text
// field; Frame Selection frames a selected joint's bodies.
#include "document/document.h"
#include "panels/scene_tree_dock.h"
#include "timeline/timeline.h"
#include "timeline/timeline_dock.h"
#include "viewport/viewport.h"
#include "window/main_window.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTextBrowser>
#include <QTreeView>
#include <QAbstractSlider>
#include <QTimer>
#include <QUndoStack>
#include <QtTest>

#include <functional>

using namespace tumble;
using namespace tumble::ui;

namespace {

Vec3 toVec(const QVector3D& v) { return Vec3(v.x(), v.y(), v.z()); }

// Within the touch tolerance the drop stops at (1e-5 of the largest body's size).
constexpr double kRest = 1e-4;

QAction* action(MainWindow& w, const char* name) {
    QAction* a = w.findChild<QAction*>(name);
    if (!a) qFatal("no action %s", name);
    return a;
}

// Opens the modal dialog `open` shows, lets `fill` set its fields, then presses OK.
void withDialog(MainWindow& w, const std::function<void()>& open, const std::function<void(QDialog*)>& fill) {
    bool seen = false;
    QTimer::singleShot(0, &w, [&] {
        auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
        QVERIFY(dialog);
        seen = true;
        fill(dialog);
        QPushButton* ok = dialog->findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok);
        QVERIFY(ok->isEnabled());
        ok->click();
    });
    open();
    QVERIFY(seen);
}

struct Window {
    MainWindow w;
    Document* doc() { return w.document(); }
    Window() {
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        w.activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(&w));
        // The new scene's ground; the view on the origin from above and aside.
        w.viewport()->setCamera(QVector3D(0, 0, 0), 12.0f, 30.0f, 35.0f);
    }
    int addBox() {
        w.findChild<SceneTreeDock*>()->addBodyAction(ShapeType::Box)->trigger();
        return doc()->bodyCount() - 1;
    }
};

}  // namespace

class TestBuilding : public QObject {
    Q_OBJECT
private slots:
    void addsRestOnTheSurfaceUnderTheViewAndStack() {
        Window win;
        const int ground = win.doc()->bodyCount();
        for (int k = 0; k < 3; ++k) {
            const int i = win.addBox();
            QCOMPARE(win.doc()->selection(), QList<int>{i});
            const Vec3 at = win.doc()->body(i).position;
            // A unit box on the floor, then on each other, centred under the view.
            QVERIFY2(std::abs(at.y() - (0.5 + k)) < kRest, qPrintable(QString::number(at.y(), 'g', 12)));
            QVERIFY2(Vec3(at.x(), 0, at.z()).norm() < 1e-9, qPrintable(QString::number(at.x())));
        }
        QCOMPARE(win.doc()->bodyCount(), ground + 3);
        // Looking elsewhere on the floor: the next one rests there.
        win.w.viewport()->setCamera(QVector3D(4, 0, -3), 12.0f, 30.0f, 35.0f);
        const Vec3 at = win.doc()->body(win.addBox()).position;
        QVERIFY((at - Vec3(4, 0.5, -3)).norm() < kRest);
    }

    void addsFollowGravity() {
        // Gravity along -x onto a wall at x = 0: a new body rests against the wall.
        Window win;
        SceneDesc s = win.doc()->scene();
        s.settings.gravity = Vec3(-9.81, 0, 0);
        s.bodies[0].shape.normal = Vec3::UnitX();
        win.doc()->replaceScene(s, "sideways", true);
        win.w.viewport()->setCamera(QVector3D(0, 2, 1), 12.0f, 80.0f, 10.0f);
        const Vec3 at = win.doc()->body(win.addBox()).position;
        QVERIFY2(std::abs(at.x() - 0.5) < kRest, qPrintable(QString::number(at.x(), 'g', 12)));
        QVERIFY((Vec3(0, at.y(), at.z()) - Vec3(0, 2, 1)).norm() < 1e-9);
    }

    void endDropsTheSelectionInOneUndoStep() {
        Window win;
        const int a = win.addBox();
        win.w.viewport()->setCamera(QVector3D(3, 0, 0), 12.0f, 30.0f, 35.0f);
        const int b = win.addBox();
        BodyDesc high = win.doc()->body(a);
        high.position = Vec3(0, 4, 0);
        win.doc()->setBody(a, high, "lift");
        BodyDesc over = win.doc()->body(b);
        over.position = Vec3(0.2, 7, 0);  // over a, lower side first
        win.doc()->setBody(b, over, "lift");
        win.doc()->setSelection({a, b});
        // A text field with the focus keeps End for its cursor.
        auto* field = win.w.findChild<QLineEdit*>();
        QVERIFY(field);
        field->setFocus();
        QTest::keyClick(field, Qt::Key_End);
        QCOMPARE(win.doc()->body(a).position.y(), 4.0);
        win.w.viewport()->setFocus();
        const int steps = win.doc()->undoStack()->count();
        QTest::keyClick(win.w.viewport()->renderWindow(), Qt::Key_End);
        QVERIFY(std::abs(win.doc()->body(a).position.y() - 0.5) < kRest);
        QVERIFY(std::abs(win.doc()->body(b).position.y() - 1.5) < 2 * kRest);  // onto a
        QCOMPARE(win.doc()->undoStack()->count(), steps + 1);
        win.doc()->undoStack()->undo();
        QCOMPARE(win.doc()->body(a).position.y(), 4.0);
        QCOMPARE(win.doc()->body(b).position.y(), 7.0);
        // Resting already: nothing moves, nothing is added to undo.
        win.doc()->undoStack()->redo();
        QTest::keyClick(win.w.viewport()->renderWindow(), Qt::Key_End);
        QCOMPARE(win.doc()->undoStack()->count(), steps + 1);
    }

    void copyAndPasteBesideInOneUndoStep() {
        Window win;
        const int a = win.addBox();
        win.doc()->setSelection({a});
        win.w.viewport()->setFocus();
        QTest::keyClick(win.w.viewport()->renderWindow(), Qt::Key_C, Qt::ControlModifier);
        const int before = win.doc()->bodyCount();
        QTest::keyClick(win.w.viewport()->renderWindow(), Qt::Key_V, Qt::ControlModifier);
        QTest::keyClick(win.w.viewport()->renderWindow(), Qt::Key_V, Qt::ControlModifier);
        QCOMPARE(win.doc()->bodyCount(), before + 2);
        QSet<QString> names;
        for (int i = 0; i < win.doc()->bodyCount(); ++i) names.insert(QString::fromStdString(win.doc()->body(i).name));
        QCOMPARE(names.size(), win.doc()->bodyCount());
        const Vec3 p0 = win.doc()->body(a).position, p1 = win.doc()->body(before).position;
        QCOMPARE(p1.y(), p0.y());
        QVERIFY2((p1 - p0).norm() >= 1.1 - 1e-9, qPrintable(QString::number((p1 - p0).norm())));  // beside, not inside
        QCOMPARE(win.doc()->selection(), QList<int>{before + 1});
        win.doc()->undoStack()->undo();
        QCOMPARE(win.doc()->bodyCount(), before + 1);
    }

    void arrayMakesAGrid() {
        Window win;
        const int a = win.addBox();
        win.doc()->setSelection({a});
        const int before = win.doc()->bodyCount();
        withDialog(win.w, [&] { action(win.w, "array")->trigger(); }, [](QDialog* d) {
            d->findChild<QSpinBox*>("count1")->setValue(4);
            d->findChild<QSpinBox*>("count2")->setValue(3);
            d->findChild<QDoubleSpinBox*>("step1x")->setValue(1.5);
            d->findChild<QDoubleSpinBox*>("step2z")->setValue(-2.0);
        });
        QCOMPARE(win.doc()->bodyCount(), before + 11);
        const Vec3 p0 = win.doc()->body(a).position;
        const Vec3 last = win.doc()->body(win.doc()->bodyCount() - 1).position;
        QVERIFY((last - (p0 + Vec3(4.5, 0, -4.0))).norm() < 1e-12);
        win.doc()->undoStack()->undo();
        QCOMPARE(win.doc()->bodyCount(), before);
    }

    void makeStackPyramidAndWall() {
        Window win;
        const int ground = win.doc()->bodyCount();
        withDialog(win.w, [&] { action(win.w, "makePyramid")->trigger(); }, [](QDialog*) {});
        QCOMPARE(win.doc()->bodyCount(), ground + 55);  // rows of 10, 9, ... 1
        double low = HUGE_VAL, high = -HUGE_VAL;
        for (int i = ground; i < win.doc()->bodyCount(); ++i) {
            low = std::min(low, win.doc()->body(i).position.y());
            high = std::max(high, win.doc()->body(i).position.y());
        }
        QVERIFY(std::abs(low - 0.25) < kRest && std::abs(high - 4.75) < kRest);  // 0.5 m boxes on the floor
        win.doc()->undoStack()->undo();
        QCOMPARE(win.doc()->bodyCount(), ground);
        withDialog(win.w, [&] { action(win.w, "makeStack")->trigger(); }, [](QDialog* d) {
            d->findChild<QSpinBox*>("count")->setValue(7);
        });
        QCOMPARE(win.doc()->bodyCount(), ground + 7);
        // Made while the view looks at the stack: the next layout rests on top of it.
        withDialog(win.w, [&] { action(win.w, "makeStack")->trigger(); }, [](QDialog* d) {
            d->findChild<QSpinBox*>("count")->setValue(2);
        });
        QCOMPARE(win.doc()->bodyCount(), ground + 9);
        QVERIFY(std::abs(win.doc()->body(ground + 7).position.y() - 3.75) < kRest);
        win.doc()->undoStack()->undo();
        win.w.viewport()->setCamera(QVector3D(0, 0, 5), 12.0f, 30.0f, 35.0f);  // the floor beside it
        withDialog(win.w, [&] { action(win.w, "makeWall")->trigger(); }, [](QDialog* d) {
            d->findChild<QSpinBox*>("count")->setValue(20);
            d->findChild<QSpinBox*>("rows")->setValue(1);
            d->findChild<QDoubleSpinBox*>("sizex")->setValue(0.05);  // dominoes
            d->findChild<QDoubleSpinBox*>("sizey")->setValue(0.5);
            d->findChild<QDoubleSpinBox*>("gap")->setValue(0.2);
        });
        QCOMPARE(win.doc()->bodyCount(), ground + 27);
        const BodyDesc& domino = win.doc()->body(ground + 7);
        QCOMPARE(domino.shape.halfExtents, Vec3(0.025, 0.25, 0.25));
        QVERIFY(std::abs(domino.position.y() - 0.25) < kRest);
        QVERIFY(std::abs(domino.position.z() - 5.0) < 1e-9);
    }

    void viewportKeysWorkFromEveryDock() {
        Window win;
        const int a = win.addBox();
        win.w.viewport()->setCamera(QVector3D(6, 0, 0), 12.0f, 30.0f, 35.0f);
        win.addBox();
        // Focus in the Scene list (a click there), then in the properties, then the timeline.
        QWidget* list = win.w.findChild<SceneTreeDock*>()->view();
        auto* field = win.w.findChild<QLineEdit*>("name");
        QVERIFY(field);
        QWidget* slider = win.w.timelineDock()->findChild<QAbstractSlider*>();
        QVERIFY(slider);
        for (QWidget* focus : {list, static_cast<QWidget*>(win.w.viewport()), slider}) {
            win.doc()->setSelection({a});
            focus->setFocus();
            QTest::keyClick(focus, Qt::Key_F);
            QVERIFY(win.w.viewport()->cameraTarget().distanceToPoint(QVector3D(0, 0.5f, 0)) < 1e-4f);
            QTest::keyClick(focus, Qt::Key_E);
            QCOMPARE(win.w.viewport()->transformMode(), Viewport::TransformMode::Rotate);
            QTest::keyClick(focus, Qt::Key_W);
            QCOMPARE(win.w.viewport()->transformMode(), Viewport::TransformMode::Move);
            QTest::keyClick(focus, Qt::Key_A);
            QVERIFY(win.w.viewport()->cameraTarget().distanceToPoint(QVector3D(0, 0.5f, 0)) > 1.0f);  // both boxes
        }
        // A text field keeps its letters: F typed into the name renames, the camera stays.
        win.doc()->setSelection({a});
        field->setFocus();
        QTRY_VERIFY(field->hasFocus());
        const QVector3D before = win.w.viewport()->cameraTarget();
        QTest::keyClick(field, Qt::Key_End);
        QTest::keyClick(field, Qt::Key_F);
        QVERIFY(field->text().endsWith('f'));
        QCOMPARE(win.w.viewport()->cameraTarget(), before);
    }

    // Duplicate (Ctrl+D) and Delete work wherever the focus is, not only in the Scene list; a
    // text field keeps Delete for its text.
    void editingKeysWorkFromEveryDock() {
        Window win;
        win.addBox();
        QWidget* list = win.w.findChild<SceneTreeDock*>()->view();
        QWidget* slider = win.w.timelineDock()->findChild<QAbstractSlider*>();
        QVERIFY(slider);
        for (QWidget* focus : {static_cast<QWidget*>(win.w.viewport()), slider, list}) {
            const int before = win.doc()->bodyCount();
            win.doc()->setSelection({before - 1});
            focus->setFocus();
            QTest::keyClick(focus, Qt::Key_D, Qt::ControlModifier);
            QCOMPARE(win.doc()->bodyCount(), before + 1);
            win.doc()->setSelection({before});
            focus->setFocus();
            QTest::keyClick(focus, Qt::Key_Delete);
            QCOMPARE(win.doc()->bodyCount(), before);
        }
        auto* field = win.w.findChild<QLineEdit*>("name");
        QVERIFY(field);
        const int before = win.doc()->bodyCount();
        win.doc()->setSelection({before - 1});
        field->setFocus();
        QTRY_VERIFY(field->hasFocus());
        const QString name = field->text();
        QTest::keyClick(field, Qt::Key_Home);
        QTest::keyClick(field, Qt::Key_Delete);
        QCOMPARE(win.doc()->bodyCount(), before);
        QCOMPARE(field->text(), name.mid(1));
    }

    void standardViewsLookAlongTheAxes() {
        Window win;
        win.w.viewport()->setCamera(QVector3D(1, 2, 3), 10.0f, 30.0f, 35.0f);
        QWidget* list = win.w.findChild<SceneTreeDock*>()->view();
        list->setFocus();
        struct Case {
            int key;
            Qt::KeyboardModifiers mods;
            QVector3D from;  // where the camera sits, from the target
        };
        const Case cases[] = {{Qt::Key_1, Qt::KeypadModifier, {0, 0, 10}},
                              {Qt::Key_1, Qt::KeypadModifier | Qt::ControlModifier, {0, 0, -10}},
                              {Qt::Key_3, Qt::KeypadModifier, {10, 0, 0}},
                              {Qt::Key_3, Qt::ControlModifier, {-10, 0, 0}},
                              {Qt::Key_7, Qt::NoModifier, {0, 10, 0}},
                              {Qt::Key_7, Qt::KeypadModifier | Qt::ControlModifier, {0, -10, 0}}};
        for (const Case& c : cases) {
            QTest::keyClick(list, Qt::Key(c.key), c.mods);
            const QVector3D from = win.w.viewport()->cameraPosition() - win.w.viewport()->cameraTarget();
            QVERIFY2((from - c.from).length() < 1e-4f, qPrintable(QStringLiteral("%1 %2 %3").arg(from.x()).arg(from.y()).arg(from.z())));
            QCOMPARE(win.w.viewport()->cameraTarget(), QVector3D(1, 2, 3));
        }
    }

    // View > Standard Views > Orthographic (5, from any dock): a parallel projection, as large
    // at the target as the perspective view; points along the line of sight fall on one
    // pixel; a click picks the body drawn there; the handles keep their size at any depth;
    // 5 again goes back.
    void orthographicViewIsParallelAndPicks() {
        Window win;
        Viewport* view = win.w.viewport();
        const int a = win.addBox();  // a unit box resting on the origin
        view->setCamera(QVector3D(0, 0.5f, 0), 10.0f, 0.0f, 0.0f);  // the front view
        const QVector3D side(1.5f, 0.5f, 0.0f);
        const QVector3D beside = view->projectToWidget(side);
        QWidget* slider = win.w.timelineDock()->findChild<QAbstractSlider*>();
        QVERIFY(slider);
        slider->setFocus();
        QTest::keyClick(slider, Qt::Key_5, Qt::KeypadModifier);
        QVERIFY(view->isOrthographic());
        QVERIFY(action(win.w, "viewOrthographic")->isChecked());
        // As large at the target's depth as before.
        QVERIFY((view->projectToWidget(side) - beside).toVector2D().length() < 0.01f);
        // Parallel: nearer and farther along the line of sight, the same pixel.
        for (float dz : {-4.0f, 3.0f}) {
            const QVector3D p = view->projectToWidget(side + QVector3D(0, 0, dz));
            QVERIFY2((p - beside).toVector2D().length() < 0.01f, qPrintable(QString::number(dz)));
        }
        // Picking casts parallel rays: the box's corner region, seen edge on, is the box.
        win.doc()->setSelection({});
        const QVector3D corner = view->projectToWidget(QVector3D(0.45f, 0.95f, 0.5f));
        QTest::mouseClick(view->renderWindow(), Qt::LeftButton, Qt::NoModifier, corner.toPoint());
        QCOMPARE(win.doc()->selection(), QList<int>{a});
        // The handles are as large on screen wherever the body stands along the line of sight:
        // their size in the world does not change with its depth.
        const float near = view->handlesSize();
        BodyDesc moved = win.doc()->body(a);
        moved.position.z() -= 6.0;
        win.doc()->setBody(a, moved, "Move");
        QVERIFY(std::abs(view->handlesSize() - near) < 1e-5f);
        QTest::keyClick(slider, Qt::Key_5);
        QVERIFY(!view->isOrthographic());
        QVERIFY(!action(win.w, "viewOrthographic")->isChecked());
        QVERIFY(view->handlesSize() > near);  // in perspective they grow with depth to look the same
    }

    void frameSelectionFramesAJoint() {
        Window win;
        const int a = win.addBox();
        win.w.viewport()->setCamera(QVector3D(10, 0, 0), 12.0f, 30.0f, 35.0f);
        const int b = win.addBox();
        JointDesc j;
        j.name = "pin";
        j.bodyA = win.doc()->body(a).name;
        j.bodyB = win.doc()->body(b).name;
        win.doc()->addJoint(j);
        QVERIFY(win.doc()->selection().isEmpty() && win.doc()->selectedJoint() == 0);
        win.w.viewport()->setCamera(QVector3D(-30, 0, 40), 3.0f, 30.0f, 35.0f);
        QTest::keyClick(&win.w, Qt::Key_F);
        QVERIFY(win.w.viewport()->cameraTarget().distanceToPoint(QVector3D(5, 0.5f, 0)) < 1e-4f);  // between them
    }

    void selectAllOfAKind() {
        Window win;
        withDialog(win.w, [&] { action(win.w, "makeStack")->trigger(); }, [](QDialog* d) {
            d->findChild<QSpinBox*>("count")->setValue(4);
        });
        win.w.viewport()->setCamera(QVector3D(5, 0, 0), 12.0f, 30.0f, 35.0f);
        win.w.findChild<SceneTreeDock*>()->addBodyAction(ShapeType::Sphere)->trigger();
        const QString box = QString::fromUtf8(toString(ShapeType::Box));
        action(win.w, qPrintable("select" + box))->trigger();
        QCOMPARE(win.doc()->selection().size(), 4);
        for (int i : win.doc()->selection()) QCOMPARE(win.doc()->body(i).shape.type, ShapeType::Box);
        action(win.w, qPrintable("select" + QString::fromUtf8(toString(Motion::Static))))->trigger();
        QCOMPARE(win.doc()->selection(), QList<int>{0});  // the ground
        action(win.w, qPrintable("select" + QString::fromUtf8(toString(Motion::Dynamic))))->trigger();
        QCOMPARE(win.doc()->selection().size(), 5);
    }

    void boxSelectTakesWhatItEncloses() {
        Window win;
        const int a = win.addBox();
        win.w.viewport()->setCamera(QVector3D(3, 0, 0), 12.0f, 30.0f, 35.0f);
        const int b = win.addBox();
        win.w.viewport()->setCamera(QVector3D(-6, 0, 0), 12.0f, 30.0f, 35.0f);
        const int c = win.addBox();
        win.w.viewport()->setCamera(QVector3D(1.5f, 0.5f, 0), 14.0f, 0.0f, 10.0f);  // from the front
        Viewport* v = win.w.viewport();
        auto at = [v](const Vec3& p) {
            const QVector3D w = v->projectToWidget(QVector3D(float(p.x()), float(p.y()), float(p.z())));
            return QPoint(qRound(w.x()), qRound(w.y()));
        };
        auto drag = [v](const QPoint& from, const QPoint& to, Qt::KeyboardModifiers release = {}) {
            QWindow* w = v->renderWindow();
            QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
            for (int i = 1; i <= 4; ++i) QTest::mouseMove(w, from + (to - from) * i / 4);
            QTest::mouseRelease(w, Qt::LeftButton, release, to);
        };
        const QPoint from = at(Vec3(-1, 1.5, 0)), to = at(Vec3(4, -0.5, 0));  // around a and b
        win.doc()->setSelection({c});
        QTest::keyClick(&win.w, Qt::Key_B);
        QVERIFY(v->boxSelectArmed());
        drag(from, to);
        QCOMPARE(win.doc()->selection(), (QList<int>{a, b}));
        QVERIFY(!v->boxSelectArmed());  // one drag
        // Ctrl at the release adds; an unarmed drag orbits and selects nothing new.
        win.doc()->setSelection({c});
        QTest::keyClick(&win.w, Qt::Key_B);
        drag(at(Vec3(2, 1.5, 0)), at(Vec3(4, -0.5, 0)), Qt::ControlModifier);
        auto selected = [&] {
            QList<int> s = win.doc()->selection();
            std::sort(s.begin(), s.end());
            return s;
        };
        QCOMPARE(selected(), (QList<int>{b, c}));
        drag(from, to);
        QCOMPARE(selected(), (QList<int>{b, c}));
        // Esc gives it up.
        QTest::keyClick(&win.w, Qt::Key_B);
        v->setFocus();
        QTest::keyClick(v->renderWindow(), Qt::Key_Escape);
        QVERIFY(!v->boxSelectArmed());
    }

    void shiftWhileMovingRestsOnTheSurface() {
        Window win;
        win.w.viewport()->setCamera(QVector3D(3, 0, 0), 12.0f, 30.0f, 35.0f);
        win.addBox();
        win.addBox();  // a tower of two at x = 3
        win.w.viewport()->setCamera(QVector3D(0, 0, 0), 12.0f, 0.0f, 20.0f);
        const int a = win.addBox();  // on the floor at the origin
        win.doc()->setSelection({a});
        Viewport* v = win.w.viewport();
        const Vec3 o = toVec(v->handlesOrigin());
        const double L = v->handlesSize();
        auto at = [v](const Vec3& p) {
            const QVector3D w = v->projectToWidget(QVector3D(float(p.x()), float(p.y()), float(p.z())));
            return QPoint(qRound(w.x()), qRound(w.y()));
        };
        const QPoint from = at(o + 0.6 * L * Vec3::UnitX()), to = at(o + (0.6 * L + 3.0) * Vec3::UnitX());
        QCOMPARE(v->handleAt(from), 0);
        // Dragged along x with Shift held: onto the tower's top, not into it.
        QWindow* w = v->renderWindow();
        QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
        for (int i = 1; i <= 4; ++i) QTest::mouseMove(w, from + (to - from) * i / 4);
        QTest::mouseRelease(w, Qt::LeftButton, Qt::ShiftModifier, to);
        const Vec3 p = win.doc()->body(a).position;
        QVERIFY2(std::abs(p.x() - 3.0) < 0.05, qPrintable(QString::number(p.x())));  // a pixel's worth
        QVERIFY2(std::abs(p.y() - 2.5) < 1e-4, qPrintable(QString::number(p.y(), 'g', 12)));
        QCOMPARE(win.doc()->undoStack()->undoText(), QString("Move %1").arg(QString::fromStdString(win.doc()->body(a).name)));
    }

    void helpOpensTheManual() {
        Window win;
        action(win.w, "manual")->trigger();
        QTextBrowser* page = nullptr;
        QTRY_VERIFY((page = win.w.findChild<QTextBrowser*>("manual")) != nullptr && page->isVisible());
        QVERIFY(page->toPlainText().contains("Building a scene"));
        QVERIFY(page->toPlainText().contains("Drop to Surface"));
        // Its picture is built in too.
        const QVariant picture =
            page->document()->resource(QTextDocument::ImageResource, QUrl("qrc:/docs/images/editor-make-pyramid.png"));
        QVERIFY(!picture.isNull());
        // A link to another built-in page follows it.
        page->setSource(QUrl("qrc:/docs/scene-format.md"), QTextDocument::MarkdownResource);
        QVERIFY(page->toPlainText().contains("bodies"));
        page->window()->close();
    }

    void ctrlEndIsTheTimelines() {
        Window win;
        QString error;
        QVERIFY(win.w.openScene(":/scenes/projectile.json", &error));
        Timeline* t = win.w.timeline();
        QVERIFY(QTest::qWaitFor([&] { return t->status() == Timeline::Status::Complete; }, 60000));
        QTest::keyClick(&win.w, Qt::Key_End, Qt::ControlModifier);
        QCOMPARE(t->currentFrame(), t->frameCount() - 1);
        QTest::keyClick(&win.w, Qt::Key_Home, Qt::ControlModifier);
        QCOMPARE(t->currentFrame(), 0);
    }
};

QTEST_MAIN(TestBuilding)
#include "tst_building.moc"
