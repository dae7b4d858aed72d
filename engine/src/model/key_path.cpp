#include <tumble/key_path.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble {

namespace {

// The rotation vector of a unit quaternion (angle in [0, pi]).
Vec3 logOf(const Quat& q) {
    const Quat u = q.w() < 0.0 ? Quat(-q.coeffs()) : q;
    const double s = u.vec().norm();
    if (s < 1e-300) return Vec3::Zero();
    return (2.0 * std::atan2(s, u.w()) / s) * u.vec();
}

Quat expOf(const Vec3& h) {
    const double angle = h.norm();
    if (angle < 1e-300) return Quat::Identity();
    return Quat(Eigen::AngleAxisd(angle, h / angle));
}

Mat3 skew(const Vec3& v) {
    Mat3 k;
    k << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return k;
}

// SO(3)'s right Jacobian: for q(t) = q0 exp(h(t)) the angular velocity in the body frame
// of q(t) is J(h) dh/dt.
Mat3 rightJacobian(const Vec3& h) {
    const double a = h.norm();
    const Mat3 k = skew(h);
    if (a < 1e-4) return Mat3::Identity() - 0.5 * k + k * k / 6.0;  // (the series: error ~a^3/24)
    return Mat3::Identity() - (1.0 - std::cos(a)) / (a * a) * k + (a - std::sin(a)) / (a * a * a) * k * k;
}

// The cubic Hermite basis and its derivative in u.
struct Hermite {
    double h00, h10, h01, h11, d00, d10, d01, d11;
    explicit Hermite(double u)
        : h00(2 * u * u * u - 3 * u * u + 1),
          h10(u * u * u - 2 * u * u + u),
          h01(-2 * u * u * u + 3 * u * u),
          h11(u * u * u - u * u),
          d00(6 * u * u - 6 * u),
          d10(3 * u * u - 4 * u + 1),
          d01(-6 * u * u + 6 * u),
          d11(3 * u * u - 2 * u) {}
};

}  // namespace

KeyPath::KeyPath(std::vector<BodyKey> keys, KeyInterpolation interpolation)
    : keys_(std::move(keys)), interpolation_(interpolation) {
    for (size_t k = 0; k < keys_.size(); ++k) {
        keys_[k].orientation.normalize();
        if (k > 0 && keys_[k].orientation.dot(keys_[k - 1].orientation) < 0.0)
            keys_[k].orientation.coeffs() *= -1.0;
    }
    if (interpolation_ != KeyInterpolation::Smooth) return;
    const size_t n = keys_.size();
    velocity_.assign(n, Vec3::Zero());
    spin_.assign(n, Vec3::Zero());
    // (The first and last keys keep zero: the path eases in and out of its holds.)
    auto segmentSpin = [&](size_t k) {  // the constant-rate angular velocity over segment k
        const BodyKey &a = keys_[k], &b = keys_[k + 1];
        return Vec3(a.orientation * logOf(a.orientation.conjugate() * b.orientation) / (b.time - a.time));
    };
    for (size_t k = 1; k + 1 < n; ++k) {
        velocity_[k] =
            (keys_[k + 1].position - keys_[k - 1].position) / (keys_[k + 1].time - keys_[k - 1].time);
        spin_[k] = 0.5 * (segmentSpin(k - 1) + segmentSpin(k));
    }
}

PathPoint KeyPath::at(double t) const {
    PathPoint p;
    if (t < keys_.front().time || keys_.size() == 1) {
        p.position = keys_.front().position;
        p.orientation = keys_.front().orientation;
        return p;
    }
    if (t >= keys_.back().time) {
        p.position = keys_.back().position;
        p.orientation = keys_.back().orientation;
        return p;
    }
    const auto next = std::upper_bound(keys_.begin(), keys_.end(), t,
                                       [](double time, const BodyKey& key) { return time < key.time; });
    const size_t k = static_cast<size_t>(next - keys_.begin()) - 1;
    const BodyKey &a = keys_[k], &b = keys_[k + 1];
    const double span = b.time - a.time, u = (t - a.time) / span;
    const Vec3 turn = logOf(a.orientation.conjugate() * b.orientation);  // in a's body frame
    if (interpolation_ == KeyInterpolation::Linear) {
        p.position = a.position + u * (b.position - a.position);
        p.velocity = (b.position - a.position) / span;
        p.orientation = (a.orientation * expOf(u * turn)).normalized();
        p.angularVelocity = a.orientation * turn / span;  // (the axis is the same in every frame of the turn)
        return p;
    }
    const Hermite w(u);
    p.position = w.h00 * a.position + w.h10 * span * velocity_[k] + w.h01 * b.position +
                 w.h11 * span * velocity_[k + 1];
    p.velocity = (w.d00 * a.position + w.d10 * span * velocity_[k] + w.d01 * b.position +
                  w.d11 * span * velocity_[k + 1]) /
                 span;
    // h from 0 to `turn`, its rates at the ends the keys' spins carried into h's terms.
    const Vec3 m0 = a.orientation.conjugate() * spin_[k];  // J(0) = I
    const Vec3 m1 = rightJacobian(turn).inverse() * (b.orientation.conjugate() * spin_[k + 1]);
    const Vec3 h = w.h10 * span * m0 + w.h01 * turn + w.h11 * span * m1;
    const Vec3 dh = (w.d10 * span * m0 + w.d01 * turn + w.d11 * span * m1) / span;
    p.orientation = (a.orientation * expOf(h)).normalized();
    p.angularVelocity = p.orientation * (rightJacobian(h) * dh);
    return p;
}

double KeyPath::fastest(double reach) const {
    double top = 0.0;
    for (size_t k = 0; k + 1 < keys_.size(); ++k) {
        const double t0 = keys_[k].time, span = keys_[k + 1].time - t0;
        for (int n = 0; n <= 32; ++n) {
            const PathPoint p = at(n == 32 ? std::nextafter(t0 + span, t0) : t0 + span * n / 32.0);
            top = std::max(top, p.velocity.norm() + p.angularVelocity.norm() * reach);
        }
    }
    return top;
}

}  // namespace tumble
