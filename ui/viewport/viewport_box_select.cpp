// Box select (issue 52): Edit > Box Select (B) arms it; the next left drag in the view draws
// a rubber band and selects the bodies whose centres (where the view draws them: the
// document's poses, or the frame at the playhead) fall inside it. Ctrl at the release adds
// them to the selection. Planes have no centre to enclose and are left out.
#include "viewport/viewport_impl.h"

#include <tumble/collision.h>

namespace tumble::ui {

using namespace viewport_detail;

void Viewport::armBoxSelect() {
    d_->boxArmed = true;
    d_->container->setCursor(Qt::CrossCursor);
}

bool Viewport::boxSelectArmed() const {
    return d_->boxArmed;
}

bool Viewport::boxPress(const QPoint& pos) {
    if (!d_->boxArmed) return false;
    d_->boxing = true;
    d_->dragButton = Qt::LeftButton;
    d_->pressPos = d_->lastPos = pos;
    d_->dragged = false;
    if (!d_->band) d_->band = std::make_unique<QRubberBand>(QRubberBand::Rectangle);  // top level
    return true;
}

bool Viewport::boxMove(const QPoint& pos) {
    if (!d_->boxing) return false;
    d_->dragged = true;
    const QRect rect = QRect(d_->pressPos, pos).normalized();
    d_->band->setGeometry(QRect(d_->container->mapToGlobal(rect.topLeft()), rect.size()));
    d_->band->show();
    return true;
}

bool Viewport::boxRelease(const QPoint& pos, Qt::KeyboardModifiers modifiers) {
    if (!d_->boxing) return false;
    d_->boxing = d_->boxArmed = false;
    d_->dragButton = Qt::NoButton;
    d_->band->hide();
    d_->container->unsetCursor();
    const QRect rect = QRect(d_->pressPos, pos).normalized();
    const SceneDesc& scene = d_->doc->scene();
    const State* state = d_->shownFrame > 0 ? d_->frameState() : nullptr;
    const auto model = state ? d_->timeline->model() : nullptr;
    QList<int> inside = modifiers & Qt::ControlModifier ? d_->doc->selection() : QList<int>{};
    for (int i = 0; i < static_cast<int>(scene.bodies.size()); ++i) {
        if (scene.bodies[i].shape.type == ShapeType::Plane || inside.contains(i)) continue;
        const Vec3 at = state ? bodyFramePosition(model->bodies[i], state->bodies[i]) : scene.bodies[i].position;
        const QVector3D p = projectToWidget(toQt(at));
        if (p.z() < -1.0f || p.z() > 1.0f) continue;  // behind the camera or past its far plane
        if (rect.contains(QPoint(qRound(p.x()), qRound(p.y())))) inside.append(i);
    }
    d_->doc->setSelection(inside);
    return true;
}

}  // namespace tumble::ui
