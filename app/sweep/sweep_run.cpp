#include "sweep_run.h"

#include "stop_signals.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

namespace tumble::sweep {

namespace {

// A variant's stdout and stderr come through a pipe: this process writes them into its log
// and keeps the last bytes, so that a variant's message is known even when its log cannot
// be written (a full disk took the message of the variants it stopped).
struct Running {
    pid_t pid = 0;
    int variant = 0;
    std::chrono::steady_clock::time_point start;
    int out = -1;  // the pipe's read end (non-blocking)
    std::ofstream log;
    std::string tail;  // the last bytes it printed
};

// Moves what `r` printed so far into its log and its tail.
void drain(Running& r) {
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(r.out, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        r.log.write(buffer, n);
        r.log.flush();
        r.tail.append(buffer, static_cast<size_t>(n));
        if (r.tail.size() > 8192) r.tail.erase(0, r.tail.size() - 4096);
    }
}

std::string lastLineOf(const std::string& text) {
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last;
}

// Starts a job with stdout and stderr into the write end `out` of a pipe and stdin from
// /dev/null; 0 on failure.
pid_t start(const Job& job, int out) {
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&files, out, 1);
    posix_spawn_file_actions_adddup2(&files, out, 2);
    // The child starts with default signal handling and nothing blocked, whatever this
    // process has set.
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    std::vector<char*> argv;
    for (const std::string& a : job.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int r = posix_spawn(&pid, argv[0], &files, &attr, argv.data(), environ);
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&files);
    return r == 0 ? pid : 0;
}

}  // namespace

bool runLocally(const std::vector<Job>& jobs, int parallel, const std::function<bool(const Outcome&)>& done,
                const std::function<void(int running)>& tick) {
    const cli::StopSignals signals;
    std::vector<Running> running;
    std::size_t next = 0;
    bool startMore = true;
    auto lastTick = std::chrono::steady_clock::now();
    while (!cli::StopSignals::received() && ((startMore && next < jobs.size()) || !running.empty())) {
        while (!cli::StopSignals::received() && startMore && next < jobs.size() &&
               static_cast<int>(running.size()) < parallel) {
            const Job& job = jobs[next++];
            const auto t0 = std::chrono::steady_clock::now();
            int pipe[2] = {-1, -1};
            const pid_t pid = ::pipe2(pipe, O_CLOEXEC) == 0 ? start(job, pipe[1]) : 0;
            const int why = errno;
            if (pipe[1] >= 0) ::close(pipe[1]);
            if (pid == 0) {  // could not start: reported as a failure of its own
                if (pipe[0] >= 0) ::close(pipe[0]);
                const std::string message =
                    "tumble sweep: could not start " + job.argv[0] + ": " + std::strerror(why);
                std::ofstream(job.log) << message << "\n";
                startMore = done({job.variant, 127, 0, 0.0, message}) && startMore;
                continue;
            }
            ::fcntl(pipe[0], F_SETFL, O_NONBLOCK);
            Running r{pid, job.variant, t0, pipe[0], std::ofstream(job.log, std::ios::trunc), {}};
            running.push_back(std::move(r));
        }
        bool reaped = false;
        for (std::size_t k = 0; k < running.size();) {
            drain(running[k]);
            int status = 0;
            const pid_t r = waitpid(running[k].pid, &status, WNOHANG);
            if (r != running[k].pid) {
                ++k;
                continue;
            }
            Outcome o;
            o.variant = running[k].variant;
            o.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - running[k].start).count();
            if (WIFEXITED(status)) o.exitCode = WEXITSTATUS(status);
            if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
            drain(running[k]);  // what it printed last
            ::close(running[k].out);
            o.message = lastLineOf(running[k].tail);
            running.erase(running.begin() + static_cast<long>(k));
            reaped = true;
            // A variant stopped by the same Ctrl-C as this process (one process group) is
            // not a result.
            if (cli::StopSignals::received() && o.signal != 0) continue;
            startMore = done(o) && startMore;
        }
        const auto now = std::chrono::steady_clock::now();
        if (now - lastTick >= std::chrono::milliseconds(100)) {
            tick(static_cast<int>(running.size()));
            lastTick = now;
        }
        if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!cli::StopSignals::received()) return true;
    for (const Running& r : running) kill(r.pid, SIGTERM);
    for (Running& r : running) {
        int status = 0;
        waitpid(r.pid, &status, 0);
        drain(r);
        ::close(r.out);
    }
    return false;
}

std::string selfExecutable() {
    std::error_code ec;
    const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("tumble") : p.string();
}

std::string lastLine(const std::filesystem::path& log) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last;
}

}  // namespace tumble::sweep
