// Reading a mesh file in a child process. assimp 5.2 can abort on an internal assertion
// (a PLY whose faces do not match its header trips one in its triangulation) or loop for
// ever on a malformed file; in a child process that costs the import, not the editor or the
// run, and the user gets a message naming the file instead of a crash.
#pragma once

#include <tumble/mass.h>

#include <atomic>
#include <functional>
#include <string>

namespace tumble::io {

/// Runs `read` in a forked child and returns the mesh it read. An InputError it throws comes
/// back as an InputError for `name` with the same message; a child that dies (a signal) or
/// does not finish within `timeLimit` seconds (it is killed) gives an InputError for `name`
/// that says so. When `cancel` is set while it waits, the child is killed and
/// MeshImportCancelled thrown.
TriangleMesh readMeshInChild(const std::string& name, double timeLimit,
                             const std::function<TriangleMesh()>& read,
                             const std::atomic<bool>* cancel = nullptr);

}  // namespace tumble::io
