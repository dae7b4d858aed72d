#include "viewport/viewport_camera.h"

#include <QtMath>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

void OrbitCamera::set(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees) {
    target_ = target;
    distance_ = std::clamp(distance, 0.05f, 1.0e5f);
    yaw_ = std::fmod(yawDegrees, 360.0f);
    pitch_ = std::clamp(pitchDegrees, -90.0f, 90.0f);  // (straight down: the top view)
}

QVector3D OrbitCamera::up() const {
    const float yaw = qDegreesToRadians(yaw_);
    const float pitch = qDegreesToRadians(pitch_);
    return QVector3D(-std::sin(pitch) * std::sin(yaw), std::cos(pitch), -std::sin(pitch) * std::cos(yaw));
}

QVector3D OrbitCamera::eye() const {
    const float yaw = qDegreesToRadians(yaw_);
    const float pitch = qDegreesToRadians(pitch_);
    const QVector3D dir(std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw));
    return target_ + distance_ * dir;
}

float OrbitCamera::nearPlane() const {
    if (orthographic_) return -(distance_ * 10.0f + 500.0f);
    return std::max(0.01f, distance_ * 0.01f);
}

float OrbitCamera::orthographicHalfHeight() const {
    return distance_ * std::tan(qDegreesToRadians(fov_) / 2);
}

float OrbitCamera::screenScaleAt(const QVector3D& point) const {
    return orthographic_ ? distance_ : (eye() - point).length();
}

float OrbitCamera::farPlane() const {
    return distance_ * 20.0f + 500.0f;
}

QMatrix4x4 OrbitCamera::view() const {
    QMatrix4x4 m;
    m.lookAt(eye(), target_, up());
    return m;
}

QMatrix4x4 OrbitCamera::projection(float aspect) const {
    QMatrix4x4 m;
    if (orthographic_) {
        const float h = orthographicHalfHeight(), w = h * aspect;
        m.ortho(-w, w, -h, h, nearPlane(), farPlane());
    } else {
        m.perspective(fov_, aspect, nearPlane(), farPlane());
    }
    return m;
}

void OrbitCamera::orbit(float dYawDegrees, float dPitchDegrees) {
    set(target_, distance_, yaw_ + dYawDegrees, pitch_ + dPitchDegrees);
}

void OrbitCamera::pan(float dx, float dy, float heightPx) {
    if (heightPx <= 0) return;
    // World size of one pixel at the target's depth.
    const float perPixel = 2.0f * distance_ * std::tan(qDegreesToRadians(fov_) / 2) / heightPx;
    const QVector3D forward = (target_ - eye()).normalized();
    const QVector3D right = QVector3D::crossProduct(forward, up()).normalized();
    const QVector3D camUp = QVector3D::crossProduct(right, forward);
    target_ += (-dx * right + dy * camUp) * perPixel;
}

void OrbitCamera::zoom(float factor) {
    set(target_, distance_ * factor, yaw_, pitch_);
}

void OrbitCamera::frame(const QVector3D& centre, float radius) {
    radius = std::max(radius, 0.1f);
    // Fit the sphere in the narrower of the two fields (assume a square-ish view).
    const float half = qDegreesToRadians(fov_) / 2;
    set(centre, radius / std::sin(half) * 1.1f, yaw_, pitch_);
}

void OrbitCamera::rayThrough(float x, float y, float w, float h, QVector3D* origin,
                             QVector3D* direction) const {
    const QMatrix4x4 inv = (projection(w / h) * view()).inverted();
    const float nx = 2.0f * x / w - 1.0f;
    const float ny = 1.0f - 2.0f * y / h;
    const QVector3D nearPt = inv.map(QVector3D(nx, ny, -1.0f));
    const QVector3D farPt = inv.map(QVector3D(nx, ny, 1.0f));
    *origin = nearPt;
    *direction = (farPt - nearPt).normalized();
}

QVector3D OrbitCamera::project(const QVector3D& world, float w, float h) const {
    const QVector4D clip = projection(w / h) * view() * QVector4D(world, 1.0f);
    if (clip.w() <= 0) return QVector3D(-1, -1, 2);
    const QVector3D ndc = clip.toVector3DAffine();
    return QVector3D((ndc.x() + 1.0f) / 2.0f * w, (1.0f - ndc.y()) / 2.0f * h, ndc.z());
}

}  // namespace tumble::ui
