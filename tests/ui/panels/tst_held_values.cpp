// Issue 46 item 2 on the body page: a vector or matrix is edited as one value. An edit
// that would leave it refused part way (a plane normal turned from y to z passes through
// zero; an inertia tensor between two physical ones) is held as typed, framed red, with the
// reason in the panel's words, until the whole value is valid (then it is applied as one
// undo step, exactly as typed) or Esc gives it up; the document never holds a mix the user
// did not type. The same for a force's start and end times.
#include "document/document.h"
#include "panel_test_util.h"
#include "panels/forces_edit.h"
#include "panels/inertia_edit.h"
#include "panels/property_dock.h"
#include "panels/property_spin_box.h"
#include "panels/vector_edit.h"

#include <QApplication>
#include <QCheckBox>
#include <QLabel>
#include <QLineEdit>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

BodyDesc ground() {
    BodyDesc b;
    b.name = "ground";
    b.motion = Motion::Static;
    b.shape.type = ShapeType::Plane;
    b.shape.normal = Vec3(0, 1, 0);
    return b;
}

BodyDesc box(const std::string& name, const Vec3& halfExtents) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = halfExtents;
    b.mass = 1.0;
    return b;
}

struct Fixture {
    Document doc;
    PropertyDock dock{&doc};
    int plane = -1, a = -1, b = -1;
    Fixture() {
        doc.newScene();
        plane = doc.addBody(ground());
        a = doc.addBody(box("a", Vec3(0.5, 0.25, 1.0)));
        b = doc.addBody(box("b", Vec3(0.2, 0.3, 0.4)));
        doc.undoStack()->clear();
    }
    int steps() const { return doc.undoStack()->count(); }
    PropertySpinBox* spin(const QString& name) const { return test::field<PropertySpinBox>(dock, name); }
    VectorEdit* vector(const QString& name) const { return test::field<VectorEdit>(dock, name); }
};

}  // namespace

class TestHeldValues : public QObject {
    Q_OBJECT
private slots:
    // The case on the body page: a plane's normal from (0, 1, 0) to (0, 0, 1), one
    // field at a time, y first.
    void aNormalTurnedThroughZeroIsHeldThenAppliedWhole() {
        Fixture f;
        f.doc.setSelection({f.plane});
        VectorEdit* normal = f.vector("shape.normal");
        f.spin("shape.normal.y")->setValue(0.0);
        QCOMPARE(f.doc.body(f.plane).shape.normal, Vec3(0, 1, 0));  // nothing reached the document
        QCOMPARE(f.steps(), 0);
        QVERIFY(normal->isHeld());
        QCOMPARE(normal->value(), Vec3(0, 0, 0));  // the fields show what was typed
        const QString why = f.dock.fieldError("shape.normal");
        QVERIFY2(why.contains("cannot be zero") && why.contains("Esc"), qPrintable(why));
        QVERIFY2(!why.contains("shape.") && !why.contains("bodies["), qPrintable(why));  // no file jargon

        f.spin("shape.normal.z")->setValue(1.0);
        QCOMPARE(f.doc.body(f.plane).shape.normal, Vec3(0, 0, 1));  // exactly as typed, not (0, 1, 1)
        QVERIFY(!normal->isHeld());
        QVERIFY(f.dock.fieldError("shape.normal").isEmpty());
        QCOMPARE(f.steps(), 1);  // one step for the one value
        f.doc.undoStack()->undo();
        QCOMPARE(f.doc.body(f.plane).shape.normal, Vec3(0, 1, 0));
        QCOMPARE(normal->value(), Vec3(0, 1, 0));
    }

    // Esc gives the held value up: the last valid one is shown again, framed no more, and a
    // later edit starts from it (not from the held parts).
    void escRestoresTheLastValidValue() {
        Fixture f;
        f.doc.setSelection({f.plane});
        VectorEdit* normal = f.vector("shape.normal");
        f.spin("shape.normal.y")->setValue(0.0);
        QVERIFY(normal->isHeld());
        QTest::keyClick(f.spin("shape.normal.y"), Qt::Key_Escape);
        QVERIFY(!normal->isHeld());
        QCOMPARE(normal->value(), Vec3(0, 1, 0));
        QVERIFY(f.dock.fieldError("shape.normal").isEmpty());
        f.spin("shape.normal.x")->setValue(1.0);
        QCOMPARE(f.doc.body(f.plane).shape.normal, Vec3(1, 1, 0));
        QCOMPARE(f.steps(), 1);
    }

    // Another selection drops the held value: coming back shows the document's.
    void anotherSelectionDropsTheHeldValue() {
        Fixture f;
        f.doc.setSelection({f.plane});
        f.spin("shape.normal.y")->setValue(0.0);
        QVERIFY(f.vector("shape.normal")->isHeld());
        f.doc.setSelection({f.a});
        f.doc.setSelection({f.plane});
        QVERIFY(!f.vector("shape.normal")->isHeld());
        QCOMPARE(f.vector("shape.normal")->value(), Vec3(0, 1, 0));
        QVERIFY(f.dock.fieldError("shape.normal").isEmpty());
        f.spin("shape.normal.z")->setValue(1.0);
        QCOMPARE(f.doc.body(f.plane).shape.normal, Vec3(0, 1, 1));  // from the document's value
    }

    // The inertia matrix, from diag(0.1, 0.1, 0.15) to diag(1, 1, 1.5) cell by cell: the
    // first cell alone gives moments (1, 0.1, 0.15), which no body has; it is held, and the
    // second cell makes the whole valid.
    void anInertiaTensorPassesThroughAnUnphysicalOne() {
        Fixture f;
        f.doc.setSelection({f.a});
        auto* inertia = test::field<InertiaEdit>(f.dock, "inertia");
        BodyDesc b = f.doc.body(f.a);
        b.inertia = Vec3(0.1, 0.1, 0.15).asDiagonal().toDenseMatrix();
        f.doc.setBody(f.a, b, "inertia");
        QVERIFY(inertia->overrideSwitch()->isChecked());
        QCOMPARE(inertia->cell(2, 2)->value(), 0.15);
        const int steps = f.steps();

        inertia->cell(0, 0)->setValue(1.0);
        QVERIFY(inertia->isHeld());
        QCOMPARE((*f.doc.body(f.a).inertia)(0, 0), 0.1);
        QCOMPARE(f.steps(), steps);
        QVERIFY2(f.dock.fieldError("inertia").contains("sum of the other two"),
                 qPrintable(f.dock.fieldError("inertia")));

        inertia->cell(1, 1)->setValue(1.0);
        QVERIFY(!inertia->isHeld());
        QVERIFY(f.doc.body(f.a).inertia->isApprox(Vec3(1, 1, 0.15).asDiagonal().toDenseMatrix(), 0));
        QCOMPARE(f.steps(), steps + 1);
        inertia->cell(2, 2)->setValue(1.5);
        QVERIFY(f.doc.body(f.a).inertia->isApprox(Vec3(1, 1, 1.5).asDiagonal().toDenseMatrix(), 0));

        // An off-diagonal cell held shows its mirror as typed too.
        inertia->cell(0, 1)->setValue(5.0);
        QVERIFY(inertia->isHeld());
        QCOMPARE(inertia->cell(1, 0)->value(), 5.0);
        QCOMPARE((*f.doc.body(f.a).inertia)(0, 1), 0.0);
        QTest::keyClick(inertia->cell(0, 1), Qt::Key_Escape);
        QCOMPARE(inertia->cell(1, 0)->value(), 0.0);
        QCOMPARE(inertia->cell(0, 1)->value(), 0.0);
    }

    // Several boxes: a half extent typed as 0 is held for all of them; the next value is
    // applied to each, each keeping its own other components.
    void aHeldComponentOverSeveralBodies() {
        Fixture f;
        f.doc.setSelection({f.a, f.b});
        f.spin("shape.half_extents.x")->setValue(0.0);
        QVERIFY(f.vector("shape.half_extents")->isHeld());
        QVERIFY2(f.dock.fieldError("shape.half_extents").contains("greater than 0"),
                 qPrintable(f.dock.fieldError("shape.half_extents")));
        QCOMPARE(f.doc.body(f.a).shape.halfExtents, Vec3(0.5, 0.25, 1.0));
        f.spin("shape.half_extents.x")->setValue(0.3);
        QCOMPARE(f.doc.body(f.a).shape.halfExtents, Vec3(0.3, 0.25, 1.0));
        QCOMPARE(f.doc.body(f.b).shape.halfExtents, Vec3(0.3, 0.3, 0.4));
        QVERIFY(!f.vector("shape.half_extents")->isHeld());
        QCOMPARE(f.steps(), 1);
    }

    // Leaving a held field keeps its reason in view (a plain refused number's message goes
    // when the field is left: the field shows its last good value again).
    void theReasonStaysWhileTheValueIsHeld() {
        Fixture f;
        f.doc.setSelection({f.plane});
        f.dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&f.dock));
        QApplication::setActiveWindow(&f.dock);
        PropertySpinBox* y = f.spin("shape.normal.y");
        y->setFocus();
        QTRY_VERIFY(y->hasFocus());
        y->selectAll();
        QTest::keyClicks(y, "0");
        QTest::keyClick(y, Qt::Key_Return);
        QVERIFY(!f.dock.fieldError("shape.normal").isEmpty());
        auto* name = test::field<QLineEdit>(f.dock, "name");
        name->setFocus();
        QTRY_VERIFY(name->hasFocus());
        QVERIFY(!f.dock.fieldError("shape.normal").isEmpty());
        QVERIFY(f.vector("shape.normal")->isHeld());
    }

    // A force's start and end are one window: moving [1, 3] s to [5, 8] s start first goes
    // through [5, 3], which is held (both fields framed, a line saying why), not refused.
    void aForceWindowMovedStartFirst() {
        Fixture f;
        BodyDesc b = f.doc.body(f.a);
        ForceDesc force;
        force.vector = Vec3(0, 10, 0);
        force.start = 1.0;
        force.end = 3.0;
        b.forces.push_back(force);
        f.doc.setBody(f.a, b, "force");
        f.doc.setSelection({f.a});
        auto* why = test::field<QLabel>(f.dock, "forces.window.error");
        QVERIFY(why->isHidden());
        const int steps = f.steps();
        f.spin("forces.start")->setValue(5.0);
        QCOMPARE(f.doc.body(f.a).forces[0].start, std::optional(1.0));
        QCOMPARE(f.steps(), steps);
        QVERIFY(f.spin("forces.start")->isHeld() && f.spin("forces.end")->isHeld());
        QCOMPARE(f.spin("forces.start")->value(), 5.0);
        QVERIFY(!why->isHidden());
        QVERIFY(why->text().contains("later than the start"));

        f.spin("forces.end")->setValue(8.0);
        QCOMPARE(f.doc.body(f.a).forces[0].start, std::optional(5.0));
        QCOMPARE(f.doc.body(f.a).forces[0].end, std::optional(8.0));
        QCOMPARE(f.steps(), steps + 1);
        QVERIFY(!f.spin("forces.start")->isHeld());
        QVERIFY(why->isHidden());

        // Esc on a held window: the last valid times again.
        f.spin("forces.end")->setValue(4.0);
        QVERIFY(f.spin("forces.end")->isHeld());
        QTest::keyClick(f.spin("forces.end"), Qt::Key_Escape);
        QCOMPARE(f.spin("forces.end")->value(), 8.0);
        QVERIFY(!f.spin("forces.end")->isHeld());
        QCOMPARE(f.doc.body(f.a).forces[0].end, std::optional(8.0));
    }
};

QTEST_MAIN(TestHeldValues)
#include "tst_held_values.moc"
