#include "panels/forces_edit.h"

#include "panels/property_spin_box.h"
#include "panels/vector_edit.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QMenu>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include <algorithm>

namespace tumble::ui {

namespace {

QString vec(const Vec3& v) {
    return QStringLiteral("(%1, %2, %3)").arg(v.x(), 0, 'g', 4).arg(v.y(), 0, 'g', 4).arg(v.z(), 0, 'g', 4);
}

// A check box in front of an editor: the optional value is given when checked.
QWidget* optionalRow(QCheckBox* on, QWidget* editor) {
    auto* row = new QWidget;
    auto* layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(on);
    layout->addWidget(editor, 1);
    return row;
}

}  // namespace

ForcesEdit::ForcesEdit(QWidget* parent) : QWidget(parent) {
    setObjectName("forces");
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);

    list_ = new QListWidget(this);
    list_->setObjectName("forces.list");
    list_->setMaximumHeight(110);
    layout->addWidget(list_);

    auto* buttons = new QHBoxLayout;
    add_ = new QPushButton(tr("Add"), this);
    add_->setObjectName("forces.add");
    auto* menu = new QMenu(add_);
    menu->addAction(tr("Force"), this, [this] { addForce(ForceType::Force); });
    menu->addAction(tr("Torque"), this, [this] { addForce(ForceType::Torque); });
    menu->addAction(tr("Spring"), this, [this] { addForce(ForceType::Spring); });
    add_->setMenu(menu);
    remove_ = new QPushButton(tr("Remove"), this);
    remove_->setObjectName("forces.remove");
    buttons->addWidget(add_);
    buttons->addWidget(remove_);
    buttons->addStretch(1);
    layout->addLayout(buttons);
    connect(remove_, &QPushButton::clicked, this, &ForcesEdit::removeCurrent);

    editor_ = new QWidget(this);
    form_ = new QFormLayout(editor_);
    form_->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(editor_);

    type_ = new QComboBox;
    type_->setObjectName("forces.type");
    type_->addItem(tr("Force"), int(ForceType::Force));
    type_->addItem(tr("Torque"), int(ForceType::Torque));
    type_->addItem(tr("Spring"), int(ForceType::Spring));
    form_->addRow(tr("Type"), type_);
    connect(type_, &QComboBox::activated, this, [this](int i) {
        const auto t = ForceType(type_->itemData(i).toInt());
        edit("type", tr("Set force type"), [t](ForceDesc& f) { f.type = t; });
    });

    frame_ = new QComboBox;
    frame_->setObjectName("forces.frame");
    frame_->addItem(tr("World"), int(Frame::World));
    frame_->addItem(tr("Body"), int(Frame::Body));
    form_->addRow(tr("Frame"), frame_);
    connect(frame_, &QComboBox::activated, this, [this](int i) {
        const auto fr = Frame(frame_->itemData(i).toInt());
        edit("frame", tr("Set force frame"), [fr](ForceDesc& f) { f.frame = fr; });
    });

    vector_ = new VectorEdit("forces.vector", " N");
    form_->addRow(tr("Vector"), vector_);
    connect(vector_, &VectorEdit::componentEdited, this, [this](int k, double v) {
        edit("vector", tr("Set force vector"), [k, v](ForceDesc& f) { f.vector[k] = v; });
    });

    pointOn_ = new QCheckBox;
    pointOn_->setObjectName("forces.point.on");
    pointOn_->setToolTip(tr("Off: at the centre of mass"));
    point_ = new VectorEdit("forces.point", " m");
    point_->setToolTip(tr("Point of application in the body frame"));
    pointRow_ = optionalRow(pointOn_, point_);
    form_->addRow(tr("Point (body)"), pointRow_);
    connect(pointOn_, &QCheckBox::clicked, this, [this](bool on) {
        edit("point", tr("Set force point"), [on](ForceDesc& f) {
            if (on)
                f.point = Vec3::Zero();
            else
                f.point.reset();
        });
    });
    connect(point_, &VectorEdit::componentEdited, this, [this](int k, double v) {
        edit("point", tr("Set force point"), [k, v](ForceDesc& f) {
            Vec3 p = f.point.value_or(Vec3::Zero());
            p[k] = v;
            f.point = p;
        });
    });

    anchor_ = new VectorEdit("forces.anchor", " m");
    anchor_->setToolTip(tr("Fixed world point the spring is tied to"));
    form_->addRow(tr("Anchor (world)"), anchor_);
    connect(anchor_, &VectorEdit::componentEdited, this, [this](int k, double v) {
        edit("anchor", tr("Set spring anchor"), [k, v](ForceDesc& f) { f.anchor[k] = v; });
    });

    auto scalar = [this](const char* name, const QString& label, const QString& suffix,
                         double ForceDesc::*member, const QString& text) {
        auto* spin = new PropertySpinBox;
        spin->setObjectName(QStringLiteral("forces.%1").arg(name));
        spin->setSuffix(suffix);
        form_->addRow(label, spin);
        const QString field = QString::fromLatin1(name);
        connect(spin, &PropertySpinBox::valueChanged, this, [this, member, field, text](double v) {
            edit(field, text, [member, v](ForceDesc& f) { f.*member = v; });
        });
        connect(spin, &PropertySpinBox::editingFinished, this, &ForcesEdit::editingFinished);
        return spin;
    };
    stiffness_ =
        scalar("stiffness", tr("Stiffness"), " N/m", &ForceDesc::stiffness, tr("Set spring stiffness"));
    restLength_ =
        scalar("rest_length", tr("Rest length"), " m", &ForceDesc::restLength, tr("Set spring rest length"));
    damping_ = scalar("damping", tr("Damping"), " N·s/m", &ForceDesc::damping, tr("Set spring damping"));

    auto optionalTime = [this](const char* name, const QString& label,
                               std::optional<double> ForceDesc::*member, QCheckBox** on,
                               PropertySpinBox** spin, QWidget** row) {
        *on = new QCheckBox;
        (*on)->setObjectName(QStringLiteral("forces.%1.on").arg(name));
        *spin = new PropertySpinBox;
        (*spin)->setObjectName(QStringLiteral("forces.%1").arg(name));
        (*spin)->setSuffix(" s");
        (*spin)->setSingleStep(0.1);
        *row = optionalRow(*on, *spin);
        form_->addRow(label, *row);
        const QString field = QString::fromLatin1(name);
        const QString text = tr("Set force %1 time").arg(field);
        connect(*on, &QCheckBox::clicked, this, [this, member, field, text, spin](bool checked) {
            const double v = (*spin)->value();
            editWindow(field, text, [member, checked, v](ForceDesc& f) {
                if (checked)
                    f.*member = v;
                else
                    (f.*member).reset();
            });
        });
        connect(*spin, &PropertySpinBox::valueChanged, this, [this, member, field, text](double v) {
            editWindow(field, text, [member, v](ForceDesc& f) { f.*member = v; });
        });
        connect(*spin, &PropertySpinBox::editingFinished, this, &ForcesEdit::editingFinished);
        connect(*spin, &PropertySpinBox::heldCancelled, this, [this] {
            heldWindow_.reset();
            showCurrent();
        });
    };
    optionalTime("start", tr("Start"), &ForceDesc::start, &startOn_, &start_, &startRow_);
    optionalTime("end", tr("End"), &ForceDesc::end, &endOn_, &end_, &endRow_);
    windowError_ = new QLabel;
    windowError_->setObjectName("forces.window.error");
    windowError_->setStyleSheet("color: #c62828;");
    windowError_->setWordWrap(true);
    windowError_->setText(tr("The end must be later than the start. (Esc: back to the last valid times)"));
    form_->addRow(QString(), windowError_);
    startOn_->setToolTip(tr("Off: from the beginning"));
    endOn_->setToolTip(tr("Off: to the end"));

    for (VectorEdit* v : {vector_, point_, anchor_})
        connect(v, &VectorEdit::editingFinished, this, &ForcesEdit::editingFinished);
    connect(list_, &QListWidget::currentRowChanged, this, [this] { showCurrent(); });
    showCurrent();
}

QString ForcesEdit::summary(const ForceDesc& f) {
    QString s;
    switch (f.type) {
        case ForceType::Force:
            s = tr("Force %1 N, %2").arg(vec(f.vector), f.frame == Frame::World ? tr("world") : tr("body"));
            break;
        case ForceType::Torque:
            s = tr("Torque %1 N·m, %2")
                    .arg(vec(f.vector), f.frame == Frame::World ? tr("world") : tr("body"));
            break;
        case ForceType::Spring:
            s = tr("Spring %1 N/m to %2 m").arg(f.stiffness, 0, 'g', 4).arg(vec(f.anchor));
            break;
    }
    if (f.start || f.end) {
        s += tr(", %1 to %2 s")
                 .arg(f.start ? QString::number(*f.start, 'g', 4) : QStringLiteral("0"),
                      f.end ? QString::number(*f.end, 'g', 4) : QStringLiteral("∞"));
    }
    return s;
}

void ForcesEdit::setForces(const std::vector<ForceDesc>& forces) {
    const int row = list_->currentRow();
    forces_ = forces;
    {
        const QSignalBlocker block(list_);
        list_->clear();
        for (const ForceDesc& f : forces_) list_->addItem(summary(f));
        const int n = static_cast<int>(forces_.size());
        list_->setCurrentRow(n == 0 ? -1 : std::clamp(row, 0, n - 1));
    }
    showCurrent();
}

int ForcesEdit::currentIndex() const {
    return list_->currentRow();
}

void ForcesEdit::setCurrentIndex(int index) {
    list_->setCurrentRow(index);
}

void ForcesEdit::addForce(ForceType type) {
    std::vector<ForceDesc> next = forces_;
    ForceDesc f;
    f.type = type;
    next.push_back(f);
    const char* what = type == ForceType::Force ? "force" : type == ForceType::Torque ? "torque" : "spring";
    emit forcesEdited(next, tr("Add %1").arg(QString::fromLatin1(what)), QString());
    // Select the new entry if the owner took it.
    if (forces_.size() == next.size()) setCurrentIndex(static_cast<int>(forces_.size()) - 1);
}

void ForcesEdit::removeCurrent() {
    const int row = currentIndex();
    if (row < 0 || row >= static_cast<int>(forces_.size())) return;
    std::vector<ForceDesc> next = forces_;
    next.erase(next.begin() + row);
    emit forcesEdited(next, tr("Remove force"), QString());
}

void ForcesEdit::edit(const QString& field, const QString& text,
                      const std::function<void(ForceDesc&)>& change) {
    const int row = currentIndex();
    if (row < 0 || row >= static_cast<int>(forces_.size())) return;
    std::vector<ForceDesc> next = forces_;
    change(next[static_cast<size_t>(row)]);
    emit forcesEdited(next, text, QStringLiteral("forces[%1].%2").arg(row).arg(field));
}

void ForcesEdit::editWindow(const QString& field, const QString& text,
                            const std::function<void(ForceDesc&)>& change) {
    const int row = currentIndex();
    if (row < 0 || row >= static_cast<int>(forces_.size())) return;
    ForceDesc f = forces_[static_cast<size_t>(row)];
    if (heldWindow_ && heldWindow_->row == row) {
        f.start = heldWindow_->start;
        f.end = heldWindow_->end;
    }
    change(f);
    if (f.start && f.end && !(*f.end > *f.start)) {
        heldWindow_ = HeldWindow{row, f.start, f.end};
        showCurrent();  // the times as typed, framed red, and why
        return;
    }
    heldWindow_.reset();
    edit(field, text, [&f](ForceDesc& g) {
        g.start = f.start;
        g.end = f.end;
    });
    showCurrent();
}

void ForcesEdit::showCurrent() {
    const int row = currentIndex();
    const bool has = row >= 0 && row < static_cast<int>(forces_.size());
    remove_->setEnabled(has);
    editor_->setVisible(has);
    if (!has) return;
    if (heldWindow_ && heldWindow_->row != row) heldWindow_.reset();
    ForceDesc f = forces_[static_cast<size_t>(row)];
    if (heldWindow_) {
        f.start = heldWindow_->start;
        f.end = heldWindow_->end;
    }
    const bool spring = f.type == ForceType::Spring;
    {
        const QSignalBlocker b1(type_), b2(frame_), b3(pointOn_), b4(startOn_), b5(endOn_);
        type_->setCurrentIndex(type_->findData(int(f.type)));
        frame_->setCurrentIndex(frame_->findData(int(f.frame)));
        pointOn_->setChecked(f.point.has_value());
        startOn_->setChecked(f.start.has_value());
        endOn_->setChecked(f.end.has_value());
    }
    vector_->setSuffix(f.type == ForceType::Torque ? " N·m" : " N");
    vector_->showValue(f.vector);
    point_->showValue(f.point.value_or(Vec3::Zero()));
    point_->setEnabled(f.point.has_value());
    anchor_->showValue(f.anchor);
    stiffness_->showValue(f.stiffness);
    restLength_->showValue(f.restLength);
    damping_->showValue(f.damping);
    start_->showValue(f.start.value_or(0.0));
    start_->setEnabled(f.start.has_value());
    end_->showValue(f.end.value_or(0.0));
    end_->setEnabled(f.end.has_value());
    start_->setHeld(heldWindow_.has_value());
    end_->setHeld(heldWindow_.has_value());
    form_->setRowVisible(windowError_, heldWindow_.has_value());
    form_->setRowVisible(frame_, !spring);
    form_->setRowVisible(vector_, !spring);
    form_->setRowVisible(pointRow_, f.type != ForceType::Torque);
    form_->setRowVisible(anchor_, spring);
    form_->setRowVisible(stiffness_, spring);
    form_->setRowVisible(restLength_, spring);
    form_->setRowVisible(damping_, spring);
}

}  // namespace tumble::ui
