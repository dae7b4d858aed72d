#include <tumble/io/atomic_file.h>

#include <fcntl.h>
#include <unistd.h>

#include <random>
#include <stdexcept>

namespace tumble::io {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
    std::random_device rd;
    temp_ = target_;
    temp_ += ".tmp-" + std::to_string(rd() % 1000000);
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) throw std::runtime_error(target_.string() + ": cannot be written (no such folder, or no permission)");
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
    // Make the data durable before the rename makes it visible.
    const int fd = ::open(temp_.c_str(), O_RDONLY);
    if (fd >= 0) {
        ::fsync(fd);
        ::close(fd);
    }
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec) throw std::runtime_error(target_.string() + ": cannot be replaced: " + ec.message());
    committed_ = true;
}

void writeFileAtomically(const fs::path& path, const std::string& contents) {
    AtomicFile file(path);
    file.stream() << contents;
    file.commit();
}

}  // namespace tumble::io
