// Writes a recording's frames to a trajectory file (CSV, JSON, glTF, glb) in a worker
// thread, with progress and cancel. The file appears whole when every frame is written,
// or not at all (cancel, a failure): the engine's writers go through AtomicFile.
#pragma once

#include "timeline/timeline.h"

#include <tumble/io/trajectory_writer.h>

#include <QObject>
#include <QString>

#include <atomic>
#include <memory>
#include <thread>

namespace tumble::ui {

class TrajectoryExport : public QObject {
    Q_OBJECT
public:
    explicit TrajectoryExport(QObject* parent = nullptr);
    ~TrajectoryExport() override;

    /// Starts writing `file` (format by its extension) from `frames` (Timeline::frames()).
    /// Returns at once; false with the reason when it cannot start (no recording, a bad
    /// extension, options that do not fit the run, a file that cannot be opened).
    bool start(const Timeline::Frames& frames, const QString& file, const io::ExportOptions& options,
               QString* error);
    void cancel();
    bool isRunning() const { return running_; }

signals:
    void progress(int done, int total);
    /// ok: the file is in place; else `message` says why (or that it was cancelled).
    void finished(bool ok, const QString& message);

private:
    void join();

    std::thread worker_;
    std::atomic<bool> cancel_{false};
    bool running_ = false;
    int id_ = 0;
};

}  // namespace tumble::ui
