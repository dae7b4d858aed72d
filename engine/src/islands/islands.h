// Which bodies a step's impacts concern (World::step). An island is a group of awake
// dynamic bodies linked by the step's broadphase pairs, whose boxes are swept over the whole
// step, and by the joints that hold: bodies of different islands cannot meet within the
// step, nor pull on each other. Static, kinematic and sleeping bodies do not link (they
// move the same whatever their partners do). Only the islands with a moment of impact are
// cut and integrated again; the others keep their free step and are "parked" meanwhile.
#pragma once

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/profile.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace tumble {

/// The root of i in a union-find forest (parent[r] == r at a root), halving the path.
inline int islandRoot(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

struct IslandScratch {
    std::vector<int> parent;
    std::vector<std::uint8_t> impacted;  // per island root
    std::vector<int> cursor;             // impactIslands' filling, per island
};

/// parked[i] = 1 for the awake dynamic bodies whose island has none of `impacts`; returns
/// how many there are.
int parkIslandsWithoutImpact(const Model& model, const State& state,
                             const std::vector<std::pair<int, int>>& pairs,
                             const std::vector<collision::ImpactEvent>& impacts, IslandScratch& scratch,
                             std::vector<std::uint8_t>& parked);

/// The islands of the last parkIslandsWithoutImpact that have an impact, ordered by their
/// lowest body: island g's awake dynamic bodies are bodies[begin[g], begin[g + 1]). Returns
/// how many there are (begin is empty when none).
int impactIslands(const Model& model, const State& state, IslandScratch& scratch,
                  std::vector<int>& groupOfRoot, std::vector<int>& bodies, std::vector<int>& begin);

}  // namespace tumble
