// Three spin boxes (x, y, z) with a unit suffix. Each component is edited on its own,
// so a multi-selection edit of x keeps each body's own y and z.
#pragma once

#include <tumble/math.h>

#include <QWidget>

#include <array>
#include <optional>

namespace tumble::ui {

class PropertySpinBox;

class VectorEdit : public QWidget {
    Q_OBJECT
public:
    /// Child spin boxes are named `<objectName>.x`, `.y`, `.z` (set the name first, or call
    /// setObjectName later: the children follow).
    explicit VectorEdit(const QString& name, const QString& suffix, QWidget* parent = nullptr);

    /// Shows one value per component; an empty component shows "—" (the bodies differ).
    /// `base` is where stepping a "—" component starts from.
    void showValue(const std::array<std::optional<double>, 3>& v, const Vec3& base = Vec3::Zero());
    void showValue(const Vec3& v);
    /// Each component's soft minimum (PropertySpinBox::setSoftMinimum).
    void setSoftMinimum(double min);
    void setSuffix(const QString& suffix);
    void setSingleStep(double step);
    PropertySpinBox* component(int k) const { return spins_[static_cast<size_t>(k)]; }
    Vec3 value() const;
    /// Marks the field as holding a value the document refused (a red frame), or not.
    void setHeld(bool held);
    bool isHeld() const;

signals:
    void componentEdited(int k, double value);
    void editingFinished();
    /// Esc in one of the components: the edit is given up (the panel shows the last valid
    /// value again).
    void cancelled();

private:
    std::array<PropertySpinBox*, 3> spins_{};
};

}  // namespace tumble::ui
