// The velocity view of the bodies that the impulse stages work on: v and ω with the inverse
// mass and world inverse inertia. Dynamic awake bodies are loaded from (P, L) and written
// back; kinematic bodies move with their fixed velocities and static or sleeping ones stand
// still, all three with zero inverse mass so that no impulse moves them.
#pragma once

#include <array>
#include <cstdint>

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/state.h>

#include <vector>

namespace tumble {

/// A body's velocities alone: what the contact solver keeps of every body at the start of
/// the step and as it was given them (ContactSolverScratch::start, entry; 56 bytes a body
/// where a SolverBody is 160, for every body of the scene).
struct BodyVelocity {
    Vec3 v = Vec3::Zero();
    Vec3 w = Vec3::Zero();
    bool touched = false;  ///< an impulse was applied: write the momenta back
};

struct SolverBody : BodyVelocity {
    Vec3 x = Vec3::Zero();  ///< centre of mass, world
    double invMass = 0.0;
    Mat3 invI = Mat3::Zero();  ///< world frame
};

/// The bodies of `contacts`, ascending, each once. `seen` is scratch: one flag per body,
/// all 0 before and after (sized here on first use).
void bodiesOf(const collision::ManifoldList& contacts, std::vector<std::uint8_t>& seen,
              std::vector<int>& out);
/// `list` made ascending with each body once, `seen` as for bodiesOf.
void uniqueBodies(std::vector<int>& list, std::vector<std::uint8_t>& seen);

/// `out` sized to the body count and every entry written once. The stages' per-body arrays
/// are sized by the World's constructor: the first write of a few hundred kilobytes took
/// the first step of a 910-body scene 4.3 ms on this machine (0.1 ms on later steps).
void sizeSolverBodies(const Model& model, std::vector<SolverBody>& out);

/// Loads the bodies `only` of `state` (ascending); the others are left standing still with
/// no mass (`out` is resized to the body count). The solver's cost stays with its contacts.
/// Body i of `state` as the solver sees it: its velocities, and its inverse mass and world
/// inverse inertia if it can move (dynamic and awake); the same as loadSolverBodies loads.
SolverBody solverBody(const Model& model, const State& state, int i);
void loadSolverBodies(const Model& model, const State& state, std::vector<SolverBody>& out,
                      const std::vector<int>& only);
/// The animated bodies among `only`: the velocities of their path's chord from `before` to
/// `state`, what the solve over that interval must match (a box carried by a keyed lift
/// then moves exactly as far as the lift: at the step's end velocity it gained a h² / 2 a
/// step while the lift sped up, and came off it). The impacts keep the path's own velocity
/// at their moment.
/// Body i's chord velocities over [before, state] into `out`, when it is animated and the
/// interval not empty; else false, `out` as it was.
bool chordVelocity(const Model& model, const State& state, const State& before, int i, BodyVelocity& out);
/// (For the solver's bodies, and for the velocities it starts from: friction's work is taken
/// against the same motion of the lift.)
template <class Body>
void chordVelocities(const Model& model, const State& state, const State& before, std::vector<Body>& out,
                     const std::vector<int>& only);
/// The same for the velocities alone (`out` sized to the body count once, as above).
void loadVelocities(const Model& model, const State& state, std::vector<BodyVelocity>& out,
                    const std::vector<int>& only);

/// Writes back the momenta of the bodies `only` that are dynamic, awake and took an
/// impulse: P = M v, L = I(t) ω.
void storeSolverBodies(const Model& model, const std::vector<SolverBody>& bodies, State& state,
                       const std::vector<int>& only);

inline Vec3 pointVelocity(const BodyVelocity& b, const Vec3& r) {
    return b.v + b.w.cross(r);
}

/// Cannot move, or ends the solve exactly at rest (stopRoundingMotion; still_islands.h).
inline bool atRest(const SolverBody& b) {
    return b.invMass == 0.0 || (b.v.isZero(0.0) && b.w.isZero(0.0));
}

/// Applies the impulse J at the offset r from the centre of mass (the paper's (22), (23)).
inline void applyImpulse(SolverBody& b, const Vec3& r, const Vec3& J) {
    if (J.isZero(0.0)) return;
    b.v += b.invMass * J;
    b.w += b.invI * r.cross(J);
    b.touched = true;
}

/// The inverse effective mass of the pair along the unit direction d at the offsets rA, rB:
/// the denominator of the paper's (27).
inline double inverseEffectiveMass(const SolverBody& a, const Vec3& rA, const SolverBody& b, const Vec3& rB,
                                   const Vec3& d) {
    return a.invMass + b.invMass + d.dot((a.invI * rA.cross(d)).cross(rA)) +
           d.dot((b.invI * rB.cross(d)).cross(rB));
}

/// Velocity of A's point relative to B's point at the same world place.
inline Vec3 relativeVelocity(const BodyVelocity& a, const Vec3& rA, const BodyVelocity& b, const Vec3& rB) {
    return pointVelocity(a, rA) - pointVelocity(b, rB);
}

/// Applies J to A and -J to B at their offsets and returns the kinetic energy it took out
/// of the pair: -J·(u⁻ + u⁺)/2 with u the relative point velocity before and after (exact
/// for an impulse on rigid bodies).
inline double applyPairImpulse(SolverBody& a, const Vec3& rA, SolverBody& b, const Vec3& rB, const Vec3& J) {
    const Vec3 before = relativeVelocity(a, rA, b, rB);
    applyImpulse(a, rA, J);
    applyImpulse(b, rB, -J);
    const Vec3 after = relativeVelocity(a, rA, b, rB);
    return -0.5 * J.dot(before + after);
}

/// The work the impulse J (on a at rA, −J on b at rB) draws from a body that no impulse
/// moves (no mass here: a kinematic or animated one; a static or sleeping one stands still
/// and gives 0): the impulse it gives times its point's velocity (EnergyLedger::doneByKinematic).
inline double drivenWork(const SolverBody& a, const Vec3& rA, const SolverBody& b, const Vec3& rB,
                         const Vec3& J) {
    double w = 0.0;
    if (a.invMass == 0.0) w -= J.dot(a.v + a.w.cross(rA));
    if (b.invMass == 0.0) w += J.dot(b.v + b.w.cross(rB));
    return w;
}

/// The pseudo-inverse of the symmetric positive semi-definite K (the normal responses of
/// up to four contact points; entries outside the top-left k × k are ignored and come back
/// zero). K may be singular (the four corners of a face give rank 3): eigen-directions
/// below 1e-9 of the largest eigenvalue count as null, so rounding is never divided by
/// almost zero and the answer is the least-norm one, symmetric for symmetric points.
Eigen::Matrix4d leastNormInverse(const Eigen::Matrix4d& K, int k);

/// The same by eigen-decomposition alone (what leastNormInverse falls back on), for tests.
Eigen::Matrix4d leastNormInverseReference(const Eigen::Matrix4d& K, int k);

/// The least-norm inverses of a K's principal sub-blocks computed last, by the points kept
/// (bit i: point i): the iterations of the contact solver ask pushingImpulses for the same
/// one or two subsets again and again, and an eigen-decomposition per ask was half of a
/// resting pyramid's step. Valid for one K only: reset it when K changes.
struct SubsetInverses {
    std::array<std::uint8_t, 2> mask{0, 0};  // 0: empty slot
    std::array<Eigen::Matrix4d, 2> inverse{Eigen::Matrix4d::Zero(), Eigen::Matrix4d::Zero()};
    int next = 0;
};

/// Impulses λ ≥ 0 for k points with K λ = g where they push: the least-norm solution
/// (Kinv = leastNormInverse(K, k)); every point whose impulse would pull is let go at once
/// (λ = 0; not the worst first, so that ties between symmetric points are not broken by
/// their order) and the others are solved again without it. `cache`, if given, keeps the
/// inverses of the subsets (the answer is the same with or without it).
Eigen::Vector4d pushingImpulses(const Eigen::Matrix4d& K, const Eigen::Matrix4d& Kinv,
                                const Eigen::Vector4d& g, int k, SubsetInverses* cache = nullptr);

/// Two unit tangents completing n to a right-handed frame.
void tangentFrame(const Vec3& n, Vec3& t1, Vec3& t2);

}  // namespace tumble
