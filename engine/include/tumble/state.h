// The runtime state: plain, copyable, hashable. Everything that changes during a run
// is here; everything fixed is in the Model. A snapshot of State is a recorded frame.
#pragma once

#include <tumble/math.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tumble {

/// The paper's state vector (17): centre of mass x, orientation q (unit quaternion,
/// body to world), linear momentum P, angular momentum L, all in world coordinates.
struct BodyState {
    Vec3 x = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 P = Vec3::Zero();
    Vec3 L = Vec3::Zero();
};

struct State {
    double time = 0.0;
    std::vector<BodyState> bodies;
};

/// A 64-bit FNV-1a digest of the exact bits of the time and every body's x, q, P, L.
std::uint64_t hashState(const State& state);

/// The digest as 16 lower-case hex digits.
std::string hashHex(std::uint64_t hash);

}  // namespace tumble
