// The Scene menu's dialogs: Array (copies of the selection along up to three offsets, a line
// or a grid) and Make Stack / Pyramid / Wall (a layout of boxes, placement.h). Each shows how
// many bodies it will add and refuses more than placement.h's kMostLaidOut.
#pragma once

#include "document/placement.h"

#include <QDialog>

#include <array>

class QCheckBox;
class QDialogButtonBox;
class QDoubleSpinBox;
class QLabel;
class QSpinBox;

namespace tumble::ui {

class ArrayDialog : public QDialog {
    Q_OBJECT
public:
    /// `size`: the selection's size along the world axes (the default offsets: a copy beside
    /// the last, 0.1 m apart); `bodies`: how many are selected.
    ArrayDialog(const Vec3& size, int bodies, QWidget* parent);
    std::array<int, 3> counts() const;
    std::array<Vec3, 3> steps() const;

private:
    void update();
    int bodies_;
    std::array<QSpinBox*, 3> count_{};
    std::array<std::array<QDoubleSpinBox*, 3>, 3> step_{};
    QLabel* total_;
    QDialogButtonBox* buttons_;
};

class LayoutDialog : public QDialog {
    Q_OBJECT
public:
    LayoutDialog(Layout kind, QWidget* parent);
    LayoutSpec spec() const;
    double mass() const;

private:
    void update();
    Layout kind_;
    QSpinBox* count_;
    QSpinBox* rows_ = nullptr;
    QCheckBox* option_ = nullptr;  // Pyramid: square layers; Wall: staggered rows
    std::array<QDoubleSpinBox*, 3> size_{};
    QDoubleSpinBox* gap_;
    QDoubleSpinBox* mass_;
    QLabel* total_;
    QDialogButtonBox* buttons_;
};

}  // namespace tumble::ui
