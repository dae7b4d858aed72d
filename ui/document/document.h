// The scene document: the SceneDesc the editor edits, its file, its undo stack and the
// selection. Every change goes through an undo command on the one QUndoStack (principle 8
// of DESIGN.md): panels, the scene tree and the viewport never write the scene directly.
//
// Edits are whole-value replacements (a body, the settings), which keeps every command the
// same small shape: "before" and "after". Consecutive edits with the same merge id (a drag,
// a spin-box scrub) merge into one undo step; compound edits are macros.
#pragma once

#include <tumble/scene.h>

#include <QDateTime>
#include <QHash>
#include <QList>
#include <QObject>
#include <QString>
#include <QStringList>

class QUndoStack;

namespace tumble::ui {

class Document : public QObject {
    Q_OBJECT
public:
    explicit Document(QObject* parent = nullptr);
    ~Document() override;

    const SceneDesc& scene() const { return scene_; }
    int bodyCount() const { return static_cast<int>(scene_.bodies.size()); }
    const BodyDesc& body(int index) const { return scene_.bodies.at(static_cast<size_t>(index)); }
    QUndoStack* undoStack() const { return undo_; }

    // ---- Files. Messages name the file and, for bad content, the field.

    /// An empty scene (default settings and a ground plane), no file, nothing to undo.
    void newScene();
    /// Reads a scene file, or a ":/scenes/..." sample (which then has no file: Save asks).
    /// On failure the current scene is untouched and `error` says why. Opening a file also
    /// removes the temporaries that saves of it killed mid-way left beside it
    /// (io::removeStaleTemporaries: their process gone, older than a minute).
    bool open(const QString& path, QString* error);
    /// What the last open() could not load but opened without: each mesh file that could not
    /// be read ("FILE: bodies[i].shape.file: MESH: reason"). Those bodies have no meshData.
    const QStringList& openWarnings() const { return openWarnings_; }
    /// Writes the scene atomically (io::AtomicFile) to `path` and makes it the document's file;
    /// on failure (no such folder, no permission) the file on disk is as it was and `error`
    /// names it.
    /// Mesh files are written relative to the new file's folder (in the document they are
    /// absolute paths), so a Save As to another folder keeps them reachable.
    bool saveAs(const QString& path, QString* error);
    /// Saves like saveAs, and copies every mesh file the scene uses into a folder beside it
    /// (<scene name>-meshes/), the scene referring to the copies: the folder and the scene
    /// travel together. Nothing is left half written: every copy and the scene are written
    /// out before any replaces its old file. Refused, naming the body and the file, when a
    /// mesh file is gone or changed on disk since it was loaded (a copy would not be the
    /// mesh the scene shows).
    bool saveWithMeshes(const QString& path, QString* error);
    /// The mesh files the scene's bodies were loaded from that are gone or changed on disk
    /// since (another size or modification time), each as "NAME (removed)" or "NAME
    /// (changed)". The scene keeps the meshes as loaded; a save refers to the files.
    QStringList meshFilesChangedOnDisk() const;
    /// The scene file, empty when the scene has never been saved (new or a sample).
    const QString& filePath() const { return path_; }
    /// Makes `path` the document's file without reading or writing it (a recovered scene
    /// whose file is gone: Save writes it there again).
    void setFilePath(const QString& path);
    /// A name for the title bar: the file name, or "untitled".
    QString displayName() const;
    /// Changed since it was opened or saved (the undo stack is not at its clean index).
    bool isModified() const;
    /// Replaces the whole scene (recovery, revert), as one undoable step when `undoable`.
    void replaceScene(const SceneDesc& scene, const QString& text, bool undoable);

    // ---- Edits (each an undo command).

    /// Replaces body `index`. Consecutive calls with the same nonzero `mergeId` on the same
    /// body merge into one undo step (a drag, a scrub). A new name is carried into the
    /// joints that name the body (the same undo step). The undo entry is `text` of the body
    /// ("Set mass of box-3") unless `text` names it already; setJoint's the same.
    void setBody(int index, const BodyDesc& body, const QString& text, int mergeId = 0);
    /// An undo entry's words for a changed value: "Set mass of box-3 to 25 kg" (`what`,
    /// `who`, `value`); without a value, "Set mass of box-3".
    static QString editText(const QString& what, const QString& who, const QString& value = QString());
    void setSettings(const Settings& settings, const QString& text, int mergeId = 0);
    /// Inserts `body` at `index` (-1: at the end) with a name made unique; returns its index.
    int addBody(const BodyDesc& body, int index = -1);
    /// Removes the bodies (one undo step), and from the selection, and the joints that name
    /// any of them.
    void removeBodies(QList<int> indices);
    /// Copies of the bodies, named uniquely, placed after the last one; selects the copies.
    void duplicateBodies(QList<int> indices);
    /// Makes the bodies one compound body (one undo step; ui::groupBodies says how) and
    /// selects it; false, with the reason in `why`, when they cannot be grouped.
    bool group(QList<int> indices, QString* why);
    /// Keeps every two of the bodies apart (`apart`: they pass through each other; the scene's
    /// no_collide) or lets them collide again; one undo step; false when nothing changes.
    bool keepApart(QList<int> indices, bool apart);
    /// Makes the compound body `index` a body per part (one undo step; ui::ungroupBody) and
    /// selects them; false, with the reason in `why`, when it cannot be.
    bool ungroup(int index, QString* why);
    /// Adds a part of `type` to body `index` (one undo step; ui::withPartAdded says where and
    /// how) and selects it; returns its index, or -1 with the reason in `why`.
    int addPart(int index, ShapeType type, QString* why);
    /// Removes part `part` of body `index` (one undo step) and selects the body; false, with
    /// the reason in `why`, when it cannot be (ui::withoutPart).
    bool removePart(int index, int part, QString* why);
    /// Adds `joint` (one undo step) with its name made unique among the joints, and selects it.
    void addJoint(const JointDesc& joint);
    /// Replaces joint `index` (one undo step; consecutive calls with the same nonzero
    /// `mergeId` on the same joint merge, as setBody's do).
    void setJoint(int index, const JointDesc& joint, const QString& text, int mergeId = 0);
    /// Removes joint `index` (one undo step).
    void removeJoint(int index);
    int jointCount() const { return static_cast<int>(scene_.joints.size()); }
    const JointDesc& joint(int index) const { return scene_.joints.at(static_cast<size_t>(index)); }
    /// Groups the edits between begin and end into one undo step named `text`.
    void beginMacro(const QString& text);
    void endMacro();

    /// `base` if no body has that name, else base-2, base-3, ...
    QString uniqueName(const QString& base) const;

    // ---- Selection (shared by the scene tree, the property panel and the viewport).
    // A joint can be selected instead (the scene tree's joint list, the property panel's
    // joint page): selecting bodies deselects it and selecting it deselects the bodies.
    const QList<int>& selection() const { return selection_; }
    /// The selection in the order its bodies were picked (the first picked first): the
    /// joint a selection makes has the first picked body as its base (presetJoint).
    QList<int> selectionInPickOrder() const;
    void setSelection(QList<int> indices);
    /// The selected part of the one selected (compound) body, or -1: the scene tree's part
    /// rows and the part panel. Selecting bodies or a joint deselects it.
    int selectedPart() const { return selectedPart_; }
    /// Selects body `body` alone and its part `part` (-1: the body itself).
    void selectPart(int body, int part);
    /// The selected joint's index, or -1.
    int selectedJoint() const { return selectedJoint_; }
    void selectJoint(int index);

    // ---- Used by the undo commands only.
    void applyBody(int index, const BodyDesc& body);
    void applySettings(const Settings& settings);
    void applyInsert(int index, const BodyDesc& body);
    void applyRemove(int index);
    void applyScene(const SceneDesc& scene);
    void applyJoints(const std::vector<JointDesc>& joints);
    void applyNoCollide(const std::vector<std::array<std::string, 2>>& pairs);

signals:
    void bodyChanged(int index);
    void bodyInserted(int index);
    void bodyRemoved(int index);
    void settingsChanged();
    /// The joints changed (added, edited, removed, or a body they name was renamed or removed).
    void jointsChanged();
    /// Everything may have changed (open, new, revert, recovery).
    void sceneReset();
    void selectionChanged();
    /// The file, its name or the modified state changed (for the title bar).
    void fileStateChanged();

private:
    SceneDesc scene_;
    QString path_;
    QStringList openWarnings_;
    // Each loaded mesh file's size and modification time when it was read (absolute path).
    struct FileStamp {
        qint64 size = -1;
        QDateTime modified;
        bool operator==(const FileStamp&) const = default;
    };
    QHash<QString, FileStamp> meshStamps_;
    void stampMeshes();  // stamps the mesh files of bodies with a mesh not stamped yet
    static FileStamp stampOf(const QString& file);
    // "(removed)", "(changed)" or "" for the body's mesh file.
    QString meshFileChange(const ShapeDesc& shape) const;
    QList<int> selection_;
    QList<int>
        picked_;  // the selection's bodies in the order they were picked (maybe stale: selectionInPickOrder)
    int selectedJoint_ = -1;
    int selectedPart_ = -1;
    QUndoStack* undo_ = nullptr;
};

/// The default empty scene: default settings and a static ground plane.
SceneDesc emptyScene();

}  // namespace tumble::ui
