// Split into Convex Parts (issue 49 item 4): a mesh body's split made in the background with
// its progress, shown as a picture of the parts in colours with the figures that judge it
// (parts, volume over the mesh's, how far a part reaches out, time), and applied to the body
// (its collision becomes "convex-parts" with those parts: one undo step, nothing made again).
// Max parts and the tolerance can be changed and the split made again; Cancel stops it.
#pragma once

#include <tumble/convex_parts.h>
#include <tumble/scene.h>

#include <QDialog>

#include <atomic>
#include <memory>

class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QThread;
class QTimer;

namespace tumble::ui {

class ConvexPartsPreview;
class Document;

class ConvexSplitDialog : public QDialog {
    Q_OBJECT
public:
    /// For body `body` of `doc`, a mesh with its triangles loaded; the split starts at once
    /// with the body's max parts and tolerance.
    ConvexSplitDialog(Document* doc, int body, QWidget* parent = nullptr);
    ~ConvexSplitDialog() override;

    /// Starts the split again with the options in the fields (stopping one under way).
    void split();
    bool running() const { return thread_ != nullptr; }
    /// The last split made, or none (running, failed, or stopped).
    std::shared_ptr<const mesh::ConvexParts> result() const { return result_; }
    /// What the dialog says under the picture (the figures, or why there are none).
    QString status() const;
    ConvexPartsPreview* preview() const { return preview_; }
    QSpinBox* maxPartsField() const { return maxParts_; }
    QDoubleSpinBox* toleranceField() const { return tolerance_; }
    /// Applies the result to the body (one undo step) and closes; does nothing without one.
    void apply();

private:
    void finished();
    void stop();
    void join();  // waits for the splitting thread and lets it go

    Document* doc_;
    int body_;
    ShapeDesc shape_;  // the body's mesh shape as the dialog opened
    QSpinBox* maxParts_;
    QDoubleSpinBox* tolerance_;
    QPushButton* splitButton_;
    QPushButton* applyButton_;
    QProgressBar* progress_;
    QLabel* status_;
    ConvexPartsPreview* preview_;
    QTimer* poll_;
    QThread* thread_ = nullptr;
    // Shared with the splitting thread: its progress (per mille), the stop request, and what
    // it made or why it failed (read once the thread has finished).
    struct Job {
        std::atomic<int> permille{0};
        std::atomic<bool> stop{false};
        std::shared_ptr<const mesh::ConvexParts> parts;
        std::string error;
        bool stopped = false;
    };
    std::shared_ptr<Job> job_;
    std::shared_ptr<const mesh::ConvexParts> result_;
};

}  // namespace tumble::ui
