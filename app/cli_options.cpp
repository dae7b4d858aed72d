#include "cli_options.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace tumble::cli {

namespace {

constexpr std::size_t kHelpColumn = 22;  // where each option's help starts

// Levenshtein distance (insertions, deletions, substitutions; a swap counts two).
std::size_t distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

}  // namespace

std::string optionsHelp(const std::vector<OptionSpec>& options) {
    std::ostringstream out;
    for (const OptionSpec& o : options) {
        std::string head = "  " + o.flag + (o.value.empty() ? "" : " " + o.value);
        std::istringstream lines(o.help);
        std::string line;
        bool first = true;
        while (std::getline(lines, line)) {
            if (first && head.size() + 2 > kHelpColumn) {
                out << head << "\n";  // too long to share its first line
                first = false;
            }
            out << (first ? head + std::string(kHelpColumn - head.size(), ' ')
                          : std::string(kHelpColumn, ' '))
                << line << "\n";
            first = false;
        }
    }
    return out.str();
}

const OptionSpec* findOption(const std::vector<OptionSpec>& options, const std::string& flag) {
    for (const OptionSpec& o : options)
        if (o.flag == flag) return &o;
    return nullptr;
}

std::string nearest(const std::string& word, const std::vector<std::string>& known) {
    std::string best;
    std::size_t bestDistance = 3;
    for (const std::string& k : known) {
        const std::size_t d = distance(word, k);
        if (d < bestDistance && 2 * d < std::max(word.size(), k.size())) {
            best = k;
            bestDistance = d;
        }
    }
    return best;
}

std::string unknownOption(const std::string& flag, const std::vector<OptionSpec>& options,
                          const std::string& more) {
    std::vector<std::string> flags;
    for (const OptionSpec& o : options) flags.push_back(o.flag);
    const std::string guess = nearest(flag, flags);
    return "unknown option '" + flag + "'" + (guess.empty() ? "" : "; did you mean " + guess + "?") + more;
}

bool looksLikeFlag(const std::string& text) {
    return text.size() > 1 && text[0] == '-' && !std::isdigit(static_cast<unsigned char>(text[1])) &&
           text[1] != '.';
}

}  // namespace tumble::cli
