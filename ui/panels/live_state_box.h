// The selected body's state at the timeline's playhead, read-only, in the property panel:
// position, orientation, velocity, angular velocity and kinetic energy, with the time and
// frame they belong to. What the user sees at frame k is snapshot k's values, not the
// initial state above it in the panel.
#pragma once

#include <QGroupBox>

class QFormLayout;
class QLabel;

namespace tumble::ui {

class Document;
class Timeline;

class LiveStateBox : public QGroupBox {
    Q_OBJECT
public:
    LiveStateBox(Document* document, Timeline* timeline, QWidget* parent = nullptr);

    /// The text of a row: "position", "orientation", "velocity", "angular_velocity",
    /// "kinetic_energy", "frame", "sleeping".
    QString valueText(const QString& row) const;

public slots:
    void refresh();

private:
    QLabel* addRow(QFormLayout* form, const QString& label, const QString& name);

    Document* doc_;
    Timeline* timeline_;
    QLabel* frame_;
    QLabel* position_;
    QLabel* orientation_;
    QLabel* velocity_;
    QLabel* omega_;
    QLabel* kinetic_;
    QLabel* sleeping_;
};

}  // namespace tumble::ui
