// libFuzzer target: a mesh file as the editor's import or a scene's mesh body reads it.
// The first byte picks the file's extension (assimp chooses its reader by it), the rest is
// the file. Whatever the bytes, importMesh gives a mesh or an InputError naming the file
// (assimp runs in a child process: its own crash or hang is such a message); a mesh is then
// compiled as a dynamic body both ways a scene can ask (convex hull, and the triangles as
// they are), which either works or gives a SceneError; anything else (a crash, a sanitizer
// report, another exception, a non-finite mass property) is a bug.
#include "fuzz_compile.h"

#include <tumble/errors.h>
#include <tumble/io/mesh_import.h>
#include <tumble/model.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

namespace {

using tumble::fuzz::bug;

// The formats docs/scene-format.md names; the seed corpus has one file or more of each.
constexpr const char* kExtensions[] = {".obj", ".stl", ".ply", ".off", ".glb"};
constexpr std::size_t kExtensionCount = sizeof kExtensions / sizeof kExtensions[0];

std::string tempFolder() {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp");
}

void keep(const std::uint8_t* data, std::size_t size) {
    const char* dir = std::getenv("TUMBLE_FUZZ_KEEP");
    if (!dir || !*dir) return;
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a: one file per distinct input
    for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
    char name[40];
    std::snprintf(name, sizeof name, "/reader-fault-%016llx", static_cast<unsigned long long>(h));
    std::ofstream(std::string(dir) + name, std::ios::binary).write(reinterpret_cast<const char*>(data),
                                                                   static_cast<std::streamsize>(size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static const std::string folder = tempFolder();
    const std::string path =
        folder + "/tumble-fuzz-mesh-" + std::to_string(::getpid()) + kExtensions[data[0] % kExtensionCount];
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
        if (!out) bug("fuzz_mesh", "cannot write the temporary file", path);
    }
    std::shared_ptr<const tumble::TriangleMesh> mesh;
    try {
        tumble::io::MeshImportOptions options;
        options.timeLimit = 5;  // under libFuzzer's own 10 s: a hang of assimp's is a message
        mesh = std::make_shared<const tumble::TriangleMesh>(
            tumble::io::importMesh(path, tumble::Vec3(1, 1, 1), options));
    } catch (const tumble::io::InputError& e) {
        if (e.file() != path) bug("fuzz_mesh", "an InputError that does not name the file", e.what());
        // assimp reads in a child process (engine/io/src/mesh_child.cpp): a crash of assimp's
        // own there, or a sanitizer report with assimp on the stack, is a message, as the user
        // gets it; a sanitizer report in Tumble's code in the child ends it with status 1,
        // which is a bug. (The start of the message: assimp's
        // own messages come after "cannot be read as a mesh: " and may quote the file.)
        if (e.message().starts_with("the mesh reader stopped without an answer"))
            bug("fuzz_mesh", "the mesh reader failed", e.what());
        // assimp's own fault (a crash, a sanitizer report inside it, a loop stopped at the
        // time limit): handled, as above, and the input kept for the regressions when the
        // run says where (run_fuzz.sh: WORKDIR/reader-faults/), since the parent must go on
        // refusing it cleanly.
        if (e.message().starts_with("the mesh reader (assimp)")) keep(data, size);
    }
    std::remove(path.c_str());
    if (!mesh) return 0;
    tumble::fuzz::compileBody("fuzz_mesh", mesh, tumble::MeshCollision::ConvexHull);
    tumble::fuzz::compileBody("fuzz_mesh", mesh, tumble::MeshCollision::Triangles);
    return 0;
}
