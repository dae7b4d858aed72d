#include "solver/joint_drive.h"

#include <algorithm>
#include <cmath>

namespace tumble::joint {

namespace {

// expm1(x) / x, 1 at 0.
double relativeExpm1(double x) {
    return x == 0.0 ? 1.0 : std::expm1(x) / x;
}

// The map's eigenvalues z₁, z₂ as their product D, b = −(1 − z₁)(1 − z₂) and c = −b / (q h²)
// (finite for q = 0).
struct Roots {
    double D = 1.0, b = 0.0, c = 1.0;
};

// The exact ones, z = e^{λh} for λ of m c'' = −k c − d c', computed without the cancellation
// of 1 + z₁z₂ − (z₁ + z₂) for small steps.
Roots exact(double p, double q, double h) {
    Roots r;
    r.D = std::exp(-p * h);
    const double half = 0.5 * p, disc = half * half - q;
    if (disc < 0.0) {  // underdamped: z = ρ e^{±iφ}, (1 − z)(1 − z̄) = |1 − z|²
        const double rho = std::exp(-half * h), phi = std::sqrt(-disc) * h;
        const double s = std::sin(0.5 * phi);
        const double re = -std::expm1(-half * h) + 2.0 * rho * s * s, im = rho * std::sin(phi);
        r.b = -(re * re + im * im);
        r.c = -r.b / (q * h * h);
        return r;
    }
    // Real roots λ = −p/2 ± √disc, the one near 0 as −q / (p/2 + √disc): (1 − z_slow) / (q h²)
    // = E(λ_slow h) / ((p/2 + √disc) h), E(x) = expm1(x) / x, finite for q = 0 (a damper).
    const double root = std::sqrt(disc), sum = half + root;
    if (!(sum > 0.0)) return r;  // neither stiffness nor damping
    const double slow = -q / sum, fast = -half - root;
    r.c = relativeExpm1(slow * h) / (sum * h) * -std::expm1(fast * h);
    r.b = -q * h * h * r.c;
    return r;
}

// Implicit Euler's, z = 1 / (1 − λh).
Roots implicitEuler(double p, double q, double h) {
    Roots r;
    r.D = r.c = 1.0 / (1.0 + p * h + q * h * h);
    r.b = -q * h * h * r.c;
    return r;
}

Roots blended(double p, double q, double h) {
    const double theta = std::sqrt(q) * h;
    // Critically damped or overdamped: real eigenvalues in (0, 1), exact at any step.
    if (0.5 * p * h >= theta || theta <= 0.5) return exact(p, q, h);
    if (theta >= 1.5) return implicitEuler(p, q, h);
    const double u = theta - 0.5, w = 1.0 - u * u * (3.0 - 2.0 * u);  // smoothstep from 1 to 0
    const Roots e = exact(p, q, h), i = implicitEuler(p, q, h);
    return {w * e.D + (1.0 - w) * i.D, w * e.b + (1.0 - w) * i.b, w * e.c + (1.0 - w) * i.c};
}

}  // namespace

DriveStep driveStep(double p, double q, double h) {
    const Roots r = blended(p, q, h);
    // With the half nudge the map of (c, v) has trace 1 + α + 3b/2 and determinant α + b/2.
    DriveStep d;
    d.b = r.b;
    d.alpha = r.D - 0.5 * r.b;
    d.kappa = r.c * (1.0 + 0.5 * q * h * h);
    return d;
}

}  // namespace tumble::joint
