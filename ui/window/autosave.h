// Each running editor's own autosave (issue 46): a file of its own in the app-data folder,
// held by a lock file while the editor runs, that names the scene it is the unsaved work of
// and when it was written. Two editors never share or delete each other's; an autosave
// whose editor is gone (killed, crashed: its lock is stale) is a leftover the next editor
// offers to recover, every one of them.
#pragma once

#include <tumble/scene.h>

#include <QDateTime>
#include <QList>
#include <QLockFile>
#include <QString>

#include <memory>

namespace tumble::ui {

/// An autosave left by an editor that did not end cleanly.
struct AutosaveLeftover {
    QString file;       ///< the autosave
    QString scenePath;  ///< the scene file it is the unsaved work of; empty: untitled
    QDateTime savedAt;  ///< when it was written
};

class Autosave {
public:
    /// A new autosave name for this editor, locked at once (nothing is written yet).
    Autosave();
    /// The lock goes; the file stays (a window destroyed without closing: as after a crash).
    ~Autosave();
    Autosave(const Autosave&) = delete;
    Autosave& operator=(const Autosave&) = delete;

    /// This editor's autosave file.
    const QString& file() const { return file_; }
    /// Writes `scene`, the unsaved work of `scenePath` (empty: untitled), whole or not at all
    /// (a failed write keeps the previous autosave). False, with `error` naming the file and
    /// the reason, if it could not be written.
    bool write(const SceneDesc& scene, const QString& scenePath, QString* error = nullptr);
    /// Removes this editor's autosave (saved, or closed cleanly).
    void remove();

    /// The folder of every editor's autosaves.
    static QString folder();
    /// The autosaves whose editor is gone, newest first; never a running editor's. The
    /// autosave of versions before issue 46 (one shared autosave.json) is among them,
    /// untitled.
    static QList<AutosaveLeftover> leftovers();
    /// What `file` holds: its scene path and time (false, with `error`, if it is not an
    /// autosave that can be read).
    static bool describe(const QString& file, AutosaveLeftover* out, QString* error);
    /// Reads the scene of `leftover`, its meshes resolved against its scene's folder (the
    /// current one when untitled); false with `error` naming the autosave.
    static bool read(const AutosaveLeftover& leftover, SceneDesc* scene, QString* error);
    /// Removes a leftover (recovered, or discarded by the user).
    static void discard(const AutosaveLeftover& leftover);

private:
    QString file_;
    std::unique_ptr<QLockFile> lock_;
};

}  // namespace tumble::ui
