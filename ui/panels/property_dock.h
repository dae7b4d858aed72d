// The property panel: every value of the selected bodies (shape, mass, material, initial
// state, forces) with its unit. Each edit is checked with the engine's own validation
// before it reaches the document; a refused value is explained beside its field and the
// field goes back to the last good value. With several bodies selected, a field shows a
// value only where they all agree ("—" otherwise) and an edit sets it on all of them as
// one undo step.
#pragma once

#include <QDockWidget>

#include <memory>

namespace tumble::ui {

class Document;
class Timeline;

class PropertyDock : public QDockWidget {
    Q_OBJECT
public:
    PropertyDock(Document* doc, QWidget* parent = nullptr);
    ~PropertyDock() override;

    /// The message beside a field (its key, e.g. "shape.radius", "mass", "inertia"), or
    /// empty when the field has none.
    QString fieldError(const QString& field) const;

    /// Shows the selected body's state at the timeline's playhead, read-only, above the
    /// editable fields (see LiveStateBox).
    void setTimeline(Timeline* timeline);

public slots:
    /// Shows the selected bodies again (called on every document change that concerns them).
    void refresh();

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
