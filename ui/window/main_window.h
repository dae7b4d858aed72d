// The editor's main window: the viewport in the centre, the scene tree, properties, scene
// settings and undo history as docks, and the File, Edit and View menus. It owns the
// document; every dock and the viewport work on the document, never on each other.
#pragma once

#include <tumble/scene.h>

#include <tumble/io/mesh_import.h>
#include <tumble/io/trajectory_writer.h>

#include "document/placement.h"
#include "window/shortcuts_dialog.h"

#include <QMainWindow>
#include <QSize>
#include <QString>
#include <QStringList>

#include <functional>
#include <memory>
#include <vector>

class QMenu;
class QTimer;

namespace tumble::ui {

class Autosave;
struct AutosaveLeftover;
class Document;
class ImageExporter;
class MeshImportJob;
class TrajectoryExport;
class SceneTreeDock;
class Timeline;
class TimelineDock;
class Viewport;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    Document* document() const { return doc_; }
    /// Every key of the window (Help > Keyboard Shortcuts): the menus' and the viewport's.
    QList<ShortcutRow> shortcuts() const;
    Viewport* viewport() const { return viewport_; }
    Timeline* timeline() const { return timeline_; }
    TimelineDock* timelineDock() const { return timelineDock_; }

    /// Loads a scene file (or a ":/scenes/..." sample). On failure returns false, keeps the
    /// current scene and puts the message (file and field) in `error`. Does not ask about
    /// unsaved changes: the menu actions do that first.
    bool openScene(const QString& path, QString* error);
    const SceneDesc& scene() const;
    /// The file or sample the scene came from ("" for a new scene).
    const QString& scenePath() const { return source_; }

    /// Imports mesh files as new bodies in front of the camera, one undo step for all of
    /// them, reading them in the background (MeshImportJob: a progress dialog with Cancel
    /// after a moment; the window keeps running). Returns at once; importFinished() follows.
    /// A file that cannot be read adds nothing; its error is in the signal, and in a
    /// message box when `tellUser`. Refused (false) while another import runs.
    bool startImport(const QStringList& paths, bool convexHull, double scale, bool tellUser = true);
    bool isImporting() const;
    void cancelImport();
    /// The import running now, or null (its progress dialog, for tests).
    MeshImportJob* importJob() const { return importJob_; }
    /// The reader's time limit and checks for the imports started from now on.
    void setMeshImportOptions(const io::MeshImportOptions& options) { importOptions_ = options; }
    /// One mesh file, as startImport, returning when it is read (the event loop turns
    /// meanwhile). On failure the scene is untouched and `error` names the file and the
    /// reason; a cancelled import returns false with an empty error.
    bool importMesh(const QString& path, bool convexHull, double scale, QString* error);

    /// Exports the recording to `target` as the dialog's options say (see ExportDialog): a
    /// trajectory file, or images / a video. Returns at once; exportFinished() follows.
    /// False with the reason when it cannot start.
    bool startExport(int kind, const QString& target, const io::ExportOptions& options,
                     const QSize& imageSize, QString* error);
    bool isExporting() const;
    void cancelExport();

    /// Writes this editor's autosave now if the scene has unsaved changes (the timer calls
    /// it every minute); removes it when there is nothing unsaved.
    void autosave();
    /// This editor's own autosave file: each running editor has one (window/autosave.h).
    QString autosavePath() const;
    /// Offers every autosave that an editor which did not end cleanly left, naming its
    /// scene, folder and time: Recover, Discard, or Later (kept, offered again next start).
    void offerRecovery();
    /// Recovers `leftover` as what it was: its own file (undo goes back to the file as on
    /// disk) or untitled, unsaved. In this window only if nothing here would be lost or
    /// mixed (no unsaved work, and untitled or that very file); else in a new editor
    /// (startEditor with --recover). False with the reason when it cannot.
    bool recover(const AutosaveLeftover& leftover, QString* error);
    /// recover() of the newest leftover; false when there is none or it cannot be read.
    bool recoverAutosave(QString* error);
    /// Opens the autosave `file` in this window as what it was (`tumble --recover FILE`).
    bool recoverFile(const QString& file, QString* error);
    /// Starts another editor with these arguments (tests replace it).
    std::function<bool(const QStringList&)> startEditor;

    /// The sample scene opened when no scene is given.
    static QString defaultScenePath();

signals:
    void exportFinished(bool ok, const QString& message);
    /// An import ended: `added` bodies were added; `errors` has a line per file that could
    /// not be read (empty if none); nothing was added if it was cancelled.
    void importFinished(int added, const QString& errors, bool cancelled);

protected:
    void closeEvent(QCloseEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void buildMenus();
    void showShortcuts();
    void updateTitle();
    /// The file name of the scene, or of the sample it came from, or "untitled".
    QString sceneName() const;
    bool maybeSave();  // false: the user cancelled
    void newScene();
    void openDialog();
    bool save();
    bool saveAsDialog();
    /// After a save: says which mesh files are gone or changed on disk since they were read.
    void warnOfChangedMeshes();
    /// A scene file to save to, asked for (empty: cancelled); ".json" added when none is typed.
    QString askSceneFile(const QString& title);
    void revert();
    // File > Import Mesh, drops and the import job (ui/window/main_window_import.cpp).
    void importDialog();
    void importDone();
    // File > Export and Save with Meshes (ui/window/main_window_export.cpp).
    void exportDialog();
    bool saveWithMeshesDialog();
    void addRecent(const QString& path);
    void fillRecentMenu();
    void openPath(const QString& path);
    /// Keys the one selected body's pose at the playhead (Edit > Insert Key, I in the
    /// viewport): at frame 0 the pose it is placed at, later the recorded one.
    void insertKey();
    // Building (ui/window/main_window_build.cpp): the Scene menu, Copy and Paste.
    void buildSceneMenu(QMenu* edit);
    /// View > Front / Back / Right / Left / Top / Bottom: the camera turned to look along an
    /// axis at the same target and distance (numpad 1, 3, 7 and with Ctrl the opposite, as
    /// in Blender; the plain digits too, for keyboards without a numpad).
    void addStandardViews(QMenu* view);
    /// Where the view looks on the scene's surfaces: the first hit of the ray through the
    /// view's centre, else the camera's target; the body hit (-1: none or a plane).
    Vec3 viewPoint(int* hitBody = nullptr) const;
    /// `body` set down resting on the surface under the view's centre (placement.h
    /// setDownAt); on another body, centred on it (adds in a row stack up). Set down in
    /// `scene` when given (the document's and the bodies about to be added with it).
    BodyDesc setDownUnderView(BodyDesc body, const SceneDesc* scene = nullptr) const;
    void dropSelection();
    void copySelection();
    void pasteBodies();
    void arrayDialog();
    void layoutDialog(Layout kind);
    /// New bodies in one undo step called `text`, then selected.
    void addBodies(const std::vector<BodyDesc>& bodies, const QString& text);
    SceneDesc copied_;      // the last Copy, with its meshes' triangles
    QString copiedText_;    // ... and the text it put on the clipboard

    Document* doc_ = nullptr;
    Timeline* timeline_ = nullptr;
    Viewport* viewport_ = nullptr;
    SceneTreeDock* tree_ = nullptr;
    TimelineDock* timelineDock_ = nullptr;
    QString source_;
    QMenu* recentMenu_ = nullptr;
    QTimer* autosaveTimer_ = nullptr;
    std::unique_ptr<Autosave> autosave_;
    QString autosaveFailure_;  // the status bar's message while autosaves fail
    bool recoverHere(const AutosaveLeftover& leftover, QString* error);
    TrajectoryExport* trajectoryExport_ = nullptr;
    ImageExporter* imageExport_ = nullptr;
    MeshImportJob* importJob_ = nullptr;
    io::MeshImportOptions importOptions_;
    struct ImportRequest {
        bool convexHull = true;
        double scale = 1.0;
        bool tellUser = true;
        bool ask = false;  // Import Mesh: the options are chosen with the mesh read (scale 1)
    } importRequest_;
};

}  // namespace tumble::ui
