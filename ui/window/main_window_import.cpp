// File > Import Mesh, dropped meshes and the import job behind both (MeshImportJob): the
// files are read in the background and added together, as one undo step, when the last
// one is read.
#include "window/main_window.h"

#include "document/document.h"
#include "import/mesh_import_job.h"
#include "viewport/viewport.h"

#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QEventLoop>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QMessageBox>
#include <QStatusBar>

#include <algorithm>

namespace tumble::ui {

bool MainWindow::startImport(const QStringList& paths, bool convexHull, double scale, bool tellUser) {
    if (importJob_ || paths.isEmpty()) return false;
    importRequest_ = {convexHull, scale, tellUser};
    importJob_ = new MeshImportJob(paths, Vec3::Constant(scale), importOptions_, this);
    connect(importJob_, &MeshImportJob::finished, this, &MainWindow::importDone);
    importJob_->start();
    statusBar()->showMessage(tr("Importing %n mesh(es)...", nullptr, static_cast<int>(paths.size())));
    return true;
}

bool MainWindow::isImporting() const {
    return importJob_ && importJob_->isRunning();
}

void MainWindow::cancelImport() {
    if (importJob_) importJob_->cancel();
}

// The meshes read become bodies in front of the camera; the document holds their files as
// absolute paths (a save writes them relative to the scene's folder).
void MainWindow::importDone() {
    MeshImportJob* job = importJob_;
    importJob_ = nullptr;
    job->deleteLater();
    if (job->wasCancelled()) {
        statusBar()->showMessage(tr("Import cancelled"), 3000);
        emit importFinished(0, QString(), true);
        return;
    }
    QStringList errors;
    std::vector<BodyDesc> bodies;
    for (const MeshImportJob::Result& r : job->results()) {
        if (!r.mesh) {
            errors << r.error;
            continue;
        }
        BodyDesc body;
        body.shape.type = ShapeType::Mesh;
        body.shape.scale = Vec3::Constant(importRequest_.scale);
        body.shape.collision = importRequest_.convexHull ? MeshCollision::ConvexHull : MeshCollision::Triangles;
        body.shape.meshData = r.mesh;
        body.shape.file = QFileInfo(r.path).absoluteFilePath().toStdString();
        body.name = QFileInfo(r.path).completeBaseName().toStdString();
        body.density = 1000.0;
        body.mass.reset();
        const QVector3D at = viewport_->cameraTarget();
        body.position = Vec3(at.x(), std::max(static_cast<double>(at.y()), 1.0), at.z());
        bodies.push_back(std::move(body));
    }
    QList<int> added;
    if (bodies.size() > 1) doc_->beginMacro(tr("Import %1 Meshes").arg(bodies.size()));
    for (const BodyDesc& b : bodies) added << doc_->addBody(b);
    if (bodies.size() > 1) doc_->endMacro();
    if (!added.isEmpty()) doc_->setSelection(added);
    statusBar()->showMessage(tr("Imported %n mesh(es)", nullptr, static_cast<int>(added.size())), 3000);
    const QString message = errors.join("\n\n");
    if (!errors.isEmpty() && importRequest_.tellUser) QMessageBox::warning(this, tr("Import mesh"), message);
    emit importFinished(static_cast<int>(added.size()), message, false);
}

bool MainWindow::importMesh(const QString& path, bool convexHull, double scale, QString* error) {
    if (!startImport({path}, convexHull, scale, false)) {
        if (error) *error = tr("Another import is running");
        return false;
    }
    int added = 0;
    QString errors;
    QEventLoop loop;
    connect(this, &MainWindow::importFinished, &loop, [&](int n, const QString& e, bool) {
        added = n;
        errors = e;
        loop.quit();
    });
    loop.exec();
    if (error) *error = errors;
    return added == 1;
}

void MainWindow::importDialog() {
    if (importJob_) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Import mesh"), QString(), meshFileFilter());
    if (path.isEmpty()) return;
    QDialog dialog(this);
    dialog.setWindowTitle(tr("Import %1").arg(QFileInfo(path).fileName()));
    auto* form = new QFormLayout(&dialog);
    auto* collision = new QComboBox(&dialog);
    collision->addItems({tr("Convex hull"), tr("Triangles (concave allowed)")});
    auto* scale = new QDoubleSpinBox(&dialog);
    scale->setRange(1e-6, 1e6);
    scale->setDecimals(6);
    scale->setValue(1.0);
    form->addRow(tr("Collision"), collision);
    form->addRow(tr("Scale"), scale);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dialog);
    form->addRow(buttons);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    if (dialog.exec() != QDialog::Accepted) return;
    startImport({path}, collision->currentIndex() == 0, scale->value());
}

}  // namespace tumble::ui
