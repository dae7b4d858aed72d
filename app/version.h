// What `tumble --version` prints: the version and the commit the build was made from.
#pragma once

#include <string>

namespace tumble::cli {

/// "tumble 0.1.0 (commit 0123456789ab)": the commit as git named it at the build ("-dirty"
/// with changes not committed, "unknown" when built outside a git checkout).
std::string versionLine();

}  // namespace tumble::cli
