// The convex parts' sidecar (tumble/io/convex_parts_cache.h).
#include <tumble/io/atomic_file.h>
#include <tumble/io/convex_parts_cache.h>
#include <tumble/io/scene_file.h>

#include <tumble/convex_parts.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace tumble::io {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kFormat = "tumble-convex-parts";
constexpr int kVersion = 1;

std::string hex(std::uint64_t h) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

json vec(const Vec3& v) {
    return json::array({v.x(), v.y(), v.z()});
}

Vec3 vecOf(const json& j) {
    if (!j.is_array() || j.size() != 3) throw std::runtime_error("a vector is not 3 numbers");
    return Vec3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

json hullJson(const collision::ConvexHull& h) {
    json vertices = json::array(), faces = json::array(), edges = json::array();
    for (const Vec3& v : h.vertices) vertices.push_back(vec(v));
    for (const auto& f : h.faces) {
        const auto ids = h.verticesOf(f);
        faces.push_back({{"normal", vec(f.normal)},
                         {"offset", f.offset},
                         {"vertices", std::vector<int>(ids.begin(), ids.end())}});
    }
    for (const auto& e : h.edges) edges.push_back({e[0], e[1]});
    return {{"vertices", vertices}, {"faces", faces}, {"edges", edges}, {"interior", vec(h.interiorPoint)}};
}

// A hull as written, its indices checked (a cache edited by hand must not crash a run).
collision::ConvexHull hullOf(const json& j) {
    collision::ConvexHull h;
    for (const json& v : j.at("vertices")) h.vertices.push_back(vecOf(v));
    const int n = static_cast<int>(h.vertices.size());
    auto index = [&](const json& k) {
        const int i = k.get<int>();
        if (i < 0 || i >= n) throw std::runtime_error("a vertex index is out of range");
        return i;
    };
    for (const json& f : j.at("faces")) {
        std::vector<int> ids;
        for (const json& k : f.at("vertices")) ids.push_back(index(k));
        if (ids.size() < 3) throw std::runtime_error("a face has fewer than 3 vertices");
        h.addFace(vecOf(f.at("normal")), f.at("offset").get<double>(), ids);
    }
    for (const json& e : j.at("edges")) h.edges.push_back({index(e.at(0)), index(e.at(1))});
    h.interiorPoint = vecOf(j.at("interior"));
    if (h.vertices.size() < 4 || h.faces.size() < 4)
        throw std::runtime_error("a hull has too few vertices or faces");
    return h;
}

std::string keyOf(std::uint64_t hash, const mesh::ConvexPartsOptions& o) {
    char text[96];
    std::snprintf(text, sizeof text, "%s %d %.17g %d", hex(hash).c_str(), o.maxParts, o.tolerance,
                  o.resolution);
    return text;
}

}  // namespace

fs::path convexPartsCachePath(const fs::path& sceneFile) {
    fs::path p = sceneFile;
    if (p.extension() == ".json") p.replace_extension();
    p += ".convex-parts.json";
    return p;
}

std::vector<std::pair<ShapeDesc*, std::string>> convexPartsShapes(SceneDesc& scene) {
    std::vector<std::pair<ShapeDesc*, std::string>> out;
    for (size_t i = 0; i < scene.bodies.size(); ++i)
        forEachShape(scene.bodies[i], "bodies[" + std::to_string(i) + "]",
                     [&](ShapeDesc& s, const std::string& path) {
                         if (s.type == ShapeType::Mesh && s.collision == MeshCollision::ConvexParts)
                             out.emplace_back(&s, path);
                     });
    return out;
}

int readConvexPartsCache(SceneDesc& scene, const fs::path& cache, std::string* problem) {
    std::error_code ec;
    if (!fs::exists(cache, ec)) return 0;
    std::map<std::string, std::shared_ptr<const mesh::ConvexParts>> entries;
    try {
        std::ifstream in(cache, std::ios::binary);
        if (!in) throw std::runtime_error("cannot be read");
        std::ostringstream text;
        text << in.rdbuf();
        const json j = json::parse(text.str());
        if (j.at("format") != kFormat || j.at("version") != kVersion)
            throw std::runtime_error("is not a convex parts cache of version 1");
        for (const json& e : j.at("entries")) {
            auto parts = std::make_shared<mesh::ConvexParts>();
            parts->meshHash = std::stoull(e.at("mesh_hash").get<std::string>(), nullptr, 16);
            parts->options.maxParts = e.at("max_parts").get<int>();
            parts->options.tolerance = e.at("tolerance").get<double>();
            parts->options.resolution = e.at("resolution").get<int>();
            parts->meshVolume = e.at("mesh_volume").get<double>();
            parts->partsVolume = e.at("parts_volume").get<double>();
            parts->tolerance = e.at("tolerance_used").get<double>();
            parts->largestPokeOut = e.at("largest_poke_out").get<double>();
            parts->withinTolerance = e.at("within_tolerance").get<bool>();
            parts->seconds = e.at("seconds").get<double>();
            for (const json& h : e.at("parts")) parts->parts.push_back(hullOf(h));
            if (parts->parts.empty()) throw std::runtime_error("an entry has no parts");
            entries[keyOf(parts->meshHash, parts->options)] = std::move(parts);
        }
    } catch (const std::exception& e) {
        if (problem) *problem = cache.string() + ": " + e.what() + "; the convex parts are made again";
        return 0;
    }
    int found = 0;
    for (auto& [shape, path] : convexPartsShapes(scene)) {
        if (!shape->meshData || (shape->convexParts && mesh::convexPartsFit(*shape->convexParts, *shape)))
            continue;
        const auto it =
            entries.find(keyOf(mesh::meshHash(*shape->meshData), mesh::convexPartsOptionsOf(*shape)));
        if (it == entries.end()) continue;
        shape->convexParts = it->second;
        ++found;
    }
    return found;
}

int makeConvexParts(SceneDesc& scene, const std::string& sceneName,
                    const std::function<void(int, int, const std::string&)>& progress,
                    const std::atomic<bool>* cancel) {
    std::vector<std::pair<ShapeDesc*, std::string>> missing;
    for (auto& entry : convexPartsShapes(scene)) {
        ShapeDesc& s = *entry.first;
        if (s.meshData && !(s.convexParts && mesh::convexPartsFit(*s.convexParts, s)))
            missing.push_back(entry);
    }
    // Shapes of one mesh and options share their parts: made once.
    std::map<std::string, std::shared_ptr<const mesh::ConvexParts>> made;
    int done = 0;
    for (auto& [shape, path] : missing) {
        if (cancel && cancel->load()) break;
        if (progress) progress(done, static_cast<int>(missing.size()), path);
        auto& slot = made[keyOf(mesh::meshHash(*shape->meshData), mesh::convexPartsOptionsOf(*shape))];
        if (!slot) {
            try {
                slot = std::make_shared<const mesh::ConvexParts>(mesh::convexPartsOfShape(*shape));
            } catch (const std::invalid_argument& e) {
                throw InputError(sceneName, path + ".collision", shape->file + ": " + e.what());
            }
        }
        shape->convexParts = slot;
        ++done;
    }
    return done;
}

void writeConvexPartsCache(SceneDesc& scene, const fs::path& cache) {
    json entries = json::array();
    std::map<std::string, bool> written;
    for (auto& [shape, path] : convexPartsShapes(scene)) {
        const auto& parts = shape->convexParts;
        if (!parts || !mesh::convexPartsFit(*parts, *shape)) continue;
        if (written[keyOf(parts->meshHash, parts->options)]) continue;
        written[keyOf(parts->meshHash, parts->options)] = true;
        json hulls = json::array();
        for (const auto& h : parts->parts) hulls.push_back(hullJson(h));
        entries.push_back({{"mesh", shape->file},
                           {"mesh_hash", hex(parts->meshHash)},
                           {"max_parts", parts->options.maxParts},
                           {"tolerance", parts->options.tolerance},
                           {"resolution", parts->options.resolution},
                           {"mesh_volume", parts->meshVolume},
                           {"parts_volume", parts->partsVolume},
                           {"tolerance_used", parts->tolerance},
                           {"largest_poke_out", parts->largestPokeOut},
                           {"within_tolerance", parts->withinTolerance},
                           {"seconds", parts->seconds},
                           {"parts", hulls}});
    }
    if (entries.empty()) return;
    const json doc = {{"format", kFormat}, {"version", kVersion}, {"entries", entries}};
    writeFileAtomically(cache, doc.dump(1) + "\n");
}

}  // namespace tumble::io
