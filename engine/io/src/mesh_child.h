// Reading a mesh file in a child process. assimp 5.2 can abort on an internal assertion
// (a PLY whose faces do not match its header trips one in its triangulation) or loop for
// ever on a malformed file; in a child process that costs the import, not the editor or the
// run, and the user gets a message naming the file instead of a crash.
#pragma once

#include <tumble/mass.h>

#include <sys/types.h>

#include <atomic>
#include <functional>
#include <string>

namespace tumble::io {

/// Runs `read` in a forked child and returns the mesh it read. An InputError it throws comes
/// back as an InputError for `name` with the same message; a child that dies (a signal) or
/// does not finish within `timeLimit` seconds (it is killed) gives an InputError for `name`
/// that says so. When `cancel` is set while it waits, the child is killed and
/// MeshImportCancelled thrown.
/// The child's answer on the pipe, and back: 'M', the vertex and triangle counts, the
/// vertices (3 doubles each) and the triangles (3 int32 each); or 'E' and a message.
/// meshFromAnswer throws InputError for `name` with the message, or when the answer is
/// not one (cut short, counts that do not match its length). Apart for the fuzzer of the
/// parent's side (tests/fuzz/fuzz_meshdata.cpp).
std::string encodeMeshAnswer(const TriangleMesh& mesh);
TriangleMesh meshFromAnswer(const std::string& name, const std::string& answer);

TriangleMesh readMeshInChild(const std::string& name, double timeLimit,
                             const std::function<TriangleMesh()>& read,
                             const std::atomic<bool>* cancel = nullptr);

/// The same with the reader program (tumble-mesh-reader, mesh_reader.cpp) in place of a
/// fork: what importMesh uses when it finds the program. A fork copies one thread of a
/// process whose other threads may hold locks (the editor reads on a worker thread while the
/// GUI and Qt3D threads run; under AddressSanitizer its allocator's lock was one, and the
/// child waited on it for ever); a new program starts with none.
/// Throws InputError for `name` when the program cannot be started.
TriangleMesh readMeshWithProgram(const std::string& program, const std::string& name, const Vec3& scale,
                                 double timeLimit, const std::atomic<bool>* cancel = nullptr);

/// The parent's side: reads the answer of the child `pid` from `fd` (and closes it), at most
/// `timeLimit` seconds, reaps the child, and returns the mesh or throws as above.
TriangleMesh awaitMeshAnswer(const std::string& name, double timeLimit, pid_t pid, int fd,
                             const std::atomic<bool>* cancel);

/// The child's side: runs `read` and writes its answer to `fd`, then ends the process
/// (status 0 when the answer was written). Under AddressSanitizer a report with assimp on
/// the stack ends it with status 3, which the parent reports as the reader's fault.
[[noreturn]] void answerInThisProcess(int fd, const std::function<TriangleMesh()>& read);

/// assimp's reading and Tumble's checks of what it read (mesh_import.cpp); throws
/// InputError for `name`.
TriangleMesh readWithAssimp(const std::string& name, const Vec3& scale);

}  // namespace tumble::io
