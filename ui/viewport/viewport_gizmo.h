// The move and rotate handles drawn on the selection: three arrows along the world axes
// (move) or three rings about them (rotate), x red, y green, z blue, the active or hovered
// one yellow. Solid triangles with a fixed shading (the RHI renderer draws lines one pixel
// wide), in the viewport's overlay layer, drawn after the scene without a depth test: never
// hidden by a body. Only the drawing: the viewport picks and drags them.
#pragma once

#include <QVector3D>

namespace Qt3DCore {
class QEntity;
class QTransform;
}  // namespace Qt3DCore
namespace Qt3DRender {
class QGeometryRenderer;
}

namespace tumble::ui {

class ViewportGizmo {
public:
    enum class Mode { Move, Rotate };

    /// The arrow shaft ends at this fraction of the size; the cone takes the rest.
    static constexpr float kShaftEnd = 0.78f;
    /// Segments of a ring (picking uses the same polygon).
    static constexpr int kRingSegments = 96;

    /// Under `root`; the caller puts entity() in its overlay layer.
    explicit ViewportGizmo(Qt3DCore::QEntity* root);
    ViewportGizmo(const ViewportGizmo&) = delete;
    ViewportGizmo& operator=(const ViewportGizmo&) = delete;

    Qt3DCore::QEntity* entity() const { return entity_; }
    void setMode(Mode mode);
    /// The handles' centre and their size (arrow length, ring radius) in metres.
    void setPose(const QVector3D& origin, float size);
    void setVisible(bool visible);
    /// The axis drawn highlighted (0, 1, 2), or -1.
    void setHighlight(int axis);

private:
    void rebuild();

    Qt3DCore::QEntity* entity_ = nullptr;
    Qt3DCore::QTransform* transform_ = nullptr;
    Qt3DCore::QEntity* arrows_ = nullptr;
    Qt3DCore::QEntity* rings_ = nullptr;
    Qt3DRender::QGeometryRenderer* arrowsGeometry_ = nullptr;
    Qt3DRender::QGeometryRenderer* ringsGeometry_ = nullptr;
    Mode mode_ = Mode::Move;
    bool visible_ = false;
    int highlight_ = -1;
};

}  // namespace tumble::ui
