#include "window/build_dialogs.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>

namespace tumble::ui {

namespace {

QDoubleSpinBox* metres(QWidget* parent, double value, double lowest, const QString& name) {
    auto* box = new QDoubleSpinBox(parent);
    box->setObjectName(name);
    box->setDecimals(3);
    box->setRange(lowest, 1000.0);
    box->setSingleStep(0.05);
    box->setSuffix(QStringLiteral(" m"));
    box->setValue(value);
    return box;
}

QSpinBox* counter(QWidget* parent, int value, int lowest, const QString& name) {
    auto* box = new QSpinBox(parent);
    box->setObjectName(name);
    box->setRange(lowest, 10000);
    box->setValue(value);
    return box;
}

QDialogButtonBox* okCancel(QDialog* dialog) {
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, dialog);
    QObject::connect(buttons, &QDialogButtonBox::accepted, dialog, &QDialog::accept);
    QObject::connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::reject);
    return buttons;
}

}  // namespace

ArrayDialog::ArrayDialog(const Vec3& size, int bodies, QWidget* parent) : QDialog(parent), bodies_(bodies) {
    setWindowTitle(tr("Array"));
    auto* form = new QFormLayout(this);
    form->addRow(new QLabel(tr("Copies of the selection along up to three offsets: a row, a grid or a block.\n"
                               "The selection itself is the first of them."),
                            this));
    const std::array<Vec3, 3> defaults = {Vec3(size.x() + 0.1, 0, 0), Vec3(0, 0, size.z() + 0.1),
                                          Vec3(0, size.y() + 0.1, 0)};
    const std::array<int, 3> counts = {5, 1, 1};
    const char* axes = "xyz";
    for (int d = 0; d < 3; ++d) {
        auto* row = new QHBoxLayout;
        count_[d] = counter(this, counts[d], 1, QStringLiteral("count%1").arg(d + 1));
        count_[d]->setSuffix(tr(" ×"));
        row->addWidget(count_[d]);
        for (int k = 0; k < 3; ++k) {
            step_[d][k] = metres(this, defaults[d][k], -1000.0, QStringLiteral("step%1%2").arg(d + 1).arg(axes[k]));
            step_[d][k]->setPrefix(QStringLiteral("%1 ").arg(QChar(axes[k])));
            row->addWidget(step_[d][k]);
        }
        form->addRow(tr("Offset %1").arg(d + 1), row);
        connect(count_[d], &QSpinBox::valueChanged, this, &ArrayDialog::update);
    }
    total_ = new QLabel(this);
    total_->setObjectName("total");
    form->addRow(total_);
    buttons_ = okCancel(this);
    form->addRow(buttons_);
    update();
}

std::array<int, 3> ArrayDialog::counts() const {
    return {count_[0]->value(), count_[1]->value(), count_[2]->value()};
}

std::array<Vec3, 3> ArrayDialog::steps() const {
    std::array<Vec3, 3> out;
    for (int d = 0; d < 3; ++d) out[d] = Vec3(step_[d][0]->value(), step_[d][1]->value(), step_[d][2]->value());
    return out;
}

void ArrayDialog::update() {
    const long places = long(count_[0]->value()) * count_[1]->value() * count_[2]->value();
    const long added = (places - 1) * bodies_;
    const bool ok = places <= kMostLaidOut && added <= kMostLaidOut;
    total_->setText(ok ? tr("%n new bodies", nullptr, int(added))
                       : tr("%1 places: at most %2").arg(places).arg(kMostLaidOut));
    buttons_->button(QDialogButtonBox::Ok)->setEnabled(ok && added > 0);
}

LayoutDialog::LayoutDialog(Layout kind, QWidget* parent) : QDialog(parent), kind_(kind) {
    auto* form = new QFormLayout(this);
    const LayoutSpec defaults;
    switch (kind) {
        case Layout::Stack:
            setWindowTitle(tr("Make Stack"));
            count_ = counter(this, 10, 1, "count");
            form->addRow(tr("Boxes"), count_);
            break;
        case Layout::Pyramid:
            setWindowTitle(tr("Make Pyramid"));
            count_ = counter(this, 10, 1, "count");
            form->addRow(tr("Bottom row"), count_);
            option_ = new QCheckBox(tr("Square layers"), this);
            option_->setObjectName("square");
            form->addRow(option_);
            break;
        case Layout::Wall:
            setWindowTitle(tr("Make Wall"));
            count_ = counter(this, 10, 1, "count");
            form->addRow(tr("Boxes a row"), count_);
            rows_ = counter(this, 5, 1, "rows");
            form->addRow(tr("Rows"), rows_);
            option_ = new QCheckBox(tr("Staggered rows (a brick bond)"), this);
            option_->setObjectName("staggered");
            option_->setChecked(true);
            form->addRow(option_);
            break;
    }
    auto* size = new QHBoxLayout;
    const char* axes = "xyz";
    for (int k = 0; k < 3; ++k) {
        size_[k] = metres(this, 2.0 * defaults.halfExtents[k], 0.001, QStringLiteral("size%1").arg(axes[k]));
        size_[k]->setPrefix(QStringLiteral("%1 ").arg(QChar(axes[k])));
        size->addWidget(size_[k]);
    }
    form->addRow(tr("Box size"), size);
    gap_ = metres(this, kind == Layout::Stack ? 0.0 : 0.01, 0.0, "gap");
    gap_->setToolTip(tr("Between neighbours in a row; boxes rest on each other"));
    form->addRow(tr("Gap"), gap_);
    mass_ = new QDoubleSpinBox(this);
    mass_->setObjectName("mass");
    mass_->setRange(0.001, 1e6);
    mass_->setDecimals(3);
    mass_->setSuffix(QStringLiteral(" kg"));
    mass_->setValue(1.0);
    form->addRow(tr("Mass of a box"), mass_);
    total_ = new QLabel(this);
    total_->setObjectName("total");
    form->addRow(total_);
    buttons_ = okCancel(this);
    form->addRow(buttons_);
    connect(count_, &QSpinBox::valueChanged, this, &LayoutDialog::update);
    if (rows_) connect(rows_, &QSpinBox::valueChanged, this, &LayoutDialog::update);
    if (option_) connect(option_, &QCheckBox::toggled, this, &LayoutDialog::update);
    update();
}

LayoutSpec LayoutDialog::spec() const {
    LayoutSpec s;
    s.kind = kind_;
    s.count = count_->value();
    if (rows_) s.rows = rows_->value();
    if (kind_ == Layout::Pyramid) s.square = option_->isChecked();
    if (kind_ == Layout::Wall) s.staggered = option_->isChecked();
    s.halfExtents = 0.5 * Vec3(size_[0]->value(), size_[1]->value(), size_[2]->value());
    s.gap = gap_->value();
    return s;
}

double LayoutDialog::mass() const { return mass_->value(); }

void LayoutDialog::update() {
    const long n = layoutCount(spec());
    const bool ok = n <= kMostLaidOut;
    total_->setText(ok ? tr("%n boxes", nullptr, int(n)) : tr("%1 boxes: at most %2").arg(n).arg(kMostLaidOut));
    buttons_->button(QDialogButtonBox::Ok)->setEnabled(ok && n > 0);
}

}  // namespace tumble::ui
