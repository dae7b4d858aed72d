#include "panels/keys_edit.h"

#include "panels/property_euler.h"
#include "panels/property_spin_box.h"
#include "panels/vector_edit.h"

#include <QFormLayout>
#include <QHBoxLayout>
#include <QListWidget>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include <algorithm>

namespace tumble::ui {

KeysEdit::KeysEdit(QWidget* parent) : QWidget(parent) {
    setObjectName("keys");
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);

    list_ = new QListWidget(this);
    list_->setObjectName("keys.list");
    list_->setMaximumHeight(110);
    layout->addWidget(list_);

    auto* buttons = new QHBoxLayout;
    add_ = new QPushButton(tr("Add"), this);
    add_->setObjectName("keys.add");
    add_->setToolTip(
        tr("A key 1 s after the last one, where that one is (Edit > Insert Key, I, keys the "
           "pose at the playhead)"));
    remove_ = new QPushButton(tr("Remove"), this);
    remove_->setObjectName("keys.remove");
    buttons->addWidget(add_);
    buttons->addWidget(remove_);
    buttons->addStretch(1);
    layout->addLayout(buttons);
    connect(add_, &QPushButton::clicked, this, &KeysEdit::addKey);
    connect(remove_, &QPushButton::clicked, this, &KeysEdit::removeCurrent);

    editor_ = new QWidget(this);
    auto* form = new QFormLayout(editor_);
    form->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(editor_);

    time_ = new PropertySpinBox;
    time_->setObjectName("keys.time");
    time_->setSuffix(" s");
    time_->setSingleStep(0.1);
    form->addRow(tr("Time"), time_);
    connect(time_, &PropertySpinBox::valueChanged, this,
            [this](double v) { edit("time", tr("Set key time"), [v](BodyKey& k) { k.time = v; }); });
    connect(time_, &PropertySpinBox::editingFinished, this, &KeysEdit::editingFinished);

    position_ = new VectorEdit("keys.position", " m");
    position_->setToolTip(tr("Where the body frame's origin is at this key (world)"));
    form->addRow(tr("Position"), position_);
    connect(position_, &VectorEdit::componentEdited, this, [this](int c, double v) {
        edit("position", tr("Set key position"), [c, v](BodyKey& k) { k.position[c] = v; });
    });
    rotation_ = new VectorEdit("keys.rotation", "°");
    rotation_->setToolTip(tr("Its orientation at this key: Euler angles about x, y, z (degrees)"));
    form->addRow(tr("Rotation"), rotation_);
    connect(rotation_, &VectorEdit::componentEdited, this, [this](int c, double v) {
        edit("orientation", tr("Set key rotation"), [c, v](BodyKey& k) {
            Vec3 degrees = quatToEulerDegrees(k.orientation);
            degrees[c] = v;
            k.orientation = eulerDegreesToQuat(degrees);
        });
    });
    for (VectorEdit* v : {position_, rotation_})
        connect(v, &VectorEdit::editingFinished, this, &KeysEdit::editingFinished);
    connect(list_, &QListWidget::currentRowChanged, this, [this] { showCurrent(); });
    showCurrent();
}

QString KeysEdit::summary(const BodyKey& k) {
    const Vec3& p = k.position;
    return tr("%1 s: (%2, %3, %4) m")
        .arg(k.time, 0, 'g', 6)
        .arg(p.x(), 0, 'g', 4)
        .arg(p.y(), 0, 'g', 4)
        .arg(p.z(), 0, 'g', 4);
}

void KeysEdit::setKeys(const std::vector<BodyKey>& keys) {
    const int row = list_->currentRow();
    keys_ = keys;
    {
        const QSignalBlocker block(list_);
        list_->clear();
        for (const BodyKey& k : keys_) list_->addItem(summary(k));
        const int n = static_cast<int>(keys_.size());
        list_->setCurrentRow(n == 0 ? -1 : std::clamp(row, 0, n - 1));
    }
    showCurrent();
}

int KeysEdit::currentIndex() const {
    return list_->currentRow();
}

void KeysEdit::setCurrentIndex(int index) {
    list_->setCurrentRow(index);
}

void KeysEdit::addKey() {
    std::vector<BodyKey> next = keys_;
    BodyKey k = next.empty() ? BodyKey{} : next.back();
    if (!next.empty()) k.time += 1.0;
    next.push_back(k);
    emit keysEdited(next, tr("Add key"), QString());
    if (keys_.size() == next.size()) setCurrentIndex(static_cast<int>(keys_.size()) - 1);
}

void KeysEdit::removeCurrent() {
    const int row = currentIndex();
    if (row < 0 || row >= static_cast<int>(keys_.size()) || keys_.size() <= 1) return;
    std::vector<BodyKey> next = keys_;
    next.erase(next.begin() + row);
    emit keysEdited(next, tr("Remove key"), QString());
}

void KeysEdit::edit(const QString& field, const QString& text, const std::function<void(BodyKey&)>& change) {
    const int row = currentIndex();
    if (row < 0 || row >= static_cast<int>(keys_.size())) return;
    std::vector<BodyKey> next = keys_;
    change(next[static_cast<size_t>(row)]);
    // In time order: a key moved past another takes its place (and stays the current one).
    const BodyKey moved = next[static_cast<size_t>(row)];
    std::stable_sort(next.begin(), next.end(),
                     [](const BodyKey& a, const BodyKey& b) { return a.time < b.time; });
    const int at = static_cast<int>(std::find(next.begin(), next.end(), moved) - next.begin());
    emit keysEdited(next, text, QStringLiteral("keys[%1].%2").arg(at).arg(field));
    if (at != row && keys_ == next) setCurrentIndex(at);
}

void KeysEdit::showCurrent() {
    const int row = currentIndex();
    const bool has = row >= 0 && row < static_cast<int>(keys_.size());
    remove_->setEnabled(has && keys_.size() > 1);
    editor_->setVisible(has);
    if (!has) return;
    const BodyKey& k = keys_[static_cast<size_t>(row)];
    time_->showValue(k.time);
    position_->showValue(k.position);
    rotation_->showValue(quatToEulerDegrees(k.orientation));
}

}  // namespace tumble::ui
