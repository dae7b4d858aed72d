// libFuzzer target: the parent's side of a mesh import, without assimp. The input is what
// the reader's child sends back on its pipe (engine/io/src/mesh_child.h: 'M', counts,
// vertices and triangles; or 'E' and a message). Whatever the bytes, meshFromAnswer gives a
// mesh or an InputError naming the file; a mesh is then compiled as a dynamic body both ways
// a scene can ask (convex hull, and the triangles as they are), which works or gives a
// SceneError; anything else (a crash, a sanitizer report, another exception, a non-finite
// mass property) is a bug. fuzz_mesh goes through assimp in a child process per input
// (some 40 inputs a second); this one reaches Tumble's own code behind it thousands of
// times a second: any triangles at all, as assimp could hand them over.
//
// Seeds: with TUMBLE_MAKE_SEEDS=DIR and TUMBLE_SEED_MESHES=FILE:FILE:... in the
// environment, the program reads those mesh files (assimp, in its child) and writes their
// answers into DIR, then exits (tests/fuzz/run_fuzz.sh).
#include "fuzz_compile.h"

#include <tumble/errors.h>
#include <tumble/io/mesh_import.h>
#include <tumble/model.h>

#include "mesh_child.h"  // engine/io/src

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace {

using tumble::fuzz::bug;

void makeSeeds(const char* dir, const char* files) {
    std::stringstream list(files);
    std::string file;
    int n = 0;
    while (std::getline(list, file, ':')) {
        if (file.empty()) continue;
        try {
            const tumble::TriangleMesh mesh = tumble::io::importMesh(file);
            const std::string answer = tumble::io::encodeMeshAnswer(mesh);
            if (answer.size() > 65536) continue;  // libFuzzer's -max_len
            char name[32];
            std::snprintf(name, sizeof name, "/%03d.answer", n++);
            std::ofstream(std::string(dir) + name, std::ios::binary) << answer;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "fuzz_meshdata: seed %s left out: %s\n", file.c_str(), e.what());
        }
    }
    // And one error answer.
    std::ofstream(std::string(dir) + "/error.answer", std::ios::binary) << "Eholds no triangles";
    std::fprintf(stderr, "fuzz_meshdata: %d seeds written to %s\n", n + 1, dir);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    const char* dir = std::getenv("TUMBLE_MAKE_SEEDS");
    const char* files = std::getenv("TUMBLE_SEED_MESHES");
    if (dir && files) {
        makeSeeds(dir, files);
        std::exit(0);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string answer(reinterpret_cast<const char*>(data), size);
    const std::string name = "fuzzed.obj";
    std::shared_ptr<const tumble::TriangleMesh> mesh;
    try {
        mesh = std::make_shared<const tumble::TriangleMesh>(tumble::io::meshFromAnswer(name, answer));
    } catch (const tumble::io::InputError& e) {
        if (e.file() != name) bug("fuzz_meshdata", "an InputError that does not name the file", e.what());
        return 0;
    }
    tumble::fuzz::compileBody("fuzz_meshdata", mesh, tumble::MeshCollision::ConvexHull);
    tumble::fuzz::compileBody("fuzz_meshdata", mesh, tumble::MeshCollision::Triangles);
    return 0;
}
