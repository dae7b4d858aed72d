// What approach is settling rather than an impact, along a contact's normal (detect.cpp,
// impact.cpp). The resting speed (World: 2 |g| h, twice what gravity adds in the step) is
// what gravity can give a pair pressed together along n; across n it gives nothing, and a
// body grazing a box's edge while falling past it (normal nearly level) met it at 0.57 m/s
// at 1/30 s, under the 0.65 m/s resting speed, and flew on through the box's corner
// (issue 45). Along n the share of gravity counts, at least a quarter of it (contacts
// between moving bodies, which gravity alone does not press together, keep a floor).
#pragma once

#include <tumble/math.h>

#include <algorithm>
#include <cmath>

namespace tumble {

inline double restingShare(const Vec3& gravity, const Vec3& normal) {
    const double g = gravity.norm();
    return g > 0.0 ? std::max(std::abs(gravity.dot(normal)) / g, 0.25) : 1.0;
}

}  // namespace tumble
