// Scene files, version 1 (docs/scene-format.md): reading with a message that names the
// file and the field for every bad input, and writing in normalised form.
#pragma once

#include <tumble/scene.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tumble::io {

/// Bad input: what() reads "FILE: FIELD: MESSAGE", e.g.
/// "drop.json: bodies[2].shape.radius: must be greater than 0".
class InputError : public std::runtime_error {
public:
    InputError(std::string file, std::string field, std::string message);
    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    const std::string& message() const { return message_; }

private:
    std::string file_, field_, message_;
};

/// The newest scene version this build reads and writes.
inline constexpr int kSceneVersion = 1;

/// Parses and validates scene text. `fileName` is used in messages only.
SceneDesc parseScene(std::string_view text, const std::string& fileName);

/// Reads and validates a scene file. Messages name the file as given.
SceneDesc readSceneFile(const std::filesystem::path& path);

/// The scene as normalised JSON text: every setting and every body field written out,
/// unit quaternions and plane normals, numbers that read back exactly.
std::string sceneToJson(const SceneDesc& scene);

/// Writes sceneToJson atomically (a temporary file beside it, then a rename).
void writeSceneFile(const SceneDesc& scene, const std::filesystem::path& path);

}  // namespace tumble::io
