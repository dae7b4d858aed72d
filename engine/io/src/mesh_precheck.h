// Files that assimp 5.2 (Debian 12's) never returns from, refused before it sees them.
// Each check here comes from a fuzzing find (tests/fuzz/regressions/mesh/) and says what is
// wrong in the user's terms.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace tumble::io {

/// Why assimp must not be given `file`, or nothing when it may.
std::optional<std::string> meshFileAssimpWouldHangOn(const std::filesystem::path& file);

}  // namespace tumble::io
