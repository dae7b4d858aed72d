// "Sweep this value…" (issue 22): from a property field's context menu, the dialog runs
// `tumble sweep` in the background, shows each variant's row and plots a measure against
// the value (one line per value of a second one); Cancel stops it; double-clicking a row
// opens that variant in place of the scene, and Undo brings the scene back.
#include "document/document.h"
#include "panels/property_dock.h"
#include "panels/property_spin_box.h"
#include "sweep/sweep_dialog.h"
#include "panel_test_util.h"

#include <QApplication>
#include <QContextMenuEvent>
#include <QMenu>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableWidget>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

// The ball of tst_cli_sweep: radius 0.05, dropped from 1 m (its bottom) onto a ground that
// bounces nothing back, 1 s.
SceneDesc drop(double dt = 1.0 / 240.0) {
    SceneDesc s;
    s.settings.dt = dt;
    s.settings.duration = 1.0;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.restitution = 0.0;
    BodyDesc ball;
    ball.name = "ball";
    ball.shape.type = ShapeType::Sphere;
    ball.shape.radius = 0.05;
    ball.mass = 0.2;
    ball.position = Vec3(0, 1.05, 0);
    ball.restitution = 0.5;
    s.bodies = {ground, ball};
    return s;
}

}  // namespace

class TestSweepDialog : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);  // the sweeps' folders under ~/.qttest
        SweepDialog::setExecutable(TUMBLE_EXECUTABLE);
    }

    // Right-click on the restitution field, "Sweep this value…": the dialog for
    // ball.restitution, starting around the value (0.5: 0.25 to 0.75).
    void theFieldsContextMenuOpensIt() {
        Document doc;
        doc.replaceScene(drop(), "drop", false);
        PropertyDock dock(&doc);
        dock.show();
        doc.setSelection({1});
        auto* spin = test::field<PropertySpinBox>(dock, "restitution");
        QContextMenuEvent event(QContextMenuEvent::Mouse, QPoint(5, 5), spin->mapToGlobal(QPoint(5, 5)));
        QApplication::sendEvent(spin, &event);
        QMenu* menu = nullptr;
        QTRY_VERIFY((menu = qobject_cast<QMenu*>(QApplication::activePopupWidget())) != nullptr);
        QAction* sweep = menu->findChild<QAction*>("sweepThisValue");
        QVERIFY(sweep);
        QVERIFY(sweep->isEnabled());
        QCOMPARE(menu->actions().value(0), sweep);  // first, not under the text editing entries
        QVERIFY(!sweep->icon().isNull());
        menu->close();
        sweep->trigger();
        auto* dialog = dock.findChild<SweepDialog*>();
        QVERIFY(dialog);
        QCOMPARE(dialog->windowTitle(), QString("Sweep ball.restitution"));
        QCOMPARE(test::field<PropertySpinBox>(*dialog, "from")->value(), 0.25);
        QCOMPARE(test::field<PropertySpinBox>(*dialog, "to")->value(), 0.75);
        // Several bodies selected: which one's value would it be? Not offered.
        doc.setSelection({0, 1});
        QApplication::sendEvent(spin, &event);
        QTRY_VERIFY((menu = qobject_cast<QMenu*>(QApplication::activePopupWidget())) != nullptr);
        QVERIFY(!menu->findChild<QAction*>("sweepThisValue")->isEnabled());
        menu->close();
        delete dialog;
    }

    // Five values of restitution and two of friction: ten rows, all ok, and two lines of
    // five points each, the ball's highest point the 1.05 m it started at in every one.
    // Double-clicking the row of restitution 0.6, friction 1 opens it; Undo brings the
    // scene back.
    void runsPlotsAndOpensAVariant() {
        Document doc;
        doc.replaceScene(drop(), "drop", false);
        SweepDialog dialog(&doc, "ball.restitution", 0.5);
        dialog.setRange(0.2, 1.0, 5);
        dialog.setSecond("ball.friction", 0.0, 1.0, 2);
        dialog.show();
        QSignalSpy done(&dialog, &SweepDialog::sweepFinished);
        dialog.run();
        QVERIFY(dialog.isRunning());
        QVERIFY(done.wait(120000));
        QCOMPARE(done.first().first().toInt(), 0);
        QTableWidget* table = dialog.table();
        QCOMPARE(table->rowCount(), 10);
        int status = -1;
        for (int c = 0; c < table->columnCount(); ++c)
            if (table->horizontalHeaderItem(c)->text() == "status") status = c;
        QVERIFY(status > 0);
        for (int r = 0; r < 10; ++r) QCOMPARE(table->item(r, status)->text(), QString("ok"));
        QVERIFY2(dialog.status().contains("10 variants: 10 ran"), qPrintable(dialog.status()));

        dialog.setMeasure("ball.highest");
        const auto lines = dialog.plotted();
        QCOMPARE(lines.size(), 2);
        QCOMPARE(lines[0].first, QString("ball.friction = 0"));
        QCOMPARE(lines[1].first, QString("ball.friction = 1"));
        for (const auto& line : lines) {
            QCOMPARE(line.second.size(), 5);
            for (int k = 0; k < 5; ++k) {
                QCOMPARE(line.second[k].x(), 0.2 + 0.2 * k);
                QCOMPARE(line.second[k].y(), 1.05);
            }
        }

        const int steps = doc.undoStack()->count();
        emit table->cellDoubleClicked(5, 0);  // restitution 0.6 (the third), friction 1 (the second)
        QCOMPARE(doc.body(1).restitution, 0.6);
        QCOMPARE(doc.body(1).friction, 1.0);
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        doc.undoStack()->undo();
        QCOMPARE(doc.body(1).restitution, 0.5);
        QCOMPARE(doc.body(1).friction, drop().bodies[1].friction);
    }

    // Cancel stops the sweep (tumble sweep's exit status 130), and says so.
    void cancelStopsIt() {
        Document doc;
        doc.replaceScene(drop(1e-5), "slow drop", false);  // about a second a variant
        SweepDialog dialog(&doc, "ball.restitution", 0.5);
        dialog.setRange(0.1, 0.9, 20);
        QSignalSpy done(&dialog, &SweepDialog::sweepFinished);
        dialog.run();
        QTest::qWait(500);
        dialog.cancel();
        QVERIFY(done.wait(60000));
        QCOMPARE(done.first().first().toInt(), 130);
        QVERIFY2(dialog.status().startsWith("Cancelled"), qPrintable(dialog.status()));
        QVERIFY(!dialog.isRunning());
    }
};

QTEST_MAIN(TestSweepDialog)
#include "tst_sweep_dialog.moc"
