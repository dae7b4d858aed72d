// The pool's handshake. A run publishes its tickets (generation, chunk count, next chunk:
// one 64-bit word) and bumps `generation_`; helpers that finished the last run spin on it
// for a while, yielding (a step hands the pool several short runs, and waking a sleeping
// thread costs more than a small run's work on this kind of machine), then sleep on
// `wake_`. Every thread, the caller included, draws tickets until one is past the end; the
// caller then waits for `finished_` to reach the chunk count, not for the helpers: a helper
// that is slow to wake draws a number past the end and does nothing. A chunk can only be
// drawn while its run is the current one, and the run cannot end before that chunk is done,
// so `job_` is always the run's own when a chunk reads it.
#include "common/workers.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace tumble {

namespace {

constexpr auto kSpin = std::chrono::microseconds(200);  // how long a thread spins before sleeping
constexpr std::uint64_t kIndexMask = (1ULL << 24) - 1;

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
    if (helpers_.empty()) return;
    // The dispatch cost: the median of 15 runs of one empty chunk a thread.
    std::vector<double> times;
    const std::function<void(int)> nothing = [](int) {};
    for (int k = 0; k < 15; ++k) {
        const auto t = std::chrono::steady_clock::now();
        run(this->threads(), nothing);
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
    }
    std::nth_element(times.begin(), times.begin() + 7, times.end());
    dispatch_ = times[7];
    runs_ = 0;
}

bool PoolGate::worthIt(const Workers* pool, int n) {
    if (perItem_ < 0.0) return false;
    const unsigned call = calls_++;
    if (call % 16 == 15) return false;  // (timed on one thread)
    const double gain = perItem_ * n * (1.0 - 1.0 / pool->threads());
    const double d = overhead_ < 0.0 ? pool->dispatchSeconds() : overhead_;
    // The overhead is timed again now and then (one run in 64) when it may have been taken
    // too high: the saving is over a quarter of it and over 1.5 times the pool's own measure.
    // A pooled run that was slow once (helpers woken from sleep) had kept a stage that pays
    // on one thread for good; probing every stage that small made small scenes slower
    // (static-field 0.040 -> 0.065 ms a step on two threads, probing one run in 16 without
    // the quarter).
    if (call % 64 == 7 && gain > 0.25 * d && gain > 1.5 * pool->dispatchSeconds()) return true;
    return gain > 1.5 * d;
}

void PoolGate::record(const Workers* pool, int n, double seconds, bool pooled) {
    if (n <= 0) return;
    // Averages that follow a scene as it settles (a fifth of each new run).
    auto follow = [](double& average, double x) { average = average < 0.0 ? x : 0.8 * average + 0.2 * x; };
    if (pooled)
        follow(overhead_, std::max(0.0, seconds - perItem_ * n / pool->threads()));
    else
        follow(perItem_, seconds / n);
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
    for (;;) {
        const std::uint64_t t = ticket_.fetch_add(1);
        const int chunks = static_cast<int>((t >> 24) & kIndexMask);
        const int c = static_cast<int>(t & kIndexMask);
        if (c >= chunks) return;  // this run (or one that has ended) has no chunk left
        try {
            (*job_)(c);
        } catch (...) {
            std::lock_guard lock(m_);
            if (!error_) error_ = std::current_exception();
        }
        if (finished_.fetch_add(1) + 1 == chunks) {
            { std::lock_guard lock(m_); }  // the caller is either waiting or will see it
            done_.notify_one();
        }
    }
}

void Workers::helperLoop() {
    std::uint32_t seen = 0;
    for (;;) {
        auto announced = [&] { return stop_.load() || generation_.load() != seen; };
        if (!spinFor(announced)) {
            std::unique_lock lock(m_);
            wake_.wait(lock, announced);
        }
        if (stop_) return;
        seen = generation_.load();
        takeChunks();
    }
}

void Workers::run(int chunks, const std::function<void(int)>& job) {
    if (chunks <= 0) return;
    if (static_cast<std::uint64_t>(chunks) > kIndexMask / 2)
        throw std::invalid_argument("Workers::run: too many chunks");
    std::lock_guard turn(callers_);
    ++runs_;
    job_ = &job;
    finished_.store(0);
    const std::uint32_t generation = generation_.load() + 1;
    ticket_.store((static_cast<std::uint64_t>(generation & 0xffff) << 48) |
                  (static_cast<std::uint64_t>(chunks) << 24));
    generation_.store(generation);  // helpers spinning start here
    { std::lock_guard lock(m_); }   // a helper going to sleep has either seen it or waits now
    wake_.notify_all();
    takeChunks();
    auto finished = [&] { return finished_.load() == chunks; };
    if (!spinFor(finished)) {
        std::unique_lock lock(m_);
        done_.wait(lock, finished);
    }
    std::exception_ptr error;
    {
        std::lock_guard lock(m_);
        std::swap(error, error_);
    }
    if (error) std::rethrow_exception(error);
}

}  // namespace tumble
