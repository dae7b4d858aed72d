// "-" for a file on the command line (issue 47 item 9): a scene read from standard input,
// an output written to standard output.
//
// An output to standard output is written, by the writer a file would have, into a
// private temporary folder, and copied to standard output only once the run has succeeded:
// as with a file, a run that fails or is stopped writes nothing (a reader of the pipe gets
// all or nothing, and the exit status says which).
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

namespace tumble::cli {

/// The name messages give a scene read from standard input.
inline constexpr const char* kStdinName = "<stdin>";

/// The whole of standard input. Throws std::runtime_error when it cannot be read.
std::string readStandardInput();

class StdoutFile {
public:
    /// A temporary folder of this process's own (under $TMPDIR, else /tmp), and in it the
    /// file `name` for the writer; throws std::runtime_error when it cannot be made.
    explicit StdoutFile(const std::string& name);
    /// Removes the folder and whatever is in it.
    ~StdoutFile();
    StdoutFile(const StdoutFile&) = delete;
    StdoutFile& operator=(const StdoutFile&) = delete;

    /// Where the writer writes.
    const std::filesystem::path& path() const { return path_; }
    /// Copies the written file to `out` and flushes it; throws std::runtime_error ("standard
    /// output: could not be written: ...") when it could not.
    void copyTo(std::ostream& out) const;

private:
    std::filesystem::path folder_, path_;
};

}  // namespace tumble::cli
