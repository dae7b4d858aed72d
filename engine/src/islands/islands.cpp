#include "islands/islands.h"

namespace tumble {

int parkIslandsWithoutImpact(const Model& model, const State& state,
                             const std::vector<std::pair<int, int>>& pairs,
                             const std::vector<collision::ImpactEvent>& impacts, IslandScratch& s,
                             std::vector<std::uint8_t>& parked) {
    const int n = static_cast<int>(model.bodies.size());
    auto links = [&](int b) { return model.bodies[b].motion == Motion::Dynamic && !state.isAsleep(b); };
    s.parent.resize(n);
    for (int i = 0; i < n; ++i) s.parent[i] = i;
    for (const auto& [a, b] : pairs)
        if (links(a) && links(b)) s.parent[islandRoot(s.parent, a)] = islandRoot(s.parent, b);
    // A joint that holds joins its bodies' islands: they are cut, or parked, together.
    for (const JointModel& j : model.joints)
        if (j.b >= 0 && !state.jointBroken(j.index) && links(j.a) && links(j.b))
            s.parent[islandRoot(s.parent, j.a)] = islandRoot(s.parent, j.b);
    s.impacted.assign(n, 0);
    for (const auto& e : impacts)
        for (int b : {e.bodyA, e.bodyB})
            if (links(b)) s.impacted[islandRoot(s.parent, b)] = 1;
    parked.assign(n, 0);
    int count = 0;
    for (int i : model.dynamicBodies) {
        if (!links(i) || s.impacted[islandRoot(s.parent, i)]) continue;
        parked[i] = 1;
        ++count;
    }
    return count;
}

int impactIslands(const Model& model, const State& state, IslandScratch& s, std::vector<int>& groupOfRoot,
                  std::vector<int>& bodies, std::vector<int>& begin) {
    auto links = [&](int b) { return model.bodies[b].motion == Motion::Dynamic && !state.isAsleep(b); };
    auto root = [&](int i) {  // (without halving: the forest is read only)
        while (s.parent[i] != i) i = s.parent[i];
        return i;
    };
    groupOfRoot.assign(model.bodies.size(), -1);
    begin.assign(1, 0);
    for (int i : model.dynamicBodies) {
        if (!links(i) || !s.impacted[root(i)]) continue;
        int& g = groupOfRoot[root(i)];
        if (g < 0) {
            g = static_cast<int>(begin.size()) - 1;
            begin.push_back(0);
        }
        ++begin[g + 1];
    }
    const int groups = static_cast<int>(begin.size()) - 1;
    for (int g = 0; g < groups; ++g) begin[g + 1] += begin[g];
    bodies.resize(begin.back());
    s.cursor.assign(begin.begin(), begin.end() - 1);
    for (int i : model.dynamicBodies)
        if (links(i) && s.impacted[root(i)]) bodies[s.cursor[groupOfRoot[root(i)]]++] = i;
    if (groups == 0) begin.clear();
    return groups;
}

}  // namespace tumble
