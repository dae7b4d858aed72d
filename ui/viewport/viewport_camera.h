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
    /// Orthographic: a parallel projection showing, at every depth, what the perspective one
    /// shows at the target's (a view 2 d tan(fov / 2) tall); the eye and the orbit stay.
    bool isOrthographic() const { return orthographic_; }
    void setOrthographic(bool on) { orthographic_ = on; }

    /// Pitch is clamped short of the poles, distance to a small positive minimum.
    void set(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees);

    QVector3D eye() const;
    /// The screen's up: square to the line of sight, in the vertical plane through it (world
    /// y seen from any side; looking straight down, the way the yaw faces).
    QVector3D up() const;
    /// The depth range; orthographic, it starts behind the eye (nothing between the eye and
    /// the far side of the scene is cut).
    float nearPlane() const;
    float farPlane() const;
    /// Half the height of the orthographic view (m), the perspective one's at the target.
    float orthographicHalfHeight() const;
    /// The length that scales things drawn at a constant size on screen at `point` (the
    /// handles): its distance from the eye, or the camera's distance when orthographic.
    float screenScaleAt(const QVector3D& point) const;
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
    bool orthographic_ = false;
};

}  // namespace tumble::ui
