// The scene settings dock: gravity, time step, duration, integrator, frame rate, sleeping,
// solver iterations and the energy guard. Each edit is one Document::setSettings call; a scrub of one
// field merges into one undo step. A value the engine would refuse never reaches the
// document: the field shows why and keeps its last good value.
#pragma once

#include <QDockWidget>

#include <array>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSpinBox;

namespace tumble {
struct Settings;
}

namespace tumble::ui {

class Document;

class SettingsDock : public QDockWidget {
    Q_OBJECT
public:
    SettingsDock(Document* doc, QWidget* parent);

    enum Field {
        GravityX,
        GravityY,
        GravityZ,
        Step,
        Duration,
        Integrator,
        FrameRate,
        Sleeping,
        Iterations,
        EnergyGuard,
        Impacts,
        FieldCount
    };

    /// Why the last edit of `field` was refused, empty if it was not (the text shown beside it).
    QString message(Field field) const;

    /// Applies `settings`, changed in `field`, if the engine accepts them: one undo step,
    /// merged with the previous one of the same field while a scrub goes on. Otherwise the
    /// field shows the engine's reason, the document is untouched and false is returned.
    bool trySetSettings(Field field, const Settings& settings);

private:
    void edit(Field field);
    void refresh();
    void clearMessages();
    QLabel* messageLabel(Field field) const;
    QString editText(Field field) const;

    Document* doc_;
    std::array<QDoubleSpinBox*, 3> gravity_{};
    QDoubleSpinBox* step_;
    QDoubleSpinBox* duration_;
    QComboBox* integrator_;
    QDoubleSpinBox* frameRate_;
    QCheckBox* sleeping_;
    QSpinBox* iterations_;
    QCheckBox* energyGuard_;
    QComboBox* impacts_;
    QLabel* gravityMessage_;
    QLabel* stepMessage_;
    QLabel* stepNote_;  // the step used, when it is not dt
    QLabel* durationMessage_;
    QLabel* integratorMessage_;
    QLabel* frameRateMessage_;
    QLabel* sleepingMessage_;
    QLabel* iterationsMessage_;
    QLabel* energyGuardMessage_;
    QLabel* impactsMessage_;
    // A scrub merges while the field keeps the focus; finishing an edit (Enter, focus out)
    // starts a new generation, so the next change of the same field is a new undo step.
    std::array<int, FieldCount> generation_{};
};

}  // namespace tumble::ui
