// The applied forces, torques and springs of one body: a list to add to and remove from,
// and an editor for the current entry. Every change is offered to the owner as the whole
// new list (forcesEdited); the owner validates it, and either stores it in the document
// or puts the old list back with setForces.
#pragma once

#include <tumble/scene.h>

#include <QWidget>

#include <functional>
#include <optional>

#include <vector>

class QCheckBox;
class QComboBox;
class QFormLayout;
class QLabel;
class QListWidget;
class QPushButton;

namespace tumble::ui {

class PropertySpinBox;
class VectorEdit;

class ForcesEdit : public QWidget {
    Q_OBJECT
public:
    explicit ForcesEdit(QWidget* parent = nullptr);

    /// Shows `forces` (signals blocked), keeping the current entry when it still exists.
    void setForces(const std::vector<ForceDesc>& forces);
    const std::vector<ForceDesc>& forces() const { return forces_; }
    int currentIndex() const;
    void setCurrentIndex(int index);

    /// What the Add menu and the Remove button do.
    void addForce(ForceType type);
    void removeCurrent();

signals:
    /// The list the user asked for. `field` names what changed, e.g. "forces[1].stiffness";
    /// the same field edited again in a row is one undo step.
    void forcesEdited(const std::vector<ForceDesc>& forces, const QString& text, const QString& field);
    void editingFinished();

private:
    void showCurrent();
    void edit(const QString& field, const QString& text, const std::function<void(ForceDesc&)>& change);
    // The start and end times are one value: a change that would put the end at or before
    // the start is held (both fields framed red, a line saying why) and tried again with
    // the next change of either, until the window is valid or Esc gives it up.
    void editWindow(const QString& field, const QString& text, const std::function<void(ForceDesc&)>& change);
    static QString summary(const ForceDesc& f);

    std::vector<ForceDesc> forces_;
    QListWidget* list_ = nullptr;
    QPushButton* add_ = nullptr;
    QPushButton* remove_ = nullptr;
    QWidget* editor_ = nullptr;
    QFormLayout* form_ = nullptr;
    QComboBox* type_ = nullptr;
    QComboBox* frame_ = nullptr;
    VectorEdit* vector_ = nullptr;
    QCheckBox* pointOn_ = nullptr;
    VectorEdit* point_ = nullptr;
    VectorEdit* anchor_ = nullptr;
    PropertySpinBox* stiffness_ = nullptr;
    PropertySpinBox* restLength_ = nullptr;
    PropertySpinBox* damping_ = nullptr;
    QCheckBox* startOn_ = nullptr;
    PropertySpinBox* start_ = nullptr;
    QCheckBox* endOn_ = nullptr;
    PropertySpinBox* end_ = nullptr;
    QWidget* pointRow_ = nullptr;
    QWidget* startRow_ = nullptr;
    QWidget* endRow_ = nullptr;
    QLabel* windowError_ = nullptr;
    struct HeldWindow {
        int row = -1;
        std::optional<double> start, end;
    };
    std::optional<HeldWindow> heldWindow_;
};

}  // namespace tumble::ui
