// The reader program: importMesh's child as a program of its own, started with posix_spawn
// (mesh_child.h says why not a fork), and where it is found.
#include "mesh_child.h"

#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

extern char** environ;

namespace tumble::io {

namespace {

// The answer's descriptor in the reader program: stdout and stderr stay the user's (a
// sanitizer's report goes to stderr).
constexpr int kAnswerFd = 3;

bool runnable(const std::filesystem::path& p) {
    std::error_code ec;
    return std::filesystem::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

}  // namespace

std::string meshReaderProgram() {
    if (const char* given = std::getenv("TUMBLE_MESH_READER"); given && *given) return given;
    static const std::string found = [] {
        std::error_code ec;
        const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) {
            const auto beside = self.parent_path() / "tumble-mesh-reader";
            if (runnable(beside)) return beside.string();
#ifdef TUMBLE_MESH_READER_FROM_BIN
            // Installed: bin/tumble and libexec/tumble/tumble-mesh-reader under one prefix.
            const auto installed = (self.parent_path() / TUMBLE_MESH_READER_FROM_BIN).lexically_normal();
            if (runnable(installed)) return installed.string();
#endif
        }
#ifdef TUMBLE_MESH_READER_BUILT
        if (runnable(TUMBLE_MESH_READER_BUILT)) return std::string(TUMBLE_MESH_READER_BUILT);
#endif
        return std::string();
    }();
    return found;
}

TriangleMesh readMeshWithProgram(const std::string& program, const std::string& name, const Vec3& scale,
                                 double timeLimit, const std::atomic<bool>* cancel) {
    const auto cannotStart = [&](int error) {
        return InputError(name, "",
                          "the mesh reader program " + program + " cannot be started (" +
                              std::strerror(error) + ")");
    };
    int fds[2];
    // Close-on-exec: no other program started meanwhile may hold the write end.
    if (::pipe2(fds, O_CLOEXEC) != 0) throw cannotStart(errno);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    // The write end becomes descriptor 3 in the reader (a dup2 to another number clears
    // close-on-exec there); when the pipe already is 3, it is moved away first.
    int writeEnd = fds[1];
    if (writeEnd == kAnswerFd) {
        writeEnd = ::fcntl(fds[1], F_DUPFD_CLOEXEC, kAnswerFd + 1);
        ::close(fds[1]);
        fds[1] = writeEnd;
    }
    posix_spawn_file_actions_adddup2(&files, writeEnd, kAnswerFd);
    // A clean start whatever the calling thread blocked or its process handles: an abort in
    // assimp must end the reader.
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t none, defaults;
    sigemptyset(&none);
    sigemptyset(&defaults);
    for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGPIPE, SIGTERM}) sigaddset(&defaults, sig);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

    char scaleText[3][32];
    for (int k = 0; k < 3; ++k) std::snprintf(scaleText[k], sizeof scaleText[k], "%.17g", scale[k]);
    std::string file = name;
    char* argv[] = {const_cast<char*>(program.c_str()), file.data(), scaleText[0], scaleText[1],
                    scaleText[2], nullptr};
    pid_t pid = 0;
    const int error = ::posix_spawn(&pid, program.c_str(), &files, &attr, argv, environ);
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attr);
    ::close(fds[1]);
    if (error != 0) {
        ::close(fds[0]);
        throw cannotStart(error);
    }
    return awaitMeshAnswer(name, timeLimit, pid, fds[0], cancel);
}

int meshReaderMain(int argc, char** argv) {
    double scale[3] = {1, 1, 1};
    bool good = argc == 5;
    for (int k = 0; good && k < 3; ++k) {
        char* end = nullptr;
        scale[k] = std::strtod(argv[2 + k], &end);
        good = end != argv[2 + k] && *end == '\0';
    }
    if (!good || ::fcntl(kAnswerFd, F_GETFD) < 0) {
        std::fprintf(stderr,
                     "usage: tumble-mesh-reader FILE SX SY SZ 3>ANSWER\n"
                     "Reads FILE with assimp for Tumble, each vertex scaled by (SX, SY, SZ), and writes\n"
                     "the mesh to file descriptor 3. Started by Tumble for each mesh it imports.\n");
        return 2;
    }
    const std::string name = argv[1];
    const Vec3 s(scale[0], scale[1], scale[2]);
    answerInThisProcess(kAnswerFd, [&] { return readWithAssimp(name, s); });
}

}  // namespace tumble::io
