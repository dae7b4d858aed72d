// The joint panel's rows for a hinge's or slider's spring and servo and a ball joint's
// swing cone and twist limits (issue 51): each a check box that adds it with a value that
// works, and its fields in the joint's units (a hinge's angles in degrees, kept in radians).
#include "panels/joint_panel.h"

#include "document/document.h"
#include "document/joint_presets.h"
#include "panels/property_spin_box.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QListWidget>
#include <QPushButton>
#include <QVBoxLayout>
#include <QSignalBlocker>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::ui {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A hinge's coordinate is an angle (shown in degrees), a slider's a length.
double unitOf(const JointDesc& j) {
    return j.type == JointType::Hinge ? kDegree : 1.0;
}

// A ball joint's axis for its limits where it has none: along the limb, from the anchor
// towards A's frame origin (in A's frame), or A's y.
Vec3 limbAxis(const JointDesc& j) {
    return j.anchorA.norm() > 1e-9 ? Vec3(-j.anchorA.normalized()) : Vec3::UnitY();
}

}  // namespace

void JointPanel::buildDriveRows() {
    hasSpring_ = new QCheckBox;
    hasSpring_->setObjectName("joint.spring.on");
    hasSpring_->setToolTip(tr("A spring and damper pulling the joint towards its rest"));
    springStiffness_ = makeSpin("joint.spring.stiffness", QString(), 0.0, 10.0);
    springStiffness_->setToolTip(tr("Stiffness"));
    springDamping_ = makeSpin("joint.spring.damping", QString(), 0.0, 1.0);
    springDamping_->setToolTip(tr("Damping"));
    springRest_ = makeSpin("joint.spring.rest", QString(), -1e12, 5.0);
    springRest_->setToolTip(tr("Rest: where it pulls to (0: as placed)"));
    addFormRow(tr("Spring"), "spring", optionalRow(hasSpring_, {springStiffness_, springDamping_}));
    addFormRow(tr("Spring rest"), "spring_rest", springRest_);
    connect(hasSpring_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "spring", on ? tr("Add joint spring") : tr("Remove joint spring"),
            [&](JointDesc& j) {
                if (on)
                    j.spring = JointDesc::Spring{j.type == JointType::Hinge ? 10.0 : 100.0, 1.0, 0.0};
                else
                    j.spring.reset();
            },
            false);
    });
    auto springField = [this](PropertySpinBox* field, const QString& text, double JointDesc::Spring::*member,
                               bool angle) {
        connect(field, &PropertySpinBox::valueChanged, this, [this, field, text, member, angle](double v) {
            apply(
                "spring", text,
                [&](JointDesc& j) {
                    if (j.spring) (*j.spring).*member = angle ? v * unitOf(j) : v;
                },
                true, field->shownText(v));
        });
    };
    springField(springStiffness_, tr("Set spring stiffness"), &JointDesc::Spring::stiffness, false);
    springField(springDamping_, tr("Set spring damping"), &JointDesc::Spring::damping, false);
    springField(springRest_, tr("Set spring rest"), &JointDesc::Spring::rest, true);

    hasServo_ = new QCheckBox;
    hasServo_->setObjectName("joint.servo.on");
    hasServo_->setToolTip(tr("A position motor: drives the joint to its target"));
    servoTarget_ = makeSpin("joint.servo.target", QString(), -1e12, 5.0);
    servoTarget_->setToolTip(tr("Target (0: as placed)"));
    servoMax_ = makeSpin("joint.servo.max", QString(), 0.0, 1.0);
    servoMax_->setMinimum(0.0);
    servoMax_->setSpecialValueText(tr("no bound"));
    servoMax_->setToolTip(tr("At most this torque (hinge) or force (slider); 0: no bound"));
    addFormRow(tr("Servo"), "servo", optionalRow(hasServo_, {servoTarget_, servoMax_}));
    servoMode_ = new QComboBox;
    servoMode_->setObjectName("joint.servo.mode");
    servoMode_->addItem(tr("time constant"));
    servoMode_->addItem(tr("gains"));
    servoMode_->setToolTip(
        tr("Time constant: critically damped, reaching the target without passing it whatever the masses; "
           "gains: a spring and damper towards the target"));
    servoTime_ = makeSpin("joint.servo.time_constant", QStringLiteral(" s"), 0.001, 0.05);
    servoStiffness_ = makeSpin("joint.servo.stiffness", QString(), 0.0, 10.0);
    servoStiffness_->setToolTip(tr("Stiffness"));
    servoDamping_ = makeSpin("joint.servo.damping", QString(), 0.0, 1.0);
    servoDamping_->setToolTip(tr("Damping"));
    addFormRow(tr("Servo by"), "servo_mode", optionalRow(servoMode_, {servoTime_}));
    auto* gains = new QWidget;
    auto* gainsLayout = new QHBoxLayout(gains);
    gainsLayout->setContentsMargins(0, 0, 0, 0);
    gainsLayout->addWidget(servoStiffness_, 1);
    gainsLayout->addWidget(servoDamping_, 1);
    addFormRow(tr("Servo gains"), "servo_gains", gains);
    connect(hasServo_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "servo", on ? tr("Add joint servo") : tr("Remove joint servo"),
            [&](JointDesc& j) {
                if (!on) {
                    j.servo.reset();
                    return;
                }
                j.motor.reset();  // one drive: the servo replaces the motor
                JointDesc::Servo servo;
                servo.timeConstant = 0.1;
                j.servo = servo;
            },
            false);
    });
    connect(servoMode_, &QComboBox::activated, this, [this](int mode) {
        apply(
            "servo", tr("Set servo gains"),
            [&](JointDesc& j) {
                if (!j.servo) return;
                const bool gains = mode == 1;
                j.servo->timeConstant = gains ? 0.0 : 0.1;
                j.servo->stiffness = gains ? (j.type == JointType::Hinge ? 100.0 : 1000.0) : 0.0;
                j.servo->damping = gains ? (j.type == JointType::Hinge ? 20.0 : 200.0) : 0.0;
            },
            false);
    });
    auto servoField = [this](PropertySpinBox* field, const QString& text,
                              const std::function<void(JointDesc&, double)>& set) {
        connect(field, &PropertySpinBox::valueChanged, this, [this, field, text, set](double v) {
            apply(
                "servo", text,
                [&](JointDesc& j) {
                    if (j.servo) set(j, v);
                },
                true, field->shownText(v));
        });
    };
    connect(servoTarget_, &PropertySpinBox::valueChanged, this, [this](double v) {
        const int i = jointIndex(), key = servoKeys_->currentRow();
        if (i < 0) return;
        const JointDesc j = viewed(i);
        if (j.servo && !j.servo->keys.empty() && key >= 0) {
            const double target = v * unitOf(j);
            editServoKeys(tr("Set servo key"), [key, target](auto& keys) { keys[size_t(key)].target = target; });
            return;
        }
        apply(
            "servo", tr("Set servo target"),
            [&](JointDesc& jj) {
                if (jj.servo) jj.servo->target = v * unitOf(jj);
            },
            true, servoTarget_->shownText(v));
    });
    servoField(servoMax_, tr("Set servo strength"),
               [](JointDesc& j, double v) { j.servo->maxForce = v > 0.0 ? v : HUGE_VAL; });
    servoField(servoTime_, tr("Set servo time constant"), [](JointDesc& j, double v) { j.servo->timeConstant = v; });
    servoField(servoStiffness_, tr("Set servo stiffness"), [](JointDesc& j, double v) { j.servo->stiffness = v; });
    servoField(servoDamping_, tr("Set servo damping"), [](JointDesc& j, double v) { j.servo->damping = v; });
}

void JointPanel::buildServoKeyRows() {
    servoKeys_ = new QListWidget;
    servoKeys_->setObjectName("joint.servo.keys");
    servoKeys_->setMaximumHeight(80);
    servoKeys_->setToolTip(tr("The target's keys: linear between them; the target field edits the current one"));
    servoKeyAdd_ = new QPushButton(tr("Add key"));
    servoKeyAdd_->setObjectName("joint.servo.keys.add");
    servoKeyAdd_->setToolTip(tr("A key 1 s after the last, at its target (the first: keys at 0 and 1 s)"));
    servoKeyRemove_ = new QPushButton(tr("Remove"));
    servoKeyRemove_->setObjectName("joint.servo.keys.remove");
    servoKeyTime_ = makeSpin("joint.servo.keys.time", QStringLiteral(" s"), 0.0, 0.1);
    servoKeyTime_->setToolTip(tr("The current key's time"));
    auto* box = new QWidget;
    auto* layout = new QVBoxLayout(box);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(servoKeys_);
    layout->addWidget(optionalRow(servoKeyAdd_, {servoKeyRemove_, servoKeyTime_}));
    addFormRow(tr("Servo keys"), "servo_keys", box);
    connect(servoKeys_, &QListWidget::currentRowChanged, this, [this] { refresh(); });
    connect(servoKeyAdd_, &QPushButton::clicked, this, [this] {
        const int i = jointIndex();
        if (i < 0 || !viewed(i).servo) return;
        const double target = viewed(i).servo->target;
        editServoKeys(
            tr("Add servo key"),
            [target](auto& keys) {
                if (keys.empty())
                    keys = {{0.0, target}, {1.0, target}};
                else
                    keys.push_back({keys.back().time + 1.0, keys.back().target});
            },
            false);
        servoKeys_->setCurrentRow(servoKeys_->count() - 1);
    });
    connect(servoKeyRemove_, &QPushButton::clicked, this, [this] {
        const int key = servoKeys_->currentRow();
        apply(
            "servo", tr("Remove servo key"),
            [key](JointDesc& j) {
                if (!j.servo || key < 0 || key >= int(j.servo->keys.size())) return;
                std::vector<JointDesc::ServoKey>& keys = j.servo->keys;
                keys.erase(keys.begin() + key);
                if (!keys.empty()) j.servo->target = keys.front().target;
                if (keys.size() == 1) keys.clear();  // one key is a fixed target: the plain one
            },
            false);
    });
    connect(servoKeyTime_, &PropertySpinBox::valueChanged, this, [this](double v) {
        const int key = servoKeys_->currentRow();
        if (key < 0) return;
        editServoKeys(tr("Set servo key time"), [key, v](auto& keys) { keys[size_t(key)].time = v; });
    });
}

void JointPanel::editServoKeys(const QString& text,
                               const std::function<void(std::vector<JointDesc::ServoKey>&)>& change, bool merge) {
    apply(
        "servo", text,
        [&](JointDesc& j) {
            if (!j.servo) return;
            std::vector<JointDesc::ServoKey> keys = j.servo->keys;
            change(keys);
            std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
            if (!keys.empty()) j.servo->target = keys.front().target;
            j.servo->keys = keys;
        },
        merge);
}

void JointPanel::refreshServoKeys(const JointDesc& j) {
    if (!j.servo) return;
    const double unit = unitOf(j);
    const QString suffix = j.type == JointType::Hinge ? QStringLiteral("°") : QStringLiteral(" m");
    const std::vector<JointDesc::ServoKey>& keys = j.servo->keys;
    const int row = servoKeys_->currentRow();
    {
        const QSignalBlocker b(servoKeys_);
        servoKeys_->clear();
        for (const JointDesc::ServoKey& k : keys)
            servoKeys_->addItem(QStringLiteral("%1 s: %2%3").arg(k.time, 0, 'g', 6).arg(k.target / unit, 0, 'g', 6).arg(suffix));
        servoKeys_->setCurrentRow(keys.empty() ? -1 : std::clamp(row, 0, int(keys.size()) - 1));
    }
    const int key = servoKeys_->currentRow();
    servoKeyRemove_->setEnabled(key >= 0);
    servoKeyTime_->setEnabled(key >= 0);
    if (key >= 0) {
        servoKeyTime_->showValue(keys[size_t(key)].time);
        servoTarget_->showValue(keys[size_t(key)].target / unit);
    }
}

void JointPanel::buildBallLimitRows() {
    hasCone_ = new QCheckBox;
    hasCone_->setObjectName("joint.swing_limit.on");
    hasCone_->setToolTip(tr("A cone about the axis that the limb's axis stays in"));
    cone1_ = makeSpin("joint.swing_limit.first", QStringLiteral("°"), 0.1, 5.0);
    cone1_->setToolTip(tr("Half-angle towards the limb's first cross axis"));
    cone2_ = makeSpin("joint.swing_limit.second", QStringLiteral("°"), 0.1, 5.0);
    cone2_->setToolTip(tr("Half-angle towards the second (equal: a round cone)"));
    addFormRow(tr("Swing cone"), "swing_limit", optionalRow(hasCone_, {cone1_, cone2_}));
    hasTwist_ = new QCheckBox;
    hasTwist_->setObjectName("joint.twist_limits.on");
    hasTwist_->setToolTip(tr("The range of the limb's turn about its axis"));
    twistLower_ = makeSpin("joint.twist_limits.lower", QStringLiteral("°"), -180.0, 5.0);
    twistUpper_ = makeSpin("joint.twist_limits.upper", QStringLiteral("°"), -180.0, 5.0);
    addFormRow(tr("Twist"), "twist_limits", optionalRow(hasTwist_, {twistLower_, twistUpper_}));
    auto toggle = [this](QCheckBox* box, const QString& key, const QString& on, const QString& off,
                         const std::function<void(JointDesc&, bool)>& set) {
        connect(box, &QCheckBox::toggled, this, [this, key, on, off, set](bool checked) {
            apply(
                key, checked ? on : off,
                [&](JointDesc& j) {
                    if (checked && !j.axisA) j.axisA = limbAxis(j);
                    set(j, checked);
                    if (!j.swingLimit && !j.twistLimits && !j.axisB) j.axisA.reset();
                },
                false);
        });
    };
    toggle(hasCone_, "swing_limit", tr("Limit joint's swing"), tr("Free joint's swing"), [](JointDesc& j, bool on) {
        if (on)
            j.swingLimit = std::array<double, 2>{45 * kDegree, 45 * kDegree};
        else
            j.swingLimit.reset();
    });
    toggle(hasTwist_, "twist_limits", tr("Limit joint's twist"), tr("Free joint's twist"), [](JointDesc& j, bool on) {
        if (on)
            j.twistLimits = std::array<double, 2>{-45 * kDegree, 45 * kDegree};
        else
            j.twistLimits.reset();
    });
    auto angleField = [this](PropertySpinBox* field, const QString& key, const QString& text, int k, bool twist) {
        connect(field, &PropertySpinBox::valueChanged, this, [this, field, key, text, k, twist](double v) {
            apply(
                key, text,
                [&](JointDesc& j) {
                    std::optional<std::array<double, 2>>& pair = twist ? j.twistLimits : j.swingLimit;
                    if (pair) (*pair)[k] = v * kDegree;
                },
                true, field->shownText(v));
        });
    };
    angleField(cone1_, "swing_limit", tr("Set swing cone"), 0, false);
    angleField(cone2_, "swing_limit", tr("Set swing cone"), 1, false);
    angleField(twistLower_, "twist_limits", tr("Set twist limits"), 0, true);
    angleField(twistUpper_, "twist_limits", tr("Set twist limits"), 1, true);
}

void JointPanel::refreshDrives(const JointDesc& j) {
    const bool axialJoint = j.type == JointType::Hinge || j.type == JointType::Slider;
    form_->setRowVisible(rows_["spring"], axialJoint);
    form_->setRowVisible(rows_["servo"], axialJoint);
    form_->setRowVisible(rows_["spring_rest"], axialJoint && j.spring.has_value());
    form_->setRowVisible(rows_["servo_mode"], axialJoint && j.servo.has_value());
    form_->setRowVisible(rows_["servo_keys"], axialJoint && j.servo.has_value());
    const bool gainsShown = axialJoint && j.servo && !(j.servo->timeConstant > 0.0);
    form_->setRowVisible(rows_["servo_gains"], gainsShown);
    const bool hinge = j.type == JointType::Hinge;
    const double unit = unitOf(j);
    springStiffness_->setSuffix(hinge ? QStringLiteral(" N m/rad") : QStringLiteral(" N/m"));
    springDamping_->setSuffix(hinge ? QStringLiteral(" N m s/rad") : QStringLiteral(" N s/m"));
    for (PropertySpinBox* s : {springRest_, servoTarget_}) s->setSuffix(hinge ? QStringLiteral("°") : QStringLiteral(" m"));
    servoMax_->setSuffix(hinge ? QStringLiteral(" N m") : QStringLiteral(" N"));
    servoStiffness_->setSuffix(springStiffness_->suffix());
    servoDamping_->setSuffix(springDamping_->suffix());
    {
        const QSignalBlocker b(hasSpring_);
        hasSpring_->setChecked(j.spring.has_value());
    }
    for (PropertySpinBox* s : {springStiffness_, springDamping_, springRest_}) s->setEnabled(j.spring.has_value());
    if (j.spring) {
        springStiffness_->showValue(j.spring->stiffness);
        springDamping_->showValue(j.spring->damping);
        springRest_->showValue(j.spring->rest / unit);
    }
    {
        const QSignalBlocker b(hasServo_);
        hasServo_->setChecked(j.servo.has_value());
    }
    for (PropertySpinBox* s : {servoTarget_, servoMax_}) s->setEnabled(j.servo.has_value());
    servoTarget_->setToolTip(j.servo && !j.servo->keys.empty() ? tr("The current key's target")
                                                                : tr("Target (0: as placed)"));
    if (!j.servo) return;
    servoTarget_->showValue(j.servo->target / unit);
    servoMax_->showValue(std::isfinite(j.servo->maxForce) ? j.servo->maxForce : 0.0);
    const bool gains = !(j.servo->timeConstant > 0.0);
    {
        const QSignalBlocker b(servoMode_);
        servoMode_->setCurrentIndex(gains ? 1 : 0);
    }
    servoTime_->setVisible(!gains);
    if (gains) {
        servoStiffness_->showValue(j.servo->stiffness);
        servoDamping_->showValue(j.servo->damping);
    } else {
        servoTime_->showValue(j.servo->timeConstant);
    }
    refreshServoKeys(j);
}

void JointPanel::refreshBallLimits(const JointDesc& j) {
    const bool ball = j.type == JointType::Ball;
    form_->setRowVisible(rows_["swing_limit"], ball);
    form_->setRowVisible(rows_["twist_limits"], ball);
    {
        const QSignalBlocker b(hasCone_);
        hasCone_->setChecked(j.swingLimit.has_value());
    }
    {
        const QSignalBlocker b(hasTwist_);
        hasTwist_->setChecked(j.twistLimits.has_value());
    }
    for (PropertySpinBox* s : {cone1_, cone2_}) s->setEnabled(j.swingLimit.has_value());
    for (PropertySpinBox* s : {twistLower_, twistUpper_}) s->setEnabled(j.twistLimits.has_value());
    if (j.swingLimit) {
        cone1_->showValue((*j.swingLimit)[0] / kDegree);
        cone2_->showValue((*j.swingLimit)[1] / kDegree);
    }
    if (j.twistLimits) {
        twistLower_->showValue((*j.twistLimits)[0] / kDegree);
        twistUpper_->showValue((*j.twistLimits)[1] / kDegree);
    }
}

}  // namespace tumble::ui
