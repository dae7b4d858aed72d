// One entity per shape kind: a QGeometryRenderer over the unit shape's geometry plus a
// per-instance buffer (attributes with divisor 1), instanceCount = copies. The material is
// our own shaders for either of Qt3D's renderers (viewport_shaders.h).
#include "viewport/viewport_instances.h"

#include "viewport/viewport_shaders.h"

#include <Qt3DCore/QAttribute>
#include <Qt3DCore/QBuffer>
#include <Qt3DCore/QEntity>
#include <Qt3DCore/QGeometry>
#include <Qt3DExtras/QCuboidGeometry>
#include <Qt3DExtras/QCylinderGeometry>
#include <Qt3DExtras/QPlaneGeometry>
#include <Qt3DExtras/QSphereGeometry>
#include <Qt3DRender/QGeometryRenderer>
#include <Qt3DRender/QMaterial>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace tumble::ui {

namespace {

// Per instance: the model matrix's four columns, the diffuse colour (rgb, 1) and the ambient
// colour (rgb) with the specular grey level in w.
constexpr int kFloats = 24;

// The body of both vertex shaders. The model matrix is rotation * diagonal scale, so the
// normal matrix (its inverse transpose) maps n to sum of column_i * n_i / |column_i|^2.
const char* const kVertexBody = R"(
void main()
{
    mat4 model = mat4(instanceModel0, instanceModel1, instanceModel2, instanceModel3);
    vec4 world = model * vec4(vertexPosition, 1.0);
    vec3 c0 = instanceModel0.xyz, c1 = instanceModel1.xyz, c2 = instanceModel2.xyz;
    worldNormal = c0 * (vertexNormal.x / max(dot(c0, c0), 1e-12))
                + c1 * (vertexNormal.y / max(dot(c1, c1), 1e-12))
                + c2 * (vertexNormal.z / max(dot(c2, c2), 1e-12));
    worldPosition = world.xyz;
    diffuseColor = instanceDiffuse;
    ambientColor = instanceAmbient;
    gl_Position = viewProjectionMatrix * world;
    if (instanceDiffuse.w < 0.5) gl_Position.z += behind(world.xyz, normalize(worldNormal), gl_Position);
}
)";

// A plane (instanceDiffuse.w = 0) is drawn a little behind where it is, as a polygon offset
// would: by its own change of depth over kBehindPixels pixels, measured by projecting a point
// 1 % farther from the eye along the plane, plus a fixed step, at most kMostBehind (seen edge
// on). The grid's lines lying on the ground 2 mm above it then win the depth test at every
// pixel, where they broke into dashes far away; bodies on the ground are not touched. (Qt3D's
// own QPolygonOffset, given to the planes' material, left other bodies drawn with it too under
// Qt 6.4's RHI renderer: a body in front of the y axis lost to it.) The planes come in 32 x 32
// pieces, so the offset follows the slope across them.
const char* const kBehind = R"(
float behind(vec3 world, vec3 n, vec4 clip)
{
    vec3 away = world - eyePosition;
    away -= n * dot(away, n);
    vec4 farther = viewProjectionMatrix * vec4(world + 0.01 * away, 1.0);
    float push = BEHIND_FIXED;
    if (clip.w > 1e-6 && farther.w > 1e-6) {
        vec2 a = (viewportMatrix * vec4(clip.xy / clip.w, 0.0, 1.0)).xy;
        vec2 b = (viewportMatrix * vec4(farther.xy / farther.w, 0.0, 1.0)).xy;
        float pixels = max(length(b - a), 1e-3);
        push += min(BEHIND_PIXELS * abs(farther.z / farther.w - clip.z / clip.w) / pixels, MOST_BEHIND);
    }
    return push * clip.w;
}
)";
constexpr float kBehindPixels = 1.0f;
constexpr float kBehindFixed = 2e-6f;
constexpr float kMostBehind = 1e-3f;

QByteArray behindGlsl() {
    return QByteArray(kBehind)
        .replace("BEHIND_FIXED", QByteArray::number(double(kBehindFixed), 'e', 3))
        .replace("BEHIND_PIXELS", QByteArray::number(double(kBehindPixels), 'f', 3))
        .replace("MOST_BEHIND", QByteArray::number(double(kMostBehind), 'e', 3));
}

// Qt3D's Phong (phong.inc.frag) with the scene's two directional lights (viewport_scene.cpp).
const char* const kFragmentBody = R"(
void light(vec3 n, vec3 v, vec3 towards, float intensity, inout float diffuse, inout float specular)
{
    float d = max(dot(towards, n), 0.0);
    diffuse += intensity * d;
    if (d > 0.0) {
        vec3 r = reflect(-towards, n);
        specular += intensity * (20.0 + 2.0) / 2.0 * pow(max(dot(r, v), 0.0), 20.0);
    }
}

void main()
{
    vec3 n = normalize(worldNormal);
    vec3 v = normalize(eyePosition - worldPosition);
    if (dot(n, v) < 0.0) n = -n;  // the far side of a plane
    float diffuse = 0.0, specular = 0.0;
    light(n, v, normalize(vec3(0.4, 1.0, 0.6)), 0.9, diffuse, specular);
    light(n, v, normalize(vec3(-0.6, 0.3, -0.5)), 0.35, diffuse, specular);
    // Qt3D's Phong lights the ambient colour by every light's intensity (0.9 + 0.35).
    vec3 colour = 1.25 * ambientColor.rgb + diffuseColor.rgb * diffuse + vec3(ambientColor.w * specular);
    fragColor = vec4(colour, 1.0);
}
)";

QByteArray rhiVertex() {
    return QByteArray(R"(#version 450
layout(location = 0) in vec3 vertexPosition;
layout(location = 1) in vec3 vertexNormal;
layout(location = 2) in vec4 instanceModel0;
layout(location = 3) in vec4 instanceModel1;
layout(location = 4) in vec4 instanceModel2;
layout(location = 5) in vec4 instanceModel3;
layout(location = 6) in vec4 instanceDiffuse;
layout(location = 7) in vec4 instanceAmbient;
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 diffuseColor;
layout(location = 3) out vec4 ambientColor;
)") + kRhiViewUniforms + behindGlsl() +
           kVertexBody;
}

QByteArray rhiFragment() {
    return QByteArray(R"(#version 450
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 diffuseColor;
layout(location = 3) in vec4 ambientColor;
layout(location = 0) out vec4 fragColor;
)") + kRhiViewUniforms +
           kFragmentBody;
}

QByteArray glVertex() {
    return QByteArray(R"(#version 150 core
in vec3 vertexPosition;
in vec3 vertexNormal;
in vec4 instanceModel0;
in vec4 instanceModel1;
in vec4 instanceModel2;
in vec4 instanceModel3;
in vec4 instanceDiffuse;
in vec4 instanceAmbient;
out vec3 worldPosition;
out vec3 worldNormal;
out vec4 diffuseColor;
out vec4 ambientColor;
uniform mat4 viewProjectionMatrix;
uniform mat4 viewportMatrix;
uniform vec3 eyePosition;
)") + behindGlsl() + kVertexBody;
}

QByteArray glFragment() {
    return QByteArray(R"(#version 150 core
in vec3 worldPosition;
in vec3 worldNormal;
in vec4 diffuseColor;
in vec4 ambientColor;
out vec4 fragColor;
uniform vec3 eyePosition;
)") + kFragmentBody;
}

Qt3DRender::QMaterial* makeMaterial(Qt3DCore::QNode* parent) {
    return makeShaderMaterial(parent, {rhiVertex(), rhiFragment(), glVertex(), glFragment()});
}

// Level of detail by count. On a software renderer (llvmpipe) a frame of many bodies costs
// about what its triangles cost to transform and set up, and the instanced draw calls are
// few, so the sphere and cylinder meshes get coarser as their copies grow in number: the
// finest level whose copies stay within a budget of about 250 000 triangles per kind, never
// coarser than the last. With everything in view, hundreds of bodies are a few tens of
// pixels across each and thousands a few pixels, where 24 rings look no rounder than 8.
// (A sphere of r rings and s slices has 2 s (r - 1) triangles, a cylinder of 2 rings 4 s.)
// The thresholds, in copies: spheres 169 / 347 / 710 / 1 488, cylinders 1 953 / 3 906 /
// 5 208; a few bodies always get full detail.
constexpr long kTriangleBudget = 250000;
struct Detail {
    int rings;
    int slices;
};
constexpr Detail kSphereDetail[] = {{24, 32}, {16, 24}, {12, 16}, {8, 12}, {6, 10}};
constexpr Detail kCylinderDetail[] = {{2, 32}, {2, 16}, {2, 12}, {2, 8}};

long sphereTriangles(const Detail& d) {
    return 2L * d.slices * (d.rings - 1);
}
long cylinderTriangles(const Detail& d) {
    return 2L * d.slices * (d.rings - 1) + 2L * d.slices;
}

template <size_t N>
Detail detailFor(const Detail (&levels)[N], long (*triangles)(const Detail&), int copies) {
    for (const Detail& d : levels) {
        if (long(copies) * triangles(d) <= kTriangleBudget) return d;
    }
    return levels[N - 1];
}

}  // namespace

int ViewportInstances::trianglesPerCopy(Kind kind, int copies) {
    switch (kind) {
        case Sphere: return int(sphereTriangles(detailFor(kSphereDetail, sphereTriangles, copies)));
        case Cylinder: return int(cylinderTriangles(detailFor(kCylinderDetail, cylinderTriangles, copies)));
        case Box: return 12;
        case Plane: return 2 * 32 * 32;
        case KindCount: break;
    }
    return 0;
}

struct ViewportInstances::Impl {
    struct Batch {
        Qt3DCore::QEntity* entity = nullptr;
        Qt3DRender::QGeometryRenderer* renderer = nullptr;
        Qt3DCore::QBuffer* buffer = nullptr;
        std::vector<Qt3DCore::QAttribute*> attributes;
        std::vector<float> data;  // being filled
        QByteArray uploaded;      // what the buffer holds
        int count = 0;            // drawn
        Qt3DCore::QAttribute* index = nullptr;
        Qt3DExtras::QSphereGeometry* sphere = nullptr;  // the kinds whose detail varies
        Qt3DExtras::QCylinderGeometry* cylinder = nullptr;
    };
    std::array<Batch, KindCount> batches;
};

ViewportInstances::ViewportInstances(Qt3DCore::QEntity* root) : d_(std::make_unique<Impl>()) {
    auto* material = makeMaterial(root);
    for (int k = 0; k < KindCount; ++k) {
        Impl::Batch& b = d_->batches[size_t(k)];
        b.entity = new Qt3DCore::QEntity(root);
        b.renderer = new Qt3DRender::QGeometryRenderer(b.entity);
        Qt3DCore::QGeometry* geometry = nullptr;
        Qt3DCore::QAttribute* index = nullptr;
        switch (Kind(k)) {
            case Sphere: {
                auto* g = new Qt3DExtras::QSphereGeometry(b.renderer);
                g->setRadius(1.0f);
                g->setRings(kSphereDetail[0].rings);
                g->setSlices(kSphereDetail[0].slices);
                geometry = g;
                index = g->indexAttribute();
                b.sphere = g;
                break;
            }
            case Box: {
                auto* g = new Qt3DExtras::QCuboidGeometry(b.renderer);  // 1 x 1 x 1
                geometry = g;
                index = g->indexAttribute();
                break;
            }
            case Cylinder: {
                auto* g = new Qt3DExtras::QCylinderGeometry(b.renderer);
                g->setRadius(1.0f);
                g->setLength(1.0f);
                g->setRings(kCylinderDetail[0].rings);
                g->setSlices(kCylinderDetail[0].slices);
                geometry = g;
                index = g->indexAttribute();
                b.cylinder = g;
                break;
            }
            case Plane: {
                auto* g = new Qt3DExtras::QPlaneGeometry(b.renderer);
                g->setWidth(1.0f);
                g->setHeight(1.0f);
                g->setResolution(QSize(32, 32));  // (its depth offset follows the slope: kBehind)
                geometry = g;
                index = g->indexAttribute();
                break;
            }
            case KindCount: break;
        }
        b.buffer = new Qt3DCore::QBuffer(geometry);
        const char* names[] = {"instanceModel0", "instanceModel1",  "instanceModel2",
                               "instanceModel3", "instanceDiffuse", "instanceAmbient"};
        for (int i = 0; i < 6; ++i) {
            auto* attr = new Qt3DCore::QAttribute(
                b.buffer, QString::fromLatin1(names[i]), Qt3DCore::QAttribute::Float, 4, 0,
                uint(4 * i * sizeof(float)), uint(kFloats * sizeof(float)), geometry);
            attr->setAttributeType(Qt3DCore::QAttribute::VertexAttribute);
            attr->setDivisor(1);
            geometry->addAttribute(attr);
            b.attributes.push_back(attr);
        }
        b.renderer->setGeometry(geometry);
        b.renderer->setPrimitiveType(Qt3DRender::QGeometryRenderer::Triangles);
        b.index = index;
        b.renderer->setVertexCount(index ? int(index->count()) : 0);
        b.renderer->setInstanceCount(1);
        b.entity->addComponent(b.renderer);
        b.entity->addComponent(material);
        b.entity->setEnabled(false);  // nothing to draw yet
    }
}

ViewportInstances::~ViewportInstances() = default;  // the entities belong to the root

void ViewportInstances::clear() {
    for (auto& b : d_->batches) b.data.clear();
}

void ViewportInstances::add(Kind kind, const QMatrix4x4& model, const Look& look) {
    if (kind < 0 || kind >= KindCount) return;
    std::vector<float>& v = d_->batches[size_t(kind)].data;
    const float* m = model.constData();  // column-major
    v.insert(v.end(), m, m + 16);
    v.insert(v.end(), {float(look.diffuse.redF()), float(look.diffuse.greenF()), float(look.diffuse.blueF()),
                       kind == Plane ? 0.0f : 1.0f,  // (a plane is drawn a little behind: kBehind)
                       float(look.ambient.redF()), float(look.ambient.greenF()),
                       float(look.ambient.blueF()), look.specular});
}

void ViewportInstances::commit() {
    for (auto& b : d_->batches) {
        const int n = int(b.data.size() / kFloats);
        b.count = n;
        b.entity->setEnabled(n > 0);
        if (n == 0) continue;  // not drawn: the buffer keeps its last copies
        // The detail for this many copies (the geometry regenerates only when it changes).
        if (b.sphere) {
            const Detail d = detailFor(kSphereDetail, sphereTriangles, n);
            b.sphere->setRings(d.rings);
            b.sphere->setSlices(d.slices);
        } else if (b.cylinder) {
            const Detail d = detailFor(kCylinderDetail, cylinderTriangles, n);
            b.cylinder->setRings(d.rings);
            b.cylinder->setSlices(d.slices);
        }
        if (b.index && b.renderer->vertexCount() != int(b.index->count())) {
            b.renderer->setVertexCount(int(b.index->count()));
        }
        QByteArray bytes(qsizetype(b.data.size() * sizeof(float)), Qt::Uninitialized);
        std::memcpy(bytes.data(), b.data.data(), size_t(bytes.size()));
        if (bytes == b.uploaded) continue;
        b.buffer->setData(bytes);
        b.uploaded = bytes;
        for (auto* attr : b.attributes) attr->setCount(uint(n));
        b.renderer->setInstanceCount(n);
    }
}

int ViewportInstances::count(Kind kind) const {
    return kind >= 0 && kind < KindCount ? d_->batches[size_t(kind)].count : 0;
}

int ViewportInstances::drawnTrianglesPerCopy(Kind kind) const {
    if (kind < 0 || kind >= KindCount) return 0;
    const Impl::Batch& b = d_->batches[size_t(kind)];
    return b.index ? int(b.index->count()) / 3 : 0;
}

}  // namespace tumble::ui
