// Checks shared by the collision-response suites; each returns what is wrong ("" if
// nothing), for QVERIFY2.
#pragma once

#include "scene_builders.h"

#include <tumble/model.h>

#include <QString>

#include <cmath>
#include <vector>

namespace tumble::test {

/// Newton's cradle after the impact: bodies 0..n-2 at rest and the last one moving at
/// (v, 0, 0), to 1e-9 v; kinetic energy ke0 kept to 1e-9.
inline QString cradleEndProblem(const World& w, int n, double v, double ke0) {
    auto num = [](double x) { return QString::number(x, 'g', 17); };
    for (int k = 0; k + 1 < n; ++k) {
        const Vec3 u = velocityOf(w, k);
        if (u.norm() >= 1e-9 * v)
            return QString("ball %1 moves at (%2, %3, %4), expected rest")
                .arg(k)
                .arg(num(u.x()), num(u.y()), num(u.z()));
    }
    const Vec3 u = velocityOf(w, n - 1);
    if ((u - Vec3(v, 0, 0)).norm() >= 1e-9 * v)
        return QString("last ball moves at (%1, %2, %3), expected (%4, 0, 0)")
            .arg(num(u.x()), num(u.y()), num(u.z()), num(v));
    const double ke = energy(w.model(), w.state()).kinetic;
    if (std::abs(ke - ke0) >= 1e-9 * ke0)
        return QString("kinetic energy %1 J, was %2 J").arg(num(ke), num(ke0));
    return {};
}

/// Newton's cradle along x, where each ball should be at time w.state().time: `x[k]`, given
/// by the caller from the moments of impact (the first ball stopped where it met the row,
/// the middle ones where they started, the last one moving on from its start since the
/// moment the first touched). To 1e-9 m: a moment of impact late or early by a step, or
/// a row that sank into itself for a step and was pushed apart, shows as millimetres.
inline QString cradlePositionProblem(const World& w, const std::vector<double>& x) {
    for (size_t k = 0; k < x.size(); ++k) {
        const double at = w.state().bodies[k].x.x();
        if (std::abs(at - x[k]) > 1e-9)
            return QString("ball %1 at x = %2 m, expected %3 m (%4 m off)")
                .arg(k)
                .arg(at, 0, 'g', 17)
                .arg(x[k], 0, 'g', 17)
                .arg(at - x[k], 0, 'g', 3);
    }
    return {};
}

}  // namespace tumble::test
