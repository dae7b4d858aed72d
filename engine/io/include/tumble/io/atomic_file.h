// A file that appears whole or not at all: written beside its target under a temporary
// name, flushed to disk, and renamed over the target on commit(). Destroyed without a
// commit, it removes the temporary and leaves the target as it was.
#pragma once

#include <filesystem>
#include <fstream>

namespace tumble::io {

class AtomicFile {
public:
    explicit AtomicFile(std::filesystem::path target);  ///< throws std::runtime_error
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return out_; }
    void commit();  ///< throws std::runtime_error when the data could not be written

private:
    std::filesystem::path target_, temp_;
    std::ofstream out_;
    bool committed_ = false;
};

/// Writes `contents` to `path` atomically.
void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace tumble::io
