// The viewport's orbit camera as plain numbers: a target, a distance, yaw and pitch, a
// vertical field of view. The Qt3D camera is set from it, and picking and projection use
// its matrices, so what the tests aim at is what the user sees, whatever the render loop
// is doing.
#pragma once

#include <QMatrix4x4>
#include <QVector3D>

namespace tumble::ui {

class OrbitCamera {
public:
    QVector3D target() const { return target_; }
    float distance() const { return distance_; }
    float yawDegrees() const { return yaw_; }
    float pitchDegrees() const { return pitch_; }
    float fieldOfViewDegrees() const { return fov_; }

    /// Pitch is clamped short of the poles, distance to a small positive minimum.
    void set(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees);

    QVector3D eye() const;
    /// The screen's up: square to the line of sight, in the vertical plane through it (world
    /// y seen from any side; looking straight down, the way the yaw faces).
    QVector3D up() const;
    float nearPlane() const;
    float farPlane() const;
    QMatrix4x4 view() const;
    QMatrix4x4 projection(float aspect) const;

    /// Turns about the target by the given angles.
    void orbit(float dYawDegrees, float dPitchDegrees);
    /// Moves camera and target sideways by a drag of (dx, dy) pixels in a view `heightPx`
    /// tall, so the point under the cursor follows it.
    void pan(float dx, float dy, float heightPx);
    /// Multiplies the distance (factor < 1: closer).
    void zoom(float factor);
    /// Looks at a sphere (centre, radius) so it fills the view.
    void frame(const QVector3D& centre, float radius);

    /// The world ray through widget point (x, y) of a view w x h pixels.
    void rayThrough(float x, float y, float w, float h, QVector3D* origin, QVector3D* direction) const;
    /// Where a world point appears in a view w x h pixels (z: depth in [-1, 1], beyond 1 or
    /// behind the camera when not visible).
    QVector3D project(const QVector3D& world, float w, float h) const;

private:
    QVector3D target_ = QVector3D(0, 0.5f, 0);
    float distance_ = 12.0f;
    float yaw_ = 35.0f;
    float pitch_ = 25.0f;
    float fov_ = 45.0f;
};

}  // namespace tumble::ui
