// Time of impact by conservative advancement, for continuous collision detection.
#pragma once

#include <tumble/collision.h>

#include <optional>

namespace tumble::collision {

/// A body's motion over one step: centre of mass moves linearly c0 -> c1, orientation slerps
/// q0 -> q1, the body frame sits at localCenter from the centre of mass (pose origin = c - R localCenter).
struct Sweep {
    Vec3 c0 = Vec3::Zero(), c1 = Vec3::Zero();
    /// How far the centre's path sags from the chord: c(s) = c0 + s (c1 - c0) - s (1 - s) bow,
    /// the parabola of a constant acceleration a over the step h (bow = a h² / 2; zero: the
    /// chord). Without it a body falling past an edge was swept up to g h² / 8 off its path
    /// (1.4 mm at 1/30 s), enough to miss a graze or misplace its moment.
    Vec3 bow = Vec3::Zero();
    Quat q0 = Quat::Identity(), q1 = Quat::Identity();
    Vec3 localCenter = Vec3::Zero();
    Pose at(double s) const;  ///< s in [0,1]
    Vec3 centre(double s) const { return c0 + s * (c1 - c0) - s * (1.0 - s) * bow; }
};

/// s: fraction of the step of first touch; normal out of B towards A; point midway between
/// the surfaces at that time.
struct Impact {
    double s = 0.0;
    Vec3 normal = Vec3(0, 1, 0);
    Vec3 point = Vec3::Zero();
};

/// First time in [0,1] at which the shapes come within `tolerance` of touching, or nothing.
/// Conservative advancement (Mirtich) on the GJK distance with a bound on the approach speed
/// (linear relative speed along the normal + |ω| × bounding radius of each), so it never
/// skips a contact however fast or thin the bodies.
/// Pairs: any convex-convex, convex-plane, convex-mesh, mesh-plane (per triangle the swept
/// bounds touch), mesh-mesh (per triangle pair). Plane-plane returns nothing. If the shapes
/// already touch at s = 0 the answer is s = 0.
///
/// `window` narrows the search when the caller knows more: the shapes stay farther apart than
/// the tolerance before `from` (a search with a larger tolerance ended there), and there is an
/// impact at `notAfter` (a search that has passed it may stop with nothing; an answer it does
/// give is the one it would give without it). Meshes search from 0 regardless.
struct Window {
    double from = 0.0;
    double notAfter = 1.0;
};
std::optional<Impact> timeOfImpact(const Shape& a, const Sweep& sa, const Shape& b, const Sweep& sb,
                                   double tolerance, Window window = {});

}  // namespace tumble::collision
