// glTF 2.0 written directly: the JSON with nlohmann-json, every mesh, time and key in one
// binary buffer grown by appending (amortised), so the export is linear in bodies times
// frames. (Assimp 5.2's glTF 2 exporter grows its buffer to the exact size at every
// accessor, a copy of the whole buffer each time: quadratic in the bodies.)
//
// Layout: one buffer; a buffer view per accessor; one time accessor shared by every
// sampler; per mesh POSITION (with its bounds, as the format requires), NORMAL and the
// indices; per moving body a translation and a rotation sampler. Floats are written
// little-endian, as the format says; this machine is little-endian (checked at compile
// time below).
#include <tumble/io/atomic_file.h>
#include <tumble/io/gltf_export.h>
#include <tumble/io/tessellate.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>

namespace tumble::io {

namespace fs = std::filesystem;
using nlohmann::json;

static_assert(std::endian::native == std::endian::little,
              "the glTF buffer is written as the machine holds it");

namespace {

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// What the render mesh of a shape depends on: equal keys, equal meshes. Imported meshes are
// shared by the loader per file and scale, so their data's address tells.
std::string shapeKey(const ShapeDesc& s) {
    char buf[256];
    switch (s.type) {
        case ShapeType::Mesh:
            std::snprintf(buf, sizeof buf, "mesh %p", static_cast<const void*>(s.meshData.get()));
            break;
        case ShapeType::Plane:
            std::snprintf(buf, sizeof buf, "plane %.17g %.17g %.17g %.17g", s.normal.x(), s.normal.y(),
                          s.normal.z(), s.distance);
            break;
        case ShapeType::Box:
            std::snprintf(buf, sizeof buf, "box %.17g %.17g %.17g", s.halfExtents.x(), s.halfExtents.y(),
                          s.halfExtents.z());
            break;
        case ShapeType::Compound: return "compound";  // (never looked up: its parts are)
        default:
            std::snprintf(buf, sizeof buf, "%s %.17g %.17g", toString(s.type), s.radius,
                          s.type == ShapeType::Sphere ? 0.0 : s.halfHeight);
    }
    return buf;
}

// A unit vector in single precision: normalised after rounding, so that the validator's
// unit-length checks hold for the floats written.
template <int N>
std::array<float, N> unitFloats(std::array<double, N> v) {
    double norm = 0;
    for (double c : v) norm += c * c;
    norm = std::sqrt(norm);
    std::array<float, N> out;
    for (int i = 0; i < N; ++i) out[i] = static_cast<float>(v[i] / norm);
    return out;
}

// The JSON document and its binary buffer, built together.
class Builder {
public:
    json doc = json::object();
    std::string bin;

    // Appends `count` elements of `components` floats (or uint32s) as one accessor in its
    // own buffer view; returns the accessor's index. `bounds`: with min and max per component.
    template <class T>
    int accessor(const std::vector<T>& data, int components, const char* type, int target, bool bounds) {
        static_assert(sizeof(T) == 4);
        const size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(T));
        json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}};
        if (target) view["target"] = target;
        doc["bufferViews"].push_back(std::move(view));
        json acc = {{"bufferView", doc["bufferViews"].size() - 1},
                    {"componentType", std::is_same_v<T, float> ? kFloat : kUnsignedInt},
                    {"count", data.size() / components},
                    {"type", type}};
        if (bounds) {
            std::vector<T> lo(data.begin(), data.begin() + components), hi = lo;
            for (size_t i = 0; i < data.size(); ++i) {
                lo[i % components] = std::min(lo[i % components], data[i]);
                hi[i % components] = std::max(hi[i % components], data[i]);
            }
            acc["min"] = lo;
            acc["max"] = hi;
        }
        doc["accessors"].push_back(std::move(acc));
        return static_cast<int>(doc["accessors"].size() - 1);
    }

    int mesh(const RenderMesh& m, const std::string& name) {
        std::vector<float> positions, normals;
        positions.reserve(3 * m.positions.size());
        normals.reserve(3 * m.normals.size());
        for (size_t i = 0; i < m.positions.size(); ++i) {
            for (int c = 0; c < 3; ++c) positions.push_back(static_cast<float>(m.positions[i][c]));
            const auto n = unitFloats<3>({m.normals[i].x(), m.normals[i].y(), m.normals[i].z()});
            normals.insert(normals.end(), n.begin(), n.end());
        }
        const int p = accessor(positions, 3, "VEC3", kArrayBuffer, true);
        const int n = accessor(normals, 3, "VEC3", kArrayBuffer, false);
        const int idx = accessor(m.indices, 1, "SCALAR", kElementArrayBuffer, false);
        doc["meshes"].push_back(
            {{"name", name},
             {"primitives",
              json::array(
                  {{{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", idx}, {"material", 0}}})}});
        return static_cast<int>(doc["meshes"].size() - 1);
    }
};

void writeU32(std::ostream& out, std::uint32_t v) {
    char b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    out.write(b, 4);
}

// The .gltf and its .bin cannot be renamed in one step, and a kill between two renames
// would pair an old .gltf with a new .bin. So the old .gltf is first replaced by a bridge,
// the new .gltf naming the .bin's temporary; then the .bin takes its name (the temporary
// kept as a second link); then the .gltf naming the .bin replaces the bridge. At every
// moment the .gltf on disk fits the buffer it names.
void commitPair(const fs::path& file, AtomicFile& main, AtomicFile& bin, json& doc) {
    // Failures of the .bin are named by the file the user asked for.
    auto asBuffer = [&](auto step) {
        try {
            step();
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(file.string() + ": its buffer " + e.what());
        }
    };
    const fs::path temporary = bin.temporaryPath();
    std::error_code ec;
    const fs::path folder = fs::path(file).parent_path();
    const bool besideIt =
        fs::equivalent(folder.empty() ? fs::path(".") : folder,
                       temporary.has_parent_path() ? temporary.parent_path() : fs::path("."), ec);
    if (!fs::exists(file, ec) || !besideIt) {
        // No old pair to keep (or a .bin linked elsewhere, which the .gltf cannot name).
        asBuffer([&] { bin.commit(); });
        main.commit();
        return;
    }
    doc["buffers"][0]["uri"] = temporary.filename().string();
    AtomicFile bridge(file);
    bridge.stream() << doc.dump(2);
    bridge.ready();
    bridge.commit();
    bin.keepTemporary();  // (the .gltf now names it)
    asBuffer([&] { bin.commitKeepingTemporary(); });
    main.commit();
    fs::remove(temporary, ec);
}

}  // namespace

struct GltfTrajectoryWriter::Outputs {
    std::unique_ptr<AtomicFile> main, bin;
};

GltfTrajectoryWriter::GltfTrajectoryWriter(fs::path file, bool binary, ExportOptions options)
    : TrajectoryWriter(std::move(file), std::move(options)), binary_(binary) {}

GltfTrajectoryWriter::~GltfTrajectoryWriter() = default;

void GltfTrajectoryWriter::open() {
    // Opened now so that an unwritable path fails before the run; the main file first, so
    // that the message names the file the user asked for.
    outputs_ = std::make_unique<Outputs>();
    outputs_->main = std::make_unique<AtomicFile>(file());
    // The .bin's stale temporaries are removed after the new pair is in (close()): a .gltf
    // left by an export killed mid-switch names one.
    if (!binary_)
        outputs_->bin =
            std::make_unique<AtomicFile>(fs::path(file()).replace_extension(".bin"), AtomicFile::Stale::Keep);
    times_.clear();
    poses_.assign(bodies().size(), {});
}

void GltfTrajectoryWriter::writeFrame(int k, const State& state) {
    times_.push_back(k / frameRate());
    for (size_t n = 0; n < bodies().size(); ++n) {
        const int i = bodies()[n];
        const BodyState& s = state.bodies[i];
        const Vec3 p = bodyFramePosition(model().bodies[i], s);
        for (double v : {p.x(), p.y(), p.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z()}) {
            if (!std::isfinite(v)) {
                throw std::runtime_error(file().string() + ": body '" + model().bodies[i].name +
                                         "' has a non-finite pose at frame " + std::to_string(k));
            }
        }
        poses_[n].push_back({p.x(), p.y(), p.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z()});
    }
}

void GltfTrajectoryWriter::close() {
    // A plane is drawn as a square that covers every exported position, and 10 m at least.
    double reach = 0.0;
    for (const auto& body : poses_) {
        for (const auto& p : body) reach = std::max(reach, Vec3(p[0], p[1], p[2]).norm());
    }
    const double planeHalf = std::max(10.0, 1.5 * reach + 1.0);

    Builder g;
    json& doc = g.doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "Tumble"}};
    doc["scene"] = 0;
    doc["materials"] = json::array(
        {{{"name", "body"},
          {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0}}}}});
    doc["bufferViews"] = json::array();
    doc["accessors"] = json::array();
    doc["meshes"] = json::array();

    // Node 0 is the root, named after the file; channels find their node by index, but
    // importers that go by name (assimp) must not find a body's name on the root.
    std::string rootName = fs::path(file()).stem().string();
    auto taken = [&](const std::string& n) {
        return std::any_of(bodies().begin(), bodies().end(),
                           [&](int i) { return model().bodies[i].name == n; });
    };
    while (rootName.empty() || taken(rootName)) rootName += " scene";
    json nodes = json::array({{{"name", rootName}}});
    json children = json::array();

    // The frames' times, shared by every sampler (strictly increasing, with bounds).
    int timeAccessor = -1;
    std::vector<float> times;
    times.reserve(times_.size());
    for (double t : times_) times.push_back(static_cast<float>(t));

    json samplers = json::array(), channels = json::array();
    std::map<std::string, int> shared;  // bodies of the same shape share its mesh
    for (size_t n = 0; n < bodies().size(); ++n) {
        const int i = bodies()[n];
        const BodyModel& b = model().bodies[i];
        const ShapeDesc& shape = scene().bodies[i].shape;
        const auto& first = poses_[n].front();
        json node = {{"name", b.name},
                     {"translation", {float(first[0]), float(first[1]), float(first[2])}},
                     {"rotation", unitFloats<4>({first[4], first[5], first[6], first[3]})}};

        // The mesh of a shape, shared by the shapes alike; -1 for none.
        auto meshOf = [&](const ShapeDesc& s, const std::string& name) {
            const std::string key = shapeKey(s);
            auto it = shared.find(key);
            if (it == shared.end()) {
                const RenderMesh rm = tessellate(s, segments_, planeHalf);
                it = shared.emplace(key, rm.indices.empty() ? -1 : g.mesh(rm, name)).first;
            }
            return it->second;
        };
        const int nodeIndex = static_cast<int>(nodes.size());
        children.push_back(nodeIndex);
        if (shape.type != ShapeType::Compound) {
            if (const int mesh = meshOf(shape, b.name); mesh >= 0) node["mesh"] = mesh;
            nodes.push_back(std::move(node));
        } else {
            // A compound: the body's node moves, each part a child node placed in its frame.
            nodes.push_back(std::move(node));
            json parts = json::array();
            for (size_t j = 0; j < shape.parts.size(); ++j) {
                const PartDesc& part = shape.parts[j];
                const Quat q = part.orientation.normalized();
                const std::string name =
                    part.name.empty() ? b.name + " part " + std::to_string(j) : b.name + " " + part.name;
                json child = {
                    {"name", name},
                    {"translation",
                     {float(part.position.x()), float(part.position.y()), float(part.position.z())}},
                    {"rotation", unitFloats<4>({q.x(), q.y(), q.z(), q.w()})}};
                if (const int mesh = meshOf(part.shape, name); mesh >= 0) child["mesh"] = mesh;
                parts.push_back(static_cast<int>(nodes.size()));
                nodes.push_back(std::move(child));
            }
            nodes[nodeIndex]["children"] = std::move(parts);
        }

        if (b.standsStill()) continue;
        if (timeAccessor < 0) timeAccessor = g.accessor(times, 1, "SCALAR", 0, true);
        std::vector<float> translation, rotation;
        translation.reserve(3 * times_.size());
        rotation.reserve(4 * times_.size());
        Quat previous = Quat::Identity();
        for (size_t f = 0; f < times_.size(); ++f) {
            const auto& p = poses_[n][f];
            translation.insert(translation.end(), {float(p[0]), float(p[1]), float(p[2])});
            // q and -q are one rotation; keep each key on the previous one's side, so that a
            // viewer interpolating componentwise (Blender) never passes through a zero.
            Quat q(p[3], p[4], p[5], p[6]);
            if (f > 0 && q.coeffs().dot(previous.coeffs()) < 0) q.coeffs() = -q.coeffs();
            previous = q;
            const auto r = unitFloats<4>({q.x(), q.y(), q.z(), q.w()});
            rotation.insert(rotation.end(), r.begin(), r.end());
        }
        for (const auto& [path, data, type] :
             {std::tuple{"translation", &translation, "VEC3"}, std::tuple{"rotation", &rotation, "VEC4"}}) {
            const int out = g.accessor(*data, type[3] - '0', type, 0, false);
            samplers.push_back({{"input", timeAccessor}, {"output", out}, {"interpolation", "LINEAR"}});
            channels.push_back(
                {{"sampler", samplers.size() - 1}, {"target", {{"node", nodeIndex}, {"path", path}}}});
        }
    }
    if (!children.empty()) nodes[0]["children"] = std::move(children);
    doc["nodes"] = std::move(nodes);
    doc["scenes"] = json::array({{{"nodes", {0}}}});
    if (!channels.empty()) {
        doc["animations"] = json::array(
            {{{"name", "simulation"}, {"samplers", std::move(samplers)}, {"channels", std::move(channels)}}});
    }
    for (const char* key : {"meshes", "accessors", "bufferViews"}) {
        if (doc[key].empty()) doc.erase(key);
    }

    g.bin.append((4 - g.bin.size() % 4) % 4, '\0');
    if (!g.bin.empty()) {
        json buffer = {{"byteLength", g.bin.size()}};
        if (!binary_) buffer["uri"] = fs::path(file()).filename().replace_extension(".bin").string();
        doc["buffers"] = json::array({std::move(buffer)});
    }

    std::ostream& out = outputs_->main->stream();
    if (binary_) {
        // A 12-byte header, the JSON chunk padded with spaces to 4 bytes, the binary chunk.
        std::string text = doc.dump();
        text.append((4 - text.size() % 4) % 4, ' ');
        const size_t total = 12 + 8 + text.size() + (g.bin.empty() ? 0 : 8 + g.bin.size());
        if (total > 0xffffffffu) {
            throw std::runtime_error(file().string() + ": the export would be " +
                                     std::to_string(total >> 20) +
                                     " MiB, past the 4 GiB a .glb can hold: export fewer frames or bodies, "
                                     "or write .gltf");
        }
        out.write("glTF", 4);
        writeU32(out, 2);
        writeU32(out, static_cast<std::uint32_t>(total));
        writeU32(out, static_cast<std::uint32_t>(text.size()));
        out.write("JSON", 4);
        out << text;
        if (!g.bin.empty()) {
            writeU32(out, static_cast<std::uint32_t>(g.bin.size()));
            out.write("BIN\0", 4);
            out << g.bin;
        }
    } else {
        out << doc.dump(2);
        outputs_->bin->stream() << g.bin;
    }
    // Both written out before either replaces its old file: a full disk leaves the old pair.
    // Failures of the .bin are named by the file the user asked for.
    auto binary = [&](void (AtomicFile::*step)()) {
        if (!outputs_->bin) return;
        try {
            (outputs_->bin.get()->*step)();
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(file().string() + ": its buffer " + e.what());
        }
    };
    binary(&AtomicFile::ready);
    outputs_->main->ready();
    if (!binary_ && doc.contains("buffers")) {
        commitPair(file(), *outputs_->main, *outputs_->bin, doc);
    } else {
        binary(&AtomicFile::commit);
        outputs_->main->commit();
    }
    if (outputs_->bin) removeStaleTemporaries(fs::path(file()).replace_extension(".bin"));
}

}  // namespace tumble::io
