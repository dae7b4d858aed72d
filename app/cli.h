// The headless command line (INTERFACES.md): tumble --headless SCENE [options],
// --help, --version, --list-integrators. Plain C++: it runs without Qt.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace tumble::cli {

/// True when the arguments ask for the command line rather than the editor.
bool wantsCommandLine(const std::vector<std::string>& args);

/// Runs the command line; returns the exit status (0 ok, 2 invalid input, 1 failure).
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace tumble::cli
