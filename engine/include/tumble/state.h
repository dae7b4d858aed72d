// The runtime state: plain, copyable, hashable. Everything that changes during a run
// is here; everything fixed is in the Model. A snapshot of State is a recorded frame.
#pragma once

#include <tumble/math.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tumble {

/// The paper's state vector (17): centre of mass x, orientation q (unit quaternion,
/// body to world), linear momentum P, angular momentum L, all in world coordinates. An
/// animated body has no momentum: its P is its centre's velocity and its L its angular
/// velocity, where its path has it (placeOnPath).
struct BodyState {
    Vec3 x = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 P = Vec3::Zero();
    Vec3 L = Vec3::Zero();
};

/// The contact solver's memory of one contact point: the impulses it applied in the last
/// step, to start the next step's solve from (warm starting). Matched by bodies and feature.
struct ContactMemory {
    int bodyA = -1;
    int bodyB = -1;
    std::uint32_t feature = 0;
    Vec3 position = Vec3::Zero();  ///< world, where the point was
    double normalImpulse = 0.0;    ///< N·s, along the manifold normal
    Vec3 tangentImpulse = Vec3::Zero();  ///< N·s, world: this point's share of its manifold's friction
    double twistImpulse = 0.0;           ///< N·m·s about the normal: this point's share
    double step = 0.0;                   ///< s, the step these impulses were for
};

struct State {
    double time = 0.0;
    std::vector<BodyState> bodies;
    /// Sleep bookkeeping per body (empty: every body awake, none at rest yet).
    std::vector<double> restTime;       ///< s the body has been slow enough to sleep
    std::vector<std::uint8_t> asleep;   ///< 1: not simulated until something touches it
    std::vector<ContactMemory> contacts;  ///< warm-start impulses of the last step
    /// The pairs in contact at the end of the last step (sorted pair keys, see touchingKey):
    /// the next step finds no impact between them. With it a run continued from a copy of
    /// the state is bit-for-bit the run that made the copy (the timeline re-simulates from
    /// keyframes). Unknown (a state made from a scene, or edited) means "found at the first
    /// step", where what touches already is resting contact.
    std::vector<std::uint64_t> touching;
    bool touchingKnown = false;
    /// Per joint (Model::joints): its impulse in the last step, the next step's warm start
    /// (a ball's three components; distance and rope use x; hinge, slider and fixed: the
    /// force on A in the world). Empty: none yet.
    std::vector<Vec3> jointImpulses;
    /// Per joint: the torque on A in the last step (hinge, slider and fixed; else zero).
    std::vector<Vec3> jointTorques;
    /// Per joint: the force it put on body A over the last step, at A's anchor (N, world;
    /// body B took the opposite): its rows' impulse and its position projection's, over the
    /// step's length (the force break_force is compared with), and a slider's motor and
    /// limits along its axis. Empty: none yet.
    std::vector<Vec3> jointForces;
    /// Per joint: the couple it put on body A over the last step (N m, world; B took the
    /// opposite), its angular rows' and its projection's, and a hinge's motor and limits
    /// about its axis (hinge, slider and fixed; zero for the others). With jointForces, the
    /// joint's reaction. Empty: none yet.
    std::vector<Vec3> jointCouples;
    /// Per joint: the length (s) of the solve its impulse and torque come from (0, or empty:
    /// unknown). The warm start turns them back into impulses over that time, scaled to the
    /// next step's length as the contacts' are.
    std::vector<double> jointSteps;
    /// Per joint: the time it broke (its force passed JointDesc::breakForce), NaN while it
    /// holds; empty: none has broken. A broken joint acts no more and its bodies collide.
    std::vector<double> jointBrokenAt;
    /// Per joint: a hinge's angle at the end of the last step, counted on past ±π (rad; the
    /// other joints' entries 0). A step takes each hinge's angle as the one within π of this,
    /// so that limits beyond a half turn hold. Empty: unknown (an angle is then taken within
    /// [-π, π], as the scene's poses give it).
    std::vector<double> hingeAngles;
    bool jointBroken(int k) const { return !jointBrokenAt.empty() && !std::isnan(jointBrokenAt[k]); }

    bool isAsleep(int body) const { return !asleep.empty() && asleep[body] != 0; }
};

/// A 64-bit FNV-1a digest of the exact bits of the time and every body's x, q, P, L.
std::uint64_t hashState(const State& state);

/// The digest as 16 lower-case hex digits.
std::string hashHex(std::uint64_t hash);

}  // namespace tumble
