#include "document.h"

#include "commands.h"

#include <tumble/io/scene_file.h>

#include <QFile>
#include <QFileInfo>
#include <QSaveFile>
#include <QSet>
#include <QUndoStack>

#include <algorithm>

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
    path_.clear();
    selection_.clear();
    emit sceneReset();
    emit selectionChanged();
    emit fileStateChanged();
}

bool Document::open(const QString& path, QString* error) {
    const bool sample = path.startsWith(":/");
    const QString name = sample ? QFileInfo(path).fileName() : path;
    SceneDesc scene;
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
            scene = io::readSceneFile(path.toStdString());
        }
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    undo_->clear();
    scene_ = std::move(scene);
    path_ = sample ? QString() : path;
    selection_.clear();
    emit sceneReset();
    emit selectionChanged();
    emit fileStateChanged();
    return true;
}

bool Document::saveAs(const QString& path, QString* error) {
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly)) {
        if (error) *error = tr("%1: cannot be written (%2)").arg(path, file.errorString());
        return false;
    }
    const std::string text = io::sceneToJson(scene_);
    file.write(text.data(), static_cast<qint64>(text.size()));
    if (!file.commit()) {
        if (error) *error = tr("%1: cannot be written (%2)").arg(path, file.errorString());
        return false;
    }
    path_ = path;
    undo_->setClean();
    emit fileStateChanged();
    return true;
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
}

void Document::setBody(int index, const BodyDesc& body, const QString& text, int mergeId) {
    if (index < 0 || index >= bodyCount() || body == scene_.bodies[static_cast<size_t>(index)]) return;
    undo_->push(
        new SetBodyCommand(this, index, scene_.bodies[static_cast<size_t>(index)], body, text, mergeId));
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
    undo_->push(
        new InsertBodyCommand(this, index, b, false, tr("Add %1").arg(QString::fromStdString(b.name))));
    return index;
}

void Document::removeBodies(QList<int> indices) {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    indices.removeIf([&](int i) { return i < 0 || i >= bodyCount(); });
    if (indices.isEmpty()) return;
    undo_->beginMacro(indices.size() == 1 ? tr("Delete %1").arg(QString::fromStdString(body(indices[0]).name))
                                          : tr("Delete %n bodies", nullptr, int(indices.size())));
    // From the last, so the earlier indices stay valid.
    for (auto it = indices.rbegin(); it != indices.rend(); ++it)
        undo_->push(new InsertBodyCommand(this, *it, body(*it), true, QString()));
    undo_->endMacro();
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

void Document::beginMacro(const QString& text) {
    undo_->beginMacro(text);
}
void Document::endMacro() {
    undo_->endMacro();
}

void Document::setSelection(QList<int> indices) {
    std::sort(indices.begin(), indices.end());
    indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
    indices.removeIf([&](int i) { return i < 0 || i >= bodyCount(); });
    if (indices == selection_) return;
    selection_ = indices;
    emit selectionChanged();
}

void Document::applyBody(int index, const BodyDesc& body) {
    scene_.bodies[static_cast<size_t>(index)] = body;
    emit bodyChanged(index);
}

void Document::applySettings(const Settings& settings) {
    scene_.settings = settings;
    emit settingsChanged();
}

void Document::applyInsert(int index, const BodyDesc& body) {
    scene_.bodies.insert(scene_.bodies.begin() + index, body);
    for (int& s : selection_)
        if (s >= index) ++s;
    emit bodyInserted(index);
}

void Document::applyRemove(int index) {
    scene_.bodies.erase(scene_.bodies.begin() + index);
    const qsizetype before = selection_.size();
    selection_.removeAll(index);
    for (int& s : selection_)
        if (s > index) --s;
    emit bodyRemoved(index);
    if (selection_.size() != before) emit selectionChanged();
}

void Document::applyScene(const SceneDesc& scene) {
    scene_ = scene;
    selection_.clear();
    emit sceneReset();
    emit selectionChanged();
}

}  // namespace tumble::ui
