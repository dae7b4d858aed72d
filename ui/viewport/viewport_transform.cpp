// The viewport's move and rotate handles (drag, snap, cancel), its collision-shape
// wireframes and whether the selection is drawn. See viewport_impl.h.
#include "viewport/viewport_handles.h"
#include "viewport/viewport_impl.h"

#include "document/body_keys.h"
#include "document/joint_presets.h"
#include "document/part_edits.h"
#include "document/placement.h"

#include <Qt3DExtras/Qt3DWindow>

#include <QUndoStack>
#include <QtMath>

namespace tumble::ui {

using namespace viewport_detail;

// ---- Handles.

Viewport::TransformMode Viewport::transformMode() const {
    return d_->mode;
}

void Viewport::setTransformMode(TransformMode mode) {
    if (mode == d_->mode) return;
    d_->mode = mode;
    d_->gizmo->setMode(mode == TransformMode::Move ? ViewportGizmo::Mode::Move : ViewportGizmo::Mode::Rotate);
    updateHandles();  // (a selected joint without an axis has nothing to turn)
    emit transformModeChanged(mode);
}

bool Viewport::handlesVisible() const {
    return d_->handlesShown;
}
QVector3D Viewport::handlesOrigin() const {
    return toQt(d_->handlesOrigin);
}
float Viewport::handlesSize() const {
    return d_->handlesSize;
}
bool Viewport::snapping() const {
    return d_->snapping;
}
void Viewport::setSnapping(bool on) {
    d_->snapping = on;
}
double Viewport::translationSnap() const {
    return d_->moveStep;
}
void Viewport::setTranslationSnap(double metres) {
    if (metres > 0) d_->moveStep = metres;
}
double Viewport::rotationSnapDegrees() const {
    return d_->turnStepDegrees;
}
void Viewport::setRotationSnapDegrees(double degrees) {
    if (degrees > 0) d_->turnStepDegrees = degrees;
}

void Viewport::updateHandles() {
    if (!d_->gizmo) return;
    const QList<int> movable = d_->movableSelection();
    const int joint = d_->handledJoint(d_->mode);
    // Edits are to the initial state: no handles while a later frame is drawn, but for one
    // animated body, which a drag there keys at that frame.
    const State* state = d_->shownFrame > 0 ? d_->frameState() : nullptr;
    const bool keying = state && movable.size() == 1 && joint < 0 && d_->handledPart() < 0 &&
                        d_->doc->body(movable.front()).motion == Motion::Animated && !d_->timeline->isStale();
    d_->handlesShown = ((!movable.isEmpty() || joint >= 0) && d_->shownFrame == 0) || keying;
    if (keying) {
        const int i = movable.front();
        d_->handlesOrigin =
            d_->dragKeying && d_->dragAxis >= 0
                ? d_->dragOrigin
                : bodyFramePosition(d_->timeline->model()->bodies[size_t(i)], state->bodies[size_t(i)]);
        const float distance = d_->camera.screenScaleAt(toQt(d_->handlesOrigin));
        d_->handlesSize = std::max(1e-3f, kHandleScale * distance);
        d_->gizmo->setPose(toQt(d_->handlesOrigin), d_->handlesSize);
    } else if (d_->handlesShown) {
        // A joint's stand on its anchor: they move it, or turn its axis.
        Vec3 sum = Vec3::Zero();
        for (int i : movable) sum += d_->doc->body(i).position;
        const int part = d_->handledPart();
        d_->handlesOrigin = joint >= 0  ? worldAnchorA(d_->doc->scene(), d_->doc->joint(joint))
                            : part >= 0 ? handles::partOrigin(d_->doc->body(movable.front()), part)
                                        : Vec3(sum / double(movable.size()));
        const float distance = d_->camera.screenScaleAt(toQt(d_->handlesOrigin));
        d_->handlesSize = std::max(1e-3f, kHandleScale * distance);
        d_->gizmo->setPose(toQt(d_->handlesOrigin), d_->handlesSize);
    }
    d_->gizmo->setVisible(d_->handlesShown);
}

int Viewport::handleAt(const QPoint& widgetPos) const {
    if (!d_->handlesShown) return -1;
    const QPointF p(widgetPos);
    // A selected ball joint's limit grips come first (they are small, and stand apart).
    if (const int j = d_->handledJoint(d_->mode); j >= 0 && d_->shownFrame == 0) {
        const JointDesc& joint = d_->doc->joint(j);
        if (const auto f = ballLimitFrame(d_->doc->scene(), joint)) {
            for (int g = 0; g < 4; ++g) {
                const auto grip = ballLimitGrip(*f, joint, g);
                if (!grip) continue;
                const QVector3D at = projectToWidget(toQt(*grip));
                if (onScreen(at) && std::hypot(at.x() - p.x(), at.y() - p.y()) < kHandleGrabPx)
                    return kLimitGrip + g;
            }
        }
    }
    const QVector3D o = toQt(d_->handlesOrigin);
    const float size = d_->handlesSize;
    const QVector3D e[3] = {QVector3D(1, 0, 0), QVector3D(0, 1, 0), QVector3D(0, 0, 1)};
    int best = -1;
    double bestDistance = kHandleGrabPx;
    for (int axis = 0; axis < 3; ++axis) {
        double distance = 1e300;
        if (d_->mode == TransformMode::Move) {
            const QVector3D a = projectToWidget(o), b = projectToWidget(o + size * e[axis]);
            if (!onScreen(a) || !onScreen(b)) continue;
            // An axis seen end-on cannot be dragged along: leave it to the others.
            if (std::hypot(b.x() - a.x(), b.y() - a.y()) < 2 * kHandleGrabPx) continue;
            distance = distanceToSegment(p, a.toPointF(), b.toPointF());
        } else {
            // The ring's polygon, as drawn (viewport_gizmo.cpp).
            const QVector3D u = e[(axis + 1) % 3], w = e[(axis + 2) % 3];
            QVector3D prev;
            for (int i = 0; i <= ViewportGizmo::kRingSegments; ++i) {
                const float t = 2.0f * float(M_PI) * float(i) / ViewportGizmo::kRingSegments;
                const QVector3D q = projectToWidget(o + size * (std::cos(t) * u + std::sin(t) * w));
                if (i > 0 && onScreen(prev) && onScreen(q)) {
                    distance = std::min(distance, distanceToSegment(p, prev.toPointF(), q.toPointF()));
                }
                prev = q;
            }
        }
        if (distance < bestDistance) {
            bestDistance = distance;
            best = axis;
        }
    }
    return best;
}

bool Viewport::beginHandleDrag(int axis, const QPoint& pos) {
    if (axis >= kLimitGrip && axis < kLimitGrip + 4 && d_->handlesShown) {  // a ball joint's limit
        const int j = d_->handledJoint(d_->mode);
        if (j < 0) return false;
        const auto f = ballLimitFrame(d_->doc->scene(), d_->doc->joint(j));
        if (!f || !ballLimitGrip(*f, d_->doc->joint(j), axis - kLimitGrip)) return false;
        d_->dragLimits = *f;
        d_->dragAxis = axis;
        d_->dragJoint = j;
        d_->dragJointStart = d_->doc->joint(j);
        d_->dragStart.clear();
        d_->dragPart = -1;
        d_->dragKeying = false;
        d_->dragKeyMoved = false;
        d_->dragMergeId = kDragMergeBase + (++d_->dragCounter & 0xffffff);
        d_->dragCommand = nullptr;
        return true;
    }
    if (axis < 0 || axis > 2 || !d_->handlesShown) return false;
    QVector3D o, dir;
    rayAt(pos, &o, &dir);
    const Vec3 a = Vec3::Unit(axis);
    const Vec3 origin = d_->handlesOrigin;
    if (d_->mode == TransformMode::Move) {
        const auto s = handles::axisParameter(toVec(o), toVec(dir), origin, a);
        if (!s) return false;
        d_->dragStartParameter = *s;
    } else {
        const auto hit = handles::planeHit(toVec(o), toVec(dir), origin, a);
        if (!hit || (*hit - origin).norm() < 1e-6) return false;
        d_->dragStartVector = *hit - origin;
    }
    d_->dragAxis = axis;
    d_->dragOrigin = origin;
    d_->dragStart.clear();
    d_->dragJoint = d_->handledJoint(d_->mode);
    d_->dragPart = d_->handledPart();
    d_->dragKeying = false;
    d_->dragKeyMoved = false;
    const State* state = d_->shownFrame > 0 ? d_->frameState() : nullptr;
    if (d_->dragJoint >= 0) {
        d_->dragJointStart = d_->doc->joint(d_->dragJoint);
    } else if (state) {
        // (The handles show at a later frame for one animated body only: updateHandles.)
        const int i = d_->movableSelection().front();
        BodyDesc drawn = d_->doc->body(i);
        const BodyState& s = state->bodies[size_t(i)];
        drawn.position = bodyFramePosition(d_->timeline->model()->bodies[size_t(i)], s);
        drawn.orientation = s.q;
        d_->dragStart.emplace_back(i, drawn);
        d_->dragKeying = true;
        d_->dragKeyTime = state->time;
    } else {
        for (int i : d_->movableSelection()) d_->dragStart.emplace_back(i, d_->doc->body(i));
    }
    d_->dragMergeId = kDragMergeBase + (++d_->dragCounter & 0xffffff);
    d_->dragCommand = nullptr;
    d_->gizmo->setHighlight(axis);
    return true;
}

void Viewport::dragHandle(const QPoint& pos, Qt::KeyboardModifiers modifiers) {
    if (d_->dragAxis < 0 || (d_->dragStart.empty() && d_->dragJoint < 0)) return;
    QVector3D o, dir;
    rayAt(pos, &o, &dir);
    const bool snap = d_->snapping || (modifiers & Qt::ControlModifier);
    if (d_->dragAxis >= kLimitGrip) {  // a ball joint's cone or twist bound, in one undo step
        const JointDesc& before = d_->dragJointStart;
        const int grip = d_->dragAxis - kLimitGrip;
        const JointDesc after = handles::draggedBallLimit(d_->dragLimits, before, grip, toVec(o), toVec(dir),
                                                          snap ? qDegreesToRadians(d_->turnStepDegrees) : 0.0);
        QUndoStack* stack = d_->doc->undoStack();
        const QUndoCommand* topBefore = stack->index() > 0 ? stack->command(stack->index() - 1) : nullptr;
        const int countBefore = stack->count();
        d_->doc->setJoint(d_->dragJoint, after,
                          (grip < 2 ? tr("Set swing cone of %1") : tr("Set twist limits of %1"))
                              .arg(QString::fromStdString(before.name)),
                          d_->dragMergeId);
        const QUndoCommand* topNow = stack->index() > 0 ? stack->command(stack->index() - 1) : nullptr;
        if (topNow != topBefore || stack->count() != countBefore) d_->dragCommand = topNow;
        return;
    }
    const Vec3 a = Vec3::Unit(d_->dragAxis);
    const bool move = d_->mode == TransformMode::Move;
    double amount = 0;  // metres or radians
    if (move) {
        const auto s = handles::axisParameter(toVec(o), toVec(dir), d_->dragOrigin, a);
        if (!s) return;
        amount = *s - d_->dragStartParameter;
        if (snap) amount = handles::snap(amount, d_->moveStep);
    } else {
        const auto hit = handles::planeHit(toVec(o), toVec(dir), d_->dragOrigin, a);
        if (!hit || (*hit - d_->dragOrigin).norm() < 1e-6) return;  // edge-on or at the centre
        amount = handles::signedAngle(d_->dragStartVector, *hit - d_->dragOrigin, a);
        if (snap) amount = handles::snap(amount, qDegreesToRadians(d_->turnStepDegrees));
    }
    const int part = d_->dragPart;
    auto apply = [&](const BodyDesc& b) {
        if (part >= 0)
            return move ? handles::partMoved(b, part, a, amount) : handles::partRotated(b, part, a, amount);
        return move ? handles::moved(b, a, amount) : handles::rotated(b, d_->dragOrigin, a, amount);
    };
    if (d_->dragKeying) {  // drawn as it goes; keyed when the drag ends
        const auto& [index, before] = d_->dragStart.front();
        d_->dragKeyPose = apply(before);
        d_->dragKeyMoved = true;
        d_->scene->setShownPose(index, toQt(d_->dragKeyPose.position), toQt(d_->dragKeyPose.orientation));
        return;
    }
    const QString verb = move ? tr("Move") : tr("Rotate");
    Document* doc = d_->doc;
    QUndoStack* stack = doc->undoStack();
    auto top = [stack]() -> const QUndoCommand* {
        return stack->index() > 0 ? stack->command(stack->index() - 1) : nullptr;
    };
    // An edit that changes nothing pushes nothing: only a new step on top is the drag's.
    const QUndoCommand* topBefore = top();
    const int countBefore = stack->count();
    if (d_->dragJoint >= 0) {
        // A joint: its anchor moves, or its axis turns; consecutive edits are one step.
        const JointDesc& before = d_->dragJointStart;
        const JointDesc after = move ? handles::movedAnchor(doc->scene(), before, a, amount)
                                     : handles::turnedAxis(doc->scene(), before, a, amount);
        doc->setJoint(d_->dragJoint, after,
                      (move ? tr("Move joint %1") : tr("Turn joint %1")).arg(QString::fromStdString(before.name)),
                      d_->dragMergeId);
    } else if (d_->dragStart.size() == 1) {
        // One body: consecutive edits with this drag's merge id are one undo step.
        const auto& [index, before] = d_->dragStart.front();
        const std::string what =
            part >= 0 ? partLabel(before.shape.parts.at(size_t(part)), part) + " of " + before.name
                      : before.name;
        BodyDesc after = apply(before);
        // Shift held while moving a body: it rests on the surface under it (placement.h).
        if (move && part < 0 && (modifiers & Qt::ShiftModifier)) {
            if (!d_->settler || d_->settlerDrag != d_->dragMergeId) {
                d_->settler = std::make_shared<Settler>(doc->scene(), index);
                d_->settlerDrag = d_->dragMergeId;
            }
            after = d_->settler->settle(after);
        }
        doc->setBody(index, after, tr("%1 %2").arg(verb, QString::fromStdString(what)), d_->dragMergeId);
    } else {
        // Several: a macro cannot merge, so the drag's previous macro is undone and replaced.
        if (dragCommandOnTop()) stack->undo();
        const QString text = tr("%1 %n bodies", nullptr, int(d_->dragStart.size())).arg(verb);
        doc->beginMacro(text);
        for (const auto& [index, before] : d_->dragStart) doc->setBody(index, apply(before), text);
        doc->endMacro();
    }
    if (top() != topBefore || stack->count() != countBefore) d_->dragCommand = top();
}

bool Viewport::dragCommandOnTop() const {
    const QUndoStack* stack = d_->doc->undoStack();
    return d_->dragCommand && !stack->canRedo() && stack->index() > 0 &&
           stack->command(stack->index() - 1) == d_->dragCommand;
}

void Viewport::cancelHandleDrag() {
    if (d_->dragAxis < 0) return;
    if (d_->dragKeying) {  // nothing was keyed: the frame is drawn as recorded again
        d_->dragKeyMoved = false;
        d_->dragButton = Qt::NoButton;
        endHandleDrag();
        refreshPlayback();
        return;
    }
    // The drag's step is undone (the bodies go back) and then dropped from the stack: an
    // obsolete command is deleted by QUndoStack::redo() instead of being redone, so neither
    // an undo nor a redo step is left behind.
    if (dragCommandOnTop()) {
        QUndoStack* stack = d_->doc->undoStack();
        stack->undo();
        const_cast<QUndoCommand*>(stack->command(stack->index()))->setObsolete(true);
        stack->redo();
    }
    d_->dragButton = Qt::NoButton;  // the button's release is then ignored
    endHandleDrag();
}

void Viewport::endHandleDrag() {
    if (d_->dragKeying && d_->dragKeyMoved && !d_->dragStart.empty()) {
        const int index = d_->dragStart.front().first;
        BodyDesc b = d_->doc->body(index);
        insertKey(b, d_->dragKeyTime, d_->dragKeyPose.position, d_->dragKeyPose.orientation);
        d_->dragKeying = false;  // (the edit below redraws the handles: not mid-drag any more)
        d_->doc->setBody(
            index, b,
            tr("Key %1 at %2 s").arg(QString::fromStdString(b.name)).arg(d_->dragKeyTime, 0, 'g', 6));
    }
    d_->dragKeying = false;
    d_->dragKeyMoved = false;
    d_->dragAxis = -1;
    d_->dragStart.clear();
    d_->dragJoint = -1;
    d_->dragPart = -1;
    d_->dragCommand = nullptr;
    d_->gizmo->setHighlight(-1);
    d_->hover = -1;
    updateHandles();
}

// ---- Collision shapes.

bool Viewport::showCollisionShapes() const {
    return d_->scene->showCollisionShapes();
}

int Viewport::collisionShapeCount() const {
    return d_->scene->collisionShapeCount();
}

void Viewport::setShowCollisionShapes(bool show) {
    if (show == d_->scene->showCollisionShapes()) return;
    d_->scene->setShowCollisionShapes(show);
    emit showCollisionShapesChanged(show);
}

bool Viewport::selectionShown() const {
    return d_->selectionShown;
}

void Viewport::setSelectionShown(bool shown) {
    if (shown == d_->selectionShown) return;
    if (!shown && d_->dragAxis >= 0) cancelHandleDrag();
    d_->selectionShown = shown;
    d_->scene->setSelection(d_->shownSelection());
    updateHandles();
}

}  // namespace tumble::ui
