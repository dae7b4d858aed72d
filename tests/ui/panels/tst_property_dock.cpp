// The property panel: each kind of field edit reaches the document and undo restores it; a
// scrub is one undo step; invalid values are refused with a message beside the field and
// the document untouched; several selected bodies are edited together in one step, and a
// field they disagree on shows "—".
#include "document/document.h"
#include "panels/forces_edit.h"
#include "panels/inertia_edit.h"
#include "panels/property_dock.h"
#include "panels/property_euler.h"
#include "panels/property_spin_box.h"
#include "panels/vector_edit.h"
#include "panel_test_util.h"

#include <QCheckBox>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QScrollArea>
#include <QScrollBar>
#include <QWheelEvent>
#include <QUndoStack>
#include <QtTest>

#include <numbers>

using namespace tumble;
using namespace tumble::ui;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A sphere of radius 1 and mass 2.5: its inertia is 2/5 m r² = 1 on the diagonal.
BodyDesc ball() {
    BodyDesc b;
    b.name = "ball";
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = 1.0;
    b.mass = 2.5;
    b.position = Vec3(0, 2, 0);
    return b;
}

BodyDesc crate() {
    BodyDesc b;
    b.name = "crate";
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = Vec3(0.5, 0.25, 1.0);
    b.density = 800.0;
    b.position = Vec3(3, 1, 0);
    b.restitution = 0.2;
    return b;
}

struct Fixture {
    Document doc;
    PropertyDock dock{&doc};
    int ballIndex = -1, crateIndex = -1;

    Fixture() {
        ballIndex = doc.addBody(ball());
        crateIndex = doc.addBody(crate());
        doc.undoStack()->clear();
        doc.setSelection({ballIndex});
    }
    const BodyDesc& ballBody() const { return doc.body(ballIndex); }
    const BodyDesc& crateBody() const { return doc.body(crateIndex); }
    int steps() const { return doc.undoStack()->count(); }
    template <class T>
    T* find(const QString& name) const {
        return test::field<T>(dock, name);
    }
    PropertySpinBox* spin(const QString& name) const { return find<PropertySpinBox>(name); }
    void choose(const QString& comboName, const QString& text) const { test::choose(dock, comboName, text); }
};

// "—" (and the unit): the selected bodies disagree.
bool showsMixed(const PropertySpinBox* spin) {
    return spin->isMixed() && spin->text().startsWith(PropertySpinBox::mixedText());
}

}  // namespace

class TestPropertyDock : public QObject {
    Q_OBJECT
private slots:
    // Issue 21 item 2: the wheel over a field that was not clicked into scrolls the panel
    // and leaves the value (and the undo stack) alone; Ctrl+wheel changes the field, and so
    // does the wheel once the field is being edited.
    void theWheelScrollsThePanelNotTheField() {
        Fixture f;
        f.doc.setSelection({f.crateIndex});
        f.dock.resize(340, 260);  // short: the panel scrolls
        f.dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&f.dock));
        auto* area = f.dock.findChild<QScrollArea*>();
        QVERIFY(area);
        QScrollBar* bar = area->verticalScrollBar();
        QVERIFY(bar->maximum() > 0);
        PropertySpinBox* friction = f.spin("friction");
        area->ensureWidgetVisible(friction);
        QApplication::processEvents();
        auto wheel = [&](QWidget* over, int delta, Qt::KeyboardModifiers mods) {
            const QPoint local = over->rect().center();
            QWheelEvent e(local, over->mapToGlobal(local), QPoint(), QPoint(0, delta), Qt::NoButton, mods,
                          Qt::NoScrollPhase, false);
            QApplication::sendEvent(over, &e);
        };
        // (Sent to the field: Qt passes the wheel from its line edit to it, as it does for a
        // user's; an event sent to the line edit in a test is not passed on.)
        QWidget* text = friction;
        const double value = friction->value();
        const int steps = f.steps(), at = bar->value();
        const int delta = at > 0 ? 120 : -120;  // towards where the panel can go
        wheel(text, delta, Qt::NoModifier);
        QCOMPARE(friction->value(), value);
        QCOMPARE(f.crateBody().friction, value);
        QCOMPARE(f.steps(), steps);
        QVERIFY2(bar->value() != at, "the panel did not scroll");
        // A combo box too.
        auto* kind = f.find<QComboBox>("mass.kind");
        const int index = kind->currentIndex();
        wheel(kind, -delta, Qt::NoModifier);
        QCOMPARE(kind->currentIndex(), index);
        // Ctrl+wheel changes the field under the pointer: one step of friction.
        area->ensureWidgetVisible(friction);
        wheel(friction, 120, Qt::ControlModifier);
        QVERIFY(f.crateBody().friction > value);
        QCOMPARE(f.steps(), steps + 1);
        // A field clicked into takes the wheel.
        QApplication::setActiveWindow(&f.dock);
        friction->setFocus();
        QTRY_VERIFY(friction->hasFocus());
        const double now = f.crateBody().friction;
        wheel(text, 120, Qt::NoModifier);
        QVERIFY(f.crateBody().friction > now);
    }

    void showsTheSelectedBody() {
        Fixture f;
        QCOMPARE(f.find<QLineEdit>("name")->text(), QString("ball"));
        QCOMPARE(f.spin("shape.radius")->value(), 1.0);
        QCOMPARE(f.spin("mass")->value(), 2.5);
        QCOMPARE(f.spin("mass")->suffix(), QString(" kg"));
        QCOMPARE(f.spin("position.y")->value(), 2.0);
        // The inertia shown is the one computed from shape and mass: 2/5 m r² = 1.
        auto* inertia = f.find<InertiaEdit>("inertia");
        QVERIFY(!inertia->overrideSwitch()->isChecked());
        QCOMPARE(inertia->cell(0, 0)->value(), 1.0);
        QCOMPARE(inertia->cell(1, 1)->value(), 1.0);
        QCOMPARE(inertia->cell(0, 1)->value(), 0.0);
        QVERIFY(!inertia->cell(0, 0)->isEnabled());
        // A box with a density shows kg/m³ and the mass it comes to (800 * 1 * 0.5 * 2 = 800 kg).
        f.doc.setSelection({f.crateIndex});
        QCOMPARE(f.spin("mass")->suffix(), QString(" kg/m³"));
        QCOMPARE(f.spin("mass")->value(), 800.0);
        QVERIFY(f.find<QLabel>("mass.note")->text().contains("800 kg"));
        QCOMPARE(f.spin("shape.half_extents.z")->value(), 1.0);
        // Units on the fields.
        QCOMPARE(f.spin("velocity.x")->suffix(), QString(" m/s"));
        QCOMPARE(f.spin("angular_velocity.x")->suffix(), QString(" rad/s"));
        QCOMPARE(f.spin("orientation.x")->suffix(), QString("°"));
        QCOMPARE(inertia->cell(0, 0)->suffix(), QString(" kg·m²"));
    }

    // A compound's mass, centre and inertia shown are its parts' sum (compile's): two unit
    // cubes of their own densities 100 and 300 at x = ±1 weigh 400 kg, centred at x = 0.5,
    // Iyy = 400/6 (each cube's m/6) + 100 (1.5²) + 300 (0.5²) = 366.67, Ixx = 400/6.
    void compoundShowsItsPartsSum() {
        Fixture f;
        BodyDesc c;
        c.name = "pair";
        c.shape.type = ShapeType::Compound;
        for (double x : {-1.0, 1.0}) {
            PartDesc p;
            p.shape.type = ShapeType::Box;
            p.shape.halfExtents = Vec3(0.5, 0.5, 0.5);
            p.position = Vec3(x, 0, 0);
            p.density = x < 0 ? 100.0 : 300.0;
            c.shape.parts.push_back(p);
        }
        const int index = f.doc.addBody(c);
        f.doc.setSelection({index});
        QCOMPARE(f.find<QComboBox>("shape.type")->currentText(), QString("Compound"));
        auto* inertia = f.find<InertiaEdit>("inertia");
        QVERIFY2(std::abs(inertia->cell(1, 1)->value() - (400.0 / 6.0 + 225.0 + 75.0)) < 1e-6,
                 qPrintable(QString::number(inertia->cell(1, 1)->value(), 'g', 17)));
        QVERIFY(std::abs(inertia->cell(0, 0)->value() - 400.0 / 6.0) < 1e-6);
    }

    void nameEditAndUndo() {
        Fixture f;
        auto* name = f.find<QLineEdit>("name");
        name->setText("rock");
        emit name->editingFinished();
        QCOMPARE(f.ballBody().name, std::string("rock"));
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().name, std::string("ball"));
        QCOMPARE(name->text(), QString("ball"));
        // A name another body has is refused, with a message, and the field shows the old name.
        const int before = f.steps();
        name->setText("crate");
        emit name->editingFinished();
        QCOMPARE(f.ballBody().name, std::string("ball"));
        QCOMPARE(f.steps(), before);
        QVERIFY(f.dock.fieldError("name").contains("already"));
        QCOMPARE(name->text(), QString("ball"));
    }

    void motionSwitchKeepsTheMassForLater() {
        Fixture f;
        f.choose("motion", "Static");
        QCOMPARE(f.ballBody().motion, Motion::Static);
        QVERIFY(!f.ballBody().mass);  // a static body has no mass
        QVERIFY(f.dock.fieldError("motion").isEmpty());
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().motion, Motion::Dynamic);
        QCOMPARE(*f.ballBody().mass, 2.5);
        // Static, then dynamic again: the mass comes back.
        f.choose("motion", "Static");
        f.choose("motion", "Dynamic");
        QCOMPARE(f.ballBody().motion, Motion::Dynamic);
        QCOMPARE(*f.ballBody().mass, 2.5);
        // Kinematic keeps its velocity.
        BodyDesc b = f.ballBody();
        b.velocity = Vec3(1, 0, 0);
        f.doc.setBody(f.ballIndex, b, "v");
        f.choose("motion", "Kinematic");
        QCOMPARE(f.ballBody().motion, Motion::Kinematic);
        QCOMPARE(f.ballBody().velocity, Vec3(1, 0, 0));
        QVERIFY(!f.ballBody().mass);
    }

    void aPlaneCannotBeDynamic() {
        Fixture f;
        f.doc.setSelection({0});  // the ground plane
        const SceneDesc before = f.doc.scene();
        f.choose("motion", "Dynamic");
        QCOMPARE(f.doc.scene(), before);
        QVERIFY(f.dock.fieldError("motion").contains("plane"));
        QCOMPARE(f.find<QComboBox>("motion")->currentText(), QString("Static"));
    }

    void radiusEditAndUndo() {
        Fixture f;
        f.spin("shape.radius")->setValue(2.0);
        QCOMPARE(f.ballBody().shape.radius, 2.0);
        // The computed inertia follows: 2/5 * 2.5 * 4 = 4.
        QCOMPARE(f.find<InertiaEdit>("inertia")->cell(0, 0)->value(), 4.0);
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().shape.radius, 1.0);
        QCOMPARE(f.spin("shape.radius")->value(), 1.0);
    }

    void zeroOrNegativeRadiusIsRefused() {
        Fixture f;
        const SceneDesc before = f.doc.scene();
        const int steps = f.steps();
        for (double r : {0.0, -1.0}) {
            f.spin("shape.radius")->setValue(r);
            QCOMPARE(f.doc.scene(), before);
            QCOMPARE(f.steps(), steps);
            QVERIFY(f.dock.fieldError("shape.radius").contains("greater than 0"));
            QCOMPARE(f.spin("shape.radius")->value(), 1.0);  // the last good value
        }
        // A good value clears the message.
        f.spin("shape.radius")->setValue(0.5);
        QCOMPARE(f.ballBody().shape.radius, 0.5);
        QVERIFY(f.dock.fieldError("shape.radius").isEmpty());
    }

    void massEditAndUndo() {
        Fixture f;
        f.spin("mass")->setValue(3.0);
        QCOMPARE(*f.ballBody().mass, 3.0);
        f.doc.undoStack()->undo();
        QCOMPARE(*f.ballBody().mass, 2.5);
        QCOMPARE(f.spin("mass")->value(), 2.5);
    }

    void zeroMassIsRefused() {
        Fixture f;
        const SceneDesc before = f.doc.scene();
        f.spin("mass")->setValue(0.0);
        QCOMPARE(f.doc.scene(), before);
        QVERIFY(!f.dock.fieldError("mass").isEmpty());
        QCOMPARE(f.spin("mass")->value(), 2.5);
    }

    void massToDensityKeepsTheMass() {
        Fixture f;
        f.choose("mass.kind", "Density");
        QVERIFY(!f.ballBody().mass);
        const double volume = 4.0 / 3.0 * std::numbers::pi;
        QVERIFY(std::abs(*f.ballBody().density - 2.5 / volume) < 1e-12);
        QCOMPARE(f.spin("mass")->suffix(), QString(" kg/m³"));
        f.doc.undoStack()->undo();
        QCOMPARE(*f.ballBody().mass, 2.5);
        QVERIFY(!f.ballBody().density);
    }

    void inertiaOverrideAndANonPhysicalTensorIsRefused() {
        Fixture f;
        auto* inertia = f.find<InertiaEdit>("inertia");
        inertia->overrideSwitch()->click();
        QVERIFY(f.ballBody().inertia);
        QVERIFY(f.ballBody().inertia->isApprox(Mat3::Identity(), 1e-12));  // starts from the computed one
        QVERIFY(inertia->cell(2, 2)->isEnabled());

        // diag(1, 1, 5): positive definite but 1 + 1 < 5 breaks the triangle inequality.
        const SceneDesc before = f.doc.scene();
        const int steps = f.steps();
        inertia->cell(2, 2)->setValue(5.0);
        QCOMPARE(f.doc.scene(), before);
        QCOMPARE(f.steps(), steps);
        QVERIFY2(f.dock.fieldError("inertia").contains("sum of the other two"),
                 qPrintable(f.dock.fieldError("inertia")));
        QCOMPARE(inertia->cell(2, 2)->value(), 5.0);  // held as typed (tst_held_values.cpp)
        QVERIFY(inertia->isHeld());
        QTest::keyClick(inertia->cell(2, 2), Qt::Key_Escape);
        QVERIFY(!inertia->isHeld());
        QCOMPARE(inertia->cell(2, 2)->value(), 1.0);
        QVERIFY(f.dock.fieldError("inertia").isEmpty());

        // A physical one is taken; an off-diagonal cell sets its mirror too.
        inertia->cell(2, 2)->setValue(1.5);
        QCOMPARE((*f.ballBody().inertia)(2, 2), 1.5);
        QVERIFY(f.dock.fieldError("inertia").isEmpty());
        inertia->cell(0, 1)->setValue(0.1);
        QCOMPARE((*f.ballBody().inertia)(0, 1), 0.1);
        QCOMPARE((*f.ballBody().inertia)(1, 0), 0.1);
        QCOMPARE(inertia->cell(1, 0)->value(), 0.1);

        // Switched off, the computed tensor is back.
        inertia->overrideSwitch()->click();
        QVERIFY(!f.ballBody().inertia);
        QCOMPARE(inertia->cell(2, 2)->value(), 1.0);
    }

    void centreOfMassOverride() {
        Fixture f;
        f.find<QCheckBox>("center_of_mass.override")->click();
        QCOMPARE(*f.ballBody().centerOfMass, Vec3::Zero());
        f.spin("center_of_mass.y")->setValue(0.25);
        QCOMPARE(*f.ballBody().centerOfMass, Vec3(0, 0.25, 0));
        f.doc.undoStack()->undo();
        QCOMPARE(*f.ballBody().centerOfMass, Vec3::Zero());
    }

    void restitutionEditAndOutOfRangeRefused() {
        Fixture f;
        f.spin("restitution")->setValue(0.8);
        QCOMPARE(f.ballBody().restitution, 0.8);
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().restitution, 0.5);

        const SceneDesc before = f.doc.scene();
        f.spin("restitution")->setValue(1.5);
        QCOMPARE(f.doc.scene(), before);
        QVERIFY(f.dock.fieldError("restitution").contains("between 0 and 1"));
        QCOMPARE(f.spin("restitution")->value(), 0.5);
    }

    // Issue 21 item 8: a negative mass typed in is refused with the engine's message, like
    // 0 (it was turned back without a word); the arrows stop at 0; a refused value's message
    // goes once the focus leaves the field, which shows the last good value again.
    void typedValuesBelowZeroAreRefusedAloud() {
        Fixture f;
        f.dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&f.dock));
        QApplication::setActiveWindow(&f.dock);
        const SceneDesc before = f.doc.scene();
        PropertySpinBox* mass = f.spin("mass");
        mass->setFocus();
        QTRY_VERIFY(mass->hasFocus());
        mass->selectAll();
        QTest::keyClicks(mass, "-3");
        QTest::keyClick(mass, Qt::Key_Return);
        QCOMPARE(f.doc.scene(), before);
        QVERIFY2(!f.dock.fieldError("mass").isEmpty(), "no message for a negative mass");
        QCOMPARE(mass->value(), 2.5);
        // Leaving the field takes the message away; the field holds 2.5, a good value.
        f.spin("restitution")->setFocus();
        QTRY_VERIFY(f.dock.fieldError("mass").isEmpty());
        // The same for a restitution above 1.
        PropertySpinBox* e = f.spin("restitution");
        e->selectAll();
        QTest::keyClicks(e, "1.5");
        QTest::keyClick(e, Qt::Key_Return);
        QVERIFY(f.dock.fieldError("restitution").contains("between 0 and 1"));
        QCOMPARE(e->value(), 0.5);
        f.spin("friction")->setFocus();
        QTRY_VERIFY(f.dock.fieldError("restitution").isEmpty());
        // The arrows stop at 0.
        f.spin("friction")->setValue(0.05);
        f.spin("friction")->stepBy(-3);
        QCOMPARE(f.ballBody().friction, 0.0);
        QVERIFY(!(f.spin("friction")->stepEnabled() & QAbstractSpinBox::StepDownEnabled));
        QVERIFY(f.dock.fieldError("friction").isEmpty());
    }

    void frictionAndDamping() {
        Fixture f;
        f.spin("friction")->setValue(0.9);
        f.spin("linear_damping")->setValue(0.1);
        f.spin("angular_damping")->setValue(0.2);
        QCOMPARE(f.ballBody().friction, 0.9);
        QCOMPARE(f.ballBody().linearDamping, 0.1);
        QCOMPARE(f.ballBody().angularDamping, 0.2);
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().angularDamping, 0.0);
        QCOMPARE(f.ballBody().linearDamping, 0.1);
    }

    void positionEditAndUndo() {
        Fixture f;
        f.spin("position.y")->setValue(3.0);
        QCOMPARE(f.ballBody().position, Vec3(0, 3, 0));
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().position, Vec3(0, 2, 0));
        QCOMPARE(f.spin("position.y")->value(), 2.0);
    }

    void eulerAnglesToQuaternionAndBack() {
        Fixture f;
        // Convention: q = Rz(z) Ry(y) Rx(x) (intrinsic Z-Y'-X'').
        f.spin("orientation.z")->setValue(30.0);
        const Quat z30(Eigen::AngleAxisd(30 * kDeg, Vec3::UnitZ()));
        QVERIFY(sameRotation(f.ballBody().orientation, z30, 1e-12));
        f.spin("orientation.x")->setValue(10.0);
        const Quat expected = z30 * Eigen::AngleAxisd(10 * kDeg, Vec3::UnitX());
        QVERIFY(sameRotation(f.ballBody().orientation, expected, 1e-12));
        QCOMPARE(f.spin("orientation.z")->value(), 30.0);
        f.doc.undoStack()->undo();
        QVERIFY(sameRotation(f.ballBody().orientation, z30, 1e-12));
        f.doc.undoStack()->undo();
        QVERIFY(sameRotation(f.ballBody().orientation, Quat::Identity(), 1e-12));

        // A quaternion from the document shows as its angles.
        BodyDesc b = f.ballBody();
        b.orientation = Eigen::AngleAxisd(40 * kDeg, Vec3::UnitZ()) *
                        Eigen::AngleAxisd(20 * kDeg, Vec3::UnitY()) *
                        Eigen::AngleAxisd(-15 * kDeg, Vec3::UnitX());
        f.doc.setBody(f.ballIndex, b, "Rotate");
        QVERIFY(std::abs(f.spin("orientation.x")->value() + 15.0) < 1e-9);
        QVERIFY(std::abs(f.spin("orientation.y")->value() - 20.0) < 1e-9);
        QVERIFY(std::abs(f.spin("orientation.z")->value() - 40.0) < 1e-9);

        // Both directions agree over many angles, and at the gimbal lock.
        for (double x : {-170.0, -45.0, 0.0, 33.0, 179.0})
            for (double y : {-89.0, -30.0, 0.0, 60.0, 89.5})
                for (double z : {-120.0, 0.0, 15.0, 175.0}) {
                    const Vec3 e = quatToEulerDegrees(eulerDegreesToQuat(Vec3(x, y, z)));
                    QVERIFY2((e - Vec3(x, y, z)).cwiseAbs().maxCoeff() < 1e-7,
                             qPrintable(QString::number(x)));
                }
        const Quat lock = eulerDegreesToQuat(Vec3(20, 90, 50));
        QVERIFY(sameRotation(eulerDegreesToQuat(quatToEulerDegrees(lock)), lock, 1e-9));
    }

    void typedAnglesAreKeptWhileTheyDescribeTheBody() {
        Fixture f;
        // y = 120 is the same rotation as (180, 60, 180); the panel keeps what was typed.
        f.spin("orientation.y")->setValue(120.0);
        QCOMPARE(f.spin("orientation.y")->value(), 120.0);
        QCOMPARE(f.spin("orientation.x")->value(), 0.0);
        f.spin("orientation.x")->setValue(10.0);
        const Quat expected =
            Eigen::AngleAxisd(120 * kDeg, Vec3::UnitY()) * Eigen::AngleAxisd(10 * kDeg, Vec3::UnitX());
        QVERIFY(sameRotation(f.ballBody().orientation, expected, 1e-12));
    }

    void velocityEditAndUndo() {
        Fixture f;
        f.spin("velocity.x")->setValue(4.0);
        f.spin("angular_velocity.z")->setValue(-1.0);
        QCOMPARE(f.ballBody().velocity, Vec3(4, 0, 0));
        QCOMPARE(f.ballBody().angularVelocity, Vec3(0, 0, -1));
        f.doc.undoStack()->undo();
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().velocity, Vec3::Zero());
        QCOMPARE(f.ballBody().angularVelocity, Vec3::Zero());
    }

    // An animated body moves as its keys say: its velocity fields are off, and the Keys box
    // shows its keys.
    void anAnimatedBodyHasNoVelocityFields() {
        Fixture f;
        QVERIFY(f.spin("velocity.x")->isEnabled());
        f.choose("motion", "Animated");
        QCOMPARE(f.ballBody().motion, Motion::Animated);
        QCOMPARE(int(f.ballBody().keys.size()), 1);  // its first key, where it stands, at 0
        QVERIFY(!f.spin("velocity.x")->isEnabled() && !f.spin("angular_velocity.z")->isEnabled());
        QVERIFY(f.dock.findChild<QWidget*>("keys.box")->isVisibleTo(&f.dock));
        f.choose("motion", "Dynamic");
        QVERIFY(f.spin("velocity.x")->isEnabled());
        QVERIFY(f.ballBody().keys.empty());
    }

    void forceAddedEditedRemoved() {
        Fixture f;
        auto* forces = f.find<ForcesEdit>("forces");
        forces->addForce(ForceType::Force);
        QCOMPARE(f.ballBody().forces.size(), size_t(1));
        QCOMPARE(f.ballBody().forces[0].type, ForceType::Force);
        QCOMPARE(forces->currentIndex(), 0);

        f.spin("forces.vector.y")->setValue(-5.0);
        QCOMPARE(f.ballBody().forces[0].vector, Vec3(0, -5, 0));
        QCOMPARE(f.spin("forces.vector.y")->suffix(), QString(" N"));
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().forces[0].vector, Vec3::Zero());
        f.doc.undoStack()->redo();

        // An optional point and a time window.
        f.find<QCheckBox>("forces.point.on")->click();
        QCOMPARE(*f.ballBody().forces[0].point, Vec3::Zero());
        f.find<QCheckBox>("forces.end.on")->click();
        f.spin("forces.end")->setValue(2.0);
        QCOMPARE(*f.ballBody().forces[0].end, 2.0);

        // A spring with a negative stiffness is refused.
        forces->addForce(ForceType::Spring);
        QCOMPARE(f.ballBody().forces.size(), size_t(2));
        QCOMPARE(forces->currentIndex(), 1);
        f.spin("forces.stiffness")->setValue(50.0);
        QCOMPARE(f.ballBody().forces[1].stiffness, 50.0);
        const SceneDesc before = f.doc.scene();
        f.spin("forces.stiffness")->setValue(-1.0);
        QCOMPARE(f.doc.scene(), before);
        QVERIFY(f.dock.fieldError("forces").contains("0 or greater"));
        QCOMPARE(f.spin("forces.stiffness")->value(), 50.0);

        // Removing takes the current one; undo brings it back.
        forces->setCurrentIndex(0);
        forces->removeCurrent();
        QCOMPARE(f.ballBody().forces.size(), size_t(1));
        QCOMPARE(f.ballBody().forces[0].type, ForceType::Spring);
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().forces.size(), size_t(2));
        QCOMPARE(f.ballBody().forces[0].vector, Vec3(0, -5, 0));
    }

    void aScrubIsOneUndoStep() {
        Fixture f;
        const int steps = f.steps();
        auto* radius = f.spin("shape.radius");
        radius->setSingleStep(0.1);
        for (int k = 0; k < 5; ++k) radius->stepBy(1);
        QVERIFY(std::abs(f.ballBody().shape.radius - 1.5) < 1e-12);
        QCOMPARE(f.steps(), steps + 1);
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().shape.radius, 1.0);
        // Leaving the field ends the scrub: the next edit is a step of its own.
        f.doc.undoStack()->redo();
        emit radius->editingFinished();
        radius->stepBy(1);
        QCOMPARE(f.steps(), steps + 2);
    }

    // Issue 52 item 5: an undo entry names the body, what changed and the new value as its
    // field shows it; a scrub's one entry names the last value.
    void undoEntriesSayWhatChangedAndTo() {
        Fixture f;
        QUndoStack* undo = f.doc.undoStack();
        f.spin("mass")->setValue(25.0);
        QCOMPARE(undo->undoText(), QString("Set mass of ball to 25 kg"));
        f.spin("restitution")->setValue(0.75);
        QCOMPARE(undo->undoText(), QString("Set restitution of ball to 0.75"));
        f.spin("position.y")->setValue(1.0 / 3.0);
        QCOMPARE(undo->undoText(), QString("Set position y of ball to 0.333333 m"));
        f.spin("orientation.z")->setValue(30.0);
        QCOMPARE(undo->undoText(), QString("Set orientation z of ball to 30°"));
        f.choose("motion", "Static");
        QCOMPARE(undo->undoText(), QString("Set motion of ball to Static"));
        undo->undo();
        const int steps = undo->index();
        auto* radius = f.spin("shape.radius");
        radius->setSingleStep(0.1);
        for (int k = 0; k < 3; ++k) radius->stepBy(1);
        QCOMPARE(undo->index(), steps + 1);
        QCOMPARE(undo->undoText(), QString("Set radius of ball to 1.3 m"));
        f.doc.setSelection({f.ballIndex, f.crateIndex});
        f.spin("friction")->setValue(0.25);
        QCOMPARE(undo->undoText(), QString("Set friction of 2 bodies to 0.25"));
        for (double z : {1.0, 2.0}) f.spin("position.z")->setValue(z);
        QCOMPARE(undo->undoText(), QString("Set position z of 2 bodies to 2 m"));
    }

    void multiSelectionEditsAllInOneStep() {
        Fixture f;
        f.doc.setSelection({f.ballIndex, f.crateIndex});
        QVERIFY(showsMixed(f.spin("restitution")));  // 0.5 and 0.2
        QCOMPARE(f.spin("friction")->value(), 0.5);  // both 0.5
        QVERIFY(!f.spin("friction")->isMixed());
        QCOMPARE(f.spin("position.z")->value(), 0.0);
        QVERIFY(showsMixed(f.spin("position.x")));
        QVERIFY(!f.find<QLineEdit>("name")->isEnabled());

        const int steps = f.steps();
        f.spin("restitution")->setValue(0.9);
        QCOMPARE(f.ballBody().restitution, 0.9);
        QCOMPARE(f.crateBody().restitution, 0.9);
        QCOMPARE(f.steps(), steps + 1);
        QVERIFY(!f.spin("restitution")->isMixed());
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().restitution, 0.5);
        QCOMPARE(f.crateBody().restitution, 0.2);
        QVERIFY(showsMixed(f.spin("restitution")));

        // One component of a vector: each body keeps its own other components.
        f.spin("position.y")->setValue(5.0);
        QCOMPARE(f.ballBody().position, Vec3(0, 5, 0));
        QCOMPARE(f.crateBody().position, Vec3(3, 5, 0));

        // A scrub over several bodies is one step too.
        const int before = f.steps();
        for (double z : {1.0, 2.0, 3.0}) f.spin("position.z")->setValue(z);
        QCOMPARE(f.steps(), before + 1);
        QCOMPARE(f.ballBody().position.z(), 3.0);
        QCOMPARE(f.crateBody().position.z(), 3.0);
        f.doc.undoStack()->undo();
        QCOMPARE(f.ballBody().position.z(), 0.0);
        QCOMPARE(f.crateBody().position.z(), 0.0);
        QCOMPARE(f.ballBody().position.y(), 5.0);
    }

    void multiSelectionInvalidIsRefusedForAll() {
        Fixture f;
        f.doc.setSelection({f.ballIndex, f.crateIndex});
        // A mass and a density: one number cannot be both, so the value waits for a choice.
        QVERIFY(showsMixed(f.spin("mass")));
        QVERIFY(!f.spin("mass")->isEnabled());
        f.choose("mass.kind", "Mass");  // the crate keeps its 800 kg as a mass
        QCOMPARE(f.crateBody().mass.value_or(0.0), 800.0);
        QVERIFY(!f.crateBody().density);
        QVERIFY(f.spin("mass")->isEnabled());
        QCOMPARE(f.spin("mass")->suffix(), QString(" kg"));

        const SceneDesc before = f.doc.scene();
        const int steps = f.steps();
        f.spin("mass")->setValue(0.0);
        QCOMPARE(f.doc.scene(), before);
        QCOMPARE(f.steps(), steps);
        QVERIFY(!f.dock.fieldError("mass").isEmpty());
        f.spin("restitution")->setValue(1.5);
        QCOMPARE(f.doc.scene(), before);
        QVERIFY(f.dock.fieldError("restitution").contains("between 0 and 1"));
    }

    void typingTheHeldValueUnderADashAppliesIt() {
        Fixture f;
        f.doc.setSelection({f.ballIndex, f.crateIndex});
        auto* restitution = f.spin("restitution");
        QVERIFY(showsMixed(restitution));
        QCOMPARE(restitution->value(), 0.5);  // held from the first body, shown as "—"
        auto* line = restitution->findChild<QLineEdit*>();
        QVERIFY(line);
        line->setText("0.5");
        emit restitution->editingFinished();
        QCOMPARE(f.ballBody().restitution, 0.5);
        QCOMPARE(f.crateBody().restitution, 0.5);
        QVERIFY(!showsMixed(restitution));
    }

    void multiSelectionHidesWhatDoesNotApplyToAll() {
        Fixture f;
        f.doc.setSelection({f.ballIndex, f.crateIndex});
        // Radius is a sphere's, half extents a box's: neither row applies to both.
        QVERIFY(f.spin("shape.radius")->parentWidget()->isHidden());
        QVERIFY(f.find<QComboBox>("shape.type")->currentIndex() == -1);
        f.doc.setSelection({f.ballIndex});
        QVERIFY(!f.spin("shape.radius")->parentWidget()->isHidden());
        QCOMPARE(f.find<QComboBox>("shape.type")->currentText(), QString("Sphere"));
    }

    void followsTheDocumentWithoutEditingIt() {
        Fixture f;
        const int steps = f.steps();
        BodyDesc b = f.ballBody();
        b.shape.radius = 0.75;
        f.doc.setBody(f.ballIndex, b, "Resize");
        QCOMPARE(f.spin("shape.radius")->value(), 0.75);
        f.doc.undoStack()->undo();
        QCOMPARE(f.spin("shape.radius")->value(), 1.0);
        QCOMPARE(f.steps(), steps + 1);  // showing values pushed nothing
        f.doc.setSelection({});
        QVERIFY(!f.find<QLabel>("empty")->isHidden());
    }
};

QTEST_MAIN(TestPropertyDock)
#include "tst_property_dock.moc"
