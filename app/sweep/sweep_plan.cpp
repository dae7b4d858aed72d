#include "sweep_plan.h"

#include <tumble/integrators.h>
#include <tumble/io/atomic_file.h>
#include <tumble/io/scene_file.h>
#include <tumble/state.h>

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace tumble::sweep {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return {};
    return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

// A number as its shortest text that reads back exactly.
std::string shortest(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

// A number, or a fraction of two ("1/60": a step is often thought of so).
bool parseDouble(const std::string& text, double& v) {
    const std::string t = trim(text);
    if (t.empty()) return false;
    const auto slash = t.find('/');
    if (slash != std::string::npos) {
        double a = 0.0, b = 0.0;
        if (!parseDouble(t.substr(0, slash), a) || !parseDouble(t.substr(slash + 1), b) || b == 0.0)
            return false;
        v = a / b;
        return std::isfinite(v);
    }
    const char* end = t.data() + t.size();
    const auto r = std::from_chars(t.data(), end, v);
    return r.ec == std::errc() && r.ptr == end && std::isfinite(v);
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string part;
    std::istringstream in(s);
    while (std::getline(in, part, sep)) out.push_back(trim(part));
    if (!s.empty() && s.back() == sep) out.emplace_back();
    return out;
}

// One step of a path: a key, or an index into an array.
struct Step {
    std::string key;
    int index = -1;
};

// "ball.velocity[1]" -> ball, velocity, [1]. Throws on a malformed path.
std::vector<Step> stepsOf(const std::string& path) {
    std::vector<Step> steps;
    const std::string where = "--vary " + path + ": ";
    for (const std::string& part : split(path, '.')) {
        const auto bracket = part.find('[');
        const std::string key = part.substr(0, bracket);
        if (key.empty()) throw SweepError{where + "an empty name in the path (names are joined by '.')"};
        steps.push_back({key, -1});
        for (auto b = bracket; b != std::string::npos;) {
            const auto close = part.find(']', b);
            int i = -1;
            const std::string digits = close == std::string::npos ? "" : part.substr(b + 1, close - b - 1);
            const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), i);
            if (digits.empty() || r.ec != std::errc() || r.ptr != digits.data() + digits.size() || i < 0)
                throw SweepError{where + "'" + part + "': an index is [N], N a whole number from 0"};
            steps.push_back({"", i});
            b = close + 1 < part.size() ? close + 1 : std::string::npos;
            if (b != std::string::npos && part[b] != '[')
                throw SweepError{where + "'" + part + "': nothing may follow an index but another"};
        }
    }
    return steps;
}

std::string keysOf(const ojson& object) {
    std::string out;
    for (auto it = object.begin(); it != object.end(); ++it) out += (out.empty() ? "" : ", ") + it.key();
    return out;
}

// The value a path names in the normalised scene; throws naming what is missing.
ojson& resolve(ojson& scene, const std::string& path, const std::string& sceneName) {
    const std::vector<Step> steps = stepsOf(path);
    const std::string where = "--vary " + path + ": ";
    ojson* node = nullptr;
    std::string what;  // what the messages call the place reached: "body 'ball'", then "ball.shape"
    const std::string& head = steps.front().key;
    std::string shown = head;
    if (head == "settings") {
        node = &scene["settings"];
        what = "settings";
        // Settings the file leaves out when they are the default: there to be varied.
        if (steps.size() > 1 && steps[1].key == "integrator" && !node->contains("integrator"))
            (*node)["integrator"] = defaultIntegrator().name;
        if (steps.size() > 1 && steps[1].key == "impacts" && !node->contains("impacts"))
            (*node)["impacts"] = toString(ImpactTiming::Exact);
    } else {
        for (const char* list : {"bodies", "joints"}) {
            if (!scene.contains(list)) continue;
            for (ojson& item : scene[list]) {
                if (item.value("name", std::string()) != head) continue;
                if (node) throw SweepError{where + "'" + head + "' names both a body and a joint"};
                node = &item;
                what = std::string(list == std::string("bodies") ? "body" : "joint") + " '" + head + "'";
            }
        }
        if (!node) {
            std::string names;
            for (const ojson& b : scene["bodies"]) names += (names.empty() ? "" : ", ") + b.value("name", std::string());
            throw SweepError{where + "no body or joint named '" + head + "' in " + sceneName + " (bodies: " + names +
                             "; or settings)"};
        }
    }
    for (std::size_t k = 1; k < steps.size(); ++k) {
        const Step& s = steps[k];
        if (s.index >= 0) {
            if (!node->is_array())
                throw SweepError{where + what + " is not a list: no [" + std::to_string(s.index) + "]"};
            if (s.index >= static_cast<int>(node->size()))
                throw SweepError{where + what + " has " + std::to_string(node->size()) + " entries: no [" +
                                 std::to_string(s.index) + "]"};
            node = &(*node)[s.index];
            shown += "[" + std::to_string(s.index) + "]";
            what = shown;
            continue;
        }
        if (!node->is_object() || !node->contains(s.key))
            throw SweepError{where + what + " has no '" + s.key + "'" +
                             (node->is_object() ? " (it has: " + keysOf(*node) + ")" : "")};
        node = &(*node)[s.key];
        shown += "." + s.key;
        what = shown;
    }
    if (node->is_object() || node->is_array())
        throw SweepError{where + "names " + (node->is_array() ? "a list" : "a group of values") +
                         ": give one value" + (node->is_array() ? " as " + path + "[N]" : "")};
    return *node;
}

// The values a path names: one, or with a wildcard for the body ("*.restitution",
// "bodies[*].friction") the same key of every body that has it (a static body has no mass).
std::vector<ojson*> resolveAll(ojson& scene, const std::string& path, const std::string& sceneName) {
    std::string rest;
    if (path.rfind("*.", 0) == 0)
        rest = path.substr(1);
    else if (path.rfind("bodies[*].", 0) == 0)
        rest = path.substr(9);
    if (rest.empty()) return {&resolve(scene, path, sceneName)};
    std::vector<ojson*> places;
    std::string firstProblem;
    for (const ojson& b : scene["bodies"]) {
        const std::string name = b.value("name", std::string());
        try {
            places.push_back(&resolve(scene, name + rest, sceneName));
        } catch (const SweepError& e) {
            if (firstProblem.empty()) firstProblem = e.message;
        }
    }
    if (places.empty())
        throw SweepError{"--vary " + path + ": no body has it" +
                         (firstProblem.empty() ? "" : " (" + firstProblem + ")")};
    return places;
}

// The JSON value of `text` for a place holding `current`; throws when it cannot hold it.
ojson valueFor(const ojson& current, const std::string& text, const std::string& path) {
    const std::string where = "--vary " + path + ": '" + text + "' ";
    if (current.is_boolean()) {
        if (text == "true") return true;
        if (text == "false") return false;
        throw SweepError{where + "is not true or false"};
    }
    if (current.is_number()) {
        double v = 0;
        if (!parseDouble(text, v)) throw SweepError{where + "is not a number"};
        if (current.is_number_integer()) {
            if (v != std::floor(v) || std::abs(v) > 9.0e15) throw SweepError{where + "is not a whole number"};
            return static_cast<long long>(v);
        }
        return v;
    }
    return text;
}

ojson normalisedScene(const fs::path& scene) {
    try {
        return ojson::parse(io::sceneToJson(io::readSceneFile(scene)));
    } catch (const io::InputError& e) {
        throw SweepError{e.what()};
    }
}

// FNV-1a, 64 bits, of the text, in hex: the scene's content as a sweep planned it.
std::string contentHash(const std::string& text) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    return hashHex(h);
}

ojson planJson(const Plan& plan) {
    ojson j;
    j["format"] = "tumble-sweep";
    j["version"] = 1;
    j["scene"] = plan.scene.string();
    if (!plan.sceneHash.empty()) j["scene_hash"] = plan.sceneHash;
    j["vary"] = ojson::array();
    for (const Vary& v : plan.vary) j["vary"].push_back({{"path", v.path}, {"values", v.values}});
    j["count"] = plan.count;
    j["bodies"] = plan.bodies;
    return j;
}

// Mesh files are named relative to the scene's folder: made relative to the variants' one.
void moveMeshPaths(ojson& scene, const fs::path& sceneDir, const fs::path& variantsDir) {
    for (ojson& b : scene["bodies"]) {
        ojson& shape = b["shape"];
        if (shape.value("type", std::string()) != "mesh" || !shape.contains("file")) continue;
        const fs::path file = shape["file"].get<std::string>();
        if (file.is_absolute()) continue;
        const fs::path target = fs::absolute(sceneDir / file).lexically_normal();
        shape["file"] = target.lexically_relative(fs::absolute(variantsDir).lexically_normal()).generic_string();
    }
}

}  // namespace

Vary parseVary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos)
        throw SweepError{"--vary '" + text + "': give PATH=VALUES, e.g. ball.restitution=0.2,0.5,0.8"};
    Vary v;
    v.path = trim(text.substr(0, eq));
    const std::string values = trim(text.substr(eq + 1));
    const std::string where = "--vary " + v.path + ": ";
    if (v.path.empty()) throw SweepError{"--vary '" + text + "': no path before '='"};
    if (values.empty()) throw SweepError{where + "an empty list of values"};
    if (values.find(':') != std::string::npos) {
        const std::vector<std::string> parts = split(values, ':');
        double a = 0, b = 0, n = 0;
        if (parts.size() != 3 || !parseDouble(parts[0], a) || !parseDouble(parts[1], b) || !parseDouble(parts[2], n))
            throw SweepError{where + "'" + values + "' is not start:stop:count"};
        if (n != std::floor(n) || n < 1 || n > 1e6)
            throw SweepError{where + "the count '" + parts[2] + "' is not a whole number from 1 to 1000000"};
        const int count = static_cast<int>(n);
        if (count == 1 && a != b) throw SweepError{where + "one value cannot include both ends; give a count of 2 or more"};
        // Each value to 12 significant digits: 0.1 to 1.5 in 15 steps is 0.4, not
        // 0.39999999999999997 (the values are what the summary shows and the variants hold).
        for (int k = 0; k < count; ++k) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "%.12g", k == count - 1 ? b : a + (b - a) * k / (count - 1));
            v.values.push_back(shortest(std::strtod(buf, nullptr)));
        }
        return v;
    }
    v.values = split(values, ',');
    for (const std::string& s : v.values)
        if (s.empty()) throw SweepError{where + "an empty value in '" + values + "'"};
    return v;
}

std::vector<int> Plan::choice(int k) const {
    std::vector<int> c(vary.size());
    for (int i = static_cast<int>(vary.size()) - 1; i >= 0; --i) {
        const int n = static_cast<int>(vary[i].values.size());
        c[i] = k % n;
        k /= n;
    }
    return c;
}

std::string Plan::name(int k) const {
    const std::size_t width = std::max<std::size_t>(4, std::to_string(std::max(count - 1, 0)).size());
    std::string s = std::to_string(k);
    return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

Plan makePlan(const fs::path& scene, const std::vector<Vary>& vary) {
    if (vary.empty()) throw SweepError{"sweep: nothing varies: give at least one --vary PATH=VALUES"};
    Plan plan;
    plan.scene = fs::absolute(scene).lexically_normal();
    plan.vary = vary;
    ojson json = normalisedScene(scene);
    plan.sceneHash = contentHash(json.dump());
    double count = 1;
    for (std::size_t i = 0; i < vary.size(); ++i) {
        for (std::size_t k = 0; k < i; ++k)
            if (vary[k].path == vary[i].path) throw SweepError{"--vary " + vary[i].path + ": given twice"};
        for (ojson* place : resolveAll(json, vary[i].path, scene.string()))
            for (const std::string& v : vary[i].values) valueFor(*place, v, vary[i].path);
        count *= static_cast<double>(vary[i].values.size());
    }
    if (count > 1e6) throw SweepError{"sweep: " + shortest(count) + " variants: at most 1000000 in one sweep"};
    plan.count = static_cast<int>(count);
    for (const ojson& b : json["bodies"])
        if (b.value("motion", std::string()) == "dynamic") plan.bodies.push_back(b.value("name", std::string()));
    return plan;
}

fs::path variantFile(const Plan& plan, const fs::path& dir, int k) {
    return dir / "variants" / (plan.name(k) + ".json");
}

std::vector<std::string> writeVariants(const Plan& plan, const fs::path& dir,
                                       const std::function<bool()>& stopped) {
    auto stopHere = [&] {
        if (stopped && stopped()) throw SweepStopped{};
    };
    const fs::path manifest = dir / "sweep.json";
    const ojson mine = planJson(plan);
    std::error_code ec;
    if (fs::exists(manifest, ec)) {
        ojson theirs;
        try {
            std::ifstream in(manifest);
            theirs = ojson::parse(in);
        } catch (const std::exception&) {
            throw SweepError{manifest.string() + ": not a sweep's plan (it cannot be read); choose another --out"};
        }
        ojson mineAsTheirs = mine;  // a plan kept before the scene's hash was: compared without it
        if (!theirs.contains("scene_hash")) mineAsTheirs.erase("scene_hash");
        if (theirs != mineAsTheirs) {
            ojson theirsWithout = theirs, mineWithout = mine;
            theirsWithout.erase("scene_hash");
            mineWithout.erase("scene_hash");
            if (theirsWithout == mineWithout)
                throw SweepError{
                    manifest.string() + ": " + plan.scene.string() +
                    " changed since this sweep began: its variants so far are of the scene as it "
                    "was; choose another --out for the scene as it is, or remove the folder"};
            throw SweepError{manifest.string() + ": this folder holds another sweep (another scene or other --vary); "
                                                 "choose another --out, or remove the folder"};
        }
    }
    const ojson base = normalisedScene(plan.scene);
    auto variant = [&](int k) {
        ojson scene = base;
        const std::vector<int> c = plan.choice(k);
        for (std::size_t i = 0; i < plan.vary.size(); ++i)
            for (ojson* place : resolveAll(scene, plan.vary[i].path, plan.scene.string()))
                *place = valueFor(*place, plan.vary[i].values[c[i]], plan.vary[i].path);
        return scene;
    };
    // Every variant checked before any is written or run: a value the scene format refuses
    // was an `invalid` row found only when its turn came.
    // The same reading gives each variant's step note (a dt longer than a frame steps once a
    // frame: varying dt past it changes nothing).
    std::vector<std::string> notes;
    for (int k = 0; k < plan.count; ++k) {
        stopHere();
        try {
            const std::string note =
                stepNote(io::parseScene(variant(k).dump(), "variant " + plan.name(k)).settings);
            if (!note.empty()) notes.push_back(plan.name(k) + ": " + note);
        } catch (const io::InputError& e) {
            std::string values;
            const std::vector<int> c = plan.choice(k);
            for (std::size_t i = 0; i < plan.vary.size(); ++i)
                values += (i ? ", " : "") + plan.vary[i].path + "=" + plan.vary[i].values[c[i]];
            throw SweepError{std::string(e.what()) + " (" + values + "); nothing was run"};
        }
    }
    fs::create_directories(dir / "variants", ec);
    if (ec)
        throw SweepError{(dir / "variants").string() + ": cannot be made: " + io::plainReason(ec.value())};
    try {
        for (int k = 0; k < plan.count; ++k) {
            stopHere();
            const fs::path file = variantFile(plan, dir, k);
            if (fs::exists(file, ec)) continue;  // (a resumed sweep: the same plan made it)
            ojson scene = variant(k);
            moveMeshPaths(scene, plan.scene.parent_path(), dir / "variants");
            io::writeFileAtomically(file, scene.dump(2) + "\n");
        }
        if (!fs::exists(manifest, ec)) io::writeFileAtomically(manifest, mine.dump(2) + "\n");
    } catch (const std::runtime_error& e) {
        throw SweepError{e.what()};
    }
    return notes;
}

std::string valueInVariant(const Plan& plan, const fs::path& dir, int k, const std::string& path) {
    std::ifstream in(variantFile(plan, dir, k));
    if (!in) return {};
    try {
        ojson scene = ojson::parse(in);
        std::string text;
        for (const ojson* v : resolveAll(scene, path, variantFile(plan, dir, k).string())) {
            const std::string t = v->is_number_float() ? shortest(v->get<double>())
                                  : v->is_string()     ? v->get<std::string>()
                                                       : v->dump();
            if (!text.empty() && t != text) return "mixed";
            text = t;
        }
        return text;
    } catch (const SweepError&) {
        return {};
    } catch (const nlohmann::json::exception&) {
        return {};
    }
}

Plan readPlan(const fs::path& dir) {
    const fs::path manifest = dir / "sweep.json";
    std::ifstream in(manifest);
    if (!in) throw SweepError{manifest.string() + ": no sweep here (no sweep.json)"};
    try {
        const ojson j = ojson::parse(in);
        if (j.value("format", std::string()) != "tumble-sweep")
            throw SweepError{manifest.string() + ": format: not a tumble-sweep"};
        Plan plan;
        plan.scene = j.at("scene").get<std::string>();
        for (const ojson& v : j.at("vary")) plan.vary.push_back({v.at("path"), v.at("values")});
        plan.count = j.at("count").get<int>();
        plan.bodies = j.at("bodies").get<std::vector<std::string>>();
        plan.sceneHash = j.value("scene_hash", std::string());
        return plan;
    } catch (const nlohmann::json::exception& e) {
        throw SweepError{manifest.string() + ": cannot be read: " + e.what()};
    }
}

}  // namespace tumble::sweep
