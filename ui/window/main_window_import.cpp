// File > Import Mesh, dropped meshes and the import job behind both (MeshImportJob): the
// files are read in the background and added together, as one undo step, when the last
// one is read.
#include "window/main_window.h"

#include "document/body_presets.h"
#include "document/document.h"
#include "import/convex_split_dialog.h"
#include "import/import_options_dialog.h"
#include "import/mesh_import_job.h"
#include "viewport/viewport.h"

#include <QEventLoop>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QStatusBar>

#include <algorithm>

namespace tumble::ui {

bool MainWindow::startImport(const QStringList& paths, bool convexHull, double scale, bool tellUser) {
    if (importJob_ || paths.isEmpty()) return false;
    importRequest_ = {convexHull, scale, tellUser, false};
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

// The meshes read become bodies where the camera looks, dropped above the scene's bodies
// (and each other: several files are stacked), as the Add menu places a new body; the
// document holds their files as absolute paths (a save writes them relative to the scene's
// folder). From Import Mesh, the options dialog comes first, with the mesh read.
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
    std::vector<bool> split;             // per body: convex parts asked for
    constexpr double kDensity = 1000.0;  // water's, until the user gives another
    SceneDesc scratch = doc_->scene();  // and the meshes set down so far
    for (const MeshImportJob::Result& r : job->results()) {
        if (!r.mesh) {
            errors << r.error;
            continue;
        }
        double scale = importRequest_.scale;
        MeshCollision collision =
            importRequest_.convexHull ? MeshCollision::ConvexHull : MeshCollision::Triangles;
        std::shared_ptr<const TriangleMesh> mesh = r.mesh;
        if (importRequest_.ask) {
            ImportOptionsDialog options(QFileInfo(r.path).fileName(), r.mesh, kDensity, this);
            if (options.exec() != QDialog::Accepted) {
                statusBar()->showMessage(tr("Import cancelled"), 3000);
                emit importFinished(0, QString(), true);
                return;
            }
            scale = options.scale();
            collision = options.collision();
            if (scale != 1.0) {  // read at scale 1: the vertices take the chosen one
                auto scaled = std::make_shared<TriangleMesh>(*r.mesh);
                for (Vec3& v : scaled->vertices) v *= scale;
                mesh = std::move(scaled);
            }
        }
        BodyDesc body;
        body.shape.type = ShapeType::Mesh;
        body.shape.scale = Vec3::Constant(scale);
        // Convex parts are made after the body is in, in their own dialog (in the background,
        // seen before they are applied); until then, and if that is cancelled, its hull.
        split.push_back(collision == MeshCollision::ConvexParts);
        body.shape.collision =
            collision == MeshCollision::ConvexParts ? MeshCollision::ConvexHull : collision;
        body.shape.meshData = mesh;
        body.shape.file = QFileInfo(r.path).absoluteFilePath().toStdString();
        body.name = QFileInfo(r.path).completeBaseName().toStdString();
        body.density = kDensity;
        body.mass.reset();
        // Set down on the surface under the view's centre, as Add does; several, one on
        // another.
        body = setDownUnderView(std::move(body), &scratch);
        scratch.bodies.push_back(body);
        bodies.push_back(std::move(body));
    }
    QList<int> added;
    if (bodies.size() > 1) doc_->beginMacro(tr("Import %1 Meshes").arg(bodies.size()));
    for (const BodyDesc& b : bodies) added << doc_->addBody(b);
    if (bodies.size() > 1) doc_->endMacro();
    if (!added.isEmpty()) doc_->setSelection(added);
    for (int k = 0; k < static_cast<int>(added.size()); ++k) {
        if (!split[static_cast<size_t>(k)]) continue;
        ConvexSplitDialog dialog(doc_, added[k], this);
        dialog.exec();
    }
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
    // Read first (at scale 1), then the options with the mesh's size and mass (importDone).
    if (startImport({path}, true, 1.0)) importRequest_.ask = true;
}

}  // namespace tumble::ui
