#include "document/commands.h"

#include "document/document.h"

namespace tumble::ui {

SetBodyCommand::SetBodyCommand(Document* doc, int index, BodyDesc before, BodyDesc after, const QString& text,
                               int mergeId)
    : QUndoCommand(text),
      doc_(doc),
      index_(index),
      before_(std::move(before)),
      after_(std::move(after)),
      mergeId_(mergeId) {}

void SetBodyCommand::undo() {
    doc_->applyBody(index_, before_);
}
void SetBodyCommand::redo() {
    doc_->applyBody(index_, after_);
}

bool SetBodyCommand::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetBodyCommand*>(other);
    if (o->mergeId_ != mergeId_ || o->index_ != index_) return false;
    after_ = o->after_;
    setText(o->text());  // the last value's words ("... to 25 kg")
    return true;
}

SetSettingsCommand::SetSettingsCommand(Document* doc, Settings before, Settings after, const QString& text,
                                       int mergeId)
    : QUndoCommand(text),
      doc_(doc),
      before_(std::move(before)),
      after_(std::move(after)),
      mergeId_(mergeId) {}

void SetSettingsCommand::undo() {
    doc_->applySettings(before_);
}
void SetSettingsCommand::redo() {
    doc_->applySettings(after_);
}

bool SetSettingsCommand::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetSettingsCommand*>(other);
    if (o->mergeId_ != mergeId_) return false;
    after_ = o->after_;
    setText(o->text());  // the last value's words ("... to 25 kg")
    return true;
}

InsertBodyCommand::InsertBodyCommand(Document* doc, int index, BodyDesc body, bool remove,
                                     const QString& text, QUndoCommand* parent)
    : QUndoCommand(text, parent), doc_(doc), index_(index), body_(std::move(body)), remove_(remove) {}

void InsertBodyCommand::undo() {
    if (remove_)
        doc_->applyInsert(index_, body_);
    else
        doc_->applyRemove(index_);
}

void InsertBodyCommand::redo() {
    if (remove_)
        doc_->applyRemove(index_);
    else
        doc_->applyInsert(index_, body_);
}

SetJointsCommand::SetJointsCommand(Document* doc, std::vector<JointDesc> before, std::vector<JointDesc> after,
                                   const QString& text, int mergeId)
    : QUndoCommand(text), doc_(doc), before_(std::move(before)), after_(std::move(after)), mergeId_(mergeId) {}

void SetJointsCommand::undo() {
    doc_->applyJoints(before_);
}
void SetJointsCommand::redo() {
    doc_->applyJoints(after_);
}

bool SetJointsCommand::mergeWith(const QUndoCommand* other) {
    const auto* o = static_cast<const SetJointsCommand*>(other);
    if (o->mergeId_ != mergeId_ || o->before_ != after_ || o->after_.size() != after_.size()) return false;
    after_ = o->after_;
    setText(o->text());  // the last value's words ("... to 25 kg")
    return true;
}

SetNoCollideCommand::SetNoCollideCommand(Document* doc, Pairs before, Pairs after, const QString& text)
    : QUndoCommand(text), doc_(doc), before_(std::move(before)), after_(std::move(after)) {}

void SetNoCollideCommand::undo() {
    doc_->applyNoCollide(before_);
}
void SetNoCollideCommand::redo() {
    doc_->applyNoCollide(after_);
}

ReplaceSceneCommand::ReplaceSceneCommand(Document* doc, SceneDesc before, SceneDesc after,
                                         const QString& text)
    : QUndoCommand(text), doc_(doc), before_(std::move(before)), after_(std::move(after)) {}

void ReplaceSceneCommand::undo() {
    doc_->applyScene(before_);
}
void ReplaceSceneCommand::redo() {
    doc_->applyScene(after_);
}

}  // namespace tumble::ui
