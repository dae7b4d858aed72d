// The undo commands of the document: each holds the value before and after, and applies
// one or the other through the document's apply* functions (which emit the signals).
#pragma once

#include <tumble/scene.h>

#include <QUndoCommand>

namespace tumble::ui {

class Document;

/// Replaces one body. Merges with the next command of the same nonzero merge id on the
/// same body (a drag or a scrub is one undo step).
class SetBodyCommand : public QUndoCommand {
public:
    SetBodyCommand(Document* doc, int index, BodyDesc before, BodyDesc after, const QString& text,
                   int mergeId);
    void undo() override;
    void redo() override;
    int id() const override { return mergeId_ ? kId : -1; }
    bool mergeWith(const QUndoCommand* other) override;

    static constexpr int kId = 1001;

private:
    Document* doc_;
    int index_;
    BodyDesc before_, after_;
    int mergeId_;
};

class SetSettingsCommand : public QUndoCommand {
public:
    SetSettingsCommand(Document* doc, Settings before, Settings after, const QString& text, int mergeId);
    void undo() override;
    void redo() override;
    int id() const override { return mergeId_ ? kId : -1; }
    bool mergeWith(const QUndoCommand* other) override;

    static constexpr int kId = 1002;

private:
    Document* doc_;
    Settings before_, after_;
    int mergeId_;
};

/// Inserts a body at an index (undo removes it); with `remove`, the other way round.
class InsertBodyCommand : public QUndoCommand {
public:
    InsertBodyCommand(Document* doc, int index, BodyDesc body, bool remove, const QString& text,
                      QUndoCommand* parent = nullptr);
    void undo() override;
    void redo() override;

private:
    Document* doc_;
    int index_;
    BodyDesc body_;
    bool remove_;
};

/// Replaces the scene's joints (a joint edited, added or removed; a body renamed or removed
/// takes its joints along). Merges with the next command of the same nonzero merge id.
class SetJointsCommand : public QUndoCommand {
public:
    SetJointsCommand(Document* doc, std::vector<JointDesc> before, std::vector<JointDesc> after,
                     const QString& text, int mergeId = 0);
    void undo() override;
    void redo() override;
    int id() const override { return mergeId_ ? kId : -1; }
    bool mergeWith(const QUndoCommand* other) override;

    static constexpr int kId = 1003;

private:
    Document* doc_;
    std::vector<JointDesc> before_, after_;
    int mergeId_;
};

/// Replaces the scene's pairs of bodies kept apart (SceneDesc::noCollide: a body renamed or
/// removed takes its pairs along).
class SetNoCollideCommand : public QUndoCommand {
public:
    using Pairs = std::vector<std::array<std::string, 2>>;
    SetNoCollideCommand(Document* doc, Pairs before, Pairs after, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* doc_;
    Pairs before_, after_;
};

/// Replaces the whole scene (revert, recovery).
class ReplaceSceneCommand : public QUndoCommand {
public:
    ReplaceSceneCommand(Document* doc, SceneDesc before, SceneDesc after, const QString& text);
    void undo() override;
    void redo() override;

private:
    Document* doc_;
    SceneDesc before_, after_;
};

}  // namespace tumble::ui
