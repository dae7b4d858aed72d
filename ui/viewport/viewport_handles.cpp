#include "viewport/viewport_handles.h"

#include "document/joint_presets.h"

#include <algorithm>
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

Vec3 partOrigin(const BodyDesc& body, int part) {
    return body.position + body.orientation.normalized() * body.shape.parts.at(size_t(part)).position;
}

BodyDesc partMoved(const BodyDesc& body, int part, const Vec3& axis, double distance) {
    BodyDesc b = body;
    PartDesc& p = b.shape.parts.at(size_t(part));
    p.position += body.orientation.normalized().conjugate() * (distance * axis);
    return b;
}

BodyDesc partRotated(const BodyDesc& body, int part, const Vec3& axis, double angle) {
    BodyDesc b = body;
    PartDesc& p = b.shape.parts.at(size_t(part));
    const Quat q = body.orientation.normalized();
    // World turn r, seen in the body's frame: q^-1 r q, applied after the part's own turn.
    const Quat r(Eigen::AngleAxisd(angle, axis));
    p.orientation = (q.conjugate() * r * q * p.orientation).normalized();
    return b;
}

JointDesc movedAnchor(const SceneDesc& scene, const JointDesc& j, const Vec3& axis, double distance) {
    JointDesc out = j;
    const BodyFrame a = frameOf(scene, j.bodyA), b = frameOf(scene, j.bodyB);
    const Vec3 point = a.toWorld(j.anchorA) + distance * axis;
    out.anchorA = a.toLocal(point);
    if (j.type != JointType::Distance && j.type != JointType::Rope) out.anchorB = b.toLocal(point);
    return out;
}

JointDesc turnedAxis(const SceneDesc& scene, const JointDesc& j, const Vec3& axis, double angle) {
    JointDesc out = j;
    const BodyFrame a = frameOf(scene, j.bodyA), b = frameOf(scene, j.bodyB);
    const Quat r(Eigen::AngleAxisd(angle, axis));
    if (j.axisA) out.axisA = a.q.conjugate() * (r * (a.q * *j.axisA));
    if (j.axisB) out.axisB = b.q.conjugate() * (r * (b.q * *j.axisB));
    return out;
}

JointDesc draggedBallLimit(const BallLimitFrame& f, const JointDesc& j, int grip, const Vec3& rayOrigin,
                           const Vec3& rayDir, double step) {
    JointDesc out = j;
    const Vec3 e2 = f.n.cross(f.e1);
    if ((grip == 0 || grip == 1) && j.swingLimit) {
        const Vec3 towards = grip == 0 ? f.e1 : e2;
        const auto hit = planeHit(rayOrigin, rayDir, f.anchor, f.n.cross(towards));
        if (!hit) return out;
        const Vec3 d = *hit - f.anchor;
        const double degree = M_PI / 180.0;
        const double theta = std::clamp(snap(std::atan2(d.dot(towards), d.dot(f.n)), step), degree, M_PI - degree);
        const bool round = (*j.swingLimit)[0] == (*j.swingLimit)[1];
        (*out.swingLimit)[size_t(grip)] = theta;
        if (round) (*out.swingLimit)[size_t(1 - grip)] = theta;
        return out;
    }
    if ((grip == 2 || grip == 3) && j.twistLimits) {
        const auto hit = planeHit(rayOrigin, rayDir, f.anchor, f.n);
        if (!hit || !((*hit - f.anchor).norm() > 0.0)) return out;
        const double phi = snap(signedAngle(f.e1, *hit - f.anchor, f.n), step);
        auto& [lower, upper] = *out.twistLimits;
        if (grip == 2)
            lower = std::clamp(phi, -M_PI, upper);
        else
            upper = std::clamp(phi, lower, M_PI);
    }
    return out;
}

}  // namespace tumble::ui::handles
