// `tumble sweep`: variants of a scene run on this machine's cores and merged into one
// table (docs/sweeps.md).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace tumble::sweep {

/// Runs `tumble sweep ARGS` (the arguments after "sweep"); returns the exit status: 0 every
/// variant ran, 1 one or more failed (each a row of the summary with its message), 2 bad
/// input (nothing run), 130 stopped by SIGINT or SIGTERM (the same command resumes).
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace tumble::sweep
