// The property panel's page for a selected joint: its name, type, the bodies it joins,
// anchors and axes in each body's frame, and the optional length, limits, motor, spring,
// servo, cone, twist limits and breaking force, each with its unit. Every edit is checked with the engine's own
// validation before it reaches the document (a refused value is explained under its field
// and the field shows the joint as it is); each is one undo step, a scrub of one field is
// one. Changing a joint's body keeps its anchor (and axis) where they are in the world.
#pragma once

#include <tumble/scene.h>

#include <QMap>
#include <QWidget>

#include <functional>
#include <initializer_list>

class QCheckBox;
class QComboBox;
class QPushButton;
class QFormLayout;
class QLabel;
class QLineEdit;
class QListWidget;

namespace tumble::ui {

class Document;
class PropertySpinBox;
class VectorEdit;

class JointPanel : public QWidget {
    Q_OBJECT
public:
    explicit JointPanel(Document* doc, QWidget* parent = nullptr);

    /// Shows the document's selected joint (nothing when none is selected).
    void refresh();
    /// The message under a field (its key, e.g. "limits", "axis_a"), or empty.
    QString fieldError(const QString& field) const;

private:
    using Edit = std::function<void(JointDesc&)>;
    /// Applies `edit` to a copy of the selected joint; validates the scene with it; hands it
    /// to the document (merging with the last edit of the same field while it is scrubbed).
    /// `value`, the new value as its field shows it, goes into the undo entry ("Set joint
    /// length of hinge to 1.5 m").
    void apply(const QString& key, const QString& text, const Edit& edit, bool merge = true,
               const QString& value = QString());
    /// A vector field edited a component at a time is one value: a component that makes the
    /// joint refused is held (the typed values stay, the field is marked, the panel says why
    /// in plain words) until the vector is valid, or Esc shows the last valid value again;
    /// never a mix of typed and old components (issue 46).
    using VectorOf = std::function<std::optional<Vec3>(const JointDesc&)>;
    using SetVector = std::function<void(JointDesc&, const Vec3&)>;
    void editVector(const QString& key, const QString& text, int k, double v, const VectorOf& get,
                    const SetVector& set, const QString& value = QString());
    /// Frames the fields of a held value (a vector, or the two limits) red, or not.
    void markHeld(const QString& key, bool held);
    void dropHeld();
    QWidget* withError(QWidget* editor, const QString& key);
    QWidget* addFormRow(const QString& label, const QString& key, QWidget* editor);
    PropertySpinBox* makeSpin(const QString& key, const QString& suffix, double min, double step);
    /// A check box (or any switch) and the fields it enables, as one field.
    static QWidget* optionalRow(QWidget* check, std::initializer_list<QWidget*> fields);
    /// A hinge's or slider's spring and servo, and a ball joint's cone and twist limits
    /// (joint_panel_drives.cpp).
    void buildDriveRows();
    void buildBallLimitRows();
    void refreshDrives(const JointDesc& j);
    void refreshBallLimits(const JointDesc& j);
    void buildServoKeyRows();
    void refreshServoKeys(const JointDesc& j);
    /// Applies `change` to a copy of the servo's keys (kept in time order, the target the
    /// first key's) as one edit of the "servo" field.
    void editServoKeys(const QString& text, const std::function<void(std::vector<JointDesc::ServoKey>&)>& change,
                       bool merge = true);
    /// A six-axis joint's free axes and the axis its limits, motor, spring and servo rows
    /// edit (joint_panel_axes.cpp): those rows show that axis's settings as a slider's (x, y,
    /// z) or a hinge's (rx, ry, rz) would have them.
    void buildAxisRows();
    void refreshAxes(const JointDesc& j);
    /// Joint i as the rows edit it: a six-axis joint with the shown axis's settings as its
    /// own limits, motor, spring and servo (and the type of a slider or hinge); any other
    /// joint as it is. `lowered` puts an edited view back (the settings into the axis,
    /// which they free).
    JointDesc viewed(int i) const;
    JointDesc lowered(JointDesc view, int i) const;
    void clearErrors();
    int jointIndex() const;

    Document* doc_;
    QFormLayout* form_ = nullptr;
    QMap<QString, QLabel*> errors_;
    QMap<QString, QWidget*> rows_;
    int generation_ = 1;
    QMap<QString, Vec3> held_;  // refused values being typed, by field key (limits: lower, upper, 0)

    QLineEdit* name_ = nullptr;
    QComboBox* type_ = nullptr;
    QComboBox* bodyA_ = nullptr;
    QComboBox* bodyB_ = nullptr;
    QPushButton* swap_ = nullptr;
    QCheckBox* anchorsInWorld_ = nullptr;
    VectorEdit* anchorA_ = nullptr;
    VectorEdit* anchorB_ = nullptr;
    VectorEdit* axisA_ = nullptr;
    QCheckBox* hasAxisB_ = nullptr;
    VectorEdit* axisB_ = nullptr;
    QCheckBox* asPlaced_ = nullptr;
    PropertySpinBox* length_ = nullptr;
    QCheckBox* hasLimits_ = nullptr;
    PropertySpinBox* lower_ = nullptr;
    PropertySpinBox* upper_ = nullptr;
    QCheckBox* hasMotor_ = nullptr;
    PropertySpinBox* motorSpeed_ = nullptr;
    PropertySpinBox* motorMax_ = nullptr;
    QCheckBox* hasSpring_ = nullptr;
    PropertySpinBox* springStiffness_ = nullptr;
    PropertySpinBox* springDamping_ = nullptr;
    PropertySpinBox* springRest_ = nullptr;
    QCheckBox* hasServo_ = nullptr;
    PropertySpinBox* servoTarget_ = nullptr;
    PropertySpinBox* servoMax_ = nullptr;
    QComboBox* servoMode_ = nullptr;  // time constant, or gains
    PropertySpinBox* servoTime_ = nullptr;
    QListWidget* servoKeys_ = nullptr;  // a keyed target: its keys; the target field edits the current one
    QPushButton* servoKeyAdd_ = nullptr;
    QPushButton* servoKeyRemove_ = nullptr;
    PropertySpinBox* servoKeyTime_ = nullptr;
    PropertySpinBox* servoStiffness_ = nullptr;
    PropertySpinBox* servoDamping_ = nullptr;
    QCheckBox* hasCone_ = nullptr;
    PropertySpinBox* cone1_ = nullptr;
    PropertySpinBox* cone2_ = nullptr;
    QCheckBox* hasTwist_ = nullptr;
    PropertySpinBox* twistLower_ = nullptr;
    PropertySpinBox* twistUpper_ = nullptr;
    QCheckBox* freeAxes_[6] = {};
    QComboBox* drivesOn_ = nullptr;
    int sixAxis_ = 3;  // the six-axis joint's axis the rows edit (JointDesc::axes)
    QCheckBox* breaks_ = nullptr;
    QCheckBox* collide_ = nullptr;  // collide_connected
    PropertySpinBox* breakForce_ = nullptr;
};

}  // namespace tumble::ui
