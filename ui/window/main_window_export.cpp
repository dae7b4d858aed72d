// The main window's File > Export and File > Save with Meshes: the dialogs, the progress
// and the cancel. The writing itself is TrajectoryExport's (a worker thread) or
// ImageExporter's (frames drawn by a viewport of the chosen size).
#include "document/document.h"
#include "export/export_dialog.h"
#include "export/image_exporter.h"
#include "window/main_window.h"

#include "export/trajectory_export.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"
#include "window/autosave.h"

#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QProgressDialog>
#include <QStatusBar>

namespace tumble::ui {

bool MainWindow::isExporting() const {
    return (trajectoryExport_ && trajectoryExport_->isRunning()) ||
           (imageExport_ && imageExport_->isRunning());
}

void MainWindow::cancelExport() {
    if (trajectoryExport_) trajectoryExport_->cancel();
    if (imageExport_ && imageExport_->isRunning()) imageExport_->cancel();
}

bool MainWindow::startExport(int kindValue, const QString& target, const io::ExportOptions& options,
                             const QSize& imageSize, QString* error) {
    if (isExporting()) {
        if (error) *error = tr("An export is already running");
        return false;
    }
    const auto kind = static_cast<ExportDialog::Kind>(kindValue);
    if (kind == ExportDialog::Kind::Images || kind == ExportDialog::Kind::Video) {
        if (!imageExport_) {
            imageExport_ = new ImageExporter(viewport_, timeline_, this);
            connect(imageExport_, &ImageExporter::finished, this, &MainWindow::exportFinished);
        }
        ImageExportOptions o;
        o.size = imageSize;
        o.firstFrame = options.firstFrame;
        o.lastFrame = options.lastFrame;
        o.frameStep = options.frameStep;
        if (kind == ExportDialog::Kind::Video) {
            // The video's frames are kept in a folder beside it, named after it.
            const QFileInfo video(target);
            o.video = true;
            o.videoFile = target;
            o.folder = video.dir().filePath(video.completeBaseName() + QStringLiteral("-frames"));
        } else {
            o.folder = target;
        }
        imageExport_->start(o);
        return true;
    }
    if (!trajectoryExport_) {
        trajectoryExport_ = new TrajectoryExport(this);
        connect(trajectoryExport_, &TrajectoryExport::finished, this, &MainWindow::exportFinished);
    }
    return trajectoryExport_->start(timeline_->frames(), target, options, error);
}

void MainWindow::exportDialog() {
    const Timeline::Status status = timeline_->status();
    if (timeline_->isStale() || status == Timeline::Status::Running || timeline_->framesDone() == 0) {
        QMessageBox::information(
            this, tr("Export"),
            timeline_->framesDone() == 0
                ? tr("Nothing is recorded yet: simulate the scene first (Simulation > Simulate).")
                : tr("The simulation is still running or the scene was edited since: wait until "
                     "the timeline says Done (or Cancel it to export the frames made so far)."));
        return;
    }
    QStringList names;
    for (const BodyDesc& b : timeline_->frames().scene.bodies) names << QString::fromStdString(b.name);
    // (The file's path when the scene has one: the export then starts beside it.)
    const QString scene = doc_->filePath().isEmpty() ? sceneName() : doc_->filePath();
    ExportDialog dialog(names, timeline_->framesDone(), timeline_->frameRate(), scene, this);
    dialog.setHasJoints(!timeline_->frames().scene.joints.empty());
    if (dialog.exec() != QDialog::Accepted) return;

    auto* progress = new QProgressDialog(tr("Exporting to %1...").arg(QFileInfo(dialog.target()).fileName()),
                                         tr("Cancel"), 0, 100, this);
    progress->setWindowModality(Qt::WindowModal);
    progress->setMinimumDuration(300);
    progress->setAutoClose(false);
    progress->setAutoReset(false);
    auto onProgress = [progress](int done, int total) {
        progress->setMaximum(std::max(1, total));
        progress->setValue(done);
    };
    QList<QMetaObject::Connection> links;
    connect(progress, &QProgressDialog::canceled, this, &MainWindow::cancelExport);
    QString error;
    if (!startExport(int(dialog.kind()), dialog.target(), dialog.options(), dialog.imageSize(), &error)) {
        progress->deleteLater();
        QMessageBox::warning(this, tr("Export"), error);
        return;
    }
    if (trajectoryExport_)
        links << connect(trajectoryExport_, &TrajectoryExport::progress, progress, onProgress);
    if (imageExport_) links << connect(imageExport_, &ImageExporter::progress, progress, onProgress);
    auto done = std::make_shared<QMetaObject::Connection>();
    *done = connect(this, &MainWindow::exportFinished, this,
                    [this, progress, links, done](bool ok, const QString& m) {
                        for (const auto& l : links) disconnect(l);
                        disconnect(*done);
                        progress->deleteLater();
                        if (ok)
                            statusBar()->showMessage(m, 8000);
                        else if (m.contains(tr("cancelled"), Qt::CaseInsensitive))
                            statusBar()->showMessage(m, 8000);
                        else
                            QMessageBox::warning(this, tr("Export"), m);
                    });
}

bool MainWindow::saveWithMeshesDialog() {
    const QString path = askSceneFile(tr("Save scene with its meshes"));
    if (path.isEmpty()) return false;
    QString error;
    if (!doc_->saveWithMeshes(path, &error)) {
        QMessageBox::warning(this, tr("Save with meshes"), error);
        return false;
    }
    source_ = path;
    addRecent(path);
    autosave_->remove();
    updateTitle();
    statusBar()->showMessage(
        tr("Saved %1 with its meshes in %2-meshes/").arg(path, QFileInfo(path).completeBaseName()), 5000);
    return true;
}

}  // namespace tumble::ui
