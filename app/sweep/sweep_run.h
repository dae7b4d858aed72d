// Running a sweep's variants on this machine: each variant is its own process (`tumble
// --headless VARIANT --metrics ...`), at most N at once, started with posix_spawn (as the
// mesh reader is: no fork of a process that may hold threads). SIGINT and SIGTERM stop the
// run cleanly: nothing more is started, the running variants are stopped, and what they
// would have written is not there (their files are written whole or not at all), so the
// same command resumes.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tumble::sweep {

struct Job {
    int variant = 0;
    std::vector<std::string> argv;  // argv[0]: the program
    std::filesystem::path log;      // its stdout and stderr
};

struct Outcome {
    int variant = 0;
    int exitCode = -1;  // -1: killed by `signal`
    int signal = 0;
    double wall = 0.0;  // s, from start to exit
    std::string message;  // the last line it printed (also when its log could not be written)
};

/// Runs the jobs, at most `parallel` at once; `done` is called (on this thread) as each
/// ends, and returns false to start no more (the running ones end and are reported: a
/// result that could not be written); `tick` about ten times a second with the number
/// running. Returns false when stopped by SIGINT or SIGTERM (the stopped jobs are not
/// reported).
bool runLocally(const std::vector<Job>& jobs, int parallel, const std::function<bool(const Outcome&)>& done,
                const std::function<void(int running)>& tick);

/// This program's own path (/proc/self/exe), to start the variants with.
std::string selfExecutable();

/// The last line of a log that is not empty (a failed variant's message).
std::string lastLine(const std::filesystem::path& log);

}  // namespace tumble::sweep
