#include "viewport/viewport_overlay.h"

#include <Qt3DCore/QAttribute>
#include <Qt3DCore/QBuffer>
#include <Qt3DCore/QGeometry>

#include <cstring>

namespace tumble::ui {

namespace {

constexpr int kStride = 6;  // floats a vertex

QByteArray bytesOf(const std::vector<float>& data) {
    QByteArray bytes(static_cast<qsizetype>(data.size() * sizeof(float)), Qt::Uninitialized);
    if (!data.empty()) std::memcpy(bytes.data(), data.data(), static_cast<size_t>(bytes.size()));
    return bytes;
}

}  // namespace

Qt3DRender::QGeometryRenderer* makeColouredRenderer(const std::vector<float>& xyzrgb,
                                                    Qt3DRender::QGeometryRenderer::PrimitiveType type,
                                                    Qt3DCore::QNode* parent) {
    const uint count = uint(xyzrgb.size() / kStride);
    auto* renderer = new Qt3DRender::QGeometryRenderer(parent);
    auto* geometry = new Qt3DCore::QGeometry(renderer);
    auto* buffer = new Qt3DCore::QBuffer(geometry);
    buffer->setData(bytesOf(xyzrgb));
    const std::pair<QString, uint> layout[] = {{Qt3DCore::QAttribute::defaultPositionAttributeName(), 0},
                                               {Qt3DCore::QAttribute::defaultColorAttributeName(), 3}};
    for (const auto& [name, offset] : layout) {
        auto* attr =
            new Qt3DCore::QAttribute(buffer, name, Qt3DCore::QAttribute::Float, 3, count,
                                     offset * uint(sizeof(float)), kStride * uint(sizeof(float)), geometry);
        attr->setAttributeType(Qt3DCore::QAttribute::VertexAttribute);
        geometry->addAttribute(attr);
    }
    renderer->setGeometry(geometry);
    renderer->setPrimitiveType(type);
    renderer->setVertexCount(int(count));
    return renderer;
}

void setColouredData(Qt3DRender::QGeometryRenderer* renderer, const std::vector<float>& xyzrgb) {
    const uint count = uint(xyzrgb.size() / kStride);
    Qt3DCore::QGeometry* geometry = renderer->geometry();
    const auto attributes = geometry->attributes();
    if (attributes.isEmpty()) return;
    attributes.first()->buffer()->setData(bytesOf(xyzrgb));
    for (Qt3DCore::QAttribute* a : attributes) a->setCount(count);
    renderer->setVertexCount(int(count));
}

}  // namespace tumble::ui
