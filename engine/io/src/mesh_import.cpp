// Mesh import through assimp. Everything but positions and faces is stripped before
// assimp joins vertices, so copies of a vertex that differ only in normal or texture
// coordinate become one; node transforms are baked into the vertices, so a file made of
// several placed parts comes out as the user sees it in a modelling tool.
#include <tumble/io/mesh_import.h>

#include "mesh_child.h"
#include "mesh_precheck.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <fstream>
#include <map>
#include <memory>
#include <utility>

namespace tumble::io {

TriangleMesh readWithAssimp(const std::string& name, const Vec3& scale) {
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                                aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                    aiComponent_COLORS | aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS |
                                    aiComponent_ANIMATIONS | aiComponent_TEXTURES | aiComponent_LIGHTS |
                                    aiComponent_CAMERAS | aiComponent_MATERIALS);
    const unsigned flags = aiProcess_RemoveComponent | aiProcess_Triangulate |
                           aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                           aiProcess_ValidateDataStructure;
    const aiScene* scene = importer.ReadFile(name, flags);
    if (!scene) {
        const std::string why = importer.GetErrorString();
        // assimp's validation refuses files without faces or meshes before we see them;
        // say so in the words used for the files it does hand over.
        if (why.find("no faces") != std::string::npos) {
            throw InputError(name, "", "holds no triangles (no faces at all, only points or nothing)");
        }
        if (why.find("mNumMeshes is 0") != std::string::npos) throw InputError(name, "", "holds no mesh");
        throw InputError(name, "",
                         "cannot be read as a mesh: " + (why.empty() ? std::string("unknown error") : why));
    }

    TriangleMesh mesh;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* part = scene->mMeshes[m];
        if (!part || !part->mVertices) continue;
        const int base = static_cast<int>(mesh.vertices.size());
        for (unsigned v = 0; v < part->mNumVertices; ++v) {
            const aiVector3D& p = part->mVertices[v];
            const Vec3 q = Vec3(p.x, p.y, p.z).cwiseProduct(scale);
            if (!q.allFinite()) {
                throw InputError(name, "",
                                 "vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                                     " is not a finite number" +
                                     (Vec3(p.x, p.y, p.z).allFinite() ? " once scaled" : ""));
            }
            mesh.vertices.push_back(q);
        }
        for (unsigned f = 0; f < part->mNumFaces; ++f) {
            const aiFace& face = part->mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines have no surface
            std::array<int, 3> t{};
            for (int k = 0; k < 3; ++k) {
                if (face.mIndices[k] >= part->mNumVertices) {
                    throw InputError(name, "",
                                     "face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                                         " uses a vertex that does not exist");
                }
                t[k] = base + static_cast<int>(face.mIndices[k]);
            }
            mesh.triangles.push_back(t);
        }
    }
    if (mesh.triangles.empty()) {
        throw InputError(
            name, "", scene->mNumMeshes == 0 ? "holds no mesh" : "holds no triangles (only points or lines)");
    }
    return mesh;
}

TriangleMesh importMesh(const std::filesystem::path& file, const Vec3& scale,
                        const MeshImportOptions& options) {
    const std::string name = file.string();
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        throw InputError(name, "", "is a directory, not a mesh file");
    // Opening a FIFO waits for a writer for ever: anything but a file is refused first.
    const auto type = std::filesystem::status(file, ec).type();
    if (!ec && type != std::filesystem::file_type::regular && type != std::filesystem::file_type::not_found)
        throw InputError(name, "", "is not a regular file (a pipe, socket or device), not a mesh file");
    if (!std::ifstream(file, std::ios::binary)) {
        throw InputError(name, "", "cannot be read (missing, or no permission)");
    }
    if (options.refuseKnownHangs) {
        if (const auto hang = meshFileAssimpWouldHangOn(file)) throw InputError(name, "", *hang);
    }
    if (options.timeLimit <= 0) return readWithAssimp(name, scale);
    const std::string program = meshReaderProgram();
    if (!program.empty()) return readMeshWithProgram(program, name, scale, options.timeLimit, options.cancel);
    return readMeshInChild(name, options.timeLimit, [&] { return readWithAssimp(name, scale); },
                           options.cancel);
}

void loadSceneMeshes(SceneDesc& scene, const std::filesystem::path& baseDir, const std::string& sceneName,
                     std::vector<InputError>* failures) {
    std::map<std::pair<std::string, std::array<double, 3>>, std::shared_ptr<const TriangleMesh>> loaded;
    for (size_t i = 0; i < scene.bodies.size(); ++i) {
        forEachShape(
            scene.bodies[i], "bodies[" + std::to_string(i) + "]", [&](ShapeDesc& s, const std::string& path) {
                if (s.type != ShapeType::Mesh) return;
                auto& slot = loaded[{s.file, {s.scale.x(), s.scale.y(), s.scale.z()}}];
                if (!slot) {
                    try {
                        slot = std::make_shared<const TriangleMesh>(importMesh(baseDir / s.file, s.scale));
                    } catch (const InputError& e) {
                        InputError named(sceneName, path + ".file", s.file + ": " + e.message());
                        if (!failures) throw named;
                        failures->push_back(named);
                        return;  // this shape stays without its mesh
                    }
                }
                s.meshData = slot;
            });
    }
}

}  // namespace tumble::io
