#include "model/compile_groups.h"

#include "common/pair_key.h"

#include <algorithm>
#include <map>

namespace tumble {

namespace {

std::map<std::string, int> indexOf(const std::vector<std::string>& names) {
    std::map<std::string, int> index;
    for (int k = 0; k < static_cast<int>(names.size()); ++k) index.emplace(names[k], k);
    return index;
}

}  // namespace

std::vector<std::string> collisionGroupNames(const Settings& settings) {
    std::vector<std::string> names = settings.collisionGroups;
    if (std::find(names.begin(), names.end(), "default") == names.end())
        names.insert(names.begin(), "default");
    return names;
}

void validateCollisionGroups(const SceneDesc& scene) {
    const Settings& s = scene.settings;
    for (size_t k = 0; k < s.collisionGroups.size(); ++k) {
        const std::string field = "settings.collision_groups[" + std::to_string(k) + "]";
        if (s.collisionGroups[k].empty()) throw SceneError(field, "must not be empty");
        if (std::find(s.collisionGroups.begin(), s.collisionGroups.begin() + static_cast<long>(k),
                      s.collisionGroups[k]) != s.collisionGroups.begin() + static_cast<long>(k))
            throw SceneError(field, "'" + s.collisionGroups[k] + "' is already a group");
    }
    const std::vector<std::string> names = collisionGroupNames(s);
    if (static_cast<int>(names.size()) > kMostCollisionGroups)
        throw SceneError("settings.collision_groups", "names " + std::to_string(names.size()) +
                                                          " groups with \"default\"; at most " +
                                                          std::to_string(kMostCollisionGroups));
    const auto groups = indexOf(names);
    auto known = [&](const std::string& name) { return groups.contains(name); };
    auto listed = [&] {
        std::string text;
        for (const std::string& n : names) text += (text.empty() ? "'" : ", '") + n + "'";
        return text;
    };
    for (size_t k = 0; k < s.groupsApart.size(); ++k)
        for (int m = 0; m < 2; ++m)
            if (!known(s.groupsApart[k][m]))
                throw SceneError(
                    "settings.groups_apart[" + std::to_string(k) + "][" + std::to_string(m) + "]",
                    "'" + s.groupsApart[k][m] + "' is not a collision group (" + listed() + ")");
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        if (!known(scene.bodies[i].collisionGroup))
            throw SceneError("bodies[" + std::to_string(i) + "].collision_group",
                             "'" + scene.bodies[i].collisionGroup + "' is not a collision group (" +
                                 listed() + "; name it in settings.collision_groups)");
    std::map<std::string, int> bodies;
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        bodies.emplace(scene.bodies[i].name, static_cast<int>(i));
    for (size_t k = 0; k < scene.noCollide.size(); ++k) {
        const std::string at = "no_collide[" + std::to_string(k) + "]";
        for (int m = 0; m < 2; ++m)
            if (!bodies.contains(scene.noCollide[k][m]))
                throw SceneError(at + "[" + std::to_string(m) + "]",
                                 "'" + scene.noCollide[k][m] + "' is not a body");
        if (scene.noCollide[k][0] == scene.noCollide[k][1])
            throw SceneError(
                at, "names '" + scene.noCollide[k][0] + "' twice: a body never collides with itself");
    }
}

void compileCollisionGroups(const SceneDesc& scene, Model& m) {
    const std::vector<std::string> names = collisionGroupNames(scene.settings);
    const auto groups = indexOf(names);
    const std::uint64_t all = names.size() >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << names.size()) - 1;
    m.groupCollides.assign(names.size(), all);
    for (const auto& pair : scene.settings.groupsApart) {
        const int a = groups.at(pair[0]), b = groups.at(pair[1]);
        m.groupCollides[a] &= ~(std::uint64_t{1} << b);
        m.groupCollides[b] &= ~(std::uint64_t{1} << a);
        m.filtered = true;
    }
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        m.bodies[i].group = groups.at(scene.bodies[i].collisionGroup);
    std::map<std::string, int> bodies;
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        bodies.emplace(scene.bodies[i].name, static_cast<int>(i));
    m.pairsApart.clear();
    for (const auto& pair : scene.noCollide) {
        const int a = bodies.at(pair[0]), b = bodies.at(pair[1]);
        m.pairsApart.push_back(pairKey(std::min(a, b), std::max(a, b)));
    }
    std::sort(m.pairsApart.begin(), m.pairsApart.end());
    m.pairsApart.erase(std::unique(m.pairsApart.begin(), m.pairsApart.end()), m.pairsApart.end());
    m.filtered = m.filtered || !m.pairsApart.empty();
}

}  // namespace tumble
