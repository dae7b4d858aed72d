#include <tumble/io/atomic_file.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <random>
#include <stdexcept>

namespace tumble::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMark = ".tumble-tmp-";
constexpr int kHexDigits = 8;

// Where a save of `target` really goes: a symbolic link is followed (as QSaveFile did), so
// that saving through a link replaces the file it points to and keeps the link. A loop or a
// chain too long stops following and replaces the last link.
fs::path followLinks(fs::path p) {
    for (int depth = 0; depth < 40; ++depth) {
        std::error_code ec;
        if (!fs::is_symlink(p, ec)) break;
        const fs::path to = fs::read_symlink(p, ec);
        if (ec) break;
        p = to.is_absolute() ? to : p.parent_path() / to;
    }
    return p;
}

fs::path folderOf(const fs::path& target) {
    return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

std::string randomHex() {
    std::random_device rd;
    char text[kHexDigits + 1];
    std::snprintf(text, sizeof text, "%08x", static_cast<unsigned>(rd() & 0xffffffffu));
    return text;
}

}  // namespace

bool isTemporaryOf(const std::string& name, const std::string& targetName, long* pid) {
    const std::string prefix = targetName + kMark;
    if (targetName.empty() || name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0)
        return false;
    const std::string_view rest = std::string_view(name).substr(prefix.size());
    const size_t dash = rest.find('-');
    if (dash == std::string_view::npos || dash == 0 || dash > 10 || rest[0] == '0') return false;
    long value = 0;
    const auto [end, ec] = std::from_chars(rest.data(), rest.data() + dash, value);
    if (ec != std::errc() || end != rest.data() + dash || value <= 0) return false;
    const std::string_view hex = rest.substr(dash + 1);
    if (hex.size() != kHexDigits) return false;
    for (const char c : hex)
        if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
    if (pid) *pid = value;
    return true;
}

int removeStaleTemporaries(const fs::path& target, std::chrono::seconds minAge) {
    const std::string targetName = target.filename().string();
    const auto youngest = fs::file_time_type::clock::now() - minAge;
    int removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(folderOf(target), ec), end; !ec && it != end; it.increment(ec)) {
        long pid = 0;
        if (!isTemporaryOf(it->path().filename().string(), targetName, &pid)) continue;
        std::error_code fileEc;
        if (!it->is_regular_file(fileEc) || fileEc) continue;
        // Only a process known to be gone: EPERM means it runs (as another user).
        if (static_cast<pid_t>(pid) != pid || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
            continue;
        const auto written = fs::last_write_time(it->path(), fileEc);
        if (fileEc || written > youngest) continue;
        if (fs::remove(it->path(), fileEc)) ++removed;
    }
    return removed;
}

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)), final_(followLinks(target_)) {
    removeStaleTemporaries(final_);
    const std::string stem = final_.string() + kMark + std::to_string(::getpid()) + "-";
    int fd = -1;
    for (int attempt = 0; fd < 0 && attempt < 16; ++attempt) {
        temp_ = stem + randomHex();
        fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0)
        throw std::runtime_error(target_.string() + ": cannot be written (no such folder, or no permission)");
    ::close(fd);
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) {
        std::error_code ec;
        fs::remove(temp_, ec);
        throw std::runtime_error(target_.string() + ": cannot be written (no such folder, or no permission)");
    }
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        out_.close();
        std::error_code ec;
        fs::remove(temp_, ec);
    }
}

void AtomicFile::commit() {
    out_.flush();
    const bool ok = static_cast<bool>(out_);
    out_.close();
    if (!ok) throw std::runtime_error(target_.string() + ": writing failed (disk full?)");
    // A file replaced keeps its permission bits (a new one gets the umask's).
    struct stat old {};
    if (::stat(final_.c_str(), &old) == 0 && S_ISREG(old.st_mode))
        ::chmod(temp_.c_str(), old.st_mode & 07777);
    // Make the data durable before the rename makes it visible.
    const int fd = ::open(temp_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) throw std::runtime_error(target_.string() + ": cannot be replaced: " + ec.message());
    committed_ = true;
    // And the new name durable: until the folder is synced a power cut can bring back the
    // old file (whole, never a mix). Best effort: a folder that cannot be opened keeps the
    // save as it is.
    const fs::path folder = final_.has_parent_path() ? final_.parent_path() : fs::path(".");
    const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
}

void writeFileAtomically(const fs::path& path, const std::string& contents) {
    AtomicFile file(path);
    file.stream() << contents;
    file.commit();
}

}  // namespace tumble::io
