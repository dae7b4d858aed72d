// What the mesh fuzz targets do with a mesh that reads (fuzz_mesh.cpp, fuzz_meshdata.cpp):
// compile it as a dynamic body, which works or gives a SceneError; a compiled body with a
// mass that is not positive and finite, or a non-finite inertia, is a bug (abort).
#pragma once

#include <tumble/errors.h>
#include <tumble/model.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace tumble::fuzz {

[[noreturn]] inline void bug(const char* target, const char* what, const std::string& detail) {
    std::fprintf(stderr, "%s: %s: %s\n", target, what, detail.c_str());
    std::abort();
}

inline void compileBody(const char* target, const std::shared_ptr<const TriangleMesh>& mesh, MeshCollision collision) {
    SceneDesc scene;
    BodyDesc body;
    body.name = "fuzzed";
    body.shape.type = ShapeType::Mesh;
    body.shape.file = "fuzz";
    body.shape.collision = collision;
    body.shape.meshData = mesh;
    body.density = 1000.0;
    scene.bodies.push_back(body);
    try {
        const Model model = compile(scene);
        const auto& b = model.bodies.at(0);
        if (!(b.mass > 0.0) || !std::isfinite(b.mass))
            bug(target, "a compiled mesh body with a bad mass", std::to_string(b.mass));
        if (!b.inertia.allFinite()) bug(target, "a compiled mesh body with a non-finite inertia", "");
    } catch (const SceneError&) {
    }
}

}  // namespace tumble::fuzz
