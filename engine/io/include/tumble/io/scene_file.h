// Scene files, version 1 (docs/scene-format.md): reading with a message that names the
// file and the field for every bad input, and writing in normalised form.
#pragma once

#include <tumble/scene.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::io {

/// Bad input: what() reads "FILE: FIELD: MESSAGE", e.g.
/// "drop.json: bodies[2].shape.radius: must be greater than 0".
class InputError : public std::runtime_error {
public:
    InputError(std::string file, std::string field, std::string message);
    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    const std::string& message() const { return message_; }
    /// The file's other problems, each "field: message" (see sceneProblems): what() and the
    /// command line name the first alone, the editor lists them all.
    const std::vector<std::string>& more() const { return more_; }
    void addMore(std::string problem) { more_.push_back(std::move(problem)); }

private:
    std::string file_, field_, message_;
    std::vector<std::string> more_;
};

/// The newest scene version this build reads and writes.
inline constexpr int kSceneVersion = 1;

/// Parses and validates scene text. `fileName` is used in messages only. With `baseDir`,
/// the mesh files of mesh bodies are read relative to it (shape.meshData, see
/// loadSceneMeshes in tumble/io/mesh_import.h; pass "." for the current directory).
/// Without it no mesh file is read: the scene can be inspected, edited and saved, but
/// compile() refuses its mesh bodies until their meshes are loaded.
SceneDesc parseScene(std::string_view text, const std::string& fileName,
                     const std::optional<std::filesystem::path>& baseDir = std::nullopt);

/// Reads and validates a scene file, and reads its mesh files relative to the scene
/// file's folder. Messages name the file as given.
SceneDesc readSceneFile(const std::filesystem::path& path);

/// The scene as normalised JSON text: every setting and every body field written out,
/// unit quaternions and plane normals, numbers that read back exactly. A mesh body's
/// file is written as it is given (a path relative to the scene's folder stays relative);
/// its loaded triangles (meshData) are never written. A scene with joints throws
/// std::invalid_argument: the file cannot hold them yet (issue 20), and they must not be
/// dropped silently.
std::string sceneToJson(const SceneDesc& scene);

/// Writes sceneToJson atomically (a temporary file beside it, then a rename).
void writeSceneFile(const SceneDesc& scene, const std::filesystem::path& path);

}  // namespace tumble::io
