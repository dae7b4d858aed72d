// A small pool of worker threads for the stages whose items are independent: the narrow
// phase and the time of impact over pairs, the drift of the integrator over bodies.
//
// Determinism: a stage hands the pool a number of chunks; each chunk writes only its own
// items (or its own output list, joined in chunk order afterwards), so the result is the
// same bit for bit whatever the number of threads and whichever thread took which chunk.
// Nothing that sums over items (energy, the profile) runs inside a chunk.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "common/pool_gate.h"

namespace tumble {

class Workers {
public:
    /// `threads` in all, the calling thread included (1: no helper threads).
    explicit Workers(int threads);
    ~Workers();
    Workers(const Workers&) = delete;
    Workers& operator=(const Workers&) = delete;

    int threads() const { return static_cast<int>(helpers_.size()) + 1; }

    /// Calls job(c) once for every chunk c in [0, chunks), chunks < 2^23, spread over the
    /// threads, and returns when all are done (not waiting for helpers that took none). An
    /// exception thrown by a job is rethrown here (which one, when several throw, is not
    /// fixed; the others are dropped). Calls from several threads at once take turns.
    void run(int chunks, const std::function<void(int)>& job);

    /// What a run costs beyond its work (handing out the tickets, waking the helpers,
    /// waiting for the last chunk), in seconds: the median of a few empty runs timed when the
    /// pool was made.
    double dispatchSeconds() const { return dispatch_; }
    /// Runs taken since the pool was made (its own timing runs not counted).
    long runs() const { return runs_; }

private:
    void helperLoop();
    void takeChunks();

    std::vector<std::thread> helpers_;
    std::mutex callers_;  // one run at a time
    std::mutex m_;        // guards the sleeping: a run is announced under it
    std::condition_variable wake_, done_;
    const std::function<void(int)>* job_ = nullptr;  // the current run's; written before its tickets
    // The current run's tickets: its generation (16 bits), its number of chunks (24 bits) and
    // the next chunk to take (24 bits), in one word, so that a thread that comes late to a
    // run that has ended draws a number past the end and touches nothing of the next run.
    std::atomic<std::uint64_t> ticket_{0};
    std::atomic<std::uint32_t> generation_{0};  // the helpers wait for it to change
    std::atomic<int> finished_{0};              // chunks of the current run done
    std::atomic<bool> stop_{false};
    std::exception_ptr error_;  // under m_
    double dispatch_ = 0.0;
    long runs_ = 0;
};

/// Splits [0, n) into chunks of about `grain` items (at least one chunk when n > 0) and calls
/// body(begin, end) for each, on the pool when there is one and more than one chunk (and,
/// given a gate, when the gate finds the run worth it).
template <class Body>
void forEachChunk(Workers* pool, int n, int grain, Body&& body, PoolGate* gate = nullptr) {
    if (n <= 0) return;
    const int chunks = (n + grain - 1) / grain;
    const bool timed = gate && pool && pool->threads() > 1;  // (one thread: nothing to gate)
    const bool pooled = pool && pool->threads() > 1 && chunks > 1 && (!gate || gate->worthIt(pool, n));
    const auto start = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    if (!pooled) {
        body(0, n);
    } else {
        pool->run(chunks, [&](int c) {
            const int begin = static_cast<int>(static_cast<long>(n) * c / chunks);
            const int end = static_cast<int>(static_cast<long>(n) * (c + 1) / chunks);
            body(begin, end);
        });
    }
    if (timed)
        gate->record(pool, n, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                     pooled);
}

}  // namespace tumble
