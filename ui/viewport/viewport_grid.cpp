#include "viewport/viewport_grid.h"

#include "viewport/viewport_shaders.h"

#include <Qt3DRender/QBlendEquation>
#include <Qt3DRender/QBlendEquationArguments>
#include <Qt3DRender/QDepthTest>
#include <Qt3DRender/QMaterial>
#include <Qt3DRender/QNoDepthMask>
#include <Qt3DRender/QRenderPass>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

namespace {

// The fade, in GLSL and in C++ (gridOpacity) alike. On screen, lines 1 m apart seen from
// height h at distance d are about h / d² apart (times the focal length): they are faded
// out where that falls under a few pixels, d = sqrt(kCrowd h), from half that distance on.
// The grid's last 30 % fades too. The eye's height counts from 0.05 m, the grid lying there.
constexpr float kCrowd = 150.0f;
constexpr float kEdgeFade = 0.7f;

QByteArray fadeGlsl() {
    return QByteArray(R"(
float gridOpacity(float distance, float eyeHeight, float edge, float halfExtent)
{
    float far = sqrt(CROWD * max(eyeHeight, 0.05));
    return (1.0 - smoothstep(0.5 * far, far, distance)) * (1.0 - smoothstep(EDGE_FADE * halfExtent, halfExtent, edge));
}
)")
        .replace("CROWD", QByteArray::number(double(kCrowd), 'f', 3))
        .replace("EDGE_FADE", QByteArray::number(double(kEdgeFade), 'f', 3));
}

const char* const kVertexBody = R"(
void main()
{
    worldPosition = vertexPosition;
    colour = vertexColor;
    gl_Position = viewProjectionMatrix * vec4(vertexPosition, 1.0);
}
)";

const char* const kFragmentBody = R"(
void main()
{
    float edge = max(abs(worldPosition.x), abs(worldPosition.z));
    float a = gridOpacity(distance(eyePosition, worldPosition), abs(eyePosition.y), edge, HALF_EXTENT);
    fragColor = vec4(colour, a);
}
)";

float smooth(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace

float gridOpacity(float distance, float eyeHeight, float edge, float halfExtent) {
    const float far = std::sqrt(kCrowd * std::max(eyeHeight, 0.05f));
    return (1.0f - smooth(0.5f * far, far, distance)) * (1.0f - smooth(kEdgeFade * halfExtent, halfExtent, edge));
}

Qt3DRender::QMaterial* makeGridMaterial(Qt3DCore::QNode* parent, float halfExtent) {
    const QByteArray half = "#define HALF_EXTENT " + QByteArray::number(double(halfExtent), 'f', 3) + "\n" + fadeGlsl();
    ShaderSources s;
    s.rhiVertex = QByteArray(R"(#version 450
layout(location = 0) in vec3 vertexPosition;
layout(location = 1) in vec3 vertexColor;
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 colour;
)") + kRhiViewUniforms + kVertexBody;
    s.rhiFragment = QByteArray(R"(#version 450
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 colour;
layout(location = 0) out vec4 fragColor;
)") + kRhiViewUniforms + half + kFragmentBody;
    s.glVertex = QByteArray(R"(#version 150 core
in vec3 vertexPosition;
in vec3 vertexColor;
out vec3 worldPosition;
out vec3 colour;
uniform mat4 viewProjectionMatrix;
)") + kVertexBody;
    s.glFragment = QByteArray(R"(#version 150 core
in vec3 worldPosition;
in vec3 colour;
out vec4 fragColor;
uniform vec3 eyePosition;
)") + half + kFragmentBody;
    return makeShaderMaterial(parent, s, [](Qt3DRender::QRenderPass* pass) {
        auto* depth = new Qt3DRender::QDepthTest(pass);
        depth->setDepthFunction(Qt3DRender::QDepthTest::LessOrEqual);
        pass->addRenderState(depth);
        pass->addRenderState(new Qt3DRender::QNoDepthMask(pass));
        auto* blend = new Qt3DRender::QBlendEquationArguments(pass);
        blend->setSourceRgb(Qt3DRender::QBlendEquationArguments::SourceAlpha);
        blend->setDestinationRgb(Qt3DRender::QBlendEquationArguments::OneMinusSourceAlpha);
        blend->setSourceAlpha(Qt3DRender::QBlendEquationArguments::Zero);
        blend->setDestinationAlpha(Qt3DRender::QBlendEquationArguments::One);
        pass->addRenderState(blend);
        auto* equation = new Qt3DRender::QBlendEquation(pass);
        equation->setBlendFunction(Qt3DRender::QBlendEquation::Add);
        pass->addRenderState(equation);
    });
}

}  // namespace tumble::ui
