// Unlit, per-vertex coloured geometry (with QPerVertexColorMaterial): the handles and the
// collision wireframe. Buffers can be refilled in place (a highlight changes colours).
#pragma once

#include <Qt3DRender/QGeometryRenderer>

#include <vector>

namespace Qt3DCore {
class QNode;
}

namespace tumble::ui {

/// A renderer over `xyzrgb` (six floats a vertex: position, colour 0..1).
Qt3DRender::QGeometryRenderer* makeColouredRenderer(const std::vector<float>& xyzrgb,
                                                    Qt3DRender::QGeometryRenderer::PrimitiveType type,
                                                    Qt3DCore::QNode* parent);
/// Replaces the vertices of a renderer made by makeColouredRenderer.
void setColouredData(Qt3DRender::QGeometryRenderer* renderer, const std::vector<float>& xyzrgb);

}  // namespace tumble::ui
