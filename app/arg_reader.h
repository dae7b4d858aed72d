// The command line's arguments one at a time, "--flag value" and "--flag=value" alike
// (tumble --headless and tumble sweep read theirs with it).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace tumble::cli {

class ArgReader {
public:
    explicit ArgReader(const std::vector<std::string>& args) : args_(args) {}

    /// Moves to the next argument; false past the last.
    bool next() {
        if (++i_ >= args_.size()) return false;
        flag_ = args_[i_];
        inline_.reset();
        const auto eq = flag_.find('=');
        if (flag_.rfind("--", 0) == 0 && eq != std::string::npos) {
            inline_ = flag_.substr(eq + 1);
            flag_ = flag_.substr(0, eq);
        }
        return true;
    }
    /// The argument, less any "=value".
    const std::string& flag() const { return flag_; }
    /// The flag's value: what follows '=', else the next argument (taken); none at the end.
    std::optional<std::string> value() {
        if (inline_) return inline_;
        if (i_ + 1 >= args_.size()) return std::nullopt;
        return args_[++i_];
    }

private:
    const std::vector<std::string>& args_;
    std::size_t i_ = static_cast<std::size_t>(-1);
    std::string flag_;
    std::optional<std::string> inline_;
};

}  // namespace tumble::cli
