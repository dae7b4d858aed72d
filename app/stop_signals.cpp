#include "stop_signals.h"

namespace tumble::cli {

namespace {

volatile std::sig_atomic_t noted = 0;

void onSignal(int signal) {
    noted = signal;
}

}  // namespace

StopSignals::StopSignals() {
    // Nested in another (a sweep's whole run around its local runner): a signal already
    // noted is kept, so that it still stops the inner work.
    struct sigaction current {};
    sigaction(SIGINT, nullptr, &current);
    if (current.sa_handler != onSignal) noted = 0;
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &oldInt_);
    sigaction(SIGTERM, &sa, &oldTerm_);
}

StopSignals::~StopSignals() {
    sigaction(SIGINT, &oldInt_, nullptr);
    sigaction(SIGTERM, &oldTerm_, nullptr);
}

int StopSignals::received() {
    return noted;
}

}  // namespace tumble::cli
