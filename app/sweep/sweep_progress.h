// The progress line of a sweep: done, running, failed and the time left, on stderr:
// rewritten in place on a terminal, else a line at most every two seconds and at the end.
#pragma once

#include <chrono>
#include <cstdio>
#include <ostream>
#include <string>
#include <unistd.h>

namespace tumble::sweep {

class Progress {
public:
    Progress(std::ostream& err, int total, int alreadyDone)
        : err_(err), total_(total), done_(alreadyDone), tty_(isatty(2) != 0) {}
    /// A variant ended here (ok or not) after `wall` seconds.
    void finished(bool ok, double wall) {
        ++done_;
        ++ranHere_;
        failed_ += ok ? 0 : 1;
        wallSum_ += wall;
    }
    /// Counts set from outside (a Slurm job's results, read from the folder).
    void set(int done, int failed) {
        done_ = done;
        failed_ = failed;
    }
    void show(int running, int parallel, bool last = false) {
        const auto now = std::chrono::steady_clock::now();
        if (!last && !tty_ && (now - shown_ < std::chrono::seconds(2) || done_ == lastDone_)) return;
        shown_ = now;
        lastDone_ = done_;
        std::string eta;
        if (ranHere_ > 0 && done_ < total_) {
            char buf[48];
            std::snprintf(buf, sizeof buf, ", about %.0f s left",
                          wallSum_ / ranHere_ * (total_ - done_) / (parallel > 0 ? parallel : 1));
            eta = buf;
        }
        char line[200];
        std::snprintf(line, sizeof line, "sweep: %d of %d done, %d running, %d failed%s", done_, total_, running,
                      failed_, eta.c_str());
        if (tty_) err_ << '\r' << line << "\x1b[K" << (last ? "\n" : "") << std::flush;
        else err_ << line << '\n' << std::flush;
    }

private:
    std::ostream& err_;
    int total_, done_, failed_ = 0, ranHere_ = 0, lastDone_ = -1;
    double wallSum_ = 0.0;
    bool tty_;
    std::chrono::steady_clock::time_point shown_{};
};

}  // namespace tumble::sweep
