// Mesh files: any format assimp reads, as one triangle mesh in the body frame.
#pragma once

#include <tumble/io/scene_file.h>
#include <tumble/mass.h>

#include <atomic>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace tumble::io {

struct MeshImportOptions {
    /// Seconds assimp may take in its child process before it is killed; 0 reads in the
    /// calling process, unprotected.
    double timeLimit = 60.0;
    /// Refuse the files assimp 5.2 is known to loop on before it sees them (mesh_precheck);
    /// off only to test the time limit.
    bool refuseKnownHangs = true;
    /// Set (from another thread) to stop the read: the reader's child is killed within a
    /// tenth of a second and importMesh throws MeshImportCancelled. Null: no way to stop it.
    /// (Not heard with timeLimit 0, where assimp reads in the calling thread.)
    const std::atomic<bool>* cancel = nullptr;
};

/// What importMesh throws when MeshImportOptions::cancel was set: the user's choice, not an
/// error of the file.
class MeshImportCancelled : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reads every mesh of `file` (OBJ, STL ascii or binary, PLY, OFF, glTF 2, FBX, ... any
/// format assimp reads) into one triangle mesh: node transforms applied, polygons
/// triangulated, points and lines ignored, each vertex multiplied componentwise by `scale`.
/// Triangles keep the file's winding (counter-clockwise seen from outside, by convention);
/// no welding beyond exactly identical vertices (compile() cleans the mesh).
/// Throws InputError(file, "", reason) when the file is missing or unreadable, assimp
/// cannot read it (its own message is given), or it holds no triangles.
/// assimp reads in a child process (engine/io/src/mesh_child.h): a file it crashes on or
/// never finishes gives an InputError saying so, never a crash or a hang of the caller.
/// The child is the reader program, meshReaderProgram(), when there is one; a fork of the
/// caller otherwise (safe only where no other thread runs).
TriangleMesh importMesh(const std::filesystem::path& file, const Vec3& scale = Vec3(1, 1, 1),
                        const MeshImportOptions& options = {});

/// The reader program importMesh starts for each file, or "" when there is none: the
/// environment's TUMBLE_MESH_READER when set (taken as it is), else tumble-mesh-reader
/// beside the running program, else the installed one (libexec/tumble under the running
/// program's prefix), else the one in the build tree it was built in.
std::string meshReaderProgram();

/// The reader program's main (app/mesh_reader_main.cpp):
/// `tumble-mesh-reader FILE SX SY SZ` reads FILE with assimp, scaled, and writes the answer
/// to file descriptor 3 (engine/io/src/mesh_child.h); status 0 when it was written, 2 for
/// wrong arguments.
int meshReaderMain(int argc, char** argv);

/// Fills shape.meshData of every mesh shape of `scene` (a body's, or a compound's part's:
/// "bodies[2].shape.parts[1].shape.file") by reading its file relative to
/// `baseDir` (absolute paths are taken as they are) with the body's scale; bodies with the
/// same file and scale share one mesh. A failure throws InputError naming `sceneName`, the
/// field and the mesh file as written, e.g. "drop.json: bodies[2].shape.file: meshes/rock.obj:
/// cannot be read (missing, or no permission)".
/// With `failures`, a mesh that cannot be read does not stop the rest: its error goes into
/// `failures` and its bodies keep no meshData (compile() refuses them, naming the body).
void loadSceneMeshes(SceneDesc& scene, const std::filesystem::path& baseDir, const std::string& sceneName,
                     std::vector<InputError>* failures = nullptr);

}  // namespace tumble::io
