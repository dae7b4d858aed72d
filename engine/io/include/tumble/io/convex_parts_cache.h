// The convex parts of a scene's meshes (`"collision": "convex-parts"`), kept beside the scene
// file in a sidecar so that they are made once, not on every open: "drop.json" keeps them in
// "drop.convex-parts.json". Each entry is keyed by the mesh's content hash and the options
// (max_parts, tolerance), so an edited mesh file or changed options make them again; the
// hulls are stored whole (vertices, faces, edges), so a run from the cache is bit for bit
// the run from parts just made. (docs/scene-format.md "Convex parts".)
#pragma once

#include <tumble/scene.h>

#include <atomic>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tumble::io {

/// The sidecar of a scene file: its name with ".convex-parts.json" for ".json".
std::filesystem::path convexPartsCachePath(const std::filesystem::path& sceneFile);

/// Every mesh shape of the scene (bodies' and compounds' parts') with collision
/// convex-parts, and the path of each ("bodies[2].shape", "bodies[3].shape.parts[0].shape").
std::vector<std::pair<ShapeDesc*, std::string>> convexPartsShapes(SceneDesc& scene);

/// Gives each convex-parts shape without fitting parts (mesh::convexPartsFit) those of the
/// cache file that fit it. A missing cache is no error; an unreadable or malformed one is
/// passed over (its parts are made again) with the reason in `problem` when given.
/// Returns how many shapes got their parts from it.
int readConvexPartsCache(SceneDesc& scene, const std::filesystem::path& cache,
                         std::string* problem = nullptr);

/// Makes the parts of every convex-parts shape that has none fitting (with its meshData),
/// one after another: progress(done, total, path) before each; `cancel` set stops before
/// the next (the ones made are kept). Throws InputError(sceneName, path + ".collision",
/// ...) for a mesh that bounds no solid. Returns how many were made.
int makeConvexParts(SceneDesc& scene, const std::string& sceneName,
                    const std::function<void(int done, int total, const std::string& path)>& progress = {},
                    const std::atomic<bool>* cancel = nullptr);

/// Writes the parts of every convex-parts shape that has them to the cache file,
/// atomically (entries of meshes the scene no longer has are dropped). No shape with parts:
/// nothing is written. Throws std::runtime_error naming the file when it cannot be written.
void writeConvexPartsCache(SceneDesc& scene, const std::filesystem::path& cache);

}  // namespace tumble::io
