// The viewport's private parts, shared by its source files (viewport.cpp: the window,
// camera, mouse and keys, picking; viewport_transform.cpp: handles, collision shapes and
// the selection's display; viewport_playback.cpp: recorded frames and overlays). Included
// by those files only: it brings in Qt3D.
#pragma once

#include "document/document.h"
#include "document/joint_presets.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"
#include "viewport/viewport_camera.h"
#include "viewport/viewport_gizmo.h"
#include "viewport/viewport_overlays.h"
#include "viewport/viewport_scene.h"

#include <tumble/mass.h>

#include <QPointF>
#include <QPointer>
#include <QQuaternion>
#include <QRubberBand>
#include <QUndoCommand>
#include <QVector3D>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace Qt3DCore {
class QEntity;
}
namespace Qt3DExtras {
class Qt3DWindow;
}
namespace Qt3DRender {
class QFrameGraphNode;
}

namespace tumble::ui {

class Settler;  // (document/placement.h)

namespace viewport_detail {

// How far the press may move before it is a drag rather than a click (pixels).
inline constexpr int kClickSlop = 4;
// How near a handle the cursor must be to grab it (pixels).
inline constexpr double kHandleGrabPx = 8.0;
// Handle numbers past the three axes: a selected ball joint's limit grips (ballLimitGrip's
// 0 to 3: its cone's two half-angles, its twist range's ends).
inline constexpr int kLimitGrip = 3;
// Handle size: this fraction of the distance from the camera (about a sixth of the view).
inline constexpr float kHandleScale = 0.13f;
// Merge ids of handle drags: a new one per drag, in a range of their own.
inline constexpr int kDragMergeBase = 0x48000000;

inline Vec3 toVec(const QVector3D& v) {
    return Vec3(v.x(), v.y(), v.z());
}
inline QVector3D toQt(const Vec3& v) {
    return QVector3D(float(v.x()), float(v.y()), float(v.z()));
}
inline QQuaternion toQt(const Quat& q) {
    const Quat n = q.normalized();
    return QQuaternion(float(n.w()), float(n.x()), float(n.y()), float(n.z()));
}

inline double distanceToSegment(const QPointF& p, const QPointF& a, const QPointF& b) {
    const QPointF ab = b - a;
    const double len2 = QPointF::dotProduct(ab, ab);
    double t = len2 > 0 ? QPointF::dotProduct(p - a, ab) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const QPointF d = p - (a + t * ab);
    return std::hypot(d.x(), d.y());
}

inline bool onScreen(const QVector3D& projected) {
    return projected.z() >= -1.0f && projected.z() <= 1.0f;
}

// A bounding sphere of a body's shape in world space, its frame at `position`; false for
// planes (unbounded).
inline bool boundingSphere(const BodyDesc& b, const Vec3& position, Vec3* centre, double* radius) {
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
        case ShapeType::Compound: {
            // About the frame's origin: each part's sphere at its distance from it.
            double r = 0.0;
            for (const PartDesc& p : s.parts) {
                BodyDesc one;
                one.shape = p.shape;
                Vec3 c;
                double pr = 0.0;
                if (p.shape.type != ShapeType::Compound && boundingSphere(one, p.position, &c, &pr))
                    r = std::max(r, c.norm() + pr);
            }
            *radius = r;
            return true;
        }
    }
    return false;
}

}  // namespace viewport_detail

struct Viewport::Impl {
    // Guarded: the main window deletes its document before the timeline and the timeline
    // before its widgets, so the timeline's last signals reach a viewport whose document is
    // gone (the sanitized editor build caught a call on the destroyed document when the
    // window closed with a frame shown).
    QPointer<Document> doc;
    Qt3DExtras::Qt3DWindow* window = nullptr;
    QWidget* container = nullptr;
    Qt3DCore::QEntity* root = nullptr;
    // Whether the window has been shown: Qt3DWindow hands its entity tree (with our root)
    // and its render and input settings to its aspect engine, which deletes them, on the
    // first show only. Until then they are nobody's and ~Viewport deletes them.
    bool windowShown = false;
    // The frame graph's last leaf (the overlay pass) and its parent: a render capture goes
    // between them (Viewport::addRenderCapture).
    Qt3DRender::QFrameGraphNode* lastLeaf = nullptr;
    std::unique_ptr<ViewportScene> scene;
    OrbitCamera camera;

    // Mouse drag state.
    Qt::MouseButton dragButton = Qt::NoButton;
    QPoint pressPos;
    QPoint lastPos;
    bool dragged = false;
    // A poke (Ctrl+drag on a body at the playhead): the body and the world point pressed.
    int pokeBody = -1;
    Vec3 pokePoint = Vec3::Zero();
    // Box select (viewport_box_select.cpp): armed by Edit > Box Select, the next left drag
    // draws `band` (a top-level rubber band: it shows over the 3D window) and selects.
    bool boxArmed = false;
    bool boxing = false;
    std::unique_ptr<QRubberBand> band;

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
    int dragPart = -1;   // the part the drag moves (of the one body in dragStart), or -1
    int dragJoint = -1;  // a selected joint's drag: the joint, as it was
    JointDesc dragJointStart;
    BallLimitFrame dragLimits;  // a ball joint's limit grip's drag (dragAxis kLimitGrip + grip)
    int dragMergeId = 0;
    int dragCounter = 0;
    // Shift while moving: the scene compiled once for the drag (placement.h), for drag
    // settlerDrag (its merge id).
    std::shared_ptr<Settler> settler;
    int settlerDrag = 0;
    const QUndoCommand* dragCommand = nullptr;  // the drag's undo step so far (null: none yet)
    // Keying an animated body at a later frame (its handles show there too): the drag moves
    // its drawn pose only, and its end keys that pose at the frame's time (one undo step).
    bool dragKeying = false;
    bool dragKeyMoved = false;
    double dragKeyTime = 0.0;
    BodyDesc dragKeyPose;  // the body as the drag has it (its position and orientation)

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
    int shownPart() const { return selectionShown ? doc->selectedPart() : -1; }
    /// The selected part when the handles move it (its body alone selected and movable).
    int handledPart() const {
        const int part = shownPart();
        return part >= 0 && movableSelection().size() == 1 ? part : -1;
    }

    /// The selected joint when its handles apply: at frame 0, shown, and (to turn) one with
    /// an axis; -1 otherwise.
    int handledJoint(TransformMode m) const {
        const int j = selectionShown ? doc->selectedJoint() : -1;
        if (j < 0 || j >= doc->jointCount()) return -1;
        if (m == TransformMode::Rotate && !doc->joint(j).axisA) return -1;
        return j;
    }

    /// The selected bodies a handle can move (planes cannot).
    QList<int> movableSelection() const {
        QList<int> out;
        for (int i : shownSelection()) {
            if (i >= 0 && i < doc->bodyCount() && doc->body(i).shape.type != ShapeType::Plane) out.append(i);
        }
        return out;
    }
};

}  // namespace tumble::ui
