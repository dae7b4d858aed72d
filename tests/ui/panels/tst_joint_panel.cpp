// Joints in the editor: the Scene dock lists them and selecting one selects it in the
// document (and deselects the bodies, and back); the property panel's joint page edits
// every field with undo (a scrub one step), refuses what the engine would refuse with a
// message under the field, keeps an anchor where it is in the world when its body changes,
// and clears what a new type cannot have; Delete removes the selected joint.
#include "document/document.h"
#include "document/joint_presets.h"
#include "panels/joint_list.h"
#include "panels/joint_panel.h"
#include "panels/property_dock.h"
#include "panels/property_spin_box.h"
#include "panels/scene_tree_dock.h"
#include "panels/vector_edit.h"
#include "panel_test_util.h"

#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QTreeWidget>
#include <QUndoStack>
#include <QtTest>

#include <numbers>

using namespace tumble;
using namespace tumble::ui;

namespace {

BodyDesc box(const char* name, Vec3 position, Motion motion = Motion::Dynamic) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = Vec3(0.4, 1.0, 0.02);
    if (motion == Motion::Dynamic) b.mass = 20.0;
    b.motion = motion;
    b.position = position;
    return b;
}

// A door turned a quarter about y, hinged at its edge to a post.
struct Fixture {
    Document doc;
    SceneTreeDock tree{&doc, nullptr};
    PropertyDock dock{&doc};

    Fixture() {
        doc.addBody(box("post", Vec3(-0.45, 1.0, 0.0), Motion::Static));
        BodyDesc door = box("door", Vec3(0.0, 1.0, 0.0));
        door.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()));
        doc.addBody(door);
        JointDesc j;
        j.name = "hinge";
        j.type = JointType::Hinge;
        j.bodyA = "door";
        j.bodyB = "post";
        j.anchorA = Vec3(-0.4, 0, 0);
        j.anchorB = door.position + door.orientation * j.anchorA - Vec3(-0.45, 1.0, 0.0);
        j.axisA = Vec3::UnitY();
        doc.addJoint(j);
        doc.undoStack()->clear();
        doc.selectJoint(-1);
    }
    const JointDesc& joint() const { return doc.joint(0); }
    // (The document starts with a ground plane.)
    int indexOf(const std::string& name) const {
        for (int i = 0; i < doc.bodyCount(); ++i)
            if (doc.body(i).name == name) return i;
        return -1;
    }
    const BodyDesc& door() const { return doc.body(indexOf("door")); }
    JointPanel* panel() const { return dock.findChild<JointPanel*>(); }
    template <class T>
    T* find(const QString& name) const {
        return test::field<T>(dock, name);
    }
    PropertySpinBox* spin(const QString& name) const { return find<PropertySpinBox>(name); }
    void choose(const QString& comboName, const QString& text) const { test::choose(dock, comboName, text); }
    Vec3 worldAnchorB() const {
        const JointDesc& j = joint();
        for (const BodyDesc& b : doc.scene().bodies)
            if (b.name == j.bodyB) return b.position + b.orientation * j.anchorB;
        return j.anchorB;
    }
};

}  // namespace

class TestJointPanel : public QObject {
    Q_OBJECT
private slots:
    // Issue 51 item 2: the panel names the base and the moving part, and Swap exchanges them
    // in one undo step, meaning the same (anchors with their bodies, limits and motor speed
    // of the other sign); a joint to the world has nothing to swap with.
    void swapExchangesTheBaseAndTheMovingPart() {
        Fixture f;
        JointDesc j = f.joint();
        j.limits = std::array<double, 2>{0.0, 1.5};
        j.motor = JointDesc::Motor{1.0, 20.0};
        f.doc.setJoint(0, j, "Limits and motor");
        f.doc.selectJoint(0);
        auto* swap = f.find<QPushButton>("joint.swap");
        QVERIFY(swap && swap->isEnabled());
        const int steps = f.doc.undoStack()->count();
        swap->click();
        QCOMPARE(f.doc.undoStack()->count(), steps + 1);
        const JointDesc& s = f.joint();
        QCOMPARE(s.bodyA, std::string("post"));
        QCOMPARE(s.bodyB, std::string("door"));
        QCOMPARE(s.anchorA, j.anchorB);
        QCOMPARE(s.anchorB, j.anchorA);
        QVERIFY(*s.limits == (std::array<double, 2>{-1.5, 0.0}));
        QCOMPARE(s.motor->speed, -1.0);
        QCOMPARE(f.find<QComboBox>("joint.body_a")->currentText(), QString("post"));
        f.doc.undoStack()->undo();
        QCOMPARE(f.joint().bodyA, std::string("door"));
        f.choose("joint.body_b", "(world)");
        QVERIFY(!swap->isEnabled());
    }

    void listSelectsTheJointAndTheBodiesBack() {
        Fixture f;
        auto* list = f.tree.findChild<QTreeWidget*>("jointListView");
        QVERIFY(list);
        QCOMPARE(list->topLevelItemCount(), 1);
        QCOMPARE(list->topLevelItem(0)->text(JointList::NameColumn), QString("hinge"));
        QCOMPARE(list->topLevelItem(0)->text(JointList::BodiesColumn), QString("door – post"));
        f.doc.setSelection({f.indexOf("door")});
        list->topLevelItem(0)->setSelected(true);
        QCOMPARE(f.doc.selectedJoint(), 0);
        QVERIFY(f.doc.selection().isEmpty());  // the bodies are deselected
        QVERIFY(f.panel()->isVisibleTo(&f.dock));
        QCOMPARE(f.find<QLineEdit>("joint.name")->text(), QString("hinge"));
        QCOMPARE(f.spin("joint.limits.lower")->isEnabled(), false);  // no limits yet
        f.doc.setSelection({f.indexOf("door")});  // a body: the joint is deselected, its page hidden
        QCOMPARE(f.doc.selectedJoint(), -1);
        QVERIFY(list->selectedItems().isEmpty());
        QVERIFY(!f.panel()->isVisibleTo(&f.dock));
    }

    void editsAreUndoableAndAScrubIsOneStep() {
        Fixture f;
        f.doc.selectJoint(0);
        f.find<QCheckBox>("joint.motor.on")->setChecked(true);
        QVERIFY(f.joint().motor.has_value());
        QCOMPARE(f.doc.undoStack()->count(), 1);
        for (double v : {1.5, 2.0, 2.5}) f.spin("joint.motor.speed")->setValue(v);
        QCOMPARE(f.joint().motor->speed, 2.5);
        QCOMPARE(f.doc.undoStack()->count(), 2);  // the scrub merged
        // Its entry names the joint and the last value, in the field's unit (issue 52).
        QCOMPARE(f.doc.undoStack()->undoText(),
                 QString("Set motor speed of %1 to 2.5 %2")
                     .arg(QString::fromStdString(f.joint().name), f.spin("joint.motor.speed")->suffix().trimmed()));
        QVERIFY(!f.spin("joint.motor.speed")->suffix().trimmed().isEmpty());
        emit f.spin("joint.motor.speed")->editingFinished();
        f.spin("joint.motor.max")->setValue(35.0);
        QCOMPARE(f.joint().motor->maxForce, 35.0);
        QCOMPARE(f.doc.undoStack()->count(), 3);
        f.doc.undoStack()->undo();
        f.doc.undoStack()->undo();
        QCOMPARE(f.joint().motor->speed, 1.0);  // as the check box made it
        QCOMPARE(f.spin("joint.motor.speed")->value(), 1.0);
        f.doc.undoStack()->undo();
        QVERIFY(!f.joint().motor);
        QVERIFY(!f.find<QCheckBox>("joint.motor.on")->isChecked());
    }

    // Issue 50: "its bodies collide" is the joint's collide_connected, one undo step.
    void collideConnectedIsATick() {
        Fixture f;
        f.doc.selectJoint(0);
        auto* collide = f.find<QCheckBox>("joint.collide_connected");
        QVERIFY(!collide->isChecked());
        collide->setChecked(true);
        QVERIFY(f.joint().collideConnected);
        QCOMPARE(f.doc.undoStack()->count(), 1);
        f.doc.undoStack()->undo();
        QVERIFY(!f.joint().collideConnected);
        QVERIFY(!collide->isChecked());
    }

    void hingeLimitsInDegreesAndInvertedOnesHeld() {
        Fixture f;
        f.doc.selectJoint(0);
        f.find<QCheckBox>("joint.limits.on")->setChecked(true);
        QVERIFY(f.joint().limits.has_value());
        f.spin("joint.limits.upper")->setValue(90.0);
        QCOMPARE((*f.joint().limits)[1], std::numbers::pi / 2);
        emit f.spin("joint.limits.upper")->editingFinished();
        const JointDesc before = f.joint();
        const int steps = f.doc.undoStack()->count();
        f.spin("joint.limits.lower")->setValue(120.0);  // above the upper limit
        QCOMPARE(f.joint(), before);
        QCOMPARE(f.doc.undoStack()->count(), steps);
        // The two limits are one value (issue 46): held as typed, the reason in plain words.
        const QString why = f.panel()->fieldError("limits");
        QVERIFY2(why.contains("lower limit cannot be above") && !why.contains("joints["), qPrintable(why));
        QCOMPARE(f.spin("joint.limits.lower")->value(), 120.0);
        QVERIFY(f.spin("joint.limits.lower")->isHeld() && f.spin("joint.limits.upper")->isHeld());
        f.spin("joint.limits.upper")->setValue(150.0);  // [120, 150]: the window moved up, as typed
        QCOMPARE((*f.joint().limits)[0], 120.0 * std::numbers::pi / 180.0);
        QCOMPARE((*f.joint().limits)[1], 150.0 * std::numbers::pi / 180.0);
        QCOMPARE(f.doc.undoStack()->count(), steps + 1);
        QVERIFY(!f.spin("joint.limits.lower")->isHeld());
        QVERIFY(f.panel()->fieldError("limits").isEmpty());
        f.spin("joint.limits.lower")->setValue(160.0);
        QVERIFY(f.spin("joint.limits.lower")->isHeld());
        QTest::keyClick(f.spin("joint.limits.lower"), Qt::Key_Escape);  // given up: 120 again
        QCOMPARE(f.spin("joint.limits.lower")->value(), 120.0);
        QVERIFY(f.panel()->fieldError("limits").isEmpty());
        f.spin("joint.limits.lower")->setValue(-10.0);
        QVERIFY(f.panel()->fieldError("limits").isEmpty());
        // A body's own problem (a static body given a mass) is not the joint's: its edits go on.
        BodyDesc post = f.doc.body(f.indexOf("post"));
        post.mass = 5.0;
        f.doc.setBody(f.indexOf("post"), post, "bad mass");
        f.doc.selectJoint(0);
        f.spin("joint.limits.lower")->setValue(-20.0);
        QCOMPARE((*f.joint().limits)[0], -20.0 * std::numbers::pi / 180.0);
    }

    // Issue 46: turning the axis from y to z a field at a time passes through (0, 0, 0),
    // which is refused. The typed values are held (the field marked, the reason in plain
    // words), the next field completes the vector and it goes in as typed, never a mix of
    // typed and old components; Esc gives a held edit up.
    // Issue 51 item 3: anchors typed as world points (the toggle), kept in each body's
    // frame as the bodies are placed. The door is turned a quarter about y at (0, 1, 0): its
    // anchor (-0.4, 0, 0) is the world point (0, 1, 0.4); typed there as x = 0.1, it is
    // (-0.4, 0, 0.1) in the door's frame.
    void anchorsTypedAsWorldPoints() {
        Fixture f;
        f.doc.selectJoint(0);
        VectorEdit* a = f.find<VectorEdit>("joint.anchor_a");
        QVERIFY((a->value() - Vec3(-0.4, 0, 0)).norm() < 1e-12);
        f.find<QCheckBox>("joint.anchors_world")->setChecked(true);
        QVERIFY2((a->value() - Vec3(0, 1, 0.4)).norm() < 1e-12,
                 qPrintable(QString("%1 %2 %3").arg(a->value().x()).arg(a->value().y()).arg(a->value().z())));
        const Vec3 b = f.find<VectorEdit>("joint.anchor_b")->value();
        QVERIFY((b - Vec3(0, 1, 0.4)).norm() < 1e-12);  // the same point on the post
        f.spin("joint.anchor_a.x")->setValue(0.1);
        QVERIFY((f.joint().anchorA - Vec3(-0.4, 0, 0.1)).norm() < 1e-12);
        QVERIFY((a->value() - Vec3(0.1, 1, 0.4)).norm() < 1e-12);
        f.find<QCheckBox>("joint.anchors_world")->setChecked(false);
        QVERIFY((a->value() - Vec3(-0.4, 0, 0.1)).norm() < 1e-12);
    }

    void aVectorIsEditedAsOneValue() {
        Fixture f;
        f.doc.selectJoint(0);
        VectorEdit* axis = f.find<VectorEdit>("joint.axis_a");
        const int steps = f.doc.undoStack()->count();
        f.spin("joint.axis_a.y")->setValue(0.0);  // (0, 0, 0): refused, held
        QCOMPARE(*f.joint().axisA, Vec3::UnitY());
        QCOMPARE(f.doc.undoStack()->count(), steps);
        QVERIFY(axis->isHeld());
        const QString why = f.panel()->fieldError("axis_a");
        QVERIFY2(why.contains("The axis cannot be zero") && !why.contains("joints["), qPrintable(why));
        QCOMPARE(axis->value(), Vec3::Zero());    // as typed, not the joint's y back
        f.spin("joint.axis_a.z")->setValue(1.0);  // (0, 0, 1): valid, in as typed
        QCOMPARE(*f.joint().axisA, Vec3::UnitZ());
        QVERIFY(!axis->isHeld());
        QVERIFY(f.panel()->fieldError("axis_a").isEmpty());
        f.doc.undoStack()->undo();
        QCOMPARE(*f.joint().axisA, Vec3::UnitY());

        // Held, then Esc: the last valid value again, nothing changed.
        f.doc.selectJoint(0);
        f.spin("joint.axis_a.y")->setValue(0.0);
        QVERIFY(axis->isHeld());
        QTest::keyClick(f.spin("joint.axis_a.y"), Qt::Key_Escape);
        QVERIFY(!axis->isHeld());
        QCOMPARE(axis->value(), Vec3::UnitY());
        QVERIFY(f.panel()->fieldError("axis_a").isEmpty());
        QCOMPARE(*f.joint().axisA, Vec3::UnitY());
    }

    void bodyChangeKeepsTheAnchorInTheWorld() {
        Fixture f;
        f.doc.selectJoint(0);
        const Vec3 world = f.worldAnchorB();
        f.choose("joint.body_b", "(world)");
        QVERIFY(f.joint().bodyB.empty());
        QVERIFY((f.joint().anchorB - world).norm() < 1e-12);
        QVERIFY((f.worldAnchorB() - world).norm() < 1e-12);
        QCOMPARE(f.find<QComboBox>("joint.body_b")->currentText(), QString("(world)"));
        f.doc.undoStack()->undo();
        QCOMPARE(f.joint().bodyB, std::string("post"));
        // Body A to the post: nothing that moves would be joined (static to the world).
        f.choose("joint.body_b", "(world)");
        const JointDesc before = f.joint();
        f.choose("joint.body_a", "post");
        QCOMPARE(f.joint(), before);
        QVERIFY(f.panel()->fieldError("body_a").contains("must be dynamic"));
        QCOMPARE(f.find<QComboBox>("joint.body_a")->currentText(), QString("door"));
    }

    void typeChangeKeepsANameTheUserGave() {
        Fixture f;
        JointDesc named = f.joint();
        named.name = "door-pin";
        f.doc.setJoint(0, named, "Rename");
        f.doc.selectJoint(0);
        f.choose("joint.type", "slider");
        QCOMPARE(f.joint().type, JointType::Slider);
        QCOMPARE(f.joint().name, std::string("door-pin"));
    }

    void typeChangeClearsWhatTheTypeCannotHave() {
        Fixture f;
        f.doc.selectJoint(0);
        f.find<QCheckBox>("joint.limits.on")->setChecked(true);
        f.find<QCheckBox>("joint.motor.on")->setChecked(true);
        f.choose("joint.type", "ball");
        QCOMPARE(f.joint().type, JointType::Ball);
        QVERIFY(!f.joint().axisA && !f.joint().limits && !f.joint().motor);
        // "hinge", a name that only said its type, follows the type; the undo entry names it.
        QCOMPARE(f.joint().name, std::string("ball"));
        QCOMPARE(f.doc.undoStack()->undoText(), QString("Set joint type of hinge to ball"));
        QVERIFY(!f.find<VectorEdit>("joint.axis_a")->isVisibleTo(&f.dock));
        f.choose("joint.type", "slider");  // a slider needs an axis: A's x as it lies
        QVERIFY(f.joint().axisA.has_value());
        QVERIFY((*f.joint().axisA - f.door().orientation.conjugate() * Vec3::UnitX()).norm() < 1e-12);
        QCOMPARE(f.joint().name, std::string("slider"));
        f.choose("joint.type", "rope");
        QCOMPARE(f.joint().name, std::string("rope"));
        QCOMPARE(f.joint().length, -1.0);
        QVERIFY(f.find<QCheckBox>("joint.length.as_placed")->isChecked());
        f.find<QCheckBox>("joint.length.as_placed")->setChecked(false);  // the distance now
        const Vec3 a = f.door().position + f.door().orientation * f.joint().anchorA;
        QVERIFY(std::abs(f.joint().length - (a - f.worldAnchorB()).norm()) < 1e-12);
        f.doc.undoStack()->undo();
        f.doc.undoStack()->undo();
        f.doc.undoStack()->undo();
        f.doc.undoStack()->undo();
        QCOMPARE(f.joint().type, JointType::Hinge);
        QVERIFY(f.joint().limits && f.joint().motor);
    }

    // Issue 51 item 3: a hinge's spring and servo in the panel, in its units (the rest and
    // the target in degrees, kept in radians), one undo step each; the servo and the motor
    // are one drive: ticking either takes the other away; a servo by gains or a time constant.
    void springAndServoInTheJointsUnits() {
        Fixture f;
        f.doc.selectJoint(0);
        f.find<QCheckBox>("joint.spring.on")->setChecked(true);
        QVERIFY(f.joint().spring.has_value());
        QCOMPARE(f.spin("joint.spring.stiffness")->suffix(), QString(" N m/rad"));
        f.spin("joint.spring.stiffness")->setValue(250.0);
        emit f.spin("joint.spring.stiffness")->editingFinished();
        f.spin("joint.spring.rest")->setValue(30.0);
        QCOMPARE(f.joint().spring->stiffness, 250.0);
        QCOMPARE(f.joint().spring->rest, 30.0 * std::numbers::pi / 180.0);
        QCOMPARE(f.doc.undoStack()->count(), 3);
        f.find<QCheckBox>("joint.motor.on")->setChecked(true);
        f.find<QCheckBox>("joint.servo.on")->setChecked(true);  // replaces the motor
        QVERIFY(f.joint().servo && !f.joint().motor);
        QVERIFY(!f.find<QCheckBox>("joint.motor.on")->isChecked());
        QCOMPARE(f.joint().servo->timeConstant, 0.1);
        f.spin("joint.servo.target")->setValue(-45.0);
        QCOMPARE(f.joint().servo->target, -std::numbers::pi / 4);
        QVERIFY(!std::isfinite(f.joint().servo->maxForce));  // 0 shown as "no bound"
        QCOMPARE(f.spin("joint.servo.max")->text(), QString("no bound"));
        f.spin("joint.servo.max")->setValue(12.0);
        QCOMPARE(f.joint().servo->maxForce, 12.0);
        f.choose("joint.servo.mode", "gains");
        QVERIFY(f.joint().servo->timeConstant == 0.0 && f.joint().servo->stiffness > 0.0);
        QVERIFY(f.spin("joint.servo.stiffness")->isVisibleTo(&f.dock));
        QVERIFY(!f.spin("joint.servo.time_constant")->isVisibleTo(&f.dock));
        f.spin("joint.servo.stiffness")->setValue(0.0);  // gains need a stiffness: refused, said
        QVERIFY(f.joint().servo->stiffness > 0.0);
        QVERIFY2(f.panel()->fieldError("servo").contains("stiffness"), qPrintable(f.panel()->fieldError("servo")));
        // A keyed target: Add keys it at 0 and 1 s; the target field edits the current key,
        // the time field its time; removing down to one key leaves that one's target.
        f.choose("joint.servo.mode", "time constant");
        f.find<QPushButton>("joint.servo.keys.add")->click();
        QCOMPARE(f.joint().servo->keys.size(), size_t(2));
        QCOMPARE(f.find<QListWidget>("joint.servo.keys")->currentRow(), 1);
        f.spin("joint.servo.target")->setValue(90.0);
        emit f.spin("joint.servo.target")->editingFinished();
        f.spin("joint.servo.keys.time")->setValue(2.5);
        QCOMPARE(f.joint().servo->keys[1].time, 2.5);
        QCOMPARE(f.joint().servo->keys[1].target, std::numbers::pi / 2);
        QCOMPARE(f.joint().servo->target, f.joint().servo->keys[0].target);
        f.find<QListWidget>("joint.servo.keys")->setCurrentRow(0);
        f.find<QPushButton>("joint.servo.keys.remove")->click();
        QVERIFY(f.joint().servo->keys.empty());
        QCOMPARE(f.joint().servo->target, std::numbers::pi / 2);
        // Insert Key at 2 s (the timeline's frame; here the function it calls): the target
        // it has there keyed, its fixed one keyed at 0; at 1 s between keys, the line's value.
        JointDesc keyed = f.joint();
        QVERIFY(insertServoKey(keyed, 2.0));
        QCOMPARE(keyed.servo->keys.size(), size_t(2));
        QCOMPARE(keyed.servo->keys[1].time, 2.0);
        keyed.servo->keys[1].target = 1.0;
        QVERIFY(insertServoKey(keyed, 1.0));
        QCOMPARE(keyed.servo->keys.size(), size_t(3));
        QCOMPARE(keyed.servo->keys[1].target, 0.5 * (keyed.servo->keys[0].target + 1.0));
        f.find<QCheckBox>("joint.motor.on")->setChecked(true);  // and back
        QVERIFY(f.joint().motor && !f.joint().servo);
        QVERIFY(!insertServoKey(keyed = f.joint(), 1.0));
        f.choose("joint.type", "fixed");
        QVERIFY(!f.joint().spring && !f.joint().servo);
    }

    // A ball joint's swing cone and twist range in degrees; ticking one gives the joint an
    // axis along the limb (from the anchor towards the body's origin) if it has none, and
    // taking both away takes that axis away again.
    void ballConeAndTwistInDegrees() {
        Fixture f;
        f.doc.selectJoint(0);
        f.choose("joint.type", "ball");
        QVERIFY(!f.find<QCheckBox>("joint.spring.on")->isVisibleTo(&f.dock));
        f.find<QCheckBox>("joint.swing_limit.on")->setChecked(true);
        QVERIFY(f.joint().swingLimit && f.joint().axisA);
        QVERIFY((*f.joint().axisA - Vec3::UnitX()).norm() < 1e-12);  // the door's anchor is (-0.4, 0, 0)
        f.spin("joint.swing_limit.second")->setValue(20.0);
        QCOMPARE((*f.joint().swingLimit)[1], 20.0 * std::numbers::pi / 180.0);
        f.find<QCheckBox>("joint.twist_limits.on")->setChecked(true);
        f.spin("joint.twist_limits.lower")->setValue(-10.0);
        QCOMPARE((*f.joint().twistLimits)[0], -10.0 * std::numbers::pi / 180.0);
        f.spin("joint.swing_limit.first")->setValue(0.0);  // not a cone: refused, said
        QVERIFY((*f.joint().swingLimit)[0] > 0.0);
        QVERIFY(!f.panel()->fieldError("swing_limit").isEmpty());
        f.find<QCheckBox>("joint.swing_limit.on")->setChecked(false);
        f.find<QCheckBox>("joint.twist_limits.on")->setChecked(false);
        QVERIFY(!f.joint().axisA && !f.joint().swingLimit && !f.joint().twistLimits);
    }

    // A six-axis joint: its free axes ticked; the limits, spring and motor rows edit the axis
    // chosen under "Settings of", in that axis's units (about: degrees, N m; along: metres,
    // N), and giving one frees it; locking an axis takes its settings away; one undo step each.
    void sixAxisAxesAndTheirSettings() {
        Fixture f;
        f.doc.selectJoint(0);
        f.choose("joint.type", "six_axis");
        QCOMPARE(f.joint().type, JointType::SixAxis);
        QVERIFY(!f.joint().limits && !f.joint().axisB);
        QVERIFY(f.find<QCheckBox>("joint.axes.ry")->isVisibleTo(&f.dock));
        QVERIFY(!f.find<QPushButton>("joint.swap")->isEnabled());
        f.find<QCheckBox>("joint.axes.rx")->setChecked(true);
        QVERIFY(f.joint().axes[3].free && !f.joint().axes[4].free);
        f.choose("joint.drives_on", "about y");
        f.find<QCheckBox>("joint.limits.on")->setChecked(true);  // frees ry
        QVERIFY(f.joint().axes[4].free && f.joint().axes[4].limits);
        QVERIFY(!f.joint().limits);  // (the joint's own: none)
        QVERIFY(f.find<QCheckBox>("joint.axes.ry")->isChecked());
        QCOMPARE(f.spin("joint.limits.lower")->suffix(), QString("°"));
        f.spin("joint.limits.upper")->setValue(30.0);
        QCOMPARE((*f.joint().axes[4].limits)[1], 30.0 * std::numbers::pi / 180.0);
        f.choose("joint.drives_on", "along y");
        QVERIFY(!f.find<QCheckBox>("joint.limits.on")->isChecked());
        f.find<QCheckBox>("joint.spring.on")->setChecked(true);
        QCOMPARE(f.spin("joint.spring.stiffness")->suffix(), QString(" N/m"));
        f.spin("joint.spring.stiffness")->setValue(400.0);
        QCOMPARE(f.joint().axes[1].spring->stiffness, 400.0);
        QVERIFY(f.joint().axes[1].free);
        f.find<QCheckBox>("joint.motor.on")->setChecked(true);
        QCOMPARE(f.spin("joint.motor.max")->suffix(), QString(" N"));
        // A bad value for the axis is refused and said under its row.
        f.spin("joint.spring.damping")->setValue(-1.0);
        QVERIFY(f.joint().axes[1].spring->damping >= 0.0);
        const int steps = f.doc.undoStack()->count();
        f.find<QCheckBox>("joint.axes.y")->setChecked(false);  // locked: its spring and motor go
        QVERIFY(!f.joint().axes[1].free && !f.joint().axes[1].spring && !f.joint().axes[1].motor);
        QVERIFY(!f.find<QCheckBox>("joint.spring.on")->isChecked());
        QCOMPARE(f.doc.undoStack()->count(), steps + 1);
        f.doc.undoStack()->undo();
        QVERIFY(f.joint().axes[1].spring && f.joint().axes[1].free);
        QCOMPARE(f.joint().axes[4].limits.has_value(), true);
        // Another type takes the axes away.
        f.choose("joint.type", "ball");
        QVERIFY(f.joint().axes == JointDesc().axes);
    }

    void renameRefusesATakenName() {
        Fixture f;
        JointDesc second = f.joint();
        second.name = "stop";
        f.doc.addJoint(second);
        f.doc.selectJoint(0);
        auto* name = f.find<QLineEdit>("joint.name");
        name->setText("stop");
        emit name->editingFinished();
        QCOMPARE(f.joint().name, std::string("hinge"));
        QVERIFY(f.panel()->fieldError("name").contains("already the name"));
        QCOMPARE(name->text(), QString("hinge"));
        name->setText("door hinge");
        emit name->editingFinished();
        QCOMPARE(f.joint().name, std::string("door hinge"));
        auto* list = f.tree.findChild<QTreeWidget*>("jointListView");
        QCOMPARE(list->topLevelItem(0)->text(JointList::NameColumn), QString("door hinge"));
    }

    void deleteRemovesTheSelectedJoint() {
        Fixture f;
        JointDesc second = f.joint();
        second.name = "stop";
        f.doc.addJoint(second);
        QCOMPARE(f.doc.selectedJoint(), 1);  // an added joint is selected
        f.doc.selectJoint(0);
        QAction* del = nullptr;
        for (QAction* a : f.tree.actions())
            if (a->shortcut() == QKeySequence(QKeySequence::Delete)) del = a;
        QVERIFY(del && del->isEnabled());
        del->trigger();
        QCOMPARE(f.doc.jointCount(), 1);
        QCOMPARE(f.joint().name, std::string("stop"));
        QCOMPARE(f.doc.selectedJoint(), -1);
        QCOMPARE(f.doc.bodyCount(), 3);  // the bodies stay (and the ground)
        f.doc.undoStack()->undo();
        QCOMPARE(f.doc.jointCount(), 2);
        QCOMPARE(f.joint().name, std::string("hinge"));
    }
};

QTEST_MAIN(TestJointPanel)
#include "tst_joint_panel.moc"
