// A picture of a mesh's convex parts, each in its own colour (the collision wire's,
// viewport_wire.h), drawn with QPainter: the hulls' faces lit from the viewer, far faces
// first. A drag turns the picture. For the Split into Convex Parts dialog, where a 3D view
// of its own would be a second Qt3D window for one picture.
#pragma once

#include <tumble/convex_parts.h>

#include <QWidget>

#include <memory>

namespace tumble::ui {

class ConvexPartsPreview : public QWidget {
    Q_OBJECT
public:
    explicit ConvexPartsPreview(QWidget* parent = nullptr);

    /// The parts to draw (none: an empty picture with `note` in its middle).
    void setParts(std::shared_ptr<const mesh::ConvexParts> parts, const QString& note = QString());
    const mesh::ConvexParts* parts() const { return parts_.get(); }
    /// The view's turn: about the vertical axis, then tilted towards the viewer (radians).
    void setView(double yaw, double pitch);
    /// How many parts show at least one face in the picture (for tests).
    int partsDrawn() const { return partsDrawn_; }

    QSize sizeHint() const override { return {360, 280}; }

protected:
    void paintEvent(QPaintEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;

private:
    std::shared_ptr<const mesh::ConvexParts> parts_;
    QString note_;
    double yaw_ = 0.6, pitch_ = 0.45;
    QPoint last_;
    int partsDrawn_ = 0;
};

}  // namespace tumble::ui
