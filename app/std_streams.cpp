#include "std_streams.h"

#include <tumble/io/atomic_file.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <stdexcept>

namespace tumble::cli {

namespace fs = std::filesystem;

std::string readStandardInput() {
    std::cin.clear();
    std::string text{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
    if (std::cin.bad()) throw std::runtime_error(std::string(kStdinName) + ": could not be read");
    return text;
}

StdoutFile::StdoutFile(const std::string& name) {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = (tmp && *tmp ? fs::path(tmp) : fs::path("/tmp")) / "tumble-stdout-XXXXXX";
    if (!mkdtemp(pattern.data())) {
        throw std::runtime_error("standard output: cannot make a temporary folder in " +
                                 fs::path(pattern).parent_path().string() + ": " + io::plainReason(errno));
    }
    folder_ = pattern;
    path_ = folder_ / name;
}

StdoutFile::~StdoutFile() {
    std::error_code ec;
    fs::remove_all(folder_, ec);
}

void StdoutFile::copyTo(std::ostream& out) const {
    std::ifstream in(path_, std::ios::binary);
    if (!in)
        throw std::runtime_error("standard output: the written data could not be read back from " +
                                 path_.string());
    if (in.peek() != std::ifstream::traits_type::eof()) out << in.rdbuf();  // << of nothing fails
    out.flush();
    if (!out)
        throw std::runtime_error("standard output: could not be written (a closed pipe, or a full disk)");
}

}  // namespace tumble::cli
