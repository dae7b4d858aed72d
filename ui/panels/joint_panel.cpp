#include "panels/joint_panel.h"

#include "document/document.h"
#include "document/joint_presets.h"
#include "panels/field_guard.h"
#include "panels/property_spin_box.h"
#include "panels/vector_edit.h"

#include <tumble/errors.h>

#include <tumble/model.h>  // validateJoints: the engine's own validation of joints

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace tumble::ui {

namespace {

// A joint still called by its old type's default name ("hinge", "hinge-2") takes the new
// type's ("slider", unique among the joints): the name said what it was, and no longer
// would. A name the user gave is kept.
std::string renamedForType(const SceneDesc& scene, const std::string& name, JointType was, JointType type) {
    const std::string old = toString(was);
    const bool numbered = name.size() > old.size() + 1 && name.compare(0, old.size() + 1, old + "-") == 0 &&
                          std::all_of(name.begin() + long(old.size()) + 1, name.end(),
                                      [](char c) { return c >= '0' && c <= '9'; });
    if (was == type || (name != old && !numbered)) return name;
    const std::string base = toString(type);
    auto taken = [&](const std::string& candidate) {
        return std::any_of(scene.joints.begin(), scene.joints.end(),
                           [&](const JointDesc& other) { return other.name == candidate; });
    };
    std::string fresh = base;
    for (int k = 2; taken(fresh); ++k) fresh = base + "-" + std::to_string(k);
    return fresh;
}

constexpr double kDegree = std::numbers::pi / 180.0;

bool axial(JointType t) {
    return t == JointType::Hinge || t == JointType::Slider;
}
bool line(JointType t) {
    return t == JointType::Distance || t == JointType::Rope;
}

// The message the engine's validation of the joints gives the scene, or none (the joints
// alone: a body's problem, which would stop the whole validation first, is the body's).
std::optional<std::string> problemOf(const SceneDesc& scene) {
    try {
        validateJoints(scene);
    } catch (const SceneError& e) {
        return std::string(e.what());
    }
    return std::nullopt;
}

}  // namespace

JointPanel::JointPanel(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    auto* outer = new QVBoxLayout(this);
    outer->setContentsMargins(0, 0, 0, 0);
    auto* box = new QWidget;
    form_ = new QFormLayout(box);
    form_->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    outer->addWidget(box);

    auto addRow = [this](const QString& label, const QString& key, QWidget* editor) {
        return addFormRow(label, key, editor);
    };
    auto spin = [this](const QString& key, const QString& suffix, double min, double step) {
        return makeSpin(key, suffix, min, step);
    };
    auto vector = [this](const QString& key, const QString& suffix) {
        auto* v = new VectorEdit(key, suffix);
        v->setSingleStep(0.1);
        connect(v, &VectorEdit::editingFinished, this, [this] { ++generation_; });
        return v;
    };
    auto optional = [](QCheckBox* check, std::initializer_list<QWidget*> fields) {
        return optionalRow(check, fields);
    };

    name_ = new QLineEdit;
    name_->setObjectName("joint.name");
    addRow(tr("Name"), "name", name_);
    connect(name_, &QLineEdit::editingFinished, this, [this] {
        const std::string text = name_->text().trimmed().toStdString();
        apply("name", tr("Rename joint"), [&](JointDesc& j) { j.name = text; }, false);
    });

    type_ = new QComboBox;
    type_->setObjectName("joint.type");
    for (JointType t : {JointType::Ball, JointType::Hinge, JointType::Slider, JointType::Fixed, JointType::Distance,
                        JointType::Rope, JointType::SixAxis})
        type_->addItem(QString::fromLatin1(toString(t)), int(t));
    addRow(tr("Type"), "type", type_);
    connect(type_, &QComboBox::activated, this, [this](int i) {
        const auto t = JointType(type_->itemData(i).toInt());
        apply(
            "type", tr("Set joint type"),
            [&](JointDesc& j) {
                const JointType was = j.type;
                j.type = t;
                if (axial(t) && !j.axisA) {
                    const BodyFrame a = frameOf(doc_->scene(), j.bodyA);
                    j.axisA = a.q.conjugate() * (t == JointType::Hinge ? Vec3::UnitY() : Vec3::UnitX());
                }
                if (!axial(t)) {
                    if (t != JointType::Ball || !(j.swingLimit || j.twistLimits)) {
                        j.axisA.reset();
                        j.axisB.reset();
                    }
                    j.limits.reset();
                    j.motor.reset();
                    j.spring.reset();
                    j.servo.reset();
                }
                if (t != JointType::Ball) {
                    j.swingLimit.reset();
                    j.twistLimits.reset();
                }
                if (!line(t)) j.length = -1.0;
                if (t != JointType::SixAxis) j.axes = JointDesc().axes;
                j.name = renamedForType(doc_->scene(), j.name, was, t);
            },
            false, type_->itemText(i));
    });

    // The bodies: a change keeps the anchor (and the axis) where it is in the world.
    // The coordinate (a hinge's angle, a slider's offset) is A's against B: B is the base,
    // A the part that moves on it; Swap exchanges them, meaning the same.
    bodyA_ = new QComboBox;
    bodyA_->setObjectName("joint.body_a");
    bodyA_->setToolTip(
        tr("The part that moves: a positive motor turns it the right-hand way about the axis"));
    addRow(tr("Moving (A)"), "body_a", bodyA_);
    bodyB_ = new QComboBox;
    bodyB_->setObjectName("joint.body_b");
    bodyB_->setToolTip(tr("The base the part moves on, or the world"));
    swap_ = new QPushButton(tr("Swap"));
    swap_->setObjectName("joint.swap");
    swap_->setToolTip(
        tr("Make the base the moving part and the moving part the base: the same joint "
           "(its limits and motor speed change sign)"));
    auto* base = new QWidget;
    auto* baseLayout = new QHBoxLayout(base);
    baseLayout->setContentsMargins(0, 0, 0, 0);
    baseLayout->addWidget(bodyB_, 1);
    baseLayout->addWidget(swap_);
    addRow(tr("Base (B)"), "body_b", base);
    connect(swap_, &QPushButton::clicked, this, [this] {
        apply(
            "body_b", tr("Swap joint bodies"),
            [this](JointDesc& j) {
                if (const auto s = swappedJoint(doc_->scene(), j)) j = *s;
            },
            false);
    });
    auto rebind = [this](bool first, const std::string& name) {
        return [this, first, name](JointDesc& j) {
            const SceneDesc& scene = doc_->scene();
            std::string& body = first ? j.bodyA : j.bodyB;
            Vec3& anchor = first ? j.anchorA : j.anchorB;
            std::optional<Vec3>& axis = first ? j.axisA : j.axisB;
            const BodyFrame from = frameOf(scene, body), to = frameOf(scene, name);
            anchor = to.toLocal(from.toWorld(anchor));
            if (axis) axis = to.q.conjugate() * (from.q * *axis);
            body = name;
        };
    };
    connect(bodyA_, &QComboBox::activated, this, [this, rebind](int i) {
        apply("body_a", tr("Set joint's moving body"), rebind(true, bodyA_->itemData(i).toString().toStdString()), false,
              bodyA_->itemText(i));
    });
    connect(bodyB_, &QComboBox::activated, this, [this, rebind](int i) {
        apply("body_b", tr("Set joint's base"), rebind(false, bodyB_->itemData(i).toString().toStdString()), false,
              bodyB_->itemText(i));
    });

    // The anchors in their bodies' frames (as the file has them), or as world points (the
    // toggle: typed there, kept in the bodies' frames as they are placed).
    anchorsInWorld_ = new QCheckBox(tr("World coordinates"));
    anchorsInWorld_->setObjectName("joint.anchors_world");
    anchorsInWorld_->setToolTip(tr("Type the anchors as world points (kept in each body's frame as placed)"));
    addRow(QString(), "anchors_world", anchorsInWorld_);
    connect(anchorsInWorld_, &QCheckBox::toggled, this, [this] {
        dropHeld();
        refresh();
    });
    // An anchor as shown: in its body's frame, or in the world's with the toggle on.
    auto shown = [this](bool first) {
        return [this, first](const JointDesc& j) {
            const Vec3& local = first ? j.anchorA : j.anchorB;
            if (!anchorsInWorld_->isChecked()) return std::optional<Vec3>(local);
            return std::optional<Vec3>(frameOf(doc_->scene(), first ? j.bodyA : j.bodyB).toWorld(local));
        };
    };
    auto stored = [this](bool first) {
        return [this, first](JointDesc& j, const Vec3& a) {
            Vec3& local = first ? j.anchorA : j.anchorB;
            local = anchorsInWorld_->isChecked() ? frameOf(doc_->scene(), first ? j.bodyA : j.bodyB).toLocal(a) : a;
        };
    };
    anchorA_ = vector("joint.anchor_a", " m");
    addRow(tr("Anchor A"), "anchor_a", anchorA_);
    connect(anchorA_, &VectorEdit::componentEdited, this, [this, shown, stored](int k, double v) {
        editVector("anchor_a", tr("Move joint anchor A") + ' ' + QChar(u'x' + k), k, v, shown(true), stored(true),
                   anchorA_->component(k)->shownText(v));
    });
    anchorB_ = vector("joint.anchor_b", " m");
    addRow(tr("Anchor B"), "anchor_b", anchorB_);
    connect(anchorB_, &VectorEdit::componentEdited, this, [this, shown, stored](int k, double v) {
        editVector("anchor_b", tr("Move joint anchor B") + ' ' + QChar(u'x' + k), k, v, shown(false), stored(false),
                   anchorB_->component(k)->shownText(v));
    });

    axisA_ = vector("joint.axis_a", QString());
    axisA_->setToolTip(tr("In body A's frame, any length but zero"));
    addRow(tr("Axis"), "axis_a", axisA_);
    connect(axisA_, &VectorEdit::componentEdited, this, [this](int k, double v) {
        editVector(
            "axis_a", tr("Turn joint axis") + ' ' + QChar(u'x' + k), k, v, [](const JointDesc& j) { return j.axisA; },
            [](JointDesc& j, const Vec3& a) { j.axisA = a; }, axisA_->component(k)->shownText(v));
    });
    hasAxisB_ = new QCheckBox(tr("own"));
    hasAxisB_->setObjectName("joint.axis_b.on");
    hasAxisB_->setToolTip(tr("Give body B an axis of its own (else the axis as it lies at the start)"));
    axisB_ = vector("joint.axis_b", QString());
    addRow(tr("Axis on B"), "axis_b", optional(hasAxisB_, {axisB_}));
    connect(hasAxisB_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "axis_b", on ? tr("Give joint an axis on B") : tr("Take joint's axis on B away"),
            [&](JointDesc& j) {
                if (!on || !j.axisA) {
                    j.axisB.reset();
                    return;
                }
                const SceneDesc& scene = doc_->scene();
                const BodyFrame a = frameOf(scene, j.bodyA), b = frameOf(scene, j.bodyB);
                j.axisB = b.q.conjugate() * (a.q * *j.axisA);
            },
            false);
    });
    connect(axisB_, &VectorEdit::componentEdited, this, [this](int k, double v) {
        editVector(
            "axis_b", tr("Turn joint axis on B") + ' ' + QChar(u'x' + k), k, v,
            [](const JointDesc& j) { return j.axisB; }, [](JointDesc& j, const Vec3& a) { j.axisB = a; },
            axisB_->component(k)->shownText(v));
    });

    asPlaced_ = new QCheckBox(tr("as placed"));
    asPlaced_->setObjectName("joint.length.as_placed");
    asPlaced_->setToolTip(tr("The anchors' distance in the scene"));
    length_ = spin("joint.length", " m", 0.0, 0.05);
    addRow(tr("Length"), "length", optional(asPlaced_, {length_}));
    connect(asPlaced_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "length", tr("Set joint length"),
            [&](JointDesc& j) {
                if (on) {
                    j.length = -1.0;
                    return;
                }
                j.length = (worldAnchorA(doc_->scene(), j) - worldAnchorB(doc_->scene(), j)).norm();
            },
            false);
    });
    connect(length_, &PropertySpinBox::valueChanged, this, [this](double v) {
        apply(
            "length", tr("Set joint length"), [&](JointDesc& j) { j.length = v; }, true, length_->shownText(v));
    });

    buildAxisRows();

    hasLimits_ = new QCheckBox;
    hasLimits_->setObjectName("joint.limits.on");
    lower_ = spin("joint.limits.lower", QString(), -1e12, 5.0);
    upper_ = spin("joint.limits.upper", QString(), -1e12, 5.0);
    lower_->setToolTip(tr("Lower limit"));
    upper_->setToolTip(tr("Upper limit"));
    addRow(tr("Limits"), "limits", optional(hasLimits_, {lower_, upper_}));
    // A hinge's angles are shown in degrees (as orientations are), kept in radians.
    auto unit = [this](const JointDesc& j) { return j.type == JointType::Hinge ? kDegree : 1.0; };
    connect(hasLimits_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "limits", on ? tr("Limit joint") : tr("Free joint's limits"),
            [&](JointDesc& j) {
                if (on)
                    j.limits = j.type == JointType::Hinge ? std::array<double, 2>{-std::numbers::pi / 2, std::numbers::pi / 2}
                                                           : std::array<double, 2>{-0.5, 0.5};
                else
                    j.limits.reset();
            },
            false);
    });
    for (int k = 0; k < 2; ++k) {
        // The two limits are one value (editVector): lower, upper and an unused 0.
        connect(k ? upper_ : lower_, &PropertySpinBox::valueChanged, this, [this, k, unit](double v) {
            const int i = jointIndex();
            if (i < 0) return;
            editVector(
                "limits", k ? tr("Set joint upper limit") : tr("Set joint lower limit"), k, v * unit(viewed(i)),
                [](const JointDesc& j) {
                    return j.limits ? std::optional(Vec3((*j.limits)[0], (*j.limits)[1], 0.0)) : std::nullopt;
                },
                [](JointDesc& j, const Vec3& l) {
                    j.limits = std::array<double, 2>{l[0], l[1]};
                },
                (k ? upper_ : lower_)->shownText(v));
        });
    }

    hasMotor_ = new QCheckBox;
    hasMotor_->setObjectName("joint.motor.on");
    motorSpeed_ = spin("joint.motor.speed", QString(), -1e12, 0.1);
    motorSpeed_->setToolTip(tr("Target rate"));
    motorMax_ = spin("joint.motor.max", QString(), 0.0, 1.0);
    motorMax_->setToolTip(tr("At most this torque (hinge) or force (slider)"));
    addRow(tr("Motor"), "motor", optional(hasMotor_, {motorSpeed_, motorMax_}));
    connect(hasMotor_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "motor", on ? tr("Add joint motor") : tr("Remove joint motor"),
            [&](JointDesc& j) {
                if (on) {
                    j.motor = JointDesc::Motor{1.0, 10.0};
                    j.servo.reset();  // one drive: the motor replaces the servo
                } else {
                    j.motor.reset();
                }
            },
            false);
    });
    connect(motorSpeed_, &PropertySpinBox::valueChanged, this, [this](double v) {
        apply(
            "motor", tr("Set motor speed"),
            [&](JointDesc& j) {
                if (j.motor) j.motor->speed = v;
            },
            true, motorSpeed_->shownText(v));
    });
    connect(motorMax_, &PropertySpinBox::valueChanged, this, [this](double v) {
        apply(
            "motor", tr("Set motor strength"),
            [&](JointDesc& j) {
                if (j.motor) j.motor->maxForce = v;
            },
            true, motorMax_->shownText(v));
    });

    buildDriveRows();
    buildServoKeyRows();
    buildBallLimitRows();

    breaks_ = new QCheckBox;
    breaks_->setObjectName("joint.break_force.on");
    breaks_->setToolTip(tr("The joint breaks for good when the force it carries passes this"));
    breakForce_ = spin("joint.break_force", " N", 0.0, 10.0);
    addRow(tr("Breaks at"), "break_force", optional(breaks_, {breakForce_}));
    connect(breaks_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "break_force", on ? tr("Let joint break") : tr("Make joint unbreakable"),
            [&](JointDesc& j) {
                if (on)
                    j.breakForce = 1000.0;
                else
                    j.breakForce.reset();
            },
            false);
    });
    connect(breakForce_, &PropertySpinBox::valueChanged, this, [this](double v) {
        apply(
            "break_force", tr("Set joint breaking force"),
            [&](JointDesc& j) {
                if (j.breakForce) j.breakForce = v;
            },
            true, breakForce_->shownText(v));
    });

    collide_ = new QCheckBox(tr("its bodies collide"));
    collide_->setObjectName("joint.collide_connected");
    collide_->setToolTip(tr("Off: the joint's two bodies pass through each other, as a chain's links do"));
    addRow(tr("Collision"), "collide_connected", collide_);
    connect(collide_, &QCheckBox::toggled, this, [this](bool on) {
        apply(
            "collide_connected", on ? tr("Let joined bodies collide") : tr("Let joined bodies pass through"),
            [&](JointDesc& j) { j.collideConnected = on; }, false);
    });

    connect(doc_, &Document::jointsChanged, this, &JointPanel::refresh);
    connect(doc_, &Document::bodyChanged, this, &JointPanel::refresh);
    connect(doc_, &Document::bodyInserted, this, &JointPanel::refresh);
    connect(doc_, &Document::bodyRemoved, this, &JointPanel::refresh);
    connect(doc_, &Document::selectionChanged, this, [this] {
        ++generation_;
        dropHeld();
        clearErrors();
        refresh();
    });
    const auto cancel = [this] {
        dropHeld();
        clearErrors();
        refresh();
    };
    for (VectorEdit* field : {anchorA_, anchorB_, axisA_, axisB_})
        connect(field, &VectorEdit::cancelled, this, cancel);
    for (PropertySpinBox* limit : {lower_, upper_})
        connect(limit, &PropertySpinBox::heldCancelled, this, cancel);
    refresh();
}

QWidget* JointPanel::addFormRow(const QString& label, const QString& key, QWidget* editor) {
    QWidget* row = withError(editor, key);
    form_->addRow(label, row);
    rows_.insert(key, row);
    return row;
}

PropertySpinBox* JointPanel::makeSpin(const QString& key, const QString& suffix, double min, double step) {
    auto* s = new PropertySpinBox;
    s->setObjectName(key);
    s->setSuffix(suffix);
    s->setSoftMinimum(min);
    s->setSingleStep(step);
    connect(s, &PropertySpinBox::editingFinished, this, [this] { ++generation_; });
    return s;
}

QWidget* JointPanel::optionalRow(QWidget* check, std::initializer_list<QWidget*> fields) {
    auto* w = new QWidget;
    auto* layout = new QHBoxLayout(w);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(check);
    for (QWidget* f : fields) layout->addWidget(f, 1);
    return w;
}

int JointPanel::jointIndex() const {
    return doc_->selectedJoint();
}

QWidget* JointPanel::withError(QWidget* editor, const QString& key) {
    auto* box = new QWidget;
    auto* layout = new QVBoxLayout(box);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(1);
    layout->addWidget(editor);
    auto* error = new QLabel(box);
    error->setObjectName("joint." + key + ".error");
    error->setStyleSheet("color: #c62828;");
    error->setWordWrap(true);
    error->hide();
    layout->addWidget(error);
    errors_.insert(key, error);
    whenFieldLeft(editor, [this, error, key] {
        if (!held_.contains(key)) error->hide();  // a held value keeps its reason in view
    });
    return box;
}

void JointPanel::clearErrors() {
    for (QLabel* l : errors_) l->hide();
}

QString JointPanel::fieldError(const QString& field) const {
    QLabel* label = errors_.value(field);
    return label && !label->isHidden() ? label->text() : QString();
}

void JointPanel::apply(const QString& key, const QString& text, const Edit& edit, bool merge, const QString& value) {
    const int i = jointIndex();
    if (i < 0) return;
    // (A type change is made to the joint itself, every other edit to what the rows show.)
    JointDesc j = key == "type" ? doc_->joint(i) : viewed(i);
    edit(j);
    if (key != "type") j = lowered(j, i);
    if (j == doc_->joint(i)) {
        refresh();
        return;
    }
    // Refused only for a problem this edit brings (another joint may have one already).
    SceneDesc scene = doc_->scene();
    scene.joints[static_cast<size_t>(i)] = j;
    const auto problem = problemOf(scene);
    if (problem && problem != problemOf(doc_->scene())) {
        clearErrors();
        QLabel* error = errors_.value(key);
        error->setText(QString::fromStdString(*problem));
        error->show();
        refresh();
        return;
    }
    clearErrors();
    const int mergeId = merge ? static_cast<int>(qHash(key) % 100000u) + 1 + generation_ * 100003 : 0;
    const QString name = QString::fromStdString(doc_->joint(i).name);
    doc_->setJoint(i, j, value.isEmpty() ? text : Document::editText(text, name, value), mergeId);
}

namespace {

// A refused value's reason as the panel says it: the field's own words where there are
// some, else the message without the file's field path ("joints[0].axis_a: ").
QString inPlainWords(const QString& key, const std::string& problem) {
    const QString text = QString::fromStdString(problem);
    if ((key == "axis_a" || key == "axis_b") && text.contains("zero vector"))
        return JointPanel::tr("The axis cannot be zero: give it a direction.");
    if (key == "limits" && text.contains("above the upper"))
        return JointPanel::tr("The lower limit cannot be above the upper one.");
    const int cut = text.indexOf(QStringLiteral(": "));
    return cut >= 0 && text.left(cut).contains('[') ? text.mid(cut + 2) : text;
}

}  // namespace

void JointPanel::markHeld(const QString& key, bool held) {
    if (key == "limits") {
        lower_->setHeld(held);
        upper_->setHeld(held);
        return;
    }
    const QMap<QString, VectorEdit*> fields{
        {"anchor_a", anchorA_}, {"anchor_b", anchorB_}, {"axis_a", axisA_}, {"axis_b", axisB_}};
    if (VectorEdit* field = fields.value(key)) field->setHeld(held);
}

void JointPanel::editVector(const QString& key, const QString& text, int k, double v, const VectorOf& get,
                            const SetVector& set, const QString& shown) {
    const int i = jointIndex();
    if (i < 0) return;
    const std::optional<Vec3> current = get(viewed(i));
    if (!current) return;
    Vec3 value = *current;
    if (const auto it = held_.constFind(key); it != held_.cend()) value = *it;
    value[k] = v;
    JointDesc j = viewed(i);
    set(j, value);
    j = lowered(j, i);
    SceneDesc scene = doc_->scene();
    scene.joints[static_cast<size_t>(i)] = j;
    const auto problem = problemOf(scene);
    if (problem && problem != problemOf(doc_->scene())) {
        held_.insert(key, value);
        markHeld(key, true);
        clearErrors();
        QLabel* error = errors_.value(key);
        error->setText(inPlainWords(key, *problem) + ' ' + tr("(Esc: back to the last valid value)"));
        error->show();
        return;  // the components stay as typed
    }
    held_.remove(key);
    markHeld(key, false);
    apply(
        key, text, [&](JointDesc& jj) { set(jj, value); }, true, shown);
}

void JointPanel::dropHeld() {
    for (const QString& key : held_.keys()) markHeld(key, false);
    held_.clear();
}

void JointPanel::refresh() {
    const int i = jointIndex();
    if (i < 0) return;
    const JointDesc& real = doc_->joint(i);
    const JointDesc j = viewed(i);  // (a six-axis joint: the shown axis's settings as its own)
    const SceneDesc& scene = doc_->scene();
    {
        const QSignalBlocker b(name_);
        name_->setText(QString::fromStdString(j.name));
    }
    {
        const QSignalBlocker b(type_);
        type_->setCurrentIndex(type_->findData(int(real.type)));
    }
    for (QComboBox* combo : {bodyA_, bodyB_}) {
        const QSignalBlocker b(combo);
        combo->clear();
        if (combo == bodyB_) combo->addItem(tr("(world)"), QString());
        for (const BodyDesc& body : scene.bodies)
            combo->addItem(QString::fromStdString(body.name), QString::fromStdString(body.name));
        combo->setCurrentIndex(combo->findData(QString::fromStdString(combo == bodyA_ ? j.bodyA : j.bodyB)));
    }
    const bool world = anchorsInWorld_->isChecked();
    const BodyFrame frameA = frameOf(scene, j.bodyA), frameB = frameOf(scene, j.bodyB);
    anchorA_->showValue(held_.value("anchor_a", world ? frameA.toWorld(j.anchorA) : j.anchorA));
    anchorB_->showValue(held_.value("anchor_b", world ? frameB.toWorld(j.anchorB) : j.anchorB));
    anchorA_->setToolTip(world ? tr("A world point, as the bodies are placed") : tr("In body A's frame"));
    anchorB_->setToolTip(world || j.bodyB.empty() ? tr("A world point") : tr("In body B's frame"));
    const bool six = real.type == JointType::SixAxis;
    swap_->setEnabled(!j.bodyB.empty() && !six);
    swap_->setToolTip(six ? tr("A six-axis joint's frame is body A's: make it again from the other body to swap")
                          : tr("Make the base the moving part and the moving part the base: the same joint "
                               "(its limits and motor speed change sign)"));
    const bool ax = axial(j.type);
    const bool ballAxis = j.type == JointType::Ball && j.axisA.has_value();
    form_->setRowVisible(rows_["axis_a"], ax || ballAxis);
    form_->setRowVisible(rows_["axis_b"], (ax && !six) || ballAxis);
    refreshAxes(real);
    form_->setRowVisible(rows_["limits"], ax);
    form_->setRowVisible(rows_["motor"], ax);
    form_->setRowVisible(rows_["length"], line(j.type));
    if (j.axisA) axisA_->showValue(held_.value("axis_a", *j.axisA));
    {
        const QSignalBlocker b(hasAxisB_);
        hasAxisB_->setChecked(j.axisB.has_value());
    }
    axisB_->setEnabled(j.axisB.has_value());
    if (j.axisB) axisB_->showValue(held_.value("axis_b", *j.axisB));
    {
        const QSignalBlocker b(asPlaced_);
        asPlaced_->setChecked(j.length < 0.0);
    }
    length_->setEnabled(j.length >= 0.0);
    if (j.length >= 0.0) length_->showValue(j.length);
    const bool hinge = j.type == JointType::Hinge;
    const double unit = hinge ? kDegree : 1.0;
    for (PropertySpinBox* s : {lower_, upper_}) s->setSuffix(hinge ? QStringLiteral("°") : QStringLiteral(" m"));
    {
        const QSignalBlocker b(hasLimits_);
        hasLimits_->setChecked(j.limits.has_value());
    }
    lower_->setEnabled(j.limits.has_value());
    upper_->setEnabled(j.limits.has_value());
    if (j.limits) {
        const Vec3 limits = held_.value("limits", Vec3((*j.limits)[0], (*j.limits)[1], 0.0));
        lower_->showValue(limits[0] / unit);
        upper_->showValue(limits[1] / unit);
    }
    motorSpeed_->setSuffix(hinge ? QStringLiteral(" rad/s") : QStringLiteral(" m/s"));
    motorMax_->setSuffix(hinge ? QStringLiteral(" N m") : QStringLiteral(" N"));
    {
        const QSignalBlocker b(hasMotor_);
        hasMotor_->setChecked(j.motor.has_value());
    }
    motorSpeed_->setEnabled(j.motor.has_value());
    motorMax_->setEnabled(j.motor.has_value());
    if (j.motor) {
        motorSpeed_->showValue(j.motor->speed);
        motorMax_->showValue(j.motor->maxForce);
    }
    refreshDrives(j);
    refreshBallLimits(j);
    {
        const QSignalBlocker b(breaks_);
        breaks_->setChecked(j.breakForce.has_value());
    }
    breakForce_->setEnabled(j.breakForce.has_value());
    if (j.breakForce) breakForce_->showValue(*j.breakForce);
    {
        const QSignalBlocker b(collide_);
        collide_->setChecked(j.collideConnected);
    }
}

}  // namespace tumble::ui
