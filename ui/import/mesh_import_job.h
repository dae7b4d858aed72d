// Reading mesh files for the editor without stopping it: the files are read one after the
// other on a thread of the job's own (each in the reader's child process, io::importMesh),
// while a progress dialog says which file and how long, and its Cancel kills the reader at
// once. The window keeps painting and playing meanwhile. The job adds nothing to the
// scene: it hands the meshes it read, and the errors, to whoever started it.
#pragma once

#include <tumble/mass.h>

#include <tumble/io/mesh_import.h>

#include <QElapsedTimer>
#include <QProgressDialog>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

class QTimer;
class QWidget;

namespace tumble::ui {

/// Whether `path` names one of the mesh formats Import Mesh offers and a drop accepts
/// (assimp reads more; the import dialog's "All files" reaches them).
bool isMeshFile(const QString& path);
/// The open dialog's filter for them.
QString meshFileFilter();

class MeshImportJob : public QObject {
    Q_OBJECT
public:
    struct Result {
        QString path;
        std::shared_ptr<const TriangleMesh> mesh;  ///< null when it could not be read
        QString error;                             ///< why not: the file and the reason
    };

    /// Reads `paths` with `scale` applied; the progress dialog (after a moment) is window
    /// modal over `dialogParent`.
    MeshImportJob(QStringList paths, const Vec3& scale, const io::MeshImportOptions& options,
                  QWidget* dialogParent);
    /// Cancels a read still running and waits for its thread (a tenth of a second at most).
    ~MeshImportJob() override;

    void start();
    /// Stops the reading: the file being read is abandoned, the rest not started; finished()
    /// follows with cancelled set.
    void cancel();
    bool isRunning() const { return running_; }
    bool wasCancelled() const { return cancelled_; }
    /// Per file, in the order given: what was read (complete once finished() came).
    const std::vector<Result>& results() const { return results_; }
    QProgressDialog* progressDialog() const { return dialog_.data(); }

signals:
    void finished();

private:
    void fileStarted(int index);
    void fileDone(int index, std::shared_ptr<const TriangleMesh> mesh, QString error);
    void done(bool cancelled);
    void updateLabel();

    QStringList paths_;
    Vec3 scale_;
    io::MeshImportOptions options_;
    QWidget* dialogParent_ = nullptr;
    QPointer<QProgressDialog> dialog_;  // its parent (the window) may go first
    QTimer* clock_ = nullptr;  // the label's elapsed seconds
    QElapsedTimer elapsed_;
    int current_ = 0;
    std::vector<Result> results_;
    std::atomic<bool> cancel_{false};
    std::thread worker_;
    bool running_ = false;
    bool cancelled_ = false;
};

}  // namespace tumble::ui
