// A small portable random generator for the engine tests (SplitMix64): the same numbers
// on every platform and library, unlike std::uniform_real_distribution.
#pragma once

#include <tumble/math.h>

#include <cstdint>

namespace tumble::test {

struct Rng {
    std::uint64_t s;
    double uniform(double lo = 0.0, double hi = 1.0) {
        std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
    }
    Vec3 vec(double lo, double hi) { return Vec3(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)); }
    /// A unit vector, uniform over directions (rejection from the cube).
    Vec3 direction() {
        for (;;) {
            const Vec3 v = vec(-1, 1);
            if (v.squaredNorm() > 1e-4 && v.squaredNorm() <= 1.0) return v.normalized();
        }
    }
    Mat3 rotation() {
        Quat q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        return q.normalized().toRotationMatrix();
    }
};

}  // namespace tumble::test
