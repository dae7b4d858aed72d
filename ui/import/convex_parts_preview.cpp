#include "import/convex_parts_preview.h"

#include "viewport/viewport_wire.h"

#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tumble::ui {

ConvexPartsPreview::ConvexPartsPreview(QWidget* parent) : QWidget(parent) {
    setObjectName("convexPartsPreview");
    setMinimumSize(200, 160);
    setCursor(Qt::OpenHandCursor);
    setToolTip(tr("Each convex part in its own colour; drag to turn"));
}

void ConvexPartsPreview::setParts(std::shared_ptr<const mesh::ConvexParts> parts, const QString& note) {
    parts_ = std::move(parts);
    note_ = note;
    update();
}

void ConvexPartsPreview::setView(double yaw, double pitch) {
    yaw_ = yaw;
    pitch_ = std::clamp(pitch, -1.5, 1.5);
    update();
}

void ConvexPartsPreview::mousePressEvent(QMouseEvent* e) {
    last_ = e->position().toPoint();
}

void ConvexPartsPreview::mouseMoveEvent(QMouseEvent* e) {
    const QPoint now = e->position().toPoint();
    setView(yaw_ + 0.01 * (now.x() - last_.x()), pitch_ + 0.01 * (now.y() - last_.y()));
    last_ = now;
}

void ConvexPartsPreview::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), QColor(52, 56, 64));
    partsDrawn_ = 0;
    if (!parts_ || parts_->parts.empty()) {
        p.setPen(QColor(220, 220, 220));
        p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap, note_);
        return;
    }
    // View: turn about y by the yaw, then about x by the pitch; the viewer looks along -z.
    const Mat3 view = (Eigen::AngleAxisd(pitch_, Vec3::UnitX()) * Eigen::AngleAxisd(yaw_, Vec3::UnitY()))
                          .toRotationMatrix();
    collision::Aabb box;
    for (const auto& hull : parts_->parts)
        for (const Vec3& v : hull.vertices) box.add(view * v);
    const Vec3 centre = 0.5 * (box.min + box.max), extent = box.max - box.min;
    const double scale =
        0.85 * std::min(width() / std::max(extent.x(), 1e-12), height() / std::max(extent.y(), 1e-12));
    auto toScreen = [&](const Vec3& v) {
        const Vec3 q = view * v - centre;
        return QPointF(width() / 2.0 + scale * q.x(), height() / 2.0 - scale * q.y());
    };
    struct Face {
        double depth;
        QPolygonF polygon;
        QColor colour;
        int part;
    };
    std::vector<Face> faces;
    const Vec3 light = Vec3(0.3, 0.5, 1.0).normalized();
    for (size_t k = 0; k < parts_->parts.size(); ++k) {
        const collision::ConvexHull& hull = parts_->parts[k];
        const auto c = pieceColour(int(k) + 1);
        for (const auto& f : hull.faces) {
            const Vec3 n = view * f.normal;
            if (n.z() <= 0.0) continue;  // facing away: its hull's near faces cover it
            Face face{0.0, {}, {}, int(k)};
            for (int i : hull.verticesOf(f)) {
                face.polygon << toScreen(hull.vertices[size_t(i)]);
                face.depth += (view * hull.vertices[size_t(i)]).z();
            }
            face.depth /= f.count;
            const double shade = 0.35 + 0.65 * std::max(0.0, n.dot(light));
            face.colour = QColor::fromRgbF(float(c[0] * shade), float(c[1] * shade), float(c[2] * shade));
            faces.push_back(std::move(face));
        }
    }
    std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.depth < b.depth; });
    p.setRenderHint(QPainter::Antialiasing);
    std::vector<bool> drawn(parts_->parts.size(), false);
    for (const Face& f : faces) {
        p.setPen(QPen(f.colour.darker(160), 0.8));
        p.setBrush(f.colour);
        p.drawPolygon(f.polygon);
        drawn[size_t(f.part)] = true;
    }
    partsDrawn_ = int(std::count(drawn.begin(), drawn.end(), true));
}

}  // namespace tumble::ui
