// The command line's options as data: each flag, the value it takes and its help. The
// parsers (cli.cpp, sweep/sweep_cli.cpp) read flags against these tables, so an unknown
// flag is refused with the nearest known one ("did you mean --headless?"), a flag that
// takes a value never swallows the next flag as its value, and `--help` is written from
// the same table: a flag cannot be parsed and missing from the help, or the other way.
#pragma once

#include <string>
#include <vector>

namespace tumble::cli {

struct OptionSpec {
    std::string flag;   ///< "--dt"
    std::string value;  ///< its value's placeholder ("S"), empty for a switch
    std::string help;   ///< lines, '\n' between them (aligned under each other in the help)
};

/// The options as help lines: "  --flag VALUE" padded to a column, then the help.
std::string optionsHelp(const std::vector<OptionSpec>& options);

/// The spec of `flag`, or null.
const OptionSpec* findOption(const std::vector<OptionSpec>& options, const std::string& flag);

/// The known word nearest to `word` when it is near enough to be a slip of the keyboard
/// (an edit distance of at most 2, and less than half its length), else "".
std::string nearest(const std::string& word, const std::vector<std::string>& known);

/// "unknown option '--headles'; did you mean --headless?" (the question only when one is
/// near) followed by `more` (" (see --help)").
std::string unknownOption(const std::string& flag, const std::vector<OptionSpec>& options,
                          const std::string& more);

/// True when `text`, given as a flag's value, is another flag instead ("--quiet"): a value
/// is never taken from there. A negative number ("-0.5") is a value.
bool looksLikeFlag(const std::string& text);

}  // namespace tumble::cli
