// What the joint suites build and measure: a joint, how far a joint is from holding in a
// World, the energy of the dynamic bodies (kinetic plus gravity's potential along y,
// g = 9.81), the elliptic integral of a pendulum's period, and a swing's crossings.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>

#include <tumble/model.h>
#include <tumble/scene.h>
#include <tumble/state.h>
#include <tumble/world.h>

namespace tumble::test {

/// A joint of `type` from body `a` (anchor in its frame) to body `b` (empty: the world;
/// anchorB then a world point); `length` for distance and rope (negative: as placed).
inline JointDesc joint(const std::string& name, JointType type, const std::string& a, const Vec3& anchorA,
                       const std::string& b, const Vec3& anchorB, double length = -1.0) {
    JointDesc j;
    j.name = name;
    j.type = type;
    j.bodyA = a;
    j.anchorA = anchorA;
    j.bodyB = b;
    j.anchorB = anchorB;
    j.length = length;
    return j;
}

inline double anchorGap(const World& w, int k) {
    const JointModel& j = w.model().joints[k];
    const BodyState& a = w.state().bodies[j.a];
    const Vec3 pa = a.x + a.q * j.anchorA;
    const Vec3 pb = j.b < 0 ? j.anchorB : Vec3(w.state().bodies[j.b].x + w.state().bodies[j.b].q * j.anchorB);
    return (pa - pb).norm();
}

inline double energy(const World& w) {
    double e = 0.0;
    for (size_t i = 0; i < w.model().bodies.size(); ++i) {
        const BodyModel& b = w.model().bodies[i];
        if (b.motion != Motion::Dynamic) continue;
        const BodyState& s = w.state().bodies[i];
        const Derived d = derive(b, s);
        e += 0.5 * b.mass * d.v.squaredNorm() + 0.5 * d.omega.dot(s.L) - b.mass * w.model().settings.gravity.dot(s.x);
    }
    return e;
}

/// K(k), the complete elliptic integral of the first kind, by the arithmetic-geometric mean.
inline double ellipticK(double k) {
    double a = 1.0, b = std::sqrt(1.0 - k * k);
    for (int i = 0; i < 40; ++i) {
        const double an = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = an;
    }
    return std::numbers::pi / (2.0 * a);
}

/// Times at which a body's centre crosses x = 0 (interpolated within the step): the
/// period from the first to the last, two crossings a period. add() after each step.
struct Crossings {
    double lastX, first = -1.0, last = -1.0;
    int count = 0;
    explicit Crossings(double x0) : lastX(x0) {}
    void add(double t0, double h, double x) {
        if ((lastX > 0.0) != (x > 0.0)) {
            const double t = t0 + h * lastX / (lastX - x);
            if (first < 0.0) first = t;
            last = t;
            ++count;
        }
        lastX = x;
    }
    double period() const { return 2.0 * (last - first) / (count - 1); }
};

}  // namespace tumble::test
