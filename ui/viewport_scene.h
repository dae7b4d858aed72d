// The Qt3D side of the viewport: the bodies (primitive shapes drawn by instancing, one draw
// per shape kind; imported meshes an entity each), the ground grid, the axes and the lights. Kept apart from
// the widget (input, camera) and out of every other header: Qt3D headers are heavy.
#pragma once

#include <tumble/scene.h>

#include <QList>

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

    /// Drops every body and draws those of `scene`.
    void rebuild(const SceneDesc& scene);
    void insert(int index, const BodyDesc& body);
    void update(int index, const BodyDesc& body);
    void remove(int index);
    /// Highlights exactly these bodies.
    void setSelection(const QList<int>& indices);
    /// Bodies drawn (one per body of the document, however they are drawn).
    int count() const;
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
