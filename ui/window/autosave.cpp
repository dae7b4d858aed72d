#include "window/autosave.h"

#include <tumble/io/atomic_file.h>
#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStandardPaths>

#include <algorithm>
#include <atomic>
#include <filesystem>

namespace tumble::ui {

namespace {

constexpr const char* kSuffix = ".autosave.json";
constexpr const char* kFormat = "tumble-autosave";

// A name no other editor, in this process or another, takes: the process, the moment and a
// count within the process (two windows opened in the same millisecond).
QString uniqueName() {
    static std::atomic<int> count{0};
    return QStringLiteral("%1-%2-%3")
        .arg(QCoreApplication::applicationPid())
        .arg(QDateTime::currentMSecsSinceEpoch())
        .arg(count.fetch_add(1));
}

QString lockOf(const QString& file) {
    return file.left(file.size() - static_cast<int>(qstrlen(kSuffix))) + QStringLiteral(".lock");
}

// The autosave of versions before issue 46: one file for every editor.
QString sharedFile() {
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
           QStringLiteral("/autosave.json");
}

}  // namespace

QString Autosave::folder() {
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/autosave");
}

Autosave::Autosave() {
    QDir().mkpath(folder());
    file_ = folder() + '/' + uniqueName() + kSuffix;
    lock_ = std::make_unique<QLockFile>(lockOf(file_));
    lock_->setStaleLockTime(0);  // stale only when its process is gone, however old
    lock_->tryLock(0);           // (a folder that cannot be written: no lock, and no autosave either)
}

Autosave::~Autosave() = default;  // QLockFile unlocks and removes the lock

bool Autosave::write(const SceneDesc& scene, const QString& scenePath, QString* error) {
    const QJsonDocument sceneJson =
        QJsonDocument::fromJson(QByteArray::fromStdString(io::sceneToJson(scene)));
    QJsonObject wrapper;
    wrapper["format"] = kFormat;
    wrapper["version"] = 1;
    wrapper["scene_path"] = scenePath;
    wrapper["saved_at"] = QDateTime::currentDateTime().toString(Qt::ISODateWithMs);
    wrapper["scene"] = sceneJson.object();
    try {  // whole or not at all (io::AtomicFile): a failed write keeps the previous autosave
        QDir().mkpath(folder());
        io::writeFileAtomically(QFile::encodeName(file_).toStdString(),
                                QJsonDocument(wrapper).toJson(QJsonDocument::Indented).toStdString());
    } catch (const std::exception& e) {
        if (error) *error = QString::fromLocal8Bit(e.what());
        return false;
    }
    return true;
}

void Autosave::remove() {
    QFile::remove(file_);
}

bool Autosave::describe(const QString& file, AutosaveLeftover* out, QString* error) {
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly)) {
        if (error)
            *error =
                QCoreApplication::translate("Autosave", "%1: cannot be read (%2)").arg(file, f.errorString());
        return false;
    }
    const QJsonDocument doc = QJsonDocument::fromJson(f.readAll());
    out->file = file;
    out->savedAt = QFileInfo(file).lastModified();
    out->scenePath.clear();
    const QJsonObject o = doc.object();
    if (o.value("format").toString() == kFormat) {
        out->scenePath = o.value("scene_path").toString();
        const QDateTime at = QDateTime::fromString(o.value("saved_at").toString(), Qt::ISODateWithMs);
        if (at.isValid()) out->savedAt = at;
    } else if (o.value("format").toString() != QStringLiteral("tumble-scene")) {
        if (error) *error = QCoreApplication::translate("Autosave", "%1: not a Tumble autosave").arg(file);
        return false;
    }
    return true;
}

QList<AutosaveLeftover> Autosave::leftovers() {
    QList<AutosaveLeftover> out;
    const QDir dir(folder());
    for (const QFileInfo& info : dir.entryInfoList({QStringLiteral("*") + kSuffix}, QDir::Files)) {
        QLockFile lock(lockOf(info.absoluteFilePath()));
        lock.setStaleLockTime(0);
        if (!lock.tryLock(0)) continue;  // its editor runs
        lock.unlock();
        AutosaveLeftover l;
        if (describe(info.absoluteFilePath(), &l, nullptr)) out << l;
    }
    // Locks of editors that are gone and left no autosave (nothing unsaved when killed).
    for (const QFileInfo& info : dir.entryInfoList({QStringLiteral("*.lock")}, QDir::Files)) {
        const QString name = info.completeBaseName();
        if (QFileInfo::exists(dir.filePath(name + kSuffix))) continue;
        QLockFile lock(info.absoluteFilePath());
        lock.setStaleLockTime(0);
        if (lock.tryLock(0)) lock.unlock();  // (removes it)
    }
    AutosaveLeftover shared;
    if (QFileInfo::exists(sharedFile()) && describe(sharedFile(), &shared, nullptr)) out << shared;
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.savedAt > b.savedAt; });
    return out;
}

bool Autosave::read(const AutosaveLeftover& leftover, SceneDesc* scene, QString* error) {
    QFile f(leftover.file);
    if (!f.open(QIODevice::ReadOnly)) {
        if (error)
            *error = QCoreApplication::translate("Autosave", "%1: cannot be read (%2)")
                         .arg(leftover.file, f.errorString());
        return false;
    }
    const QByteArray text = f.readAll();
    QJsonObject o = QJsonDocument::fromJson(text).object();
    const QByteArray sceneText =
        o.value("format").toString() == kFormat
            ? QJsonDocument(o.value("scene").toObject()).toJson(QJsonDocument::Compact)
            : text;
    // Meshes as the scene's own file finds them (the document keeps them absolute; an older
    // autosave may not have).
    const QString base =
        leftover.scenePath.isEmpty() ? QDir::currentPath() : QFileInfo(leftover.scenePath).absolutePath();
    try {
        const std::string name = leftover.file.toStdString();
        *scene = io::parseScene(
            std::string_view(sceneText.constData(), static_cast<size_t>(sceneText.size())), name);
        std::vector<io::InputError> failures;  // a mesh gone since: the body comes without it, as on open
        io::loadSceneMeshes(*scene, base.toStdString(), name, &failures);
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    return true;
}

void Autosave::discard(const AutosaveLeftover& leftover) {
    QFile::remove(leftover.file);
    if (leftover.file.endsWith(kSuffix)) QFile::remove(lockOf(leftover.file));
}

}  // namespace tumble::ui
