// The joint panel's rows for a six-axis joint (issue 51): which of its six axes are free, and
// which one the limits, motor, spring and servo rows below edit. Those rows are the hinge's
// and slider's own: for the shown axis they see the joint as a slider (x, y, z: metres,
// newtons) or a hinge (rx, ry, rz: degrees, newton metres) with that axis's settings, and an
// edit goes back into the axis (giving an axis a setting frees it).
#include "panels/joint_panel.h"

#include "document/document.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QSignalBlocker>

namespace tumble::ui {

namespace {

const char* const kAxisKeys[6] = {"x", "y", "z", "rx", "ry", "rz"};

bool acted(const JointDesc::Axis& a) {
    return a.limits || a.motor || a.spring || a.servo;
}

}  // namespace

void JointPanel::buildAxisRows() {
    auto* row = new QWidget;
    auto* layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    for (int k = 0; k < 6; ++k) {
        auto* box = new QCheckBox(QString::fromLatin1(kAxisKeys[k]));
        box->setObjectName(QStringLiteral("joint.axes.%1").arg(kAxisKeys[k]));
        box->setToolTip(k < 3 ? tr("Free to slide along the joint frame's %1 axis (else held)").arg(kAxisKeys[k])
                              : tr("Free to turn about the joint frame's %1 axis (else held)").arg(kAxisKeys[k] + 1));
        layout->addWidget(box);
        freeAxes_[k] = box;
        connect(box, &QCheckBox::toggled, this, [this, k](bool on) {
            apply(
                "axes", on ? tr("Free joint axis") : tr("Lock joint axis"),
                [&](JointDesc& j) {
                    j.axes[k] = JointDesc::Axis{};
                    j.axes[k].free = on;
                    if (k == sixAxis_) {  // (the rows show this axis: what they show goes too)
                        j.limits.reset();
                        j.motor.reset();
                        j.spring.reset();
                        j.servo.reset();
                    }
                },
                false);
        });
    }
    layout->addStretch(1);
    addFormRow(tr("Free axes"), "axes", row);

    drivesOn_ = new QComboBox;
    drivesOn_->setObjectName("joint.drives_on");
    drivesOn_->setToolTip(tr("The axis the limits, motor, spring and servo below act on (giving it one frees it)"));
    for (int k = 0; k < 6; ++k)
        drivesOn_->addItem(k < 3 ? tr("along %1").arg(kAxisKeys[k]) : tr("about %1").arg(kAxisKeys[k] + 1), k);
    addFormRow(tr("Settings of"), "drives_on", drivesOn_);
    connect(drivesOn_, &QComboBox::activated, this, [this](int i) {
        sixAxis_ = drivesOn_->itemData(i).toInt();
        ++generation_;  // (an edit of another axis is another undo step)
        dropHeld();
        clearErrors();
        refresh();
    });
}

void JointPanel::refreshAxes(const JointDesc& j) {
    const bool six = j.type == JointType::SixAxis;
    form_->setRowVisible(rows_["axes"], six);
    form_->setRowVisible(rows_["drives_on"], six);
    if (!six) return;
    for (int k = 0; k < 6; ++k) {
        const QSignalBlocker b(freeAxes_[k]);
        freeAxes_[k]->setChecked(j.axes[k].free);
        freeAxes_[k]->setText(QString::fromLatin1(kAxisKeys[k]) + (acted(j.axes[k]) ? QStringLiteral("*") : QString()));
    }
    const QSignalBlocker b(drivesOn_);
    drivesOn_->setCurrentIndex(drivesOn_->findData(sixAxis_));
}

JointDesc JointPanel::viewed(int i) const {
    JointDesc j = doc_->joint(i);
    if (j.type != JointType::SixAxis) return j;
    const JointDesc::Axis& a = j.axes[static_cast<size_t>(sixAxis_)];
    j.type = sixAxis_ < 3 ? JointType::Slider : JointType::Hinge;
    if (!j.axisA) j.axisA = Vec3::UnitX();  // (its frame's x: the Axis row edits it)
    j.limits = a.limits;
    j.motor = a.motor;
    j.spring = a.spring;
    j.servo = a.servo;
    return j;
}

JointDesc JointPanel::lowered(JointDesc view, int i) const {
    if (doc_->joint(i).type != JointType::SixAxis) return view;
    JointDesc::Axis& a = view.axes[static_cast<size_t>(sixAxis_)];
    a.limits = view.limits;
    a.motor = view.motor;
    a.spring = view.spring;
    a.servo = view.servo;
    if (acted(a)) a.free = true;
    view.limits.reset();
    view.motor.reset();
    view.spring.reset();
    view.servo.reset();
    view.type = JointType::SixAxis;
    if (!doc_->joint(i).axisA && view.axisA == Vec3::UnitX()) view.axisA.reset();
    return view;
}

}  // namespace tumble::ui
