// Normalisation that can be applied again without effect. Eigen's normalized(), applied
// to its own result, can move a coefficient by an ulp (about a third of all quaternions
// do), so load -> save -> load would drift and a saved scene would not reproduce the run
// it came from. A value already unit to within rounding is kept bit for bit instead.
#pragma once

#include <cmath>
#include <limits>

namespace tumble::io {

// Components so large that the squared norm overflows (1e200) are scaled down first, so the
// direction survives instead of collapsing to zero.
template <typename T>
T unitLength(const T& v) {
    const double n = v.norm();
    if (std::abs(n - 1.0) <= 4.0 * std::numeric_limits<double>::epsilon()) return v;
    if (!std::isfinite(n)) {
        T scaled = v;
        if constexpr (requires { scaled.coeffs(); }) scaled.coeffs().stableNormalize();
        else scaled.stableNormalize();
        return scaled;
    }
    return v.normalized();
}

}  // namespace tumble::io
