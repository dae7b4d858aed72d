// glTF through assimp's exporter (5.2 writes TRS nodes, LINEAR samplers with times in
// seconds and the accessor bounds the validator asks for). The exporter writes through an
// IOSystem; ours keeps its files in memory, so that they reach the disk through AtomicFile
// (the .bin first, then the .gltf that names it) or not at all.
#include <tumble/io/atomic_file.h>
#include <tumble/io/gltf_export.h>
#include <tumble/io/tessellate.h>

#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/Exporter.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

class MemoryStream : public Assimp::IOStream {
public:
    explicit MemoryStream(std::string& data) : data_(data) {}
    size_t Read(void* buffer, size_t size, size_t count) override {
        if (size == 0) return 0;
        const size_t n = std::min(count, (data_.size() - pos_) / size);
        std::memcpy(buffer, data_.data() + pos_, n * size);
        pos_ += n * size;
        return n;
    }
    size_t Write(const void* buffer, size_t size, size_t count) override {
        const size_t bytes = size * count;
        if (pos_ + bytes > data_.size()) data_.resize(pos_ + bytes);
        std::memcpy(data_.data() + pos_, buffer, bytes);
        pos_ += bytes;
        return count;
    }
    aiReturn Seek(size_t offset, aiOrigin origin) override {
        const size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? pos_ : data_.size();
        pos_ = base + offset;
        if (pos_ > data_.size()) data_.resize(pos_);  // the .glb writer skips its header first
        return aiReturn_SUCCESS;
    }
    size_t Tell() const override { return pos_; }
    size_t FileSize() const override { return data_.size(); }
    void Flush() override {}

private:
    std::string& data_;
    size_t pos_ = 0;
};

class MemoryFiles : public Assimp::IOSystem {
public:
    std::map<std::string, std::string> files;

    bool Exists(const char* file) const override { return files.count(file) != 0; }
    char getOsSeparator() const override { return '/'; }
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        std::string& data = files[file];
        if (std::strchr(mode, 'w')) data.clear();
        return new MemoryStream(data);
    }
    void Close(Assimp::IOStream* stream) override { delete stream; }
};

aiVector3D toAi(const Vec3& v) {
    return aiVector3D(static_cast<ai_real>(v.x()), static_cast<ai_real>(v.y()), static_cast<ai_real>(v.z()));
}

aiMesh* toAiMesh(const RenderMesh& m, const std::string& name) {
    auto* mesh = new aiMesh();
    mesh->mName = name;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mMaterialIndex = 0;
    mesh->mNumVertices = static_cast<unsigned>(m.positions.size());
    mesh->mVertices = new aiVector3D[mesh->mNumVertices];
    mesh->mNormals = new aiVector3D[mesh->mNumVertices];
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
        mesh->mVertices[i] = toAi(m.positions[i]);
        mesh->mNormals[i] = toAi(m.normals[i]);
    }
    mesh->mNumFaces = static_cast<unsigned>(m.indices.size() / 3);
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        mesh->mFaces[f].mNumIndices = 3;
        mesh->mFaces[f].mIndices =
            new unsigned[3]{m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
    }
    return mesh;
}

template <class T>
T* copyArray(const std::vector<T>& v) {
    T* out = new T[v.size()];
    std::copy(v.begin(), v.end(), out);
    return out;
}

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
        default:
            std::snprintf(buf, sizeof buf, "%s %.17g %.17g", toString(s.type), s.radius,
                          s.type == ShapeType::Sphere ? 0.0 : s.halfHeight);
    }
    return buf;
}

std::uint32_t readU32(const std::string& bytes, size_t at) {
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
}

void writeU32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

// Assimp lists extensions it never uses (FB_ngon_encoding, KHR_materials_volume) in
// extensionsUsed; nothing in these files needs an extension, so the list goes. A .glb is a
// 12-byte header, a JSON chunk padded with spaces to 4 bytes, then the binary chunk.
std::string withoutExtensionsUsed(const std::string& glb, const fs::path& file) {
    const auto bad = [&] {
        return std::runtime_error(file.string() + ": the glTF exporter wrote a malformed .glb");
    };
    if (glb.size() < 20 || glb.compare(0, 4, "glTF") != 0 || readU32(glb, 8) != glb.size()) throw bad();
    const std::uint32_t jsonLength = readU32(glb, 12);
    if (readU32(glb, 16) != 0x4E4F534Au || 20 + size_t(jsonLength) > glb.size()) throw bad();
    nlohmann::json doc = nlohmann::json::parse(glb.substr(20, jsonLength));
    doc.erase("extensionsUsed");
    std::string json = doc.dump();
    json.append((4 - json.size() % 4) % 4, ' ');
    const std::string rest = glb.substr(20 + jsonLength);
    std::string out = glb.substr(0, 8);
    writeU32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + rest.size()));
    writeU32(out, static_cast<std::uint32_t>(json.size()));
    writeU32(out, 0x4E4F534Au);  // "JSON"
    return out + json + rest;
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
    if (!binary_) outputs_->bin = std::make_unique<AtomicFile>(fs::path(file()).replace_extension(".bin"));
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

    auto ai = std::make_unique<aiScene>();
    // Channels find their node by name, so the root must not share one with a body.
    std::string rootName = fs::path(file()).stem().string();
    auto taken = [&](const std::string& n) {
        return std::any_of(bodies().begin(), bodies().end(),
                           [&](int i) { return model().bodies[i].name == n; });
    };
    while (rootName.empty() || taken(rootName)) rootName += " scene";
    ai->mRootNode = new aiNode(rootName);
    ai->mNumMaterials = 1;
    ai->mMaterials = new aiMaterial* [1] { new aiMaterial() };
    {
        aiMaterial& m = *ai->mMaterials[0];
        const aiString name("body");
        m.AddProperty(&name, AI_MATKEY_NAME);
        const aiColor4D grey(0.8f, 0.8f, 0.8f, 1.0f);
        m.AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
        m.AddProperty(&grey, 1, AI_MATKEY_BASE_COLOR);
    }

    std::vector<aiMesh*> meshes;
    std::map<std::string, unsigned> shared;  // bodies of the same shape share its mesh
    std::vector<aiNode*> nodes;
    std::vector<aiNodeAnim*> channels;
    for (size_t n = 0; n < bodies().size(); ++n) {
        const int i = bodies()[n];
        const BodyModel& b = model().bodies[i];
        const ShapeDesc& shape = scene().bodies[i].shape;
        auto* node = new aiNode(b.name);
        node->mParent = ai->mRootNode;
        nodes.push_back(node);

        unsigned meshIndex = static_cast<unsigned>(meshes.size());
        const std::string key = shapeKey(shape);
        auto it = shared.find(key);
        if (it != shared.end()) {
            meshIndex = it->second;
        } else {
            const RenderMesh rm = tessellate(shape, segments_, planeHalf);
            if (!rm.indices.empty()) {
                meshes.push_back(toAiMesh(rm, b.name));
                shared[key] = meshIndex;
            } else {
                meshIndex = ~0u;
            }
        }
        if (meshIndex != ~0u) {
            node->mNumMeshes = 1;
            node->mMeshes = new unsigned[1]{meshIndex};
        }

        const auto& first = poses_[n].front();
        const aiQuaternion q0(static_cast<ai_real>(first[3]), static_cast<ai_real>(first[4]),
                              static_cast<ai_real>(first[5]), static_cast<ai_real>(first[6]));
        node->mTransformation =
            aiMatrix4x4(aiVector3D(1, 1, 1), q0,
                        aiVector3D(static_cast<ai_real>(first[0]), static_cast<ai_real>(first[1]),
                                   static_cast<ai_real>(first[2])));

        if (b.standsStill()) continue;
        auto* channel = new aiNodeAnim();
        channel->mNodeName = b.name;
        channel->mNumPositionKeys = channel->mNumRotationKeys = static_cast<unsigned>(times_.size());
        channel->mPositionKeys = new aiVectorKey[times_.size()];
        channel->mRotationKeys = new aiQuatKey[times_.size()];
        Quat previous = Quat::Identity();
        for (size_t f = 0; f < times_.size(); ++f) {
            const auto& p = poses_[n][f];
            // Times in frames of the run at ticks = frame rate: the exporter writes seconds.
            const double tick = times_[f] * frameRate();
            channel->mPositionKeys[f].mTime = tick;
            channel->mPositionKeys[f].mValue = aiVector3D(
                static_cast<ai_real>(p[0]), static_cast<ai_real>(p[1]), static_cast<ai_real>(p[2]));
            // q and -q are one rotation; keep each key on the previous one's side, so that a
            // viewer interpolating componentwise (Blender) never passes through a zero.
            Quat q(p[3], p[4], p[5], p[6]);
            if (f > 0 && q.coeffs().dot(previous.coeffs()) < 0) q.coeffs() = -q.coeffs();
            previous = q;
            channel->mRotationKeys[f].mTime = tick;
            channel->mRotationKeys[f].mValue =
                aiQuaternion(static_cast<ai_real>(q.w()), static_cast<ai_real>(q.x()),
                             static_cast<ai_real>(q.y()), static_cast<ai_real>(q.z()));
        }
        channels.push_back(channel);
    }
    ai->mRootNode->mNumChildren = static_cast<unsigned>(nodes.size());
    ai->mRootNode->mChildren = copyArray(nodes);
    ai->mNumMeshes = static_cast<unsigned>(meshes.size());
    ai->mMeshes = copyArray(meshes);
    if (!channels.empty()) {
        auto* anim = new aiAnimation();
        anim->mName = "simulation";
        anim->mTicksPerSecond = frameRate();
        anim->mDuration = times_.back() * frameRate();
        anim->mNumChannels = static_cast<unsigned>(channels.size());
        anim->mChannels = copyArray(channels);
        ai->mNumAnimations = 1;
        ai->mAnimations = new aiAnimation* [1] { anim };
    }

    // Export into memory under the target's own name, so that the .gltf names its .bin as
    // it will be on disk.
    const std::string name = fs::path(file()).filename().string();
    auto* files = new MemoryFiles();
    Assimp::Exporter exporter;
    exporter.SetIOHandler(files);  // the exporter owns and deletes it
    if (exporter.Export(ai.get(), binary_ ? "glb2" : "gltf2", name) != aiReturn_SUCCESS) {
        throw std::runtime_error(file().string() +
                                 ": the glTF exporter failed: " + exporter.GetErrorString());
    }
    auto main = files->files.find(name);
    if (main == files->files.end())
        throw std::runtime_error(file().string() + ": the glTF exporter wrote nothing");
    std::string mainText;
    if (!binary_) {
        // Assimp names the buffer after the file and an index (t_0.bin); on disk it is the
        // .gltf's own name with .bin, and the .gltf says so.
        if (files->files.size() != 2) {
            throw std::runtime_error(file().string() + ": the glTF exporter wrote " +
                                     std::to_string(files->files.size()) +
                                     " files, not a .gltf and its .bin");
        }
        const auto bin =
            files->files.begin()->first == name ? std::next(files->files.begin()) : files->files.begin();
        nlohmann::json doc = nlohmann::json::parse(main->second);
        if (!doc.contains("buffers") || doc["buffers"].size() != 1 ||
            doc["buffers"][0].value("uri", "") != bin->first) {
            throw std::runtime_error(file().string() + ": the glTF exporter named its buffer unexpectedly");
        }
        doc["buffers"][0]["uri"] = fs::path(name).replace_extension(".bin").string();
        doc.erase("extensionsUsed");
        mainText = doc.dump(2);
        outputs_->bin->stream() << bin->second;
    } else {
        mainText = withoutExtensionsUsed(main->second, file());
    }
    outputs_->main->stream() << mainText;
    // Both written out before either replaces its old file: a full disk leaves the old pair.
    // (Only a kill between the two renames, microseconds apart, can pair a new .bin with the
    // old .gltf.)
    if (outputs_->bin) outputs_->bin->ready();
    outputs_->main->ready();
    if (outputs_->bin) outputs_->bin->commit();
    outputs_->main->commit();
}

}  // namespace tumble::io
