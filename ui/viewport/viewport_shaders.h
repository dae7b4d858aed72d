// Materials of our own shaders, drawn under either of Qt3D's renderers: a technique for its
// RHI renderer (GLSL 450, with Qt3D's per-view uniform block) and one for its OpenGL
// renderer (GLSL 150 core, the same values as plain uniforms). Used by the instanced bodies
// (viewport_instances.cpp) and the grid (viewport_grid.cpp).
#pragma once

#include <QByteArray>

#include <functional>

namespace Qt3DCore {
class QNode;
}
namespace Qt3DRender {
class QMaterial;
class QRenderPass;
}  // namespace Qt3DRender

namespace tumble::ui {

/// Qt3D's per-view uniform block under the RHI renderer (its layout is fixed by Qt3D): the
/// declarations a GLSL 450 shader includes to read viewProjectionMatrix, eyePosition, ...
extern const char* const kRhiViewUniforms;

struct ShaderSources {
    QByteArray rhiVertex, rhiFragment;  // #version 450
    QByteArray glVertex, glFragment;    // #version 150 core
};

/// A material of one pass per technique; `states` adds render states to each pass.
Qt3DRender::QMaterial* makeShaderMaterial(Qt3DCore::QNode* parent, const ShaderSources& sources,
                                          const std::function<void(Qt3DRender::QRenderPass*)>& states = {});

}  // namespace tumble::ui
