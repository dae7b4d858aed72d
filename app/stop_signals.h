// SIGINT (Ctrl-C) and SIGTERM while a long piece of work runs (a headless run, a sweep, a
// Slurm job followed): the handler only notes which signal came, the work looks at it
// between its steps and ends cleanly. The handlers before come back when it goes.
#pragma once

#include <csignal>

namespace tumble::cli {

class StopSignals {
public:
    StopSignals();  ///< (forgets a signal noted before, unless nested in another StopSignals)
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

    /// The signal that came (SIGINT, SIGTERM), or 0.
    static int received();

private:
    struct sigaction oldInt_ {
    }, oldTerm_{};
};

}  // namespace tumble::cli
