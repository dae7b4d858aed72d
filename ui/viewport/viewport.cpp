// The widget side of the viewport: the Qt3D window in a container, the orbit camera, mouse
// and keys, picking. The camera's matrices are ours (OrbitCamera) and the Qt3D camera is
// set from them, so picking and projectToWidget are exact functions of the camera and the
// document, never of what the render thread last drew.
#include "viewport/viewport_impl.h"

#include <tumble/raycast.h>

#include "document/document.h"
#include "document/joint_presets.h"
#include "timeline/timeline.h"
#include "viewport/viewport_camera.h"
#include "viewport/viewport_gizmo.h"
#include "viewport/viewport_handles.h"
#include "viewport/viewport_overlays.h"
#include "viewport/viewport_raycast.h"
#include "viewport/viewport_scene.h"

#include <QLineF>

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
#include <Qt3DRender/QRenderCapture>
#include <Qt3DRender/QRenderSettings>
#include <Qt3DRender/QRenderStateSet>
#include <Qt3DRender/QRenderSurfaceSelector>
#include <Qt3DRender/QViewport>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QToolTip>
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

using namespace viewport_detail;

namespace {

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

// Qt3D prepares each frame with jobs on a thread pool of its own, and Qt 6.4's render jobs
// share state between pool threads without a lock: two jobs building the light uniforms of
// one frame can both fill a light's uniform block for the first time, and the second
// replaces the list the first is still reading (QTBUG-111427, fixed in Qt 6.7; a SIGSEGV in
// UniformBlockValueBuilder on a new view's first frame, seen in about 1 of 6 runs of the
// tests under load); RenderView also sorts the lights into one shared list from every job
// at once, and RenderCapture hands out requests unlocked (addRenderCapture). One pool
// thread runs those jobs one after another. It costs little here: the views draw a few
// hundred instanced bodies, and the machines Tumble runs on spend their cores on the
// simulation. QT3D_MAX_THREAD_COUNT set by the user is kept. Qt3D reads it once, when the
// first aspect engine starts, so this runs before the first window is made.
void limitQt3dJobThreads() {
    static const bool once = [] {
        if (!qEnvironmentVariableIsSet("QT3D_MAX_THREAD_COUNT")) qputenv("QT3D_MAX_THREAD_COUNT", "1");
        return true;
    }();
    (void)once;
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
Viewport::Viewport(Document* document, QWidget* parent) : QWidget(parent), d_(std::make_unique<Impl>()) {
    d_->doc = document;
    limitQt3dJobThreads();
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
    d_->overlayOn[size_t(Overlay::Joints)] = true;  // joints are part of the scene as built

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
    // The grid after the bodies and the ground: its lines fade, blended over them.
    auto* gridLayer = new Qt3DRender::QLayer(d_->root);
    d_->scene->grid()->addComponent(gridLayer);
    auto* sceneFilter = new Qt3DRender::QLayerFilter(clearAll);
    sceneFilter->addLayer(overlay);
    sceneFilter->addLayer(gridLayer);
    sceneFilter->setFilterMode(Qt3DRender::QLayerFilter::DiscardAnyMatchingLayers);
    auto* gridFilter = new Qt3DRender::QLayerFilter(cameraSelector);
    gridFilter->addLayer(gridLayer);
    gridFilter->setFilterMode(Qt3DRender::QLayerFilter::AcceptAnyMatchingLayers);
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
    d_->lastLeaf = overlayFilter;
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
        d_->dragJoint = -1;
        d_->dragCommand = nullptr;
    };
    connect(document, &Document::sceneReset, this, [this, cancelDrag] {
        cancelDrag();
        d_->scene->rebuild(d_->doc->scene());
        d_->scene->setSelection(d_->shownSelection(), d_->shownPart());
        refreshPlayback();
        updateHandles();
    });
    connect(document, &Document::bodyInserted, this, [this, cancelDrag](int i) {
        cancelDrag();
        d_->scene->insert(i, d_->doc->body(i));
        d_->scene->setSelection(d_->shownSelection(), d_->shownPart());
        refreshPlayback();
        updateHandles();
    });
    connect(document, &Document::bodyRemoved, this, [this, cancelDrag](int i) {
        cancelDrag();
        d_->scene->remove(i);
        d_->scene->setSelection(d_->shownSelection(), d_->shownPart());
        refreshPlayback();
        updateHandles();
    });
    connect(document, &Document::bodyChanged, this, [this](int i) {
        d_->scene->update(i, d_->doc->body(i));
        updateHandles();
        refreshJoints();
    });
    connect(document, &Document::jointsChanged, this, [this] {
        refreshJoints();
        if (d_->dragAxis < 0) updateHandles();  // (a drag keeps its origin: the anchor follows the pointer)
    });
    connect(document, &Document::selectionChanged, this, [this] {
        d_->scene->setSelection(d_->shownSelection(), d_->shownPart());
        updateHandles();
        refreshJoints();  // the selected joint is drawn light
    });

    d_->scene->rebuild(document->scene());
    d_->scene->setSelection(d_->shownSelection(), d_->shownPart());
    refreshJoints();
    syncCamera();
}

Viewport::~Viewport() {
    // The scene's entities belong to the root, which belongs to the window's top entity; the
    // window belongs to the container. Drop our bookkeeping first.
    for (const auto& c : d_->timelineConnections) disconnect(c);
    d_->overlays.reset();
    d_->gizmo.reset();
    d_->scene.reset();
    if (!d_->windowShown) {
        // The window never gave its top entity (our root, its camera) and its render
        // settings (our frame graph) to its aspect engine, so nothing would delete them:
        // a viewport never shown (an image export's, one in a window never shown) would
        // leak the whole scene. They go before the window (the frame graph's surface
        // selectors filter its events), which the container then deletes; its engine holds
        // no node. (Its input settings, a node of Qt3DWindow's own, cannot be reached.)
        Qt3DCore::QNode* top = d_->root->parentNode();
        delete (top ? top : d_->root);
        delete d_->window->renderSettings();
    }
}

int Viewport::samples() const {
    return d_->window->format().samples();
}

QWindow* Viewport::renderWindow() const {
    return d_->window;
}

// The capture goes above the last leaf only, never above two. Qt 6.4's backend
// RenderCapture hands its pending requests to the render views of the leaves below it, and
// each leaf's render view is set up by its own job on Qt3D's thread pool: with two leaves
// below, two pool threads can take a request from the same list at once, and
// RenderCapture::takeCaptureRequest takes it without the lock that guards the list (Qt 6.4
// rendercapture.cpp). Two requests pending (a capture asked again) made that a heap
// corruption, found later in RenderCapture::syncFromFrontEnd when the main thread appended
// the next request; one request could be taken twice, emptying the list past its start;
// and when two views of one pass each took one, the second readback replaced the first,
// whose reply never came. Below the last leaf alone one job takes at most one request a
// frame, and its readback is recorded at the end of the pass, after both passes have drawn:
// the image is the whole view.
Qt3DRender::QRenderCapture* Viewport::addRenderCapture() {
    auto* capture = new Qt3DRender::QRenderCapture();
    Qt3DCore::QNode* parent = d_->lastLeaf->parentNode();
    capture->setParent(parent);
    d_->lastLeaf->setParent(capture);
    return capture;
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

bool Viewport::isOrthographic() const {
    return d_->camera.isOrthographic();
}

void Viewport::setOrthographic(bool on) {
    if (on == d_->camera.isOrthographic()) return;
    d_->camera.setOrthographic(on);
    syncCamera();
    emit orthographicChanged(on);
}

void Viewport::setCamera(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees) {
    d_->camera.set(target, distance, yawDegrees, pitchDegrees);
    syncCamera();
}

void Viewport::syncCamera() {
    Qt3DRender::QCamera* cam = d_->window->camera();
    const float w = float(std::max(1, width()));
    const float h = float(std::max(1, height()));
    if (d_->camera.isOrthographic()) {
        const float half = d_->camera.orthographicHalfHeight();
        cam->lens()->setOrthographicProjection(-half * w / h, half * w / h, -half, half, d_->camera.nearPlane(),
                                               d_->camera.farPlane());
    } else {
        cam->lens()->setPerspectiveProjection(d_->camera.fieldOfViewDegrees(), w / h, d_->camera.nearPlane(),
                                              d_->camera.farPlane());
    }
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

int Viewport::bodyAt(const QPoint& widgetPos, int* part) const {
    QVector3D o, dir;
    rayAt(widgetPos, &o, &dir);
    // The engine's ray cast: nearest body, ties to the lower index. At a recorded frame,
    // against the bodies where they are drawn.
    if (d_->shownFrame > 0) {
        if (const State* state = d_->frameState()) {
            const auto hit = rayCast(*d_->timeline->model(), *state, toVec(o), toVec(dir));
            if (part) *part = hit ? hit->part : -1;
            return hit ? hit->body : -1;
        }
    }
    const auto hit = rayCastScene(d_->doc->scene(), toVec(o), toVec(dir));
    if (part) *part = hit ? hit->part : -1;
    return hit ? hit->body : -1;
}

int Viewport::jointAt(const QPoint& widgetPos) const {
    if (d_->shownFrame > 0 || !d_->overlayOn[size_t(Overlay::Joints)]) return -1;
    constexpr double kAnchorPx = 8.0, kLinePx = 4.0;
    const QPointF p(widgetPos);
    const SceneDesc& scene = d_->doc->scene();
    int best = -1;
    double bestScore = 1e300;
    for (int k = 0; k < d_->doc->jointCount(); ++k) {
        const JointDesc& j = scene.joints[size_t(k)];
        const QVector3D pa = projectToWidget(toQt(worldAnchorA(scene, j)));
        const QVector3D pb = projectToWidget(toQt(worldAnchorB(scene, j)));
        if (!onScreen(pa) || !onScreen(pb)) continue;
        const double anchor = std::min(QLineF(p, pa.toPointF()).length(), QLineF(p, pb.toPointF()).length());
        const double line = distanceToSegment(p, pa.toPointF(), pb.toPointF());
        // An anchor counts from farther than the line; the nearer joint wins.
        const double score = anchor <= kAnchorPx ? anchor : line <= kLinePx ? kAnchorPx + line : 1e300;
        if (score < bestScore) bestScore = score, best = k;
    }
    return best;
}

void Viewport::clickAt(const QPoint& widgetPos, Qt::KeyboardModifiers modifiers) {
    const bool toggle = modifiers & Qt::ControlModifier;
    if (!toggle) {
        if (const int joint = jointAt(widgetPos); joint >= 0) {
            d_->doc->selectJoint(joint);
            return;
        }
    }
    int part = -1;
    int hit = bodyAt(widgetPos, &part);
    // A click on the one selected body, a compound, goes into it: the part under the
    // pointer is selected (the Scene list's part row and the Part panel with it).
    // (At a recorded frame the hit is the compiled model's, whose parts a mesh split into
    // convex parts adds to: the scene's part is not known there.)
    if (!toggle && hit >= 0 && part >= 0 && d_->shownFrame == 0 && d_->doc->selection() == QList<int>{hit}) {
        d_->doc->selectPart(hit, part);
        return;
    }
    // The ground (a plane) is the floor of the view, not a thing on it: a click there is a
    // click on empty space, which clears the selection (the Scene list selects the ground).
    if (hit >= 0 && d_->doc->body(hit).shape.type == ShapeType::Plane) hit = -1;
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

// The drag's end on the plane through the pressed point that faces the camera, from that
// point; nothing when the view is edge-on to it.
std::optional<Vec3> Viewport::pokeDrag(const QPoint& pos) const {
    QVector3D o, dir;
    rayAt(pos, &o, &dir);
    const Vec3 facing = toVec(d_->camera.target() - d_->camera.eye()).normalized();
    const double along = toVec(dir).dot(facing);
    if (!(std::abs(along) > 1e-9)) return std::nullopt;
    return toVec(o) + toVec(dir) * ((d_->pokePoint - toVec(o)).dot(facing) / along) - d_->pokePoint;
}

void Viewport::showPoke(const QPoint& pos, const QPoint& global) {
    const std::optional<Vec3> drag = pokeDrag(pos);
    if (!drag) return;
    d_->overlays->set(ViewportOverlays::Poke, overlays::pokeArrow(d_->pokePoint, *drag));
    // What the release will give: the pressed point's change of velocity along the drag.
    QToolTip::showText(global, tr("Poke: Δv %1 m/s").arg(drag->norm() / kPokeSeconds, 0, 'g', 3), d_->container);
}

void Viewport::hidePoke() {
    d_->overlays->clear(ViewportOverlays::Poke);
    QToolTip::hideText();
}

bool Viewport::pokeArrowShown() const {
    return d_->overlays->count(ViewportOverlays::Poke) > 0;
}

bool Viewport::poke(int body, const Vec3& point, const Vec3& drag) {
    const State* state = d_->frameState();
    if (!state || body < 0 || body >= d_->doc->bodyCount() || !(drag.norm() > 0.0)) return false;
    const BodyModel& m = d_->timeline->model()->bodies[size_t(body)];
    if (m.motion != Motion::Dynamic || !(m.mass > 0.0)) return false;
    const BodyState& s = state->bodies[size_t(body)];
    // The impulse that changes the pressed point's velocity by drag / kPokeSeconds: the
    // point's effective mass along the drag, 1 / (1/m + |I^-1 (r x n)| ...) in closed form.
    const Vec3 r = point - s.x;
    const Vec3 n = drag.normalized();
    const Mat3 R = s.q.toRotationMatrix();
    const Mat3 invI = R * m.invInertia * R.transpose();
    const double k = 1.0 / m.mass + n.dot((invI * r.cross(n)).cross(r));
    const Vec3 impulse = (drag.norm() / kPokeSeconds / k) * n;
    const double dt = 1.0 / d_->timeline->frameRate();  // over one frame from the playhead
    ForceDesc f;
    f.type = ForceType::Force;
    f.vector = impulse / dt;
    f.frame = Frame::World;
    f.point = Vec3(s.q.conjugate() * r + m.centerOfMass);  // body frame, about the body's origin
    f.start = state->time;
    f.end = state->time + dt;
    BodyDesc b = d_->doc->body(body);
    b.forces.push_back(f);
    d_->doc->setBody(body, b, tr("Poke %1").arg(QString::fromStdString(b.name)));
    return true;
}

void Viewport::frameSelection() {
    // A joint selected (no body then): its body or two bodies.
    const int joint = d_->doc->selectedJoint();
    if (d_->doc->selection().isEmpty() && joint >= 0 && joint < d_->doc->jointCount()) {
        const JointDesc& j = d_->doc->joint(joint);
        QList<int> bodies;
        for (int i = 0; i < d_->doc->bodyCount(); ++i) {
            const std::string& name = d_->doc->body(i).name;
            if (name == j.bodyA || (!j.bodyB.empty() && name == j.bodyB)) bodies.append(i);
        }
        if (!bodies.isEmpty()) frameBodies(bodies);
        return;
    }
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
            if (d_->boxArmed && !d_->boxing) {  // box select given up before its drag
                d_->boxArmed = false;
                d_->container->unsetCursor();
                return true;
            }
            if (d_->dragAxis < 0) return false;
            cancelHandleDrag();
            return true;
        case Qt::Key_F: frameSelection(); return true;
        case Qt::Key_W: setTransformMode(TransformMode::Move); return true;
        case Qt::Key_E: setTransformMode(TransformMode::Rotate); return true;
        case Qt::Key_A: frameAll(); return true;
        case Qt::Key_I: emit insertKeyRequested(); return true;
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
            if (d_->dragButton == Qt::NoButton && e->button() == Qt::LeftButton && boxPress(p)) {
                d_->container->setFocus(Qt::MouseFocusReason);
                return true;
            }
            if (d_->dragButton == Qt::NoButton && e->button() == Qt::LeftButton &&
                !(e->modifiers() & Qt::ShiftModifier) && beginHandleDrag(handleAt(p), p)) {
                d_->dragButton = Qt::LeftButton;
                d_->pressPos = d_->lastPos = p;
                d_->dragged = true;  // never a click
            } else if (d_->dragButton == Qt::NoButton) {
                d_->dragButton = e->button();
                d_->pressPos = d_->lastPos = e->position().toPoint();
                d_->dragged = false;
                // Ctrl on a dynamic body of a recorded frame: a drag from it pokes it.
                d_->pokeBody = -1;
                if (e->button() == Qt::LeftButton && (e->modifiers() & Qt::ControlModifier) && d_->frameState()) {
                    QVector3D o, dir;
                    rayAt(p, &o, &dir);
                    const auto hit = rayCast(*d_->timeline->model(), *d_->frameState(), toVec(o), toVec(dir));
                    if (hit && d_->doc->body(hit->body).motion == Motion::Dynamic) {
                        d_->pokeBody = hit->body;
                        d_->pokePoint = hit->point;
                    }
                }
            }
            d_->container->setFocus(Qt::MouseFocusReason);
            return true;
        }
        case QEvent::MouseMove: {
            auto* e = static_cast<QMouseEvent*>(event);
            const QPoint p = e->position().toPoint();
            if (boxMove(p)) return true;
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
            if (d_->pokeBody >= 0) {  // the poke is made on release; till then its arrow and size
                showPoke(p, e->globalPosition().toPoint());
                return true;
            }
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
            if (boxRelease(e->position().toPoint(), e->modifiers())) return true;
            if (d_->dragAxis >= 0) {
                dragHandle(e->position().toPoint(), e->modifiers());  // where and how it ends
                endHandleDrag();
            } else if (d_->dragged && d_->pokeBody >= 0) {
                hidePoke();
                if (const std::optional<Vec3> drag = pokeDrag(e->position().toPoint()))
                    poke(d_->pokeBody, d_->pokePoint, *drag);
            } else if (!d_->dragged && d_->dragButton == Qt::LeftButton) {
                clickAt(e->position().toPoint(), e->modifiers());
            }
            d_->pokeBody = -1;
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
        case QEvent::Show: d_->windowShown = true; return false;
        default: return false;
    }
}

}  // namespace tumble::ui
