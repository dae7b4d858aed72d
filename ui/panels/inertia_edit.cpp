#include "panels/inertia_edit.h"

#include "panels/property_spin_box.h"

#include <QCheckBox>
#include <QGridLayout>
#include <QSignalBlocker>
#include <QVBoxLayout>

namespace tumble::ui {

InertiaEdit::InertiaEdit(const QString& name, QWidget* parent) : QWidget(parent) {
    setObjectName(name);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    override_ = new QCheckBox(tr("Override"), this);
    override_->setToolTip(tr("Give your own tensor; otherwise it is computed from the shape and the mass"));
    override_->setObjectName(name + ".override");
    layout->addWidget(override_);
    auto* grid = new QGridLayout;
    grid->setSpacing(2);
    layout->addLayout(grid);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            auto* spin = new PropertySpinBox(this);
            spin->setObjectName(QStringLiteral("%1.%2%3").arg(name).arg(i).arg(j));
            spin->setSuffix(QStringLiteral(" kg·m²"));
            spin->setSingleStep(0.01);
            spin->setMinimumWidth(40);
            spin->setEnabled(false);
            cells_[static_cast<size_t>(3 * i + j)] = spin;
            grid->addWidget(spin, i, j);
            connect(spin, &PropertySpinBox::valueChanged, this, [this, i, j](double v) {
                if (i != j) cell(j, i)->showValue(v);  // the tensor is symmetric
                emit cellEdited(i, j, v);
            });
            connect(spin, &PropertySpinBox::editingFinished, this, &InertiaEdit::editingFinished);
            connect(spin, &PropertySpinBox::heldCancelled, this, &InertiaEdit::cancelled);
        }
    }
    connect(override_, &QCheckBox::clicked, this, [this](bool on) { emit overrideToggled(on); });
}

void InertiaEdit::showValue(const std::array<std::optional<double>, 9>& cells) {
    for (size_t k = 0; k < 9; ++k) {
        if (cells[k])
            cells_[k]->showValue(*cells[k]);
        else
            cells_[k]->showMixed();
    }
}

void InertiaEdit::showValue(const Mat3& m) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) cell(i, j)->showValue(m(i, j));
}

void InertiaEdit::setHeld(bool held) {
    for (auto* c : cells_) c->setHeld(held);
}

bool InertiaEdit::isHeld() const {
    return cells_[0]->isHeld();
}

void InertiaEdit::showOverride(Qt::CheckState state) {
    const QSignalBlocker block(override_);
    override_->setTristate(state == Qt::PartiallyChecked);
    override_->setCheckState(state);
    for (auto* c : cells_) c->setEnabled(state == Qt::Checked);
}

}  // namespace tumble::ui
