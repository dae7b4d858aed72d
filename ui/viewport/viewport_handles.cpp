#include "viewport/viewport_handles.h"

#include <cmath>

namespace tumble::ui::handles {

std::optional<double> axisParameter(const Vec3& rayOrigin, const Vec3& rayDir, const Vec3& origin,
                                    const Vec3& axis) {
    const double dn = rayDir.norm();
    if (!(dn > 0)) return std::nullopt;
    const Vec3 d = rayDir / dn;
    // The two lines' closest points: minimise |origin + s a - (o + t d)|.
    const double b = axis.dot(d);
    const double denom = 1.0 - b * b;
    if (denom < 1e-6) return std::nullopt;  // within ~0.08° of parallel
    const Vec3 w = origin - rayOrigin;
    return (b * d.dot(w) - axis.dot(w)) / denom;
}

std::optional<Vec3> planeHit(const Vec3& rayOrigin, const Vec3& rayDir, const Vec3& origin,
                             const Vec3& axis) {
    const double dn = rayDir.norm();
    if (!(dn > 0)) return std::nullopt;
    const Vec3 d = rayDir / dn;
    const double denom = axis.dot(d);
    if (std::abs(denom) < 1e-4) return std::nullopt;
    const double t = axis.dot(origin - rayOrigin) / denom;
    if (t < 0) return std::nullopt;
    return rayOrigin + t * d;
}

double signedAngle(const Vec3& from, const Vec3& to, const Vec3& axis) {
    const Vec3 a = from - axis * axis.dot(from);
    const Vec3 b = to - axis * axis.dot(to);
    return std::atan2(axis.dot(a.cross(b)), a.dot(b));
}

double snap(double value, double step) {
    if (!(step > 0)) return value;
    return std::round(value / step) * step;
}

BodyDesc moved(const BodyDesc& body, const Vec3& axis, double distance) {
    BodyDesc b = body;
    b.position = body.position + distance * axis;
    return b;
}

BodyDesc rotated(const BodyDesc& body, const Vec3& pivot, const Vec3& axis, double angle) {
    BodyDesc b = body;
    const Quat r(Eigen::AngleAxisd(angle, axis));
    b.orientation = (r * body.orientation).normalized();
    b.position = pivot + r * (body.position - pivot);
    return b;
}

namespace {

// Body `name`'s placement (the world's for an empty name or one no body has).
void frameOf(const SceneDesc& scene, const std::string& name, Vec3& p, Quat& q) {
    p = Vec3::Zero();
    q = Quat::Identity();
    for (const BodyDesc& b : scene.bodies) {
        if (name.empty() || b.name != name) continue;
        p = b.position;
        q = b.orientation.normalized();
        return;
    }
}

}  // namespace

Vec3 jointAnchor(const SceneDesc& scene, const JointDesc& j) {
    Vec3 p;
    Quat q;
    frameOf(scene, j.bodyA, p, q);
    return p + q * j.anchorA;
}

JointDesc movedAnchor(const SceneDesc& scene, const JointDesc& j, const Vec3& axis, double distance) {
    JointDesc out = j;
    Vec3 pa, pb;
    Quat qa, qb;
    frameOf(scene, j.bodyA, pa, qa);
    frameOf(scene, j.bodyB, pb, qb);
    const Vec3 point = pa + qa * j.anchorA + distance * axis;
    out.anchorA = qa.conjugate() * (point - pa);
    if (j.type != JointType::Distance && j.type != JointType::Rope) out.anchorB = qb.conjugate() * (point - pb);
    return out;
}

JointDesc turnedAxis(const SceneDesc& scene, const JointDesc& j, const Vec3& axis, double angle) {
    JointDesc out = j;
    Vec3 pa, pb;
    Quat qa, qb;
    frameOf(scene, j.bodyA, pa, qa);
    frameOf(scene, j.bodyB, pb, qb);
    const Quat r(Eigen::AngleAxisd(angle, axis));
    if (j.axisA) out.axisA = qa.conjugate() * (r * (qa * *j.axisA));
    if (j.axisB) out.axisB = qb.conjugate() * (r * (qb * *j.axisB));
    return out;
}

}  // namespace tumble::ui::handles
