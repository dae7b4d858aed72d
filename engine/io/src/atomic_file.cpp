#include <tumble/io/atomic_file.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
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

}  // namespace

std::string plainReason(int err) {
    switch (err) {
        case ENOENT: return "no such folder";
        case ENOTDIR: return "a file stands where a folder of its path should be";
        case EACCES:
        case EPERM: return "no permission to write there";
        case EROFS: return "the disk is read-only";
        case ENOSPC: return "the disk is full";
        case EDQUOT: return "the disk quota is used up";
        case EFBIG: return "the file is larger than this system lets it be";
        default: return std::strerror(err);
    }
}

namespace {

// Why a write into `folder` failed: `err` (errno) when the call that failed left one,
// else a full disk when the folder's file system has no room left.
std::string whyWriteFailed(int err, const fs::path& folder) {
    struct statvfs room {};
    if ((err == 0 || err == EIO) && ::statvfs(folder.c_str(), &room) == 0 && room.f_bavail == 0) err = ENOSPC;
    return err ? plainReason(err) : std::string("the disk may be full");
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

// Writes with ::write and keeps the errno of the first write that failed (std::ofstream
// loses it), so that a failed save says why: a full disk, a file size limit, an I/O error.
class AtomicFile::Buffer : public std::streambuf {
public:
    explicit Buffer(int fd) : fd_(fd) { setp(data_, data_ + sizeof data_); }
    ~Buffer() override {
        if (fd_ >= 0) ::close(fd_);
    }
    int fd() const { return fd_; }
    int error() const { return error_; }
    /// Writes what is buffered, then closes; false (error() says why) if anything failed.
    bool close() {
        const bool drained = drain();
        if (::close(fd_) != 0 && error_ == 0) error_ = errno;
        fd_ = -1;
        return drained && error_ == 0;
    }

protected:
    int_type overflow(int_type c) override {
        if (!drain()) return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    int sync() override { return drain() ? 0 : -1; }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (n < static_cast<std::streamsize>(sizeof data_)) return std::streambuf::xsputn(s, n);
        return drain() && writeAll(s, n) ? n : 0;  // a large block goes straight through
    }

private:
    bool drain() {
        const bool ok = writeAll(pbase(), pptr() - pbase());
        setp(data_, data_ + sizeof data_);
        return ok;
    }
    bool writeAll(const char* p, std::streamsize n) {
        if (error_ != 0) return false;
        while (n > 0) {
            const ssize_t w = ::write(fd_, p, static_cast<size_t>(n));
            if (w < 0) {
                if (errno == EINTR) continue;
                error_ = errno;
                return false;
            }
            p += w;
            n -= w;
        }
        return true;
    }

    int fd_ = -1;
    int error_ = 0;
    char data_[1 << 16];
};

AtomicFile::AtomicFile(fs::path target, Stale stale)
    : target_(std::move(target)), final_(followLinks(target_)) {
    if (stale == Stale::Remove) removeStaleTemporaries(final_);
    const std::string stem = final_.string() + kMark + std::to_string(::getpid()) + "-";
    int fd = -1;
    for (int attempt = 0; fd < 0 && attempt < 16; ++attempt) {
        temp_ = stem + randomHex();
        fd = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0) throw std::runtime_error(target_.string() + ": cannot be written: " + plainReason(errno));
    buf_ = std::make_unique<Buffer>(fd);
    out_.rdbuf(buf_.get());
}

AtomicFile::~AtomicFile() {
    if (!committed_ && !keep_) {
        out_.rdbuf(nullptr);
        buf_.reset();
        std::error_code ec;
        fs::remove(temp_, ec);
    }
}

void AtomicFile::ready() {
    if (ready_) return;
    out_.flush();
    bool ok = static_cast<bool>(out_) && buf_->error() == 0;
    int err = buf_->error();
    if (ok) {
        // A file replaced keeps its permission bits (a new one gets the umask's).
        struct stat old {};
        if (::stat(final_.c_str(), &old) == 0 && S_ISREG(old.st_mode))
            ::fchmod(buf_->fd(), old.st_mode & 07777);
        // Durable before the rename makes it visible; a file system that allocates late
        // (ext4, XFS, NFS) can report a full disk only here. (EINVAL: it cannot sync.)
        if (::fsync(buf_->fd()) != 0 && errno != EINVAL) {
            ok = false;
            err = errno;
        }
    }
    if (!buf_->close() && ok) {
        ok = false;
        err = buf_->error();
    }
    out_.rdbuf(nullptr);
    buf_.reset();
    if (!ok)
        throw std::runtime_error(target_.string() +
                                 ": writing failed: " + whyWriteFailed(err, folderOf(temp_)));
    ready_ = true;
}

void AtomicFile::commit() {
    ready();
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) throw std::runtime_error(target_.string() + ": cannot be replaced: " + plainReason(ec.value()));
    committed_ = true;
    syncFolder();
}

void AtomicFile::commitKeepingTemporary() {
    ready();
    keep_ = true;  // from here on another file may name it
    const std::string stem = temp_.string().substr(0, temp_.string().size() - kHexDigits);
    fs::path second;
    std::error_code ec;
    for (int attempt = 0; attempt < 16; ++attempt) {
        second = stem + randomHex();
        fs::create_hard_link(temp_, second, ec);
        if (ec != std::errc::file_exists) break;
    }
    if (ec && ec != std::errc::file_exists) {
        // No hard links here (FAT, some network shares): a durable copy instead.
        ec.clear();
        fs::copy_file(temp_, second, fs::copy_options::none, ec);
        const int fd = ec ? -1 : ::open(second.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd >= 0) {
            if (::fsync(fd) != 0 && errno != EINVAL) ec.assign(errno, std::generic_category());
            ::close(fd);
        }
        if (ec) {
            std::error_code ignored;
            fs::remove(second, ignored);
            throw std::runtime_error(target_.string() + ": writing failed: " + plainReason(ec.value()));
        }
    }
    if (ec) throw std::runtime_error(target_.string() + ": cannot be written: " + plainReason(ec.value()));
    fs::rename(second, final_, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(second, ignored);
        throw std::runtime_error(target_.string() + ": cannot be replaced: " + plainReason(ec.value()));
    }
    committed_ = true;
    syncFolder();
}

void AtomicFile::syncFolder() const {
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
