// The inertia tensor (about the centre of mass, body axes): shown as computed from the
// shape and mass, or, with the override switch on, edited as a symmetric 3x3 matrix
// (editing (i,j) also sets (j,i)). Whether a tensor is physical is the dock's check.
#pragma once

#include <tumble/math.h>

#include <QWidget>

#include <array>
#include <optional>

class QCheckBox;

namespace tumble::ui {

class PropertySpinBox;

class InertiaEdit : public QWidget {
    Q_OBJECT
public:
    /// Children: the switch `<name>.override`, the cells `<name>.<i><j>`.
    explicit InertiaEdit(const QString& name, QWidget* parent = nullptr);

    /// Row-major cells; an empty one shows "—" (the selected bodies differ).
    void showValue(const std::array<std::optional<double>, 9>& cells);
    void showValue(const Mat3& m);
    /// Checked, unchecked or partial (some selected bodies override, some do not).
    void showOverride(Qt::CheckState state);
    QCheckBox* overrideSwitch() const { return override_; }
    PropertySpinBox* cell(int i, int j) const { return cells_[static_cast<size_t>(3 * i + j)]; }
    /// Marks the matrix as held back by the panel (a red frame on every cell), or not.
    void setHeld(bool held);
    bool isHeld() const;

signals:
    void overrideToggled(bool on);
    void cellEdited(int i, int j, double value);
    void editingFinished();
    /// Esc in a cell of a held matrix: the panel shows the last valid tensor again.
    void cancelled();

private:
    QCheckBox* override_ = nullptr;
    std::array<PropertySpinBox*, 9> cells_{};
};

}  // namespace tumble::ui
