#include "viewport/viewport_shaders.h"

#include <Qt3DRender/QEffect>
#include <Qt3DRender/QGraphicsApiFilter>
#include <Qt3DRender/QMaterial>
#include <Qt3DRender/QRenderPass>
#include <Qt3DRender/QShaderProgram>
#include <Qt3DRender/QTechnique>

namespace tumble::ui {

const char* const kRhiViewUniforms = R"(layout(std140, binding = 0) uniform qt3d_render_view_uniforms {
  mat4 viewMatrix;
  mat4 projectionMatrix;
  mat4 uncorrectedProjectionMatrix;
  mat4 clipCorrectionMatrix;
  mat4 viewProjectionMatrix;
  mat4 inverseViewMatrix;
  mat4 inverseProjectionMatrix;
  mat4 inverseViewProjectionMatrix;
  mat4 viewportMatrix;
  mat4 inverseViewportMatrix;
  vec4 textureTransformMatrix;
  vec3 eyePosition;
  float aspectRatio;
  float gamma;
  float exposure;
  float time;
  float yUpInNDC;
  float yUpInFBO;
};
)";

Qt3DRender::QMaterial* makeShaderMaterial(Qt3DCore::QNode* parent, const ShaderSources& sources,
                                          const std::function<void(Qt3DRender::QRenderPass*)>& states) {
    auto* material = new Qt3DRender::QMaterial(parent);
    auto* effect = new Qt3DRender::QEffect(material);
    auto technique = [effect, &states](Qt3DRender::QGraphicsApiFilter::Api api, int major, int minor,
                                       Qt3DRender::QGraphicsApiFilter::OpenGLProfile profile, const QByteArray& vs,
                                       const QByteArray& fs) {
        auto* t = new Qt3DRender::QTechnique(effect);
        t->graphicsApiFilter()->setApi(api);
        t->graphicsApiFilter()->setMajorVersion(major);
        t->graphicsApiFilter()->setMinorVersion(minor);
        t->graphicsApiFilter()->setProfile(profile);
        auto* pass = new Qt3DRender::QRenderPass(t);
        auto* program = new Qt3DRender::QShaderProgram(pass);
        program->setVertexShaderCode(vs);
        program->setFragmentShaderCode(fs);
        pass->setShaderProgram(program);
        if (states) states(pass);
        t->addRenderPass(pass);
        effect->addTechnique(t);
    };
    technique(Qt3DRender::QGraphicsApiFilter::RHI, 1, 0, Qt3DRender::QGraphicsApiFilter::NoProfile,
              sources.rhiVertex, sources.rhiFragment);
    technique(Qt3DRender::QGraphicsApiFilter::OpenGL, 3, 2, Qt3DRender::QGraphicsApiFilter::CoreProfile,
              sources.glVertex, sources.glFragment);
    material->setEffect(effect);
    return material;
}

}  // namespace tumble::ui
