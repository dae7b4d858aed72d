#include "export/trajectory_export.h"

#include <QFileInfo>

#include <chrono>

namespace tumble::ui {

TrajectoryExport::TrajectoryExport(QObject* parent) : QObject(parent) {}

TrajectoryExport::~TrajectoryExport() {
    cancel_ = true;
    join();
}

void TrajectoryExport::join() {
    if (worker_.joinable()) worker_.join();
}

void TrajectoryExport::cancel() {
    cancel_ = true;
}

bool TrajectoryExport::start(const Timeline::Frames& frames, const QString& file,
                             const io::ExportOptions& options, QString* error) {
    if (running_) {
        if (error) *error = tr("An export is already running");
        return false;
    }
    if (!frames.model || !frames.read) {
        if (error) *error = tr("Nothing is recorded yet: simulate the scene first");
        return false;
    }
    join();
    std::shared_ptr<io::TrajectoryWriter> writer;
    auto data = std::make_shared<Timeline::Frames>(frames);
    try {
        writer = io::makeTrajectoryWriter(file.toStdString(), options);
        writer->begin(*data->model, data->scene, data->frameCount, data->frameRate);
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    cancel_ = false;
    running_ = true;
    const int id = ++id_;
    worker_ = std::thread([this, writer, data, id, file] {
        bool ok = true;
        QString message;
        const int total = writer->selectedFrameCount();
        int done = 0;
        auto last = std::chrono::steady_clock::now();
        try {
            State state;
            for (int k = 0; k < data->frameCount && !cancel_; ++k) {
                if (!writer->selected(k)) continue;
                if (!data->read(k, &state))
                    throw std::runtime_error(tr("frame %1 is not recorded").arg(k).toStdString());
                writer->frame(k, state);
                ++done;
                const auto now = std::chrono::steady_clock::now();
                if (now - last > std::chrono::milliseconds(50)) {
                    last = now;
                    QMetaObject::invokeMethod(
                        this, [this, done, total] { emit progress(done, total); }, Qt::QueuedConnection);
                }
            }
            if (cancel_) {
                ok = false;
                message = tr("Export cancelled: %1 was not written").arg(QFileInfo(file).fileName());
            } else {
                writer->finish();
                message = tr("Exported %1 frames to %2").arg(total).arg(file);
            }
        } catch (const std::exception& e) {
            ok = false;
            message = QString::fromStdString(e.what());
        }
        // The writer's destructor removes what an unfinished export wrote.
        QMetaObject::invokeMethod(
            this,
            [this, ok, message, done, total, id] {
                if (id != id_) return;
                running_ = false;
                join();
                emit progress(done, total);
                emit finished(ok, message);
            },
            Qt::QueuedConnection);
    });
    return true;
}

}  // namespace tumble::ui
