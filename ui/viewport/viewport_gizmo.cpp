#include "viewport/viewport_gizmo.h"

#include "viewport/viewport_overlay.h"

#include <Qt3DCore/QEntity>
#include <Qt3DCore/QTransform>
#include <Qt3DExtras/QPerVertexColorMaterial>

#include <QColor>
#include <QtMath>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace tumble::ui {

namespace {

constexpr float kShaftRadius = 0.014f;
constexpr float kConeRadius = 0.07f;
constexpr float kRingTube = 0.012f;
constexpr int kSides = 16;     // around a shaft or a cone
constexpr int kTubeSides = 6;  // around a ring's tube

QColor axisColour(int axis, bool highlighted) {
    if (highlighted) return QColor(255, 222, 60);
    switch (axis) {
        case 0: return QColor(235, 72, 72);
        case 1: return QColor(96, 214, 96);
        default: return QColor(86, 140, 250);
    }
}

// The unit vector of `axis` and two unit vectors normal to it (a right-handed frame).
std::array<QVector3D, 3> frameOf(int axis) {
    const QVector3D e[3] = {QVector3D(1, 0, 0), QVector3D(0, 1, 0), QVector3D(0, 0, 1)};
    return {e[axis], e[(axis + 1) % 3], e[(axis + 2) % 3]};
}

// Flat colour with a little fixed shading by the normal, so solids read as solids.
void vertex(std::vector<float>& v, const QVector3D& p, const QVector3D& normal, const QColor& c) {
    const QVector3D light = QVector3D(0.3f, 0.8f, 0.5f).normalized();
    const float k = 0.72f + 0.28f * std::max(0.0f, QVector3D::dotProduct(normal.normalized(), light));
    v.insert(v.end(),
             {p.x(), p.y(), p.z(), k * float(c.redF()), k * float(c.greenF()), k * float(c.blueF())});
}

void quad(std::vector<float>& v, const QVector3D (&p)[4], const QVector3D (&n)[4], const QColor& c) {
    for (int i : {0, 1, 2, 0, 2, 3}) vertex(v, p[i], n[i], c);
}

QVector3D around(const QVector3D& u, const QVector3D& w, float angle) {
    return std::cos(angle) * u + std::sin(angle) * w;
}

void arrow(std::vector<float>& v, int axis, const QColor& c) {
    const auto [a, u, w] = frameOf(axis);
    const QVector3D base = ViewportGizmo::kShaftEnd * a;
    for (int i = 0; i < kSides; ++i) {
        const float t0 = 2.0f * float(M_PI) * float(i) / kSides;
        const float t1 = 2.0f * float(M_PI) * float(i + 1) / kSides;
        const QVector3D r0 = around(u, w, t0), r1 = around(u, w, t1);
        // The shaft: a thin prism from the centre to the cone.
        quad(v, {kShaftRadius * r0, kShaftRadius * r1, base + kShaftRadius * r1, base + kShaftRadius * r0},
             {r0, r1, r1, r0}, c);
        // The cone and its base.
        vertex(v, base + kConeRadius * r0, r0, c);
        vertex(v, base + kConeRadius * r1, r1, c);
        vertex(v, a, a, c);
        vertex(v, base + kConeRadius * r1, -a, c);
        vertex(v, base + kConeRadius * r0, -a, c);
        vertex(v, base, -a, c);
    }
}

void ring(std::vector<float>& v, int axis, const QColor& c) {
    const auto [a, u, w] = frameOf(axis);
    for (int i = 0; i < ViewportGizmo::kRingSegments; ++i) {
        const float t0 = 2.0f * float(M_PI) * float(i) / ViewportGizmo::kRingSegments;
        const float t1 = 2.0f * float(M_PI) * float(i + 1) / ViewportGizmo::kRingSegments;
        const QVector3D c0 = around(u, w, t0), c1 = around(u, w, t1);  // centre line, radius 1
        for (int k = 0; k < kTubeSides; ++k) {
            const float s0 = 2.0f * float(M_PI) * float(k) / kTubeSides;
            const float s1 = 2.0f * float(M_PI) * float(k + 1) / kTubeSides;
            const QVector3D n00 = around(c0, a, s0), n01 = around(c0, a, s1);
            const QVector3D n10 = around(c1, a, s0), n11 = around(c1, a, s1);
            quad(v, {c0 + kRingTube * n00, c1 + kRingTube * n10, c1 + kRingTube * n11, c0 + kRingTube * n01},
                 {n00, n10, n11, n01}, c);
        }
    }
}

}  // namespace

ViewportGizmo::ViewportGizmo(Qt3DCore::QEntity* root) {
    entity_ = new Qt3DCore::QEntity(root);
    transform_ = new Qt3DCore::QTransform(entity_);
    entity_->addComponent(transform_);
    auto* material = new Qt3DExtras::QPerVertexColorMaterial(entity_);
    auto part = [&](Qt3DRender::QGeometryRenderer** geometry) {
        auto* e = new Qt3DCore::QEntity(entity_);
        *geometry = makeColouredRenderer({}, Qt3DRender::QGeometryRenderer::Triangles, e);
        e->addComponent(*geometry);
        e->addComponent(material);
        return e;
    };
    arrows_ = part(&arrowsGeometry_);
    rings_ = part(&ringsGeometry_);
    rebuild();
    setVisible(false);
}

void ViewportGizmo::setMode(Mode mode) {
    mode_ = mode;
    setVisible(visible_);
}

void ViewportGizmo::setPose(const QVector3D& origin, float size) {
    transform_->setTranslation(origin);
    transform_->setScale(size);
}

void ViewportGizmo::setVisible(bool visible) {
    visible_ = visible;
    // Each part too: a disabled parent alone is not enough for every Qt3D version.
    entity_->setEnabled(visible);
    arrows_->setEnabled(visible && mode_ == Mode::Move);
    rings_->setEnabled(visible && mode_ == Mode::Rotate);
}

void ViewportGizmo::setHighlight(int axis) {
    if (axis < 0 || axis > 2) axis = -1;  // (a joint's limit grip: not one of the gizmo's)
    if (axis == highlight_) return;
    highlight_ = axis;
    rebuild();
}

void ViewportGizmo::rebuild() {
    std::vector<float> arrows, rings;
    // The overlay is drawn without a depth test (viewport.cpp): what comes last is on top,
    // so the highlighted axis goes last.
    std::array<int, 3> order = {0, 1, 2};
    if (highlight_ >= 0) std::rotate(order.begin(), order.begin() + highlight_ + 1, order.end());
    for (int axis : order) {
        const QColor c = axisColour(axis, axis == highlight_);
        arrow(arrows, axis, c);
        ring(rings, axis, c);
    }
    setColouredData(arrowsGeometry_, arrows);
    setColouredData(ringsGeometry_, rings);
}

}  // namespace tumble::ui
