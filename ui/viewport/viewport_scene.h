// The Qt3D side of the viewport: the bodies (primitive shapes drawn by instancing, one draw
// per shape kind; imported meshes an entity each), the ground grid, the axes and the lights. Kept apart from
// the widget (input, camera) and out of every other header: Qt3D headers are heavy.
#pragma once

#include <tumble/scene.h>

#include <QList>
#include <QMatrix4x4>
#include <QQuaternion>
#include <QVector3D>

#include <memory>

namespace Qt3DCore {
class QEntity;
}

namespace tumble::ui {

class ViewportScene {
public:
    /// Builds the grid, axes and lights under `root`; bodies come with rebuild/insert.
    explicit ViewportScene(Qt3DCore::QEntity* root);
    ~ViewportScene();
    ViewportScene(const ViewportScene&) = delete;
    ViewportScene& operator=(const ViewportScene&) = delete;

    /// The grid and the axes: blended over the scene, in a pass of their own after it.
    Qt3DCore::QEntity* grid() const;

    /// Drops every body and draws those of `scene`.
    void rebuild(const SceneDesc& scene);
    void insert(int index, const BodyDesc& body);
    void update(int index, const BodyDesc& body);
    void remove(int index);
    /// Highlights exactly these bodies.
    /// Draws the bodies `indices` selected; with `part` >= 0 (one compound body selected),
    /// that part of it instead of the whole body.
    void setSelection(const QList<int>& indices, int part = -1);
    /// Bodies drawn (one per body of the document, however they are drawn).
    int count() const;

    // ---- Playback: a recorded frame drawn instead of the document's initial poses.
    /// Draws body `index` at this pose (its frame origin, body to world) until
    /// clearShownPoses(); only the transforms change (no entity is rebuilt), and edits of
    /// the body keep this pose.
    void setShownPose(int index, const QVector3D& position, const QQuaternion& orientation);
    /// Back to the document's poses.
    void clearShownPoses();
    /// Tints a body as asleep (the Sleeping overlay).
    void setAsleep(int index, bool asleep);
    /// Bodies tinted as asleep.
    int asleepCount() const;
    /// The pose body `index` is drawn at: translation(position) * rotation(orientation).
    QMatrix4x4 drawnTransform(int index) const;
    /// Draws each body's collision shape (viewport_wire.h) as lines over it.
    void setShowCollisionShapes(bool show);
    bool showCollisionShapes() const;
    /// Wireframe entities present (bodies with a shape to outline, while shown).
    int collisionShapeCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
