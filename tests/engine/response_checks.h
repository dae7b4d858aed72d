// Checks shared by the collision-response suites; each returns what is wrong ("" if
// nothing), for QVERIFY2.
#pragma once

#include "scene_builders.h"

#include <tumble/model.h>

#include <QString>

#include <cmath>

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

}  // namespace tumble::test
