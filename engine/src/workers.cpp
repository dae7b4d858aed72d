// The pool's handshake: a run is announced by bumping `generation_`; helpers that finished
// the last run spin on it for a while (a step hands the pool several short runs, and waking
// a sleeping thread costs more than a small run's work on this kind of machine) and then
// sleep on `wake_`. The caller takes chunks itself, then waits for `working_` to reach zero,
// spinning first as well.
#include "workers.h"

#include <algorithm>
#include <chrono>

namespace tumble {

namespace {

constexpr auto kSpin = std::chrono::microseconds(200);  // how long a thread spins before sleeping

// Spins until ready() or kSpin has passed; true if ready. Each round yields the core, so a
// spinning thread gives way to one with work when there are more threads than cores (four
// threads on two cores ran a test 20 times slower with a busy spin under AddressSanitizer).
template <class Ready>
bool spinFor(Ready&& ready) {
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (int k = 0;; ++k) {
        if (ready()) return true;
        std::this_thread::yield();
        if ((k & 15) == 15 && std::chrono::steady_clock::now() > until) return false;
    }
}

}  // namespace

Workers::Workers(int threads) {
    for (int i = 1; i < std::max(threads, 1); ++i) helpers_.emplace_back([this] { helperLoop(); });
}

Workers::~Workers() {
    {
        std::lock_guard lock(m_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : helpers_) t.join();
}

void Workers::takeChunks() {
    for (int c = next_.fetch_add(1); c < chunks_; c = next_.fetch_add(1)) {
        try {
            (*job_)(c);
        } catch (...) {
            std::lock_guard lock(m_);
            if (!error_) error_ = std::current_exception();
        }
    }
}

void Workers::helperLoop() {
    unsigned long seen = 0;
    for (;;) {
        auto announced = [&] { return stop_.load() || generation_.load() != seen; };
        if (!spinFor(announced)) {
            std::unique_lock lock(m_);
            wake_.wait(lock, announced);
        }
        if (stop_) return;
        seen = generation_.load();
        takeChunks();
        if (working_.fetch_sub(1) == 1) {
            { std::lock_guard lock(m_); }  // the caller is either waiting or will see zero
            done_.notify_one();
        }
    }
}

void Workers::run(int chunks, const std::function<void(int)>& job) {
    if (chunks <= 0) return;
    std::lock_guard turn(callers_);
    job_ = &job;
    chunks_ = chunks;
    next_.store(0);
    working_.store(static_cast<int>(helpers_.size()));
    generation_.fetch_add(1);  // helpers spinning start here
    { std::lock_guard lock(m_); }  // a helper going to sleep has either seen it or waits now
    wake_.notify_all();
    takeChunks();
    auto finished = [&] { return working_.load() == 0; };
    if (!spinFor(finished)) {
        std::unique_lock lock(m_);
        done_.wait(lock, finished);
    }
    job_ = nullptr;
    std::exception_ptr error;
    {
        std::lock_guard lock(m_);
        std::swap(error, error_);
    }
    if (error) std::rethrow_exception(error);
}

}  // namespace tumble
