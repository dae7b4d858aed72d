#include "import/mesh_import_job.h"

#include <QFileInfo>
#include <QProgressDialog>
#include <QTimer>

namespace tumble::ui {

namespace {

constexpr int kShowAfterMs = 400;  // a quick import never flashes a dialog

const char* const kMeshExtensions[] = {"obj", "stl", "ply", "off", "gltf", "glb", "fbx", "dae", "3ds", "blend"};

}  // namespace

bool isMeshFile(const QString& path) {
    const QString suffix = QFileInfo(path).suffix().toLower();
    for (const char* e : kMeshExtensions)
        if (suffix == QLatin1String(e)) return true;
    return false;
}

QString meshFileFilter() {
    QStringList patterns;
    for (const char* e : kMeshExtensions) patterns << QStringLiteral("*.%1").arg(e);
    return QObject::tr("Meshes (%1);;All files (*)").arg(patterns.join(' '));
}

MeshImportJob::MeshImportJob(QStringList paths, const Vec3& scale, const io::MeshImportOptions& options,
                             QWidget* dialogParent)
    : paths_(std::move(paths)), scale_(scale), options_(options), dialogParent_(dialogParent) {
    results_.resize(static_cast<std::size_t>(paths_.size()));
    for (int i = 0; i < paths_.size(); ++i) results_[static_cast<std::size_t>(i)].path = paths_[i];
}

MeshImportJob::~MeshImportJob() {
    cancel_ = true;
    if (worker_.joinable()) worker_.join();
    delete dialog_;
}

void MeshImportJob::start() {
    if (running_ || worker_.joinable()) return;
    running_ = true;
    elapsed_.start();
    // One file: a busy bar (assimp says nothing of its progress); several: the files done.
    const int files = static_cast<int>(paths_.size());
    dialog_ = new QProgressDialog(dialogParent_);
    dialog_->setWindowTitle(tr("Import mesh"));
    dialog_->setRange(0, files > 1 ? files : 0);
    dialog_->setWindowModality(Qt::WindowModal);
    dialog_->setMinimumDuration(kShowAfterMs);
    dialog_->setAutoClose(false);
    dialog_->setAutoReset(false);
    connect(dialog_, &QProgressDialog::canceled, this, &MeshImportJob::cancel);
    clock_ = new QTimer(this);
    clock_->setInterval(500);
    connect(clock_, &QTimer::timeout, this, &MeshImportJob::updateLabel);
    clock_->start();
    updateLabel();
    dialog_->setValue(0);

    io::MeshImportOptions options = options_;
    options.cancel = &cancel_;
    // The thread reports through queued calls on this object: they run on the GUI thread,
    // and Qt drops those still queued when the object goes (the destructor joins the
    // thread first).
    worker_ = std::thread([this, options, paths = paths_, scale = scale_] {
        bool cancelled = false;
        for (int i = 0; i < paths.size() && !cancelled; ++i) {
            QMetaObject::invokeMethod(this, [this, i] { fileStarted(i); }, Qt::QueuedConnection);
            std::shared_ptr<const TriangleMesh> mesh;
            QString error;
            try {
                mesh = std::make_shared<const TriangleMesh>(io::importMesh(paths[i].toStdString(), scale, options));
            } catch (const io::MeshImportCancelled&) {
                cancelled = true;
            } catch (const std::exception& e) {
                error = QString::fromStdString(e.what());
            }
            if (cancel_) cancelled = true;
            if (!cancelled)
                QMetaObject::invokeMethod(
                    this, [this, i, mesh, error] { fileDone(i, mesh, error); }, Qt::QueuedConnection);
        }
        QMetaObject::invokeMethod(this, [this, cancelled] { done(cancelled); }, Qt::QueuedConnection);
    });
}

void MeshImportJob::cancel() {
    if (!running_) return;
    cancel_ = true;
    if (dialog_) dialog_->setLabelText(tr("Cancelling..."));
}

void MeshImportJob::fileStarted(int index) {
    current_ = index;
    updateLabel();
}

void MeshImportJob::fileDone(int index, std::shared_ptr<const TriangleMesh> mesh, QString error) {
    Result& r = results_[static_cast<std::size_t>(index)];
    r.mesh = std::move(mesh);
    r.error = std::move(error);
    if (dialog_ && paths_.size() > 1) dialog_->setValue(index + 1);
}

void MeshImportJob::done(bool cancelled) {
    if (worker_.joinable()) worker_.join();  // it has nothing left to do but return
    running_ = false;
    cancelled_ = cancelled;
    clock_->stop();
    if (dialog_) {
        dialog_->reset();  // stops its timer to show itself: hidden alone, it came up later
        dialog_->hide();   // (over the import's options dialog, which runs before it is deleted)
        dialog_->deleteLater();
        dialog_ = nullptr;
    }
    emit finished();
}

void MeshImportJob::updateLabel() {
    if (!dialog_ || cancel_) return;
    const QString name = QFileInfo(paths_.value(current_)).fileName();
    const qint64 seconds = elapsed_.elapsed() / 1000;
    QString text = paths_.size() > 1 ? tr("Reading %1 (%2 of %3)").arg(name).arg(current_ + 1).arg(paths_.size())
                                     : tr("Reading %1").arg(name);
    if (seconds > 0) text += tr(", %1 s").arg(seconds);
    dialog_->setLabelText(text);
}

}  // namespace tumble::ui
