#include "document/document.h"

#include "document/body_keys.h"
#include "document/commands.h"
#include "document/grouping.h"
#include "document/part_edits.h"

#include <tumble/io/atomic_file.h>
#include <tumble/io/convex_parts_cache.h>
#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>

#include <tumble/convex_parts.h>

#include <QCursor>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QGuiApplication>
#include <QMap>
#include <QSet>
#include <QUndoStack>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <vector>

namespace tumble::ui {

SceneDesc emptyScene() {
    SceneDesc s;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.shape.normal = Vec3::UnitY();
    s.bodies.push_back(ground);
    return s;
}

Document::Document(QObject* parent) : QObject(parent), undo_(new QUndoStack(this)) {
    scene_ = emptyScene();
    connect(undo_, &QUndoStack::cleanChanged, this, &Document::fileStateChanged);
}

Document::~Document() = default;

void Document::newScene() {
    undo_->clear();
    scene_ = emptyScene();
    meshStamps_.clear();
    path_.clear();
    selection_.clear();
    selectedJoint_ = -1;
    selectedPart_ = -1;
    emit sceneReset();
    emit selectionChanged();
    emit fileStateChanged();
}

namespace {

// In the document a mesh body's file is an absolute path, whatever folder the scene came
// from; a saved scene holds it relative to the scene's own folder (what the format says), so
// Save As to another folder keeps every mesh reachable.
void makeMeshPathsAbsolute(SceneDesc& scene, const QString& dir) {
    for (BodyDesc& b : scene.bodies)
        forEachShape(b, {}, [&](ShapeDesc& s, const std::string&) {
            if (s.type != ShapeType::Mesh || s.file.empty()) return;
            const QString file = QString::fromStdString(s.file);
            if (QFileInfo(file).isRelative())
                s.file = QDir::cleanPath(QDir(dir).absoluteFilePath(file)).toStdString();
        });
}

SceneDesc withMeshPathsRelativeTo(SceneDesc scene, const QString& dir) {
    for (BodyDesc& b : scene.bodies)
        forEachShape(b, {}, [&](ShapeDesc& s, const std::string&) {
            if (s.type != ShapeType::Mesh || s.file.empty()) return;
            const QString file = QString::fromStdString(s.file);
            if (QFileInfo(file).isAbsolute()) s.file = QDir(dir).relativeFilePath(file).toStdString();
        });
    return scene;
}

// The convex parts of the scene's meshes that ask for them: from the scene's sidecar, and
// those it lacks made now (once, not at every edit's compile) and kept in it. A sidecar that
// cannot be written is not kept, and says so in `warnings`.
void prepareConvexParts(SceneDesc& scene, const QString& path, const std::string& name,
                        QStringList& warnings) {
    if (io::convexPartsShapes(scene).empty()) return;
    const auto cache = io::convexPartsCachePath(QFile::encodeName(path).toStdString());
    std::string problem;
    io::readConvexPartsCache(scene, cache, &problem);
    if (!problem.empty()) warnings << QString::fromStdString(problem);
    try {
        if (io::makeConvexParts(scene, name) > 0) io::writeConvexPartsCache(scene, cache);
    } catch (const io::InputError& e) {
        warnings << QString::fromStdString(e.what());  // compile names it again when run
    } catch (const std::runtime_error& e) {
        warnings << QString::fromStdString(e.what());
    }
}

// Writes `bytes` to `path` whole or not at all, through the engine's AtomicFile (which also
// removes what earlier killed saves of `path` left beside it). Messages name the file.
bool writeWhole(const QString& path, const QByteArray& bytes, QString* error) {
    try {
        io::AtomicFile out(QFile::encodeName(path).toStdString());
        out.stream().write(bytes.constData(), bytes.size());
        out.commit();
    } catch (const std::exception& e) {
        if (error) *error = QString::fromLocal8Bit(e.what());
        return false;
    }
    return true;
}

}  // namespace

bool Document::open(const QString& path, QString* error) {
    const bool sample = path.startsWith(":/");
    const QString name = sample ? QFileInfo(path).fileName() : path;
    SceneDesc scene;
    QStringList warnings;
    try {
        if (sample) {
            QFile file(path);
            if (!file.open(QIODevice::ReadOnly)) {
                if (error) *error = tr("%1: cannot be read (%2)").arg(name, file.errorString());
                return false;
            }
            const QByteArray text = file.readAll();
            scene = io::parseScene(std::string_view(text.constData(), static_cast<size_t>(text.size())),
                                   name.toStdString());
        } else {
            if (!QFileInfo::exists(path)) {
                if (error) *error = tr("%1: no such file").arg(name);
                return false;
            }
            // A mesh that cannot be read does not keep the scene from opening: its bodies
            // come without their mesh (the tree marks them, the engine refuses to run them
            // and says which) and the reasons are kept for the window to show.
            QFile file(path);
            if (!file.open(QIODevice::ReadOnly)) {
                if (error) *error = tr("%1: cannot be read (%2)").arg(name, file.errorString());
                return false;
            }
            const QByteArray text = file.readAll();
            scene = io::parseScene(std::string_view(text.constData(), static_cast<size_t>(text.size())),
                                   name.toStdString());
            // What saves of this file killed long ago left beside it goes (see open()).
            io::removeStaleTemporaries(QFile::encodeName(path).toStdString());
            std::vector<io::InputError> failures;
            io::loadSceneMeshes(scene, QFileInfo(path).absolutePath().toStdString(), name.toStdString(),
                                &failures);
            for (const io::InputError& f : failures) warnings << QString::fromStdString(f.what());
            prepareConvexParts(scene, path, name.toStdString(), warnings);
            makeMeshPathsAbsolute(scene, QFileInfo(path).absolutePath());
        }
    } catch (const io::InputError& e) {
        // Every problem of the file at once, not one per try (the command line names the first).
        if (error) {
            QStringList lines{QString::fromStdString(e.what())};
            for (const std::string& more : e.more()) lines << QString::fromStdString(e.file() + ": " + more);
            *error = lines.join('\n');
        }
        return false;
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    undo_->clear();
    scene_ = std::move(scene);
    for (BodyDesc& b : scene_.bodies) followKeys(b, b);  // animated bodies where their paths start
    openWarnings_ = warnings;
    meshStamps_.clear();
    stampMeshes();
    path_ = sample ? QString() : path;
    selection_.clear();
    selectedJoint_ = -1;
    selectedPart_ = -1;
    emit sceneReset();
    emit selectionChanged();
    emit fileStateChanged();
    return true;
}

bool Document::saveAs(const QString& path, QString* error) {
    const std::string text = io::sceneToJson(withMeshPathsRelativeTo(scene_, QFileInfo(path).absolutePath()));
    if (!writeWhole(path, QByteArray::fromStdString(text), error)) return false;
    // The convex parts beside the scene, for the next open (not keeping them loses nothing).
    try {
        io::writeConvexPartsCache(scene_, io::convexPartsCachePath(QFile::encodeName(path).toStdString()));
    } catch (const std::runtime_error&) {
    }
    path_ = path;
    undo_->setClean();
    emit fileStateChanged();
    return true;
}

bool Document::saveWithMeshes(const QString& path, QString* error) {
    const QFileInfo target(path);
    const QString folderName = target.completeBaseName() + QStringLiteral("-meshes");
    const QDir dir(target.absolutePath());
    // Each distinct mesh file gets one copy, under its own name (made unique when two
    // different files share a name).
    QMap<QString, QString> copyOf;  // source -> name in the folder
    QSet<QString> names;
    // Every mesh shape: a body's, or a compound's part's.
    std::vector<std::pair<const BodyDesc*, const ShapeDesc*>> meshShapes;
    for (const BodyDesc& b : scene_.bodies)
        forEachShape(b, {}, [&](const ShapeDesc& s, const std::string&) {
            if (s.type == ShapeType::Mesh && !s.file.empty()) meshShapes.emplace_back(&b, &s);
        });
    for (const auto& [b, s] : meshShapes) {
        const QString source = QFileInfo(QString::fromStdString(s->file)).absoluteFilePath();
        if (copyOf.contains(source)) continue;
        const QString change = meshFileChange(*s);
        if (change == QLatin1String("changed")) {
            if (error)
                *error =
                    tr("%1: body \"%2\": the mesh file changed on disk since it was loaded, so a copy would "
                       "not be the mesh the scene shows; open the scene again to load it anew")
                        .arg(source, QString::fromStdString(b->name));
            return false;
        }
        if (!QFileInfo(source).isReadable()) {
            if (error)
                *error = tr("%1: body \"%2\": the mesh file cannot be read%3")
                             .arg(source, QString::fromStdString(b->name),
                                  change == QLatin1String("removed") ? tr(" (removed since it was loaded)")
                                                                     : QString());
            return false;
        }
        QString name = QFileInfo(source).fileName();
        for (int n = 2; names.contains(name); ++n)
            name = QStringLiteral("%1-%2.%3")
                       .arg(QFileInfo(source).completeBaseName())
                       .arg(n)
                       .arg(QFileInfo(source).suffix());
        names.insert(name);
        copyOf.insert(source, name);
    }
    const QString folder = dir.filePath(folderName);
    const std::filesystem::path folderPath(QFile::encodeName(folder).toStdString());
    const bool madeFolder = !copyOf.isEmpty() && !QFileInfo(folder).isDir();
    if (madeFolder) {
        std::error_code ec;
        std::filesystem::create_directories(folderPath, ec);
        if (ec) {
            if (error)
                *error = tr("%1: the folder cannot be made: %2")
                             .arg(folder, QString::fromStdString(io::plainReason(ec.value())));
            return false;
        }
    }
    SceneDesc moved = scene_;
    for (BodyDesc& b : moved.bodies)
        forEachShape(b, {}, [&](ShapeDesc& s, const std::string&) {
            if (s.type != ShapeType::Mesh || s.file.empty()) return;
            const QString source = QFileInfo(QString::fromStdString(s.file)).absoluteFilePath();
            s.file = QDir(folder).filePath(copyOf.value(source)).toStdString();
        });
    // Every copy and the scene are written out before any replaces its old file (a full disk
    // or a read-only one leaves the old save whole, copies included), then the copies first:
    // the new scene never names a copy not yet there.
    std::vector<std::unique_ptr<io::AtomicFile>> files;
    try {
        for (auto it = copyOf.cbegin(); it != copyOf.cend(); ++it) {
            const QString to = QDir(folder).filePath(it.value());
            if (QFileInfo(to).absoluteFilePath() == it.key()) continue;  // saved there already
            QFile in(it.key());
            if (!in.open(QIODevice::ReadOnly))
                throw std::runtime_error(
                    tr("%1: cannot be read (%2)").arg(it.key(), in.errorString()).toStdString());
            const QByteArray bytes = in.readAll();
            files.push_back(std::make_unique<io::AtomicFile>(QFile::encodeName(to).toStdString()));
            files.back()->stream().write(bytes.constData(), bytes.size());
        }
        files.push_back(std::make_unique<io::AtomicFile>(QFile::encodeName(path).toStdString()));
        files.back()->stream() << io::sceneToJson(withMeshPathsRelativeTo(moved, dir.absolutePath()));
        for (auto& f : files) f->ready();
        for (auto& f : files) f->commit();
    } catch (const std::exception& e) {
        if (error) *error = QString::fromLocal8Bit(e.what());
        files.clear();  // their temporaries go
        if (madeFolder) QDir().rmdir(folder);
        return false;
    }
    // The document now refers to the copies (the same meshes); not an edit to undo.
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i)
        scene_.bodies[i].shape.file = moved.bodies[i].shape.file;
    stampMeshes();
    path_ = path;
    undo_->setClean();
    emit fileStateChanged();
    return true;
}

void Document::setFilePath(const QString& path) {
    path_ = path;
    emit fileStateChanged();
}

QString Document::displayName() const {
    return path_.isEmpty() ? tr("untitled") : QFileInfo(path_).fileName();
}

bool Document::isModified() const {
    return !undo_->isClean();
}

void Document::replaceScene(const SceneDesc& scene, const QString& text, bool undoable) {
    if (undoable) {
        undo_->push(new ReplaceSceneCommand(this, scene_, scene, text));
    } else {
        undo_->clear();
        applyScene(scene);
    }
    stampMeshes();
}

namespace {

// The body with the convex parts its meshes ask for made (a mesh switched to convex parts,
// or its options changed): made once here, under a wait cursor, and kept in the scene (and
// in the undo step), not made again by every compile of the runs that follow. A mesh that
// cannot be split is left without: compile names it.
BodyDesc withConvexParts(BodyDesc body) {
    bool waiting = false;
    forEachShape(body, {}, [&](ShapeDesc& s, const std::string&) {
        if (s.type != ShapeType::Mesh || s.collision != MeshCollision::ConvexParts || !s.meshData) return;
        if (s.convexParts && mesh::convexPartsFit(*s.convexParts, s)) return;
        if (!waiting) QGuiApplication::setOverrideCursor(QCursor(Qt::WaitCursor));
        waiting = true;
        try {
            s.convexParts = std::make_shared<const mesh::ConvexParts>(mesh::convexPartsOfShape(s));
        } catch (const std::invalid_argument&) {
            s.convexParts.reset();
        }
    });
    if (waiting) QGuiApplication::restoreOverrideCursor();
    return body;
}

}  // namespace

namespace {

// An undo entry that says what it changed: "Set mass" on box-3 is "Set mass of box-3"
// (a text that names it already, "Rename box-3 to lid", is kept).
QString naming(const QString& text, const std::string& name) {
    const QString n = QString::fromStdString(name);
    if (n.isEmpty() || text.contains(n)) return text;
    return Document::tr("%1 of %2").arg(text, n);
}

}  // namespace

QString Document::editText(const QString& what, const QString& who, const QString& value) {
    return value.isEmpty() ? tr("%1 of %2").arg(what, who) : tr("%1 of %2 to %3").arg(what, who, value);
}

void Document::setBody(int index, const BodyDesc& given, const QString& plainText, int mergeId) {
    if (index < 0 || index >= bodyCount() || given == scene_.bodies[static_cast<size_t>(index)]) return;
    const QString text = naming(plainText, scene_.bodies[static_cast<size_t>(index)].name);
    BodyDesc body = withConvexParts(given);
    followKeys(scene_.bodies[static_cast<size_t>(index)],
               body);  // an animated body's pose is its path's at 0
    if (body == scene_.bodies[static_cast<size_t>(index)]) return;
    const std::string& old = scene_.bodies[static_cast<size_t>(index)].name;
    std::vector<JointDesc> joints = scene_.joints;
    for (JointDesc& j : joints) {
        if (j.bodyA == old) j.bodyA = body.name;
        if (j.bodyB == old) j.bodyB = body.name;
    }
    auto pairs = scene_.noCollide;
    for (auto& pair : pairs)
        for (std::string& name : pair)
            if (name == old) name = body.name;
    const bool renamesJoints = joints != scene_.joints, renamesPairs = pairs != scene_.noCollide;
    if (renamesJoints || renamesPairs) undo_->beginMacro(text);
    undo_->push(
        new SetBodyCommand(this, index, scene_.bodies[static_cast<size_t>(index)], body, text, mergeId));
    if (renamesJoints) undo_->push(new SetJointsCommand(this, scene_.joints, joints, text));
    if (renamesPairs) undo_->push(new SetNoCollideCommand(this, scene_.noCollide, pairs, text));
    if (renamesJoints || renamesPairs) undo_->endMacro();
}

void Document::setSettings(const Settings& settings, const QString& text, int mergeId) {
    if (settings == scene_.settings) return;
    undo_->push(new SetSettingsCommand(this, scene_.settings, settings, text, mergeId));
}

QString Document::uniqueName(const QString& base) const {
    QSet<QString> names;
    for (const BodyDesc& b : scene_.bodies) names.insert(QString::fromStdString(b.name));
    if (!names.contains(base)) return base;
    for (int k = 2;; ++k) {
        const QString candidate = QStringLiteral("%1-%2").arg(base).arg(k);
        if (!names.contains(candidate)) return candidate;
    }
}

int Document::addBody(const BodyDesc& body, int index) {
    if (index < 0 || index > bodyCount()) index = bodyCount();
    BodyDesc b = body;
    b.name = uniqueName(QString::fromStdString(body.name.empty() ? "body" : body.name)).toStdString();
    followKeys(b, b);  // an animated body is shown where its path starts
    undo_->push(
        new InsertBodyCommand(this, index, b, false, tr("Add %1").arg(QString::fromStdString(b.name))));
    stampMeshes();  // an imported mesh: as read just now
    return index;
}

Document::FileStamp Document::stampOf(const QString& file) {
    const QFileInfo info(file);
    if (!info.exists()) return {};
    return {info.size(), info.lastModified()};
}

void Document::stampMeshes() {
    for (const BodyDesc& b : scene_.bodies)
        forEachShape(b, {}, [&](const ShapeDesc& s, const std::string&) {
            if (s.type != ShapeType::Mesh || !s.meshData || s.file.empty()) return;
            const QString file = QFileInfo(QString::fromStdString(s.file)).absoluteFilePath();
            if (!meshStamps_.contains(file)) meshStamps_.insert(file, stampOf(file));
        });
}

QString Document::meshFileChange(const ShapeDesc& s) const {
    if (s.type != ShapeType::Mesh || !s.meshData || s.file.empty()) return {};
    const QString file = QFileInfo(QString::fromStdString(s.file)).absoluteFilePath();
    const auto it = meshStamps_.constFind(file);
    if (it == meshStamps_.constEnd() || it->size < 0) return {};
    const FileStamp now = stampOf(file);
    if (now.size < 0) return QStringLiteral("removed");
    return now == *it ? QString() : QStringLiteral("changed");
}

QStringList Document::meshFilesChangedOnDisk() const {
    QStringList out;
    for (const BodyDesc& b : scene_.bodies)
        forEachShape(b, {}, [&](const ShapeDesc& s, const std::string&) {
            const QString change = meshFileChange(s);
            const QString line = QStringLiteral("%1 (%2)").arg(QString::fromStdString(s.file), change);
            if (!change.isEmpty() && !out.contains(line)) out << line;
        });
    return out;
}

void Document::removeBodies(QList<int> indices) {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    indices.removeIf([&](int i) { return i < 0 || i >= bodyCount(); });
    if (indices.isEmpty()) return;
    undo_->beginMacro(indices.size() == 1 ? tr("Delete %1").arg(QString::fromStdString(body(indices[0]).name))
                                          : tr("Delete %n bodies", nullptr, int(indices.size())));
    // Their joints first (undone last: the bodies are back when the joints are).
    std::vector<JointDesc> joints;
    for (const JointDesc& j : scene_.joints) {
        const bool named = std::any_of(indices.begin(), indices.end(), [&](int i) {
            return body(i).name == j.bodyA || (!j.bodyB.empty() && body(i).name == j.bodyB);
        });
        if (!named) joints.push_back(j);
    }
    if (joints != scene_.joints) undo_->push(new SetJointsCommand(this, scene_.joints, joints, QString()));
    // And the pairs kept apart that name them.
    auto pairs = scene_.noCollide;
    std::erase_if(pairs, [&](const auto& pair) {
        return std::any_of(indices.begin(), indices.end(),
                           [&](int i) { return body(i).name == pair[0] || body(i).name == pair[1]; });
    });
    if (pairs != scene_.noCollide)
        undo_->push(new SetNoCollideCommand(this, scene_.noCollide, pairs, QString()));
    // From the last, so the earlier indices stay valid.
    for (auto it = indices.rbegin(); it != indices.rend(); ++it)
        undo_->push(new InsertBodyCommand(this, *it, body(*it), true, QString()));
    undo_->endMacro();
}

void Document::addJoint(const JointDesc& joint) {
    std::vector<JointDesc> joints = scene_.joints;
    JointDesc j = joint;
    auto taken = [&](const std::string& name) {
        for (const JointDesc& other : joints)
            if (other.name == name) return true;
        return false;
    };
    const std::string base = j.name.empty() ? std::string("joint") : j.name;
    j.name = base;
    for (int k = 2; taken(j.name); ++k) j.name = base + "-" + std::to_string(k);
    joints.push_back(j);
    undo_->push(new SetJointsCommand(this, scene_.joints, joints,
                                     tr("Add %1 joint").arg(QString::fromUtf8(toString(j.type)))));
    selectJoint(jointCount() - 1);
}

void Document::setJoint(int index, const JointDesc& joint, const QString& plainText, int mergeId) {
    if (index < 0 || index >= jointCount() || joint == scene_.joints[static_cast<size_t>(index)]) return;
    const QString text = naming(plainText, scene_.joints[static_cast<size_t>(index)].name);
    std::vector<JointDesc> joints = scene_.joints;
    joints[static_cast<size_t>(index)] = joint;
    undo_->push(new SetJointsCommand(this, scene_.joints, joints, text, mergeId));
}

void Document::removeJoint(int index) {
    if (index < 0 || index >= jointCount()) return;
    std::vector<JointDesc> joints = scene_.joints;
    const QString name = QString::fromStdString(joints[static_cast<size_t>(index)].name);
    joints.erase(joints.begin() + index);
    undo_->push(new SetJointsCommand(this, scene_.joints, joints, tr("Delete joint %1").arg(name)));
}

void Document::duplicateBodies(QList<int> indices) {
    std::sort(indices.begin(), indices.end());
    indices.removeIf([&](int i) { return i < 0 || i >= bodyCount(); });
    if (indices.isEmpty()) return;
    QList<int> copies;
    undo_->beginMacro(tr("Duplicate"));
    for (int i : indices) copies.append(addBody(body(i)));
    undo_->endMacro();
    setSelection(copies);
}

bool Document::group(QList<int> indices, QString* why) {
    std::string reason;
    const auto done = groupBodies(scene_, std::vector<int>(indices.begin(), indices.end()), &reason);
    if (!done) {
        if (why) *why = QString::fromStdString(reason);
        return false;
    }
    replaceScene(done->scene, tr("Group %n bodies", nullptr, int(indices.size())), true);
    setSelection(QList<int>(done->bodies.begin(), done->bodies.end()));
    return true;
}

bool Document::keepApart(QList<int> indices, bool apart) {
    auto pairs = scene_.noCollide;
    auto same = [](const std::array<std::string, 2>& p, const std::string& a, const std::string& b) {
        return (p[0] == a && p[1] == b) || (p[0] == b && p[1] == a);
    };
    for (int x = 0; x < indices.size(); ++x)
        for (int y = x + 1; y < indices.size(); ++y) {
            const std::string &a = body(indices[x]).name, &b = body(indices[y]).name;
            const bool listed =
                std::any_of(pairs.begin(), pairs.end(), [&](const auto& p) { return same(p, a, b); });
            if (apart && !listed) pairs.push_back({a, b});
            if (!apart) std::erase_if(pairs, [&](const auto& p) { return same(p, a, b); });
        }
    if (pairs == scene_.noCollide) return false;
    undo_->push(new SetNoCollideCommand(this, scene_.noCollide, pairs,
                                        apart ? tr("Keep %n bodies apart", nullptr, int(indices.size()))
                                              : tr("Let %n bodies collide", nullptr, int(indices.size()))));
    return true;
}

bool Document::ungroup(int index, QString* why) {
    std::string reason;
    const auto done = ungroupBody(scene_, index, &reason);
    if (!done) {
        if (why) *why = QString::fromStdString(reason);
        return false;
    }
    replaceScene(done->scene, tr("Ungroup %1").arg(QString::fromStdString(body(index).name)), true);
    setSelection(QList<int>(done->bodies.begin(), done->bodies.end()));
    return true;
}

int Document::addPart(int index, ShapeType type, QString* why) {
    std::string reason;
    const auto done = withPartAdded(body(index), type, &reason);
    if (!done) {
        if (why) *why = QString::fromStdString(reason);
        return -1;
    }
    const int part = static_cast<int>(done->shape.parts.size()) - 1;
    setBody(index, *done,
            tr("Add %1 to %2")
                .arg(QString::fromStdString(done->shape.parts.back().name),
                     QString::fromStdString(body(index).name)));
    selectPart(index, part);
    return part;
}

bool Document::removePart(int index, int part, QString* why) {
    std::string reason;
    const auto done = withoutPart(body(index), part, &reason);
    if (!done) {
        if (why) *why = QString::fromStdString(reason);
        return false;
    }
    const QString name =
        QString::fromStdString(partLabel(body(index).shape.parts[static_cast<size_t>(part)], part));
    setBody(index, *done, tr("Remove %1 from %2").arg(name, QString::fromStdString(body(index).name)));
    selectPart(index, -1);
    return true;
}

void Document::beginMacro(const QString& text) {
    undo_->beginMacro(text);
}
void Document::endMacro() {
    undo_->endMacro();
}

QList<int> Document::selectionInPickOrder() const {
    QList<int> order;
    for (int i : picked_)
        if (selection_.contains(i) && !order.contains(i)) order.append(i);
    for (int i : selection_)  // (selected otherwise: a part, a new body)
        if (!order.contains(i)) order.append(i);
    return order;
}

void Document::setSelection(QList<int> indices) {
    // The pick order: those still selected as they were picked, then the new ones as given
    // (a Ctrl+click appends the body it adds).
    QList<int> order;
    for (int i : picked_)
        if (indices.contains(i) && selection_.contains(i)) order.append(i);
    for (int i : indices)
        if (!order.contains(i) && i >= 0 && i < bodyCount()) order.append(i);
    picked_ = order;
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    indices.removeIf([&](int i) { return i < 0 || i >= bodyCount(); });
    // (Sizes first: Qt 6.4 compares two empty lists by memcmp of null pointers, which UBSan
    // reports.)
    const bool same = indices.size() == selection_.size() && (indices.isEmpty() || indices == selection_);
    if (same && selectedJoint_ < 0 && selectedPart_ < 0) return;
    selection_ = indices;
    selectedJoint_ = -1;
    selectedPart_ = -1;
    emit selectionChanged();
}

void Document::selectPart(int body, int part) {
    if (body < 0 || body >= bodyCount()) return setSelection({});
    const ShapeDesc& shape = this->body(body).shape;
    if (shape.type != ShapeType::Compound || part < 0 || part >= static_cast<int>(shape.parts.size()))
        part = -1;
    if (selection_ == QList<int>{body} && selectedJoint_ < 0 && selectedPart_ == part) return;
    selection_ = {body};
    selectedJoint_ = -1;
    selectedPart_ = part;
    emit selectionChanged();
}

void Document::selectJoint(int index) {
    if (index < 0 || index >= jointCount()) index = -1;
    if (index == selectedJoint_ && (index < 0 || selection_.isEmpty())) return;
    selectedJoint_ = index;
    if (index >= 0) {
        selection_.clear();
        selectedPart_ = -1;
    }
    emit selectionChanged();
}

void Document::applyBody(int index, const BodyDesc& body) {
    scene_.bodies[static_cast<size_t>(index)] = body;
    // A part removed (or the body no longer a compound) takes the part selection with it.
    const bool partGone = selectedPart_ >= 0 && selection_ == QList<int>{index} &&
                          (body.shape.type != ShapeType::Compound ||
                           selectedPart_ >= static_cast<int>(body.shape.parts.size()));
    if (partGone) selectedPart_ = -1;
    emit bodyChanged(index);
    if (partGone) emit selectionChanged();
}

void Document::applySettings(const Settings& settings) {
    scene_.settings = settings;
    emit settingsChanged();
}

void Document::applyInsert(int index, const BodyDesc& body) {
    scene_.bodies.insert(scene_.bodies.begin() + index, body);
    for (QList<int>* list : {&selection_, &picked_})
        for (int& s : *list)
            if (s >= index) ++s;
    emit bodyInserted(index);
}

void Document::applyRemove(int index) {
    scene_.bodies.erase(scene_.bodies.begin() + index);
    const qsizetype before = selection_.size();
    selection_.removeAll(index);
    picked_.removeAll(index);
    for (QList<int>* list : {&selection_, &picked_})
        for (int& s : *list)
            if (s > index) --s;
    if (selection_.size() != 1) selectedPart_ = -1;
    emit bodyRemoved(index);
    if (selection_.size() != before) emit selectionChanged();
}

void Document::applyJoints(const std::vector<JointDesc>& joints) {
    const bool renumbered = joints.size() != scene_.joints.size();
    scene_.joints = joints;
    emit jointsChanged();
    // A joint added or removed (an undo, a body's delete) may move the selected one's index.
    if (selectedJoint_ >= 0 && renumbered) {
        selectedJoint_ = -1;
        emit selectionChanged();
    }
}

void Document::applyNoCollide(const std::vector<std::array<std::string, 2>>& pairs) {
    scene_.noCollide = pairs;
    emit settingsChanged();
}

void Document::applyScene(const SceneDesc& scene) {
    scene_ = scene;
    for (BodyDesc& b : scene_.bodies) followKeys(b, b);  // animated bodies where their paths start
    selection_.clear();
    selectedJoint_ = -1;
    selectedPart_ = -1;
    emit sceneReset();
    emit selectionChanged();
}

}  // namespace tumble::ui
