#include "version.h"

#include "commit.h"  // (generated at every build: packaging/commit.cmake)

#ifndef TUMBLE_VERSION
#define TUMBLE_VERSION "unknown"
#endif

namespace tumble::cli {

std::string versionLine() {
    return std::string("tumble ") + TUMBLE_VERSION + " (commit " + TUMBLE_COMMIT + ")";
}

}  // namespace tumble::cli
