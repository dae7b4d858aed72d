#include "mesh_child.h"

#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>

#include <fcntl.h>

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <vector>

// In a build with AddressSanitizer, a memory error that the sanitizer finds inside assimp in
// the child (assimp 5.2 frees what it never allocated on some damaged PLY files: the mesh
// fuzzer's bad-free) is assimp's, like its crashes: the child then exits with its own status
// and the parent says the reader failed on the file. A report with no assimp frame on the
// stack stays status 1, a fault of Tumble's own (the harness's bug).
#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_CHILD_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_CHILD_ASAN 1
#endif
#endif
#ifdef TUMBLE_CHILD_ASAN
#include <dlfcn.h>
#include <execinfo.h>
extern "C" void __sanitizer_set_death_callback(void (*callback)(void));
#endif

namespace tumble::io {

namespace {

// The child's exit status when the sanitizer stopped it inside assimp.
constexpr int kReaderFault = 3;

#ifdef TUMBLE_CHILD_ASAN
void onSanitizerDeath() {
    void* frames[256];
    const int n = ::backtrace(frames, 256);
    for (int i = 0; i < n; ++i) {
        Dl_info info;
        if (::dladdr(frames[i], &info) != 0 && info.dli_fname && std::strstr(info.dli_fname, "libassimp"))
            _exit(kReaderFault);
    }
}

void watchForReaderFaults() {
    void* warm[4];
    ::backtrace(warm, 4);  // loads the unwinder now, not in the middle of a report
    __sanitizer_set_death_callback(onSanitizerDeath);
}
#else
void watchForReaderFaults() {}
#endif

void append(std::string& out, const void* data, std::size_t size) {
    out.append(static_cast<const char*>(data), size);
}

}  // namespace

std::string encodeMeshAnswer(const TriangleMesh& mesh) {
    std::string out(1, 'M');
    const std::uint64_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
    append(out, &nv, sizeof nv);
    append(out, &nt, sizeof nt);
    for (const Vec3& v : mesh.vertices) append(out, v.data(), 3 * sizeof(double));
    for (const auto& t : mesh.triangles) {
        const std::int32_t k[3] = {t[0], t[1], t[2]};
        append(out, k, sizeof k);
    }
    return out;
}

namespace {

bool writeAll(int fd, const std::string& data) {
    std::size_t done = 0;
    while (done < data.size()) {
        const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += static_cast<std::size_t>(n);
    }
    return true;
}

[[noreturn]] void runChild(int fd, const std::function<TriangleMesh()>& read) {
    std::string answer;
    try {
        answer = encodeMeshAnswer(read());
    } catch (const InputError& e) {
        answer = "E" + e.message();
    } catch (const std::exception& e) {
        answer = std::string("E") + e.what();
    }
    _exit(writeAll(fd, answer) ? 0 : 1);  // no atexit handlers, no destructors: only the answer
}

TriangleMesh decode(const std::string& name, const std::string& data) {  // an 'M' answer
    const auto broken = [&] {
        return InputError(name, "", "cannot be read as a mesh: the reader's answer was cut short");
    };
    std::uint64_t nv = 0, nt = 0;
    if (data.size() < 1 + 2 * sizeof nv) throw broken();
    std::memcpy(&nv, data.data() + 1, sizeof nv);
    std::memcpy(&nt, data.data() + 1 + sizeof nv, sizeof nt);
    const std::size_t need = 1 + 2 * sizeof nv + nv * 3 * sizeof(double) + nt * 3 * sizeof(std::int32_t);
    if (nv > data.size() || nt > data.size() || data.size() != need) throw broken();
    TriangleMesh mesh;
    mesh.vertices.resize(nv);
    mesh.triangles.resize(nt);
    const char* p = data.data() + 1 + 2 * sizeof nv;
    for (auto& v : mesh.vertices) {
        std::memcpy(v.data(), p, 3 * sizeof(double));
        p += 3 * sizeof(double);
    }
    for (auto& t : mesh.triangles) {
        std::int32_t k[3];
        std::memcpy(k, p, sizeof k);
        p += sizeof k;
        t = {k[0], k[1], k[2]};
    }
    return mesh;
}

std::string describe(int status) {
    if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        const char* what = ::strsignal(sig);
        return "the mesh reader (assimp) crashed on it (signal " + std::to_string(sig) +
               (what ? std::string(": ") + what : std::string()) +
               "); the file is damaged or in a form it cannot read";
    }
    if (WEXITSTATUS(status) == kReaderFault)
        return "the mesh reader (assimp) failed on it (a memory error inside the reader); the file is "
               "damaged "
               "or in a form it cannot read";
    return "the mesh reader stopped without an answer (exit status " + std::to_string(WEXITSTATUS(status)) +
           ")";
}

}  // namespace

TriangleMesh readMeshInChild(const std::string& name, double timeLimit,
                             const std::function<TriangleMesh()>& read, const std::atomic<bool>* cancel) {
    int fds[2];
    // Close-on-exec: a program another thread starts meanwhile (the editor's video encoder)
    // must not hold the write end, or the answer would never end.
    if (::pipe2(fds, O_CLOEXEC) != 0) return read();  // no pipe, no child: read here, unprotected
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        return read();
    }
    if (pid == 0) {
        ::close(fds[0]);
        // assimp's failed assertions abort(): let that end the child at once, whatever
        // handler the parent has (Qt Test's attaches a debugger). A sanitizer's report in
        // the child exits with status 1 instead (kReaderFault when it was inside assimp),
        // which the parent tells apart.
        ::signal(SIGABRT, SIG_DFL);
        answerInThisProcess(fds[1], read);
    }
    ::close(fds[1]);
    return awaitMeshAnswer(name, timeLimit, pid, fds[0], cancel);
}

[[noreturn]] void answerInThisProcess(int fd, const std::function<TriangleMesh()>& read) {
    watchForReaderFaults();
    runChild(fd, read);
}

TriangleMesh awaitMeshAnswer(const std::string& name, double timeLimit, pid_t pid, int fd,
                             const std::atomic<bool>* cancel) {
    // Read the whole answer, waiting at most timeLimit in all.
    using Clock = std::chrono::steady_clock;
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeLimit);
    std::string data;
    std::vector<char> buffer(1 << 16);
    bool timedOut = false, cancelled = false;
    // Waits of at most a tenth of a second when someone may cancel, so that a cancel is
    // heard at once; else of a second.
    const std::chrono::milliseconds::rep slice = cancel ? 100 : 1000;
    for (;;) {
        if (cancel && cancel->load()) {
            cancelled = true;
            break;
        }
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) {
            timedOut = true;
            break;
        }
        pollfd p{fd, POLLIN, 0};
        const int ready = ::poll(&p, 1, static_cast<int>(std::min(left, slice)));
        if (ready < 0 && errno == EINTR) continue;
        if (ready <= 0) continue;
        const ssize_t n = ::read(fd, buffer.data(), buffer.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;  // the child closed its end: the answer is complete
        data.append(buffer.data(), static_cast<std::size_t>(n));
    }
    ::close(fd);
    if (timedOut || cancelled) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (cancelled) throw MeshImportCancelled("reading " + name + " was cancelled");
    if (timedOut) {
        char limit[32];
        std::snprintf(limit, sizeof limit, "%g", timeLimit);
        throw InputError(name, "",
                         std::string("the mesh reader (assimp) did not finish reading it within ") + limit +
                             " s; the file is damaged or too large");
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw InputError(name, "", describe(status));
    if (data.empty()) throw InputError(name, "", describe(status));
    return meshFromAnswer(name, data);
}

TriangleMesh meshFromAnswer(const std::string& name, const std::string& answer) {
    if (!answer.empty() && answer[0] == 'E') throw InputError(name, "", answer.substr(1));
    if (answer.empty() || answer[0] != 'M')
        throw InputError(name, "", "cannot be read as a mesh: the reader's answer was not one");
    return decode(name, answer);
}

}  // namespace tumble::io
