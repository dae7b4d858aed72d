// The widget side of the viewport: the Qt3D window in a container, the orbit camera, mouse
// and keys, picking. The camera's matrices are ours (OrbitCamera) and the Qt3D camera is
// set from them, so picking and projectToWidget are exact functions of the camera and the
// document, never of what the render thread last drew.
#include "viewport.h"

#include "document.h"
#include "viewport_camera.h"
#include "viewport_raycast.h"
#include "viewport_scene.h"

#include <tumble/mass.h>

#include <Qt3DCore/QEntity>
#include <Qt3DExtras/QForwardRenderer>
#include <Qt3DExtras/Qt3DWindow>
#include <Qt3DRender/QCamera>
#include <Qt3DRender/QRenderSettings>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QVBoxLayout>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

namespace {

// How far the press may move before it is a drag rather than a click (pixels).
constexpr int kClickSlop = 4;

// A bounding sphere of a body's shape in world space; false for planes (unbounded).
bool boundingSphere(const BodyDesc& b, Vec3* centre, double* radius) {
    const ShapeDesc& s = b.shape;
    *centre = b.position;
    switch (s.type) {
        case ShapeType::Sphere: *radius = s.radius; return true;
        case ShapeType::Box: *radius = s.halfExtents.norm(); return true;
        case ShapeType::Capsule: *radius = s.radius + s.halfHeight; return true;
        case ShapeType::Cylinder: *radius = std::hypot(s.radius, s.halfHeight); return true;
        case ShapeType::Plane: return false;
        case ShapeType::Mesh: {
            double r = 0.5;
            if (s.meshData && !s.meshData->vertices.empty()) {
                r = 0;
                for (const Vec3& v : s.meshData->vertices) r = std::max(r, v.norm());
            }
            *radius = r;
            return true;
        }
    }
    return false;
}

}  // namespace

struct Viewport::Impl {
    Document* doc = nullptr;
    Qt3DExtras::Qt3DWindow* window = nullptr;
    QWidget* container = nullptr;
    Qt3DCore::QEntity* root = nullptr;
    std::unique_ptr<ViewportScene> scene;
    OrbitCamera camera;

    // Mouse drag state.
    Qt::MouseButton dragButton = Qt::NoButton;
    QPoint pressPos;
    QPoint lastPos;
    bool dragged = false;
};

Viewport::Viewport(Document* document, QWidget* parent) : QWidget(parent), d_(std::make_unique<Impl>()) {
    d_->doc = document;
    d_->window = new Qt3DExtras::Qt3DWindow();
    d_->window->defaultFrameGraph()->setClearColor(QColor(48, 50, 56));
    d_->window->renderSettings()->setRenderPolicy(Qt3DRender::QRenderSettings::OnDemand);
    d_->window->installEventFilter(this);

    d_->root = new Qt3DCore::QEntity();
    d_->scene = std::make_unique<ViewportScene>(d_->root);
    d_->window->setRootEntity(d_->root);

    d_->container = QWidget::createWindowContainer(d_->window, this);
    d_->container->setFocusPolicy(Qt::StrongFocus);
    d_->container->setMinimumSize(200, 150);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(d_->container);
    setFocusPolicy(Qt::StrongFocus);
    setFocusProxy(d_->container);

    connect(document, &Document::sceneReset, this, [this] {
        d_->scene->rebuild(d_->doc->scene());
        d_->scene->setSelection(d_->doc->selection());
    });
    connect(document, &Document::bodyInserted, this, [this](int i) {
        d_->scene->insert(i, d_->doc->body(i));
        d_->scene->setSelection(d_->doc->selection());
    });
    connect(document, &Document::bodyRemoved, this, [this](int i) {
        d_->scene->remove(i);
        d_->scene->setSelection(d_->doc->selection());
    });
    connect(document, &Document::bodyChanged, this,
            [this](int i) { d_->scene->update(i, d_->doc->body(i)); });
    connect(document, &Document::selectionChanged, this,
            [this] { d_->scene->setSelection(d_->doc->selection()); });

    d_->scene->rebuild(document->scene());
    d_->scene->setSelection(document->selection());
    syncCamera();
}

Viewport::~Viewport() {
    // The scene's entities belong to the root, which the window owns once set; the window
    // belongs to the container. Drop our bookkeeping first.
    d_->scene.reset();
}

QWindow* Viewport::renderWindow() const {
    return d_->window;
}

int Viewport::entityCount() const {
    return d_->scene->count();
}

QVector3D Viewport::cameraPosition() const {
    return d_->camera.eye();
}
QVector3D Viewport::cameraTarget() const {
    return d_->camera.target();
}
float Viewport::cameraDistance() const {
    return d_->camera.distance();
}

void Viewport::setCamera(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees) {
    d_->camera.set(target, distance, yawDegrees, pitchDegrees);
    syncCamera();
}

void Viewport::syncCamera() {
    Qt3DRender::QCamera* cam = d_->window->camera();
    const float w = float(std::max(1, width()));
    const float h = float(std::max(1, height()));
    cam->lens()->setPerspectiveProjection(d_->camera.fieldOfViewDegrees(), w / h, d_->camera.nearPlane(),
                                          d_->camera.farPlane());
    cam->setPosition(d_->camera.eye());
    cam->setViewCenter(d_->camera.target());
    cam->setUpVector(d_->camera.up());
}

QVector3D Viewport::projectToWidget(const QVector3D& world) const {
    return d_->camera.project(world, float(std::max(1, width())), float(std::max(1, height())));
}

int Viewport::bodyAt(const QPoint& widgetPos) const {
    QVector3D o, dir;
    d_->camera.rayThrough(float(widgetPos.x()), float(widgetPos.y()), float(std::max(1, width())),
                          float(std::max(1, height())), &o, &dir);
    const Ray ray{Vec3(o.x(), o.y(), o.z()), Vec3(dir.x(), dir.y(), dir.z())};
    int best = -1;
    double bestT = 0;
    const SceneDesc& scene = d_->doc->scene();
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        const BodyDesc& b = scene.bodies[i];
        const auto t = rayShape(ray, b.shape, b.position, b.orientation);
        if (t && (best < 0 || *t < bestT)) {
            best = int(i);
            bestT = *t;
        }
    }
    return best;
}

void Viewport::clickAt(const QPoint& widgetPos, Qt::KeyboardModifiers modifiers) {
    const int hit = bodyAt(widgetPos);
    const bool toggle = modifiers & Qt::ControlModifier;
    QList<int> selection = d_->doc->selection();
    if (toggle) {
        if (hit < 0) return;
        if (selection.contains(hit)) {
            selection.removeAll(hit);
        } else {
            selection.append(hit);
        }
    } else {
        selection.clear();
        if (hit >= 0) selection.append(hit);
    }
    d_->doc->setSelection(selection);
}

void Viewport::frameSelection() {
    frameBodies(d_->doc->selection());
}

void Viewport::frameAll() {
    frameBodies({});
}

void Viewport::frameBodies(const QList<int>& indices) {
    const SceneDesc& scene = d_->doc->scene();
    // The bounding box of the bodies' bounding spheres, then its enclosing sphere.
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    bool any = false;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        if (!indices.isEmpty() && !indices.contains(int(i))) continue;
        Vec3 c;
        double r;
        if (!boundingSphere(scene.bodies[i], &c, &r)) continue;
        lo = lo.cwiseMin(c - Vec3::Constant(r));
        hi = hi.cwiseMax(c + Vec3::Constant(r));
        any = true;
    }
    if (!any) {
        if (!indices.isEmpty()) return frameAll();  // only planes selected: show everything
        d_->camera.frame(QVector3D(0, 0, 0), 5.0f);
    } else {
        const Vec3 c = 0.5 * (lo + hi);
        const double r = 0.5 * (hi - lo).norm();
        d_->camera.frame(QVector3D(float(c.x()), float(c.y()), float(c.z())), float(r));
    }
    syncCamera();
}

void Viewport::resizeEvent(QResizeEvent* event) {
    QWidget::resizeEvent(event);
    syncCamera();
}

void Viewport::keyPressEvent(QKeyEvent* event) {
    if (!handleKey(event)) QWidget::keyPressEvent(event);
}

bool Viewport::handleKey(QKeyEvent* event) {
    OrbitCamera& cam = d_->camera;
    const float step = (event->modifiers() & Qt::ShiftModifier) ? 2.0f : 10.0f;
    switch (event->key()) {
        case Qt::Key_F: frameSelection(); return true;
        case Qt::Key_A:
        case Qt::Key_Home: frameAll(); return true;
        case Qt::Key_Left: cam.orbit(-step, 0); break;
        case Qt::Key_Right: cam.orbit(step, 0); break;
        case Qt::Key_Up: cam.orbit(0, step); break;
        case Qt::Key_Down: cam.orbit(0, -step); break;
        case Qt::Key_Plus:
        case Qt::Key_Equal: cam.zoom(1.0f / 1.15f); break;
        case Qt::Key_Minus: cam.zoom(1.15f); break;
        default: return false;
    }
    syncCamera();
    return true;
}

bool Viewport::eventFilter(QObject* watched, QEvent* event) {
    if (watched != d_->window) return QWidget::eventFilter(watched, event);
    switch (event->type()) {
        case QEvent::MouseButtonPress: {
            auto* e = static_cast<QMouseEvent*>(event);
            if (d_->dragButton == Qt::NoButton) {
                d_->dragButton = e->button();
                d_->pressPos = d_->lastPos = e->position().toPoint();
                d_->dragged = false;
            }
            d_->container->setFocus(Qt::MouseFocusReason);
            return true;
        }
        case QEvent::MouseMove: {
            auto* e = static_cast<QMouseEvent*>(event);
            if (d_->dragButton == Qt::NoButton) return false;
            const QPoint p = e->position().toPoint();
            if (!d_->dragged && (p - d_->pressPos).manhattanLength() < kClickSlop) return true;
            d_->dragged = true;
            const QPoint delta = p - d_->lastPos;
            d_->lastPos = p;
            const bool pan = d_->dragButton == Qt::MiddleButton ||
                             (d_->dragButton == Qt::LeftButton && (e->modifiers() & Qt::ShiftModifier));
            if (pan) {
                d_->camera.pan(float(delta.x()), float(delta.y()), float(std::max(1, height())));
            } else if (d_->dragButton == Qt::RightButton) {
                d_->camera.zoom(std::pow(1.01f, float(delta.y())));
            } else {
                d_->camera.orbit(-0.4f * float(delta.x()), 0.4f * float(delta.y()));
            }
            syncCamera();
            return true;
        }
        case QEvent::MouseButtonRelease: {
            auto* e = static_cast<QMouseEvent*>(event);
            if (e->button() != d_->dragButton) return true;
            if (!d_->dragged && d_->dragButton == Qt::LeftButton) {
                clickAt(e->position().toPoint(), e->modifiers());
            }
            d_->dragButton = Qt::NoButton;
            return true;
        }
        case QEvent::Wheel: {
            auto* e = static_cast<QWheelEvent*>(event);
            d_->camera.zoom(std::pow(0.999f, float(e->angleDelta().y())));
            syncCamera();
            return true;
        }
        case QEvent::KeyPress: return handleKey(static_cast<QKeyEvent*>(event));
        default: return false;
    }
}

}  // namespace tumble::ui
