// A hinge's or slider's spring and servo: a spring and damper on the joint's coordinate as a
// soft velocity row along its free axis (joints.cpp solves it with the motor and limits).
//
// Over a step of h the row sets the coordinate's rate to
//     v = α v₀ + κ (v* − v₀) + (b / h) (c − rest),
// with v₀ the rate at the step's start, v* the rate the rest of the step gives (gravity, the
// other joints and contacts) and c the coordinate at the step's new poses; then the bodies are
// moved along the axis (nudgeDrives) so that over the step the coordinate moves by h (v₀ + v)
// / 2, as a trapezoid (for the coordinate alone, what the row's own impulse would move it by
// in half the step). For the
// coordinate alone, with the effective mass m along the axis, that map of (c, v) has trace
// 1 + α + 3b/2 and determinant α + b/2; they are set to the exact eigenvalues' z₁ + z₂ and
// z₁z₂ of m c'' = −k c − d c' over h (p = d / m, q = k / m): b = −(1 − z₁)(1 − z₂), α = z₁z₂
// − b/2, so the oscillation's frequency and damping ratio are exact at any step. κ = −(b /
// (q h²))(1 + q h² / 2) makes it rest exactly at the static deflection m a / k under a steady
// push, with no rate left (for a damper alone: the exact terminal rate a / p). Past half a
// radian a step (ω h > 0.5, an underdamped spring too stiff for the step to follow) the
// eigenvalues blend into implicit Euler's (z = 1 / (1 − λ h), reached at ω h = 1.5), which
// holds a spring of any stiffness like a hard joint; both pairs lie in the stable region
// (|z₁z₂| < 1, |z₁ + z₂| < 1 + z₁z₂), which is convex, so the blend does too.
// A servo by its time constant τ (p = 2/τ, q = 1/τ²) is a rate row instead, whose target
// (b/h)(c₀ − target) + (α + b) v₀ is the same map's from the step's start (c₀, v₀): it follows
// the critically damped path whatever the masses and loads, up to its force.
#pragma once

namespace tumble::joint {

struct DriveStep {
    double alpha = 1.0;  ///< the weight of the start's rate
    double kappa = 1.0;  ///< the weight of what the rest of the step adds to it
    double b = 0.0;      ///< the pull per unit of (c − rest) per step: rate += (b / h) (c − rest)
};

/// The row's coefficients for p = damping / m (1/s), q = stiffness / m (1/s²) over h.
DriveStep driveStep(double p, double q, double h);

}  // namespace tumble::joint
