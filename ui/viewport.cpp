// The widget side of the viewport: the Qt3D window in a container, the orbit camera, mouse
// and keys, picking. The camera's matrices are ours (OrbitCamera) and the Qt3D camera is
// set from them, so picking and projectToWidget are exact functions of the camera and the
// document, never of what the render thread last drew.
#include "viewport.h"

#include <tumble/raycast.h>

#include "document.h"
#include "timeline.h"
#include "viewport_camera.h"
#include "viewport_gizmo.h"
#include "viewport_handles.h"
#include "viewport_overlays.h"
#include "viewport_raycast.h"
#include "viewport_scene.h"

#include <tumble/mass.h>

#include <Qt3DCore/QEntity>
#include <Qt3DExtras/Qt3DWindow>
#include <Qt3DRender/QCamera>
#include <Qt3DRender/QCameraSelector>
#include <Qt3DRender/QClearBuffers>
#include <Qt3DRender/QCullFace>
#include <Qt3DRender/QDepthTest>
#include <Qt3DRender/QLayer>
#include <Qt3DRender/QLayerFilter>
#include <Qt3DRender/QRenderSettings>
#include <Qt3DRender/QRenderStateSet>
#include <Qt3DRender/QRenderSurfaceSelector>
#include <Qt3DRender/QViewport>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QPointer>
#include <QSurfaceFormat>
#include <QUndoStack>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <QtMath>

#include <algorithm>
#include <array>
#include <cmath>

namespace tumble::ui {

namespace {

// How far the press may move before it is a drag rather than a click (pixels).
constexpr int kClickSlop = 4;
// How near a handle the cursor must be to grab it (pixels).
constexpr double kHandleGrabPx = 8.0;
// Handle size: this fraction of the distance from the camera (about a sixth of the view).
constexpr float kHandleScale = 0.13f;
// Merge ids of handle drags: a new one per drag, in a range of their own.
constexpr int kDragMergeBase = 0x48000000;

Vec3 toVec(const QVector3D& v) {
    return Vec3(v.x(), v.y(), v.z());
}
QVector3D toQt(const Vec3& v) {
    return QVector3D(float(v.x()), float(v.y()), float(v.z()));
}
QQuaternion toQt(const Quat& q) {
    const Quat n = q.normalized();
    return QQuaternion(float(n.w()), float(n.x()), float(n.y()), float(n.z()));
}

double distanceToSegment(const QPointF& p, const QPointF& a, const QPointF& b) {
    const QPointF ab = b - a;
    const double len2 = QPointF::dotProduct(ab, ab);
    double t = len2 > 0 ? QPointF::dotProduct(p - a, ab) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const QPointF d = p - (a + t * ab);
    return std::hypot(d.x(), d.y());
}

bool onScreen(const QVector3D& projected) {
    return projected.z() >= -1.0f && projected.z() <= 1.0f;
}

// A bounding sphere of a body's shape in world space, its frame at `position`; false for
// planes (unbounded).
bool boundingSphere(const BodyDesc& b, const Vec3& position, Vec3* centre, double* radius) {
    const ShapeDesc& s = b.shape;
    *centre = position;
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

// The GL renderer's name, asked once of a throwaway context on an offscreen surface (the
// same platform and driver Qt3D's context will get). Empty when no context can be made.
QString queryGlRenderer() {
    QOffscreenSurface surface;
    surface.setFormat(QSurfaceFormat::defaultFormat());
    surface.create();
    QOpenGLContext context;
    context.setFormat(QSurfaceFormat::defaultFormat());
    if (!surface.isValid() || !context.create() || !context.makeCurrent(&surface)) return {};
    const auto* name = reinterpret_cast<const char*>(context.functions()->glGetString(GL_RENDERER));
    const QString renderer = name ? QString::fromLatin1(name) : QString();
    context.doneCurrent();
    return renderer;
}

// Samples per pixel for the 3D view: 4 (Qt3DWindow's own choice), or none on a software
// renderer, where multisampling multiplies the cost of every pixel (llvmpipe rasterises and
// shades each sample on the CPU). TUMBLE_VIEWPORT_SAMPLES=n overrides (for measurements).
int viewportSamples() {
    static const int samples = [] {
        bool set = false;
        const int forced = qEnvironmentVariableIntValue("TUMBLE_VIEWPORT_SAMPLES", &set);
        if (set) return std::max(0, forced);
        return Viewport::isSoftwareRenderer(Viewport::glRenderer()) ? 0 : 4;
    }();
    return samples;
}

}  // namespace

QString Viewport::glRenderer() {
    static const QString renderer = queryGlRenderer();
    return renderer;
}

bool Viewport::isSoftwareRenderer(const QString& renderer) {
    for (const char* name : {"llvmpipe", "softpipe", "swrast", "Software Rasterizer", "SwiftShader"}) {
        if (renderer.contains(QLatin1String(name), Qt::CaseInsensitive)) return true;
    }
    return false;
}

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

    // Handles.
    std::unique_ptr<ViewportGizmo> gizmo;
    TransformMode mode = TransformMode::Move;
    bool handlesShown = false;
    Vec3 handlesOrigin = Vec3::Zero();
    float handlesSize = 1.0f;
    int hover = -1;
    bool snapping = false;
    double moveStep = 0.1;
    double turnStepDegrees = 15.0;
    // A handle drag: the axis (-1: none), where it started, the bodies as they were.
    int dragAxis = -1;
    Vec3 dragOrigin = Vec3::Zero();
    double dragStartParameter = 0.0;
    Vec3 dragStartVector = Vec3::Zero();
    std::vector<std::pair<int, BodyDesc>> dragStart;
    int dragMergeId = 0;
    int dragCounter = 0;
    const QUndoCommand* dragCommand = nullptr;  // the drag's undo step so far (null: none yet)

    // Playback.
    QPointer<Timeline> timeline;
    std::vector<QMetaObject::Connection> timelineConnections;
    int shownFrame = 0;  // > 0: the timeline's frame is drawn
    std::unique_ptr<ViewportOverlays> overlays;
    std::array<bool, kOverlayCount> overlayOn{};
    int asleepCount = 0;
    // Trails: each body's centre-of-mass track as far as it was asked of the timeline (the
    // frames and positions), dropped when a new run starts.
    std::vector<std::vector<int>> trackFrames;
    std::vector<std::vector<Vec3>> trackPoints;
    std::vector<std::vector<Vec3>> trails;  // as drawn

    /// The timeline's state at the playhead when it can be drawn over the document: a
    /// model with the document's number of bodies.
    const State* frameState() const {
        if (!timeline || !timeline->hasCurrentState()) return nullptr;
        const auto model = timeline->model();
        const State& state = timeline->currentState();
        const size_t n = size_t(doc->bodyCount());
        if (!model || model->bodies.size() != n || state.bodies.size() != n) return nullptr;
        return &state;
    }

    /// Whether the selection is drawn (highlight and handles); off in an image export's view.
    bool selectionShown = true;
    QList<int> shownSelection() const { return selectionShown ? doc->selection() : QList<int>(); }

    /// The selected bodies a handle can move (planes cannot).
    QList<int> movableSelection() const {
        QList<int> out;
        for (int i : shownSelection()) {
            if (i >= 0 && i < doc->bodyCount() && doc->body(i).shape.type != ShapeType::Plane) out.append(i);
        }
        return out;
    }
};

Viewport::Viewport(Document* document, QWidget* parent) : QWidget(parent), d_(std::make_unique<Impl>()) {
    d_->doc = document;
    d_->window = new Qt3DExtras::Qt3DWindow();
    // Qt3DWindow asks for 4x multisampling (and makes it the default format); that is kept
    // on a GPU and dropped on a software renderer (viewportSamples), before the window's
    // surface exists.
    const int samples = viewportSamples();
    if (d_->window->format().samples() != samples) {
        QSurfaceFormat format = d_->window->format();
        format.setSamples(samples);
        d_->window->setFormat(format);
        QSurfaceFormat::setDefaultFormat(format);
    }
    d_->window->renderSettings()->setRenderPolicy(Qt3DRender::QRenderSettings::OnDemand);
    d_->window->installEventFilter(this);

    d_->root = new Qt3DCore::QEntity();
    d_->scene = std::make_unique<ViewportScene>(d_->root);
    d_->gizmo = std::make_unique<ViewportGizmo>(d_->root);
    d_->overlays = std::make_unique<ViewportOverlays>(d_->root);

    // Two passes: the scene, then the overlay layer (the handles) with no depth test and
    // back faces culled, so no body hides them. (The RHI renderer ignores depth-range
    // states, and a depth-only clear between the passes loses the clear colour.)
    auto* overlay = new Qt3DRender::QLayer(d_->root);
    overlay->setRecursive(true);
    d_->gizmo->entity()->addComponent(overlay);
    d_->overlays->entity()->addComponent(overlay);
    auto* surface = new Qt3DRender::QRenderSurfaceSelector();
    surface->setSurface(d_->window);
    auto* viewport = new Qt3DRender::QViewport(surface);
    auto* cameraSelector = new Qt3DRender::QCameraSelector(viewport);
    cameraSelector->setCamera(d_->window->camera());
    auto* clearAll = new Qt3DRender::QClearBuffers(cameraSelector);
    clearAll->setBuffers(Qt3DRender::QClearBuffers::ColorDepthBuffer);
    clearAll->setClearColor(QColor(48, 50, 56));
    auto* sceneFilter = new Qt3DRender::QLayerFilter(clearAll);
    sceneFilter->addLayer(overlay);
    sceneFilter->setFilterMode(Qt3DRender::QLayerFilter::DiscardAnyMatchingLayers);
    auto* overlayStates = new Qt3DRender::QRenderStateSet(cameraSelector);
    auto* always = new Qt3DRender::QDepthTest(overlayStates);
    always->setDepthFunction(Qt3DRender::QDepthTest::Always);
    overlayStates->addRenderState(always);
    auto* cull = new Qt3DRender::QCullFace(overlayStates);
    cull->setMode(Qt3DRender::QCullFace::Back);
    overlayStates->addRenderState(cull);
    auto* overlayFilter = new Qt3DRender::QLayerFilter(overlayStates);
    overlayFilter->addLayer(overlay);
    overlayFilter->setFilterMode(Qt3DRender::QLayerFilter::AcceptAnyMatchingLayers);
    d_->window->setActiveFrameGraph(surface);
    d_->window->setRootEntity(d_->root);

    d_->container = QWidget::createWindowContainer(d_->window, this);
    d_->container->setFocusPolicy(Qt::StrongFocus);
    d_->container->setMinimumSize(200, 150);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(d_->container);
    setFocusPolicy(Qt::StrongFocus);
    setFocusProxy(d_->container);

    // A drag in progress ends when the bodies it holds may be gone.
    auto cancelDrag = [this] {
        d_->dragAxis = -1;
        d_->dragStart.clear();
        d_->dragCommand = nullptr;
    };
    connect(document, &Document::sceneReset, this, [this, cancelDrag] {
        cancelDrag();
        d_->scene->rebuild(d_->doc->scene());
        d_->scene->setSelection(d_->shownSelection());
        refreshPlayback();
        updateHandles();
    });
    connect(document, &Document::bodyInserted, this, [this, cancelDrag](int i) {
        cancelDrag();
        d_->scene->insert(i, d_->doc->body(i));
        d_->scene->setSelection(d_->shownSelection());
        refreshPlayback();
        updateHandles();
    });
    connect(document, &Document::bodyRemoved, this, [this, cancelDrag](int i) {
        cancelDrag();
        d_->scene->remove(i);
        d_->scene->setSelection(d_->shownSelection());
        refreshPlayback();
        updateHandles();
    });
    connect(document, &Document::bodyChanged, this, [this](int i) {
        d_->scene->update(i, d_->doc->body(i));
        updateHandles();
    });
    connect(document, &Document::selectionChanged, this, [this] {
        d_->scene->setSelection(d_->shownSelection());
        updateHandles();
    });

    d_->scene->rebuild(document->scene());
    d_->scene->setSelection(d_->shownSelection());
    syncCamera();
}

Viewport::~Viewport() {
    // The scene's entities belong to the root, which the window owns once set; the window
    // belongs to the container. Drop our bookkeeping first.
    for (const auto& c : d_->timelineConnections) disconnect(c);
    d_->overlays.reset();
    d_->gizmo.reset();
    d_->scene.reset();
}

int Viewport::samples() const {
    return d_->window->format().samples();
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
    updateHandles();  // their size follows the distance
}

QVector3D Viewport::projectToWidget(const QVector3D& world) const {
    return d_->camera.project(world, float(std::max(1, width())), float(std::max(1, height())));
}

void Viewport::rayAt(const QPoint& widgetPos, QVector3D* origin, QVector3D* direction) const {
    d_->camera.rayThrough(float(widgetPos.x()), float(widgetPos.y()), float(std::max(1, width())),
                          float(std::max(1, height())), origin, direction);
}

int Viewport::bodyAt(const QPoint& widgetPos) const {
    QVector3D o, dir;
    rayAt(widgetPos, &o, &dir);
    // The engine's ray cast: nearest body, ties to the lower index. At a recorded frame,
    // against the bodies where they are drawn.
    if (d_->shownFrame > 0) {
        if (const State* state = d_->frameState()) {
            const auto hit = rayCast(*d_->timeline->model(), *state, toVec(o), toVec(dir));
            return hit ? hit->body : -1;
        }
    }
    const auto hit = rayCastScene(d_->doc->scene(), toVec(o), toVec(dir));
    return hit ? hit->body : -1;
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
    // Where the bodies are drawn: the document, or the frame at the playhead.
    const State* state = d_->shownFrame > 0 ? d_->frameState() : nullptr;
    const auto model = state ? d_->timeline->model() : nullptr;
    // The bounding box of the bodies' bounding spheres, then its enclosing sphere.
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    bool any = false;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        if (!indices.isEmpty() && !indices.contains(int(i))) continue;
        Vec3 c;
        double r;
        const Vec3 position =
            state ? bodyFramePosition(model->bodies[i], state->bodies[i]) : scene.bodies[i].position;
        if (!boundingSphere(scene.bodies[i], position, &c, &r)) continue;
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
    // Left, Right, Home, End and Space belong to the timeline (the main window's shortcuts):
    // the keyboard orbit is Shift + arrows (plain Up and Down too).
    constexpr float step = 10.0f;
    const bool shift = event->modifiers() & Qt::ShiftModifier;
    switch (event->key()) {
        case Qt::Key_Escape:
            if (d_->dragAxis < 0) return false;
            cancelHandleDrag();
            return true;
        case Qt::Key_F: frameSelection(); return true;
        case Qt::Key_W: setTransformMode(TransformMode::Move); return true;
        case Qt::Key_E: setTransformMode(TransformMode::Rotate); return true;
        case Qt::Key_A: frameAll(); return true;
        case Qt::Key_Left:
            if (!shift) return false;
            cam.orbit(-step, 0);
            break;
        case Qt::Key_Right:
            if (!shift) return false;
            cam.orbit(step, 0);
            break;
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
            const QPoint p = e->position().toPoint();
            if (d_->dragButton == Qt::NoButton && e->button() == Qt::LeftButton &&
                !(e->modifiers() & Qt::ShiftModifier) && beginHandleDrag(handleAt(p), p)) {
                d_->dragButton = Qt::LeftButton;
                d_->pressPos = d_->lastPos = p;
                d_->dragged = true;  // never a click
            } else if (d_->dragButton == Qt::NoButton) {
                d_->dragButton = e->button();
                d_->pressPos = d_->lastPos = e->position().toPoint();
                d_->dragged = false;
            }
            d_->container->setFocus(Qt::MouseFocusReason);
            return true;
        }
        case QEvent::MouseMove: {
            auto* e = static_cast<QMouseEvent*>(event);
            const QPoint p = e->position().toPoint();
            if (d_->dragAxis >= 0) {
                dragHandle(p, e->modifiers());
                return true;
            }
            if (d_->dragButton == Qt::NoButton) {
                const int h = handleAt(p);
                if (h != d_->hover) d_->gizmo->setHighlight(d_->hover = h);
                return false;
            }
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
            if (d_->dragAxis >= 0) {
                dragHandle(e->position().toPoint(), e->modifiers());  // where and how it ends
                endHandleDrag();
            } else if (!d_->dragged && d_->dragButton == Qt::LeftButton) {
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

// ---- Handles.

Viewport::TransformMode Viewport::transformMode() const {
    return d_->mode;
}

void Viewport::setTransformMode(TransformMode mode) {
    if (mode == d_->mode) return;
    d_->mode = mode;
    d_->gizmo->setMode(mode == TransformMode::Move ? ViewportGizmo::Mode::Move : ViewportGizmo::Mode::Rotate);
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
    // Edits are to the initial state: no handles while a later frame is drawn.
    d_->handlesShown = !movable.isEmpty() && d_->shownFrame == 0;
    if (d_->handlesShown) {
        Vec3 sum = Vec3::Zero();
        for (int i : movable) sum += d_->doc->body(i).position;
        d_->handlesOrigin = sum / double(movable.size());
        const float distance = (d_->camera.eye() - toQt(d_->handlesOrigin)).length();
        d_->handlesSize = std::max(1e-3f, kHandleScale * distance);
        d_->gizmo->setPose(toQt(d_->handlesOrigin), d_->handlesSize);
    }
    d_->gizmo->setVisible(d_->handlesShown);
}

int Viewport::handleAt(const QPoint& widgetPos) const {
    if (!d_->handlesShown) return -1;
    const QPointF p(widgetPos);
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
    for (int i : d_->movableSelection()) d_->dragStart.emplace_back(i, d_->doc->body(i));
    d_->dragMergeId = kDragMergeBase + (++d_->dragCounter & 0xffffff);
    d_->dragCommand = nullptr;
    d_->gizmo->setHighlight(axis);
    return true;
}

void Viewport::dragHandle(const QPoint& pos, Qt::KeyboardModifiers modifiers) {
    if (d_->dragAxis < 0 || d_->dragStart.empty()) return;
    QVector3D o, dir;
    rayAt(pos, &o, &dir);
    const Vec3 a = Vec3::Unit(d_->dragAxis);
    const bool snap = d_->snapping || (modifiers & Qt::ControlModifier);
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
    auto apply = [&](const BodyDesc& b) {
        return move ? handles::moved(b, a, amount) : handles::rotated(b, d_->dragOrigin, a, amount);
    };
    const QString verb = move ? tr("Move") : tr("Rotate");
    Document* doc = d_->doc;
    QUndoStack* stack = doc->undoStack();
    auto top = [stack]() -> const QUndoCommand* {
        return stack->index() > 0 ? stack->command(stack->index() - 1) : nullptr;
    };
    // An edit that changes nothing pushes nothing: only a new step on top is the drag's.
    const QUndoCommand* topBefore = top();
    const int countBefore = stack->count();
    if (d_->dragStart.size() == 1) {
        // One body: consecutive edits with this drag's merge id are one undo step.
        const auto& [index, before] = d_->dragStart.front();
        doc->setBody(index, apply(before), tr("%1 %2").arg(verb, QString::fromStdString(before.name)),
                     d_->dragMergeId);
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
    d_->dragAxis = -1;
    d_->dragStart.clear();
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

// ---- Playback and overlays.

Timeline* Viewport::timeline() const {
    return d_->timeline;
}

void Viewport::setTimeline(Timeline* timeline) {
    if (timeline == d_->timeline) return;
    for (const auto& c : d_->timelineConnections) disconnect(c);
    d_->timelineConnections.clear();
    d_->timeline = timeline;
    d_->trackFrames.clear();
    d_->trackPoints.clear();
    if (timeline) {
        auto& c = d_->timelineConnections;
        c.push_back(connect(timeline, &Timeline::currentFrameChanged, this, [this] { refreshPlayback(); }));
        c.push_back(connect(timeline, &Timeline::recordingReset, this, [this] {
            d_->trackFrames.clear();
            d_->trackPoints.clear();
            refreshPlayback();
        }));
        c.push_back(connect(timeline, &Timeline::staleChanged, this, [this] { refreshPlayback(); }));
        c.push_back(connect(timeline, &QObject::destroyed, this, [this] {
            d_->timelineConnections.clear();
            refreshPlayback();
        }));
    }
    refreshPlayback();
}

int Viewport::shownFrame() const {
    return d_->shownFrame;
}

QMatrix4x4 Viewport::drawnTransform(int index) const {
    return d_->scene->drawnTransform(index);
}

void Viewport::refreshPlayback() {
    const State* state = d_->frameState();
    const int frame = state ? d_->timeline->currentFrame() : 0;
    if (frame > 0) {
        const Model& model = *d_->timeline->model();
        for (size_t i = 0; i < state->bodies.size(); ++i) {
            const BodyState& s = state->bodies[i];
            d_->scene->setShownPose(int(i), toQt(bodyFramePosition(model.bodies[i], s)), toQt(s.q));
        }
    } else {
        d_->scene->clearShownPoses();
    }
    if (frame != d_->shownFrame) {
        const bool handlesChange = (frame > 0) != (d_->shownFrame > 0);
        d_->shownFrame = frame;
        if (handlesChange) {
            if (frame > 0 && d_->dragAxis >= 0) cancelHandleDrag();  // playback began mid-drag
            updateHandles();
        }
    }
    refreshOverlays();
}

void Viewport::refreshOverlays() {
    ViewportOverlays& o = *d_->overlays;
    // The frame at the playhead, unless it is frame 0 of a stale recording (the document
    // was edited since: the recording's start is no longer what is drawn).
    const State* state = d_->frameState();
    if (state && d_->shownFrame == 0 && d_->timeline->isStale()) state = nullptr;
    const std::shared_ptr<const Model> model = state ? d_->timeline->model() : nullptr;
    auto on = [this, state](Overlay which) { return state && d_->overlayOn[size_t(which)]; };
    using K = ViewportOverlays::Kind;
    auto draw = [&](Overlay which, K kind, overlays::Lines (*compute)(const Model&, const State&)) {
        if (on(which)) {
            o.set(kind, compute(*model, *state));
        } else {
            o.clear(kind);
        }
    };
    draw(Overlay::Contacts, K::Contacts, &overlays::contacts);
    draw(Overlay::Velocities, K::Velocities, &overlays::velocities);
    draw(Overlay::AngularVelocities, K::AngularVelocities, &overlays::angularVelocities);
    draw(Overlay::Forces, K::Forces, &overlays::forces);
    draw(Overlay::CentresOfMass, K::CentresOfMass, &overlays::centresOfMass);

    // Trails: each dynamic body's centre of mass from frame 0 to the playhead. The tracks
    // are asked of the timeline as far as it has recorded, and again only when the
    // playhead passes their end.
    d_->trails.clear();
    if (on(Overlay::Trails)) {
        const int frame = d_->timeline->currentFrame();
        const size_t n = model->bodies.size();
        d_->trackFrames.resize(n);
        d_->trackPoints.resize(n);
        d_->trails.resize(n);
        const int cap = overlays::trailCap(int(model->dynamicBodies.size()));
        for (int i : model->dynamicBodies) {
            std::vector<int>& frames = d_->trackFrames[size_t(i)];
            std::vector<Vec3>& points = d_->trackPoints[size_t(i)];
            if (frames.empty() || frames.back() < frame) {
                std::vector<BodyState> states;
                d_->timeline->bodyTrack(i, &frames, &states, -1);
                points.clear();
                points.reserve(states.size());
                for (const BodyState& s : states) points.push_back(s.x);
            }
            const size_t end = size_t(std::upper_bound(frames.begin(), frames.end(), frame) - frames.begin());
            std::vector<Vec3> upTo(points.begin(),
                                   points.begin() + std::ptrdiff_t(std::min(end, points.size())));
            // The keyframes may stop short of the playhead: the trail ends where the body is.
            if (upTo.empty() || end == 0 || frames[end - 1] != frame)
                upTo.push_back(state->bodies[size_t(i)].x);
            d_->trails[size_t(i)] = overlays::thinned(upTo, cap);
        }
        o.set(K::Trails, overlays::trails(d_->trails));
    } else {
        o.clear(K::Trails);
    }

    // Sleeping bodies tinted.
    const bool tint = on(Overlay::Sleeping);
    for (int i = 0; i < d_->scene->count(); ++i) d_->scene->setAsleep(i, tint && state->isAsleep(i));
}

bool Viewport::overlay(Overlay which) const {
    return d_->overlayOn[size_t(which)];
}

void Viewport::setOverlay(Overlay which, bool on) {
    if (d_->overlayOn[size_t(which)] == on) return;
    d_->overlayOn[size_t(which)] = on;
    if (!on && which == Overlay::Trails) {  // nothing kept that is not drawn
        d_->trackFrames.clear();
        d_->trackPoints.clear();
    }
    refreshOverlays();
    emit overlayChanged(which, on);
}

int Viewport::overlayItemCount(Overlay which) const {
    using K = ViewportOverlays::Kind;
    switch (which) {
        case Overlay::Trails: return d_->overlays->count(K::Trails);
        case Overlay::Contacts: return d_->overlays->count(K::Contacts);
        case Overlay::Velocities: return d_->overlays->count(K::Velocities);
        case Overlay::AngularVelocities: return d_->overlays->count(K::AngularVelocities);
        case Overlay::Forces: return d_->overlays->count(K::Forces);
        case Overlay::CentresOfMass: return d_->overlays->count(K::CentresOfMass);
        case Overlay::Sleeping: return d_->scene->asleepCount();
    }
    return 0;
}

QList<QVector3D> Viewport::trailPoints(int index) const {
    QList<QVector3D> out;
    if (index < 0 || size_t(index) >= d_->trails.size()) return out;
    for (const Vec3& p : d_->trails[size_t(index)]) out.append(toQt(p));
    return out;
}

QString Viewport::overlayText(Overlay which) {
    switch (which) {
        case Overlay::Trails: return tr("Trails");
        case Overlay::Contacts: return tr("Contact Points");
        case Overlay::Velocities: return tr("Velocities");
        case Overlay::AngularVelocities: return tr("Angular Velocities");
        case Overlay::Forces: return tr("Applied Forces");
        case Overlay::CentresOfMass: return tr("Centres of Mass");
        case Overlay::Sleeping: return tr("Sleeping Bodies");
    }
    return {};
}

}  // namespace tumble::ui
