#include "panels/vector_edit.h"

#include "panels/property_spin_box.h"

#include <QHBoxLayout>

namespace tumble::ui {

VectorEdit::VectorEdit(const QString& name, const QString& suffix, QWidget* parent) : QWidget(parent) {
    setObjectName(name);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(2);
    static const char* axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        auto* spin = new PropertySpinBox(this);
        spin->setObjectName(name + "." + axes[k]);
        spin->setSuffix(suffix);
        spin->setToolTip(QString::fromLatin1(axes[k]));
        spin->setMinimumWidth(40);
        spins_[static_cast<size_t>(k)] = spin;
        layout->addWidget(spin, 1);
        connect(spin, &PropertySpinBox::valueChanged, this,
                [this, k](double v) { emit componentEdited(k, v); });
        connect(spin, &PropertySpinBox::editingFinished, this, &VectorEdit::editingFinished);
        connect(spin, &PropertySpinBox::heldCancelled, this, &VectorEdit::cancelled);
    }
}

void VectorEdit::setHeld(bool held) {
    for (auto* s : spins_) s->setHeld(held);
}

bool VectorEdit::isHeld() const {
    return spins_[0]->isHeld();
}

void VectorEdit::showValue(const std::array<std::optional<double>, 3>& v, const Vec3& base) {
    for (size_t k = 0; k < 3; ++k) {
        if (v[k])
            spins_[k]->showValue(*v[k]);
        else
            spins_[k]->showMixed(base[static_cast<int>(k)]);
    }
}

void VectorEdit::showValue(const Vec3& v) {
    for (int k = 0; k < 3; ++k) spins_[static_cast<size_t>(k)]->showValue(v[k]);
}

void VectorEdit::setSoftMinimum(double min) {
    for (auto* s : spins_) s->setSoftMinimum(min);
}

void VectorEdit::setSuffix(const QString& suffix) {
    for (auto* s : spins_) s->setSuffix(suffix);
}

void VectorEdit::setSingleStep(double step) {
    for (auto* s : spins_) s->setSingleStep(step);
}

Vec3 VectorEdit::value() const {
    return Vec3(spins_[0]->value(), spins_[1]->value(), spins_[2]->value());
}

}  // namespace tumble::ui
