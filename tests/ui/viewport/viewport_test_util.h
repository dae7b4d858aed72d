// Helpers shared by the viewport suites: a body of a given shape, and where a world point
// appears in the viewport's widget (the pixel to click).
#pragma once

#include "viewport/viewport.h"

#include <tumble/scene.h>

#include <QPoint>
#include <QVector3D>

#include <string>

namespace tumble::test {

inline BodyDesc body(const std::string& name, ShapeType type, const Vec3& position) {
    BodyDesc b;
    b.name = name;
    b.shape.type = type;
    b.mass = 1.0;
    b.position = position;
    return b;
}

inline QPoint projected(const ui::Viewport& v, const Vec3& p) {
    const QVector3D w = v.projectToWidget(QVector3D(float(p.x()), float(p.y()), float(p.z())));
    return QPoint(qRound(w.x()), qRound(w.y()));
}

}  // namespace tumble::test
