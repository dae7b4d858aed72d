// A file that appears whole or not at all: written beside its target under a temporary
// name, flushed to disk, and renamed over the target on commit(). Destroyed without a
// commit, it removes the temporary and leaves the target as it was.
//
// A process killed mid-save (SIGKILL, power cut) cannot remove its temporary, so the name
// says who made it: "<target>.tumble-tmp-<pid>-<8 hex digits>", beside the target (the
// rename stays on one filesystem, hence atomic). Every AtomicFile first removes the
// temporaries of its target left by processes that no longer run (see
// removeStaleTemporaries), so each save cleans up after the killed ones before it.
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>

namespace tumble::io {

class AtomicFile {
public:
    /// Removes stale temporaries of `target`, then opens a new one. A target that is a
    /// symbolic link is written through: the file it points to is replaced, the link stays.
    /// A target that exists keeps its permission bits. Throws std::runtime_error naming the
    /// target when the temporary cannot be made, with the reason (no such folder, no permission,
    /// a read-only or full disk).
    /// `stale`: Keep leaves the old temporaries for the caller to remove once its new files
    /// are in place (a .gltf left by a killed export may name its .bin's temporary).
    enum class Stale { Remove, Keep };
    explicit AtomicFile(std::filesystem::path target, Stale stale = Stale::Remove);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return out_; }
    /// Writes the data out and makes it durable, without replacing the target yet; throws
    /// std::runtime_error naming the target and the reason when it could not be written (a
    /// full disk). Several files that belong together (a .gltf and its .bin) are each made
    /// ready first, then committed: a failure leaves every one of them as it was.
    void ready();
    /// ready(), then the temporary replaces the target; throws as ready() does, or when the
    /// target cannot be replaced.
    void commit();
    /// Like commit(), but the temporary stays under its own name too (a second hard link to
    /// the same data; a copy on a file system without links), for a file that names the
    /// temporary until it is replaced in turn. The caller removes the temporary.
    void commitKeepingTemporary();
    /// The temporary (made ready) is not removed by the destructor: another file names it.
    void keepTemporary() { keep_ = true; }
    /// The temporary being written (for tests and messages).
    const std::filesystem::path& temporaryPath() const { return temp_; }

private:
    void syncFolder() const;

    std::filesystem::path target_;  // as given (messages name it)
    std::filesystem::path final_;   // the file replaced: target_, symbolic links followed
    std::filesystem::path temp_;
    class Buffer;  // the temporary's stream buffer (atomic_file.cpp): it keeps why a write failed
    std::unique_ptr<Buffer> buf_;
    std::ostream out_{nullptr};
    bool ready_ = false;
    bool committed_ = false;
    bool keep_ = false;
};

/// Why a file could not be written, from its errno, as a user reads it: "no such folder",
/// "no permission to write there", "the disk is read-only", "the disk is full", ...
std::string plainReason(int err);

/// Writes `contents` to `path` atomically.
void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

/// How old a dead process's temporary must be before it is removed: a save from another
/// machine (a shared folder) has a pid that means nothing here, and must not be removed
/// while it is being written.
inline constexpr std::chrono::seconds kStaleTemporaryAge{60};

/// True when `name` (a file name, no folder) is exactly a temporary AtomicFile makes for a
/// target named `targetName`: targetName + ".tumble-tmp-" + pid (decimal, no leading zero)
/// + "-" + 8 lowercase hex digits. Sets *pid when given.
bool isTemporaryOf(const std::string& name, const std::string& targetName, long* pid = nullptr);

/// Removes the temporaries of `target` (beside it, matching isTemporaryOf exactly) whose
/// process no longer runs here (kill(pid, 0) fails with ESRCH) and that were last written
/// more than `minAge` ago. Never throws; a file that cannot be removed is left. Returns how
/// many were removed.
int removeStaleTemporaries(const std::filesystem::path& target,
                           std::chrono::seconds minAge = kStaleTemporaryAge);

}  // namespace tumble::io
