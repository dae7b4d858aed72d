// The 3D view of the document: every body drawn and lit, a ground grid and axes, an orbit
// camera (mouse and keyboard), click to select, move and rotate handles on the selection
// (W, E; Ctrl while dragging snaps, Escape cancels a drag), the collision shapes as a wireframe on demand.
// With a timeline, the recorded frame at the playhead is drawn (frame 0: the document), with
// overlays on request (trails, contacts, velocity and force arrows, centres of mass, sleep).
// Qt3D stays behind the pimpl: this header is included by the main window and must stay light.
#pragma once

#include <QMatrix4x4>
#include <QPoint>
#include <QString>
#include <QVector3D>
#include <QWidget>

#include <memory>
#include <optional>

class QWindow;
namespace Qt3DRender {
class QRenderCapture;
}

namespace tumble::ui {

class Document;
class Timeline;

class Viewport : public QWidget {
    Q_OBJECT
public:
    /// What the handles on the selection do.
    enum class TransformMode { Move, Rotate };
    Q_ENUM(TransformMode)
    /// What can be drawn over a recorded frame (each a toggle, all off at first).
    /// Joints is on at first and drawn while editing too (from the document); the others
    /// are off at first and drawn over recorded frames only.
    enum class Overlay { Trails, Contacts, Velocities, AngularVelocities, Forces, CentresOfMass, Sleeping, Joints };
    Q_ENUM(Overlay)
    static constexpr int kOverlayCount = 8;

    explicit Viewport(Document* document, QWidget* parent = nullptr);
    ~Viewport() override;

    /// The body under a widget point: the nearest hit of the ray from the camera through that
    /// pixel against the bodies' exact shapes, or -1; `part`: the compound's part hit, or -1.
    int bodyAt(const QPoint& widgetPos, int* part = nullptr) const;
    /// The joint drawn under a widget point (while editing, with the Joints overlay on):
    /// within a few pixels of one of its anchors or of the line between them; or -1.
    int jointAt(const QPoint& widgetPos) const;
    /// Selects the joint under the point, else the body under it (Ctrl: toggles the body in
    /// the selection); empty space clears the selection (Ctrl: leaves it). A click on the one
    /// selected body, a compound, selects its part under the point. What a left click does.
    void clickAt(const QPoint& widgetPos, Qt::KeyboardModifiers modifiers = Qt::NoModifier);
    /// A poke: an impulse on dynamic body `body` at world point `point` of the frame at the
    /// playhead, along `drag` (world, m): it changes the body's velocity at that point by
    /// drag / kPokeSeconds (as if the drag were done in that time). Added to the scene as a
    /// force on the body over one frame from the playhead's time (an undo step, saved with
    /// the scene); the run is made again with it. False when there is no recorded frame or
    /// the body cannot be pushed.
    bool poke(int body, const Vec3& point, const Vec3& drag);
    static constexpr double kPokeSeconds = 0.5;

    /// Bodies drawn in the 3D scene, one per body of the document (primitives are instanced:
    /// one draw per shape kind).
    int entityCount() const;
    /// Where a world point appears, in widget pixels (z: depth, in [-1, 1] when visible).
    QVector3D projectToWidget(const QVector3D& world) const;

    // ---- The camera (an orbit about a target).
    QVector3D cameraPosition() const;
    QVector3D cameraTarget() const;
    float cameraDistance() const;
    void setCamera(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees);
    /// A parallel projection (View > Orthographic, 5), showing at every depth what the
    /// perspective view shows at the camera's target; picking, the handles and projectToWidget
    /// follow it.
    bool isOrthographic() const;
    void setOrthographic(bool on);

    /// Samples per pixel the 3D view asks for: 4, or 0 (no multisampling) when the GL
    /// renderer is a software one, where it costs too much.
    int samples() const;
    /// The OpenGL renderer's name (GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"),
    /// asked once of a throwaway context; empty if none could be made.
    static QString glRenderer();
    /// Whether a GL_RENDERER names a software rasteriser (llvmpipe, softpipe, swrast, ...).
    static bool isSoftwareRenderer(const QString& renderer);

    /// The Qt3D window inside the container (it receives the mouse and keys).
    QWindow* renderWindow() const;
    /// A render capture of the whole view, made and placed in the frame graph (owned by
    /// it): each of its requests is answered with the image of one drawn frame.
    Qt3DRender::QRenderCapture* addRenderCapture();
    /// The world ray through a widget point (direction of unit length).
    void rayAt(const QPoint& widgetPos, QVector3D* origin, QVector3D* direction) const;

    // ---- Handles. They sit at the mean position of the selected bodies that can move
    // (planes cannot); a drag on one moves along, or turns about, that world axis through
    // there. Each drag is one undo step, however many bodies it moves.
    TransformMode transformMode() const;
    /// Whether the handles are shown (something movable is selected).
    bool handlesVisible() const;
    /// Their centre, and their size in metres (arrow length, ring radius): a constant
    /// fraction of the distance to the camera, so they keep their size on screen.
    QVector3D handlesOrigin() const;
    float handlesSize() const;
    /// The handle under a widget point: 0, 1, 2 for the x, y, z axis, or -1.
    int handleAt(const QPoint& widgetPos) const;
    /// Snapping always on (else only while Ctrl is held during a drag).
    bool snapping() const;
    /// Steps: metres for a move, degrees for a turn.
    double translationSnap() const;
    double rotationSnapDegrees() const;

    // ---- Playback. With a timeline whose playhead is at a recorded frame k > 0 (of a
    // recording with as many bodies as the document), every body is drawn at frame k's pose;
    // at frame 0, without a frame, or when the body counts differ, the document's poses.
    // While a frame k > 0 is shown the handles are hidden (edits are to the initial state)
    // and picking hits the bodies where they are drawn.
    Timeline* timeline() const;
    /// The frame drawn: the playhead's k > 0, or 0 when the document's poses are drawn.
    int shownFrame() const;
    /// The pose body `index` is drawn at (its frame origin, body to world):
    /// translation(position) * rotation(orientation), in floats as handed to the renderer.
    QMatrix4x4 drawnTransform(int index) const;

    // ---- Overlays, drawn over the frame at the playhead (frame 0 too, unless the recording
    // is stale); each computed only while it is on.
    bool overlay(Overlay overlay) const;
    /// What an overlay draws now: Trails: polylines (one per dynamic body, from frame 0 to
    /// the playhead); Contacts: contact points; Velocities, AngularVelocities, Forces:
    /// arrows; CentresOfMass: markers; Sleeping: bodies tinted. 0 while off.
    int overlayItemCount(Overlay overlay) const;
    /// Whether a poke's arrow is drawn (a Ctrl+drag from a body under way).
    bool pokeArrowShown() const;
    /// The points of body `index`'s trail as drawn (empty without one).
    QList<QVector3D> trailPoints(int index) const;
    /// The menu text of an overlay ("Trails", "Contact Points", ...).
    static QString overlayText(Overlay overlay);

    /// Whether the selection is drawn (its highlight and the handles); on by default. An
    /// image export's view turns it off: the pictures show the scene, not the editing.
    bool selectionShown() const;
    void setSelectionShown(bool shown);

    // ---- Collision shapes.
    bool showCollisionShapes() const;
    /// Wireframe entities drawn (one per body with a bounded shape, while shown).
    int collisionShapeCount() const;

public slots:
    /// Draws the timeline's frame at the playhead (null: the document only). The viewport
    /// does not own it.
    void setTimeline(tumble::ui::Timeline* timeline);
    void setOverlay(tumble::ui::Viewport::Overlay overlay, bool on);
    /// Looks at the selected bodies (all of them when nothing is selected).
    void frameSelection();
    /// Looks at every body (planes excluded: they are infinite).
    void frameAll();
    /// Box select: the next left drag in the view selects the bodies whose centres it
    /// encloses (with Ctrl held at the release, adds them); Esc gives it up.
    void armBoxSelect();
    bool boxSelectArmed() const;
    void setTransformMode(tumble::ui::Viewport::TransformMode mode);
    void setSnapping(bool on);
    void setTranslationSnap(double metres);
    void setRotationSnapDegrees(double degrees);
    /// Draws each body's collision shape (a mesh: its convex hull, or its triangles when it
    /// collides by them) as lines over the render meshes.
    void setShowCollisionShapes(bool show);

signals:
    void transformModeChanged(tumble::ui::Viewport::TransformMode mode);
    void showCollisionShapesChanged(bool show);
    void orthographicChanged(bool on);
    void overlayChanged(tumble::ui::Viewport::Overlay overlay, bool on);
    /// I: key the selected body's pose at the playhead (the main window does it).
    void insertKeyRequested();

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;

private:
    bool handleKey(QKeyEvent* event);
    // A poke under way (Ctrl+drag from a body): its drag so far, its arrow and size shown.
    std::optional<Vec3> pokeDrag(const QPoint& pos) const;
    void showPoke(const QPoint& pos, const QPoint& global);
    void hidePoke();
    // Box select (viewport_box_select.cpp): the press, move and release of its drag.
    bool boxPress(const QPoint& pos);
    bool boxMove(const QPoint& pos);
    bool boxRelease(const QPoint& pos, Qt::KeyboardModifiers modifiers);
    void frameBodies(const QList<int>& indices);
    void syncCamera();
    void updateHandles();
    bool beginHandleDrag(int axis, const QPoint& pos);
    void dragHandle(const QPoint& pos, Qt::KeyboardModifiers modifiers);
    void endHandleDrag();
    /// Escape during a drag: the bodies go back to where they were, no undo step is left.
    void cancelHandleDrag();
    bool dragCommandOnTop() const;
    /// Draws the playhead's frame or the document's poses, and the overlays that are on.
    void refreshPlayback();
    void refreshOverlays();
    void refreshJoints();

    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
