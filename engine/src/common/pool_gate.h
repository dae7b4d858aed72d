// PoolGate: whether a stage's items are worth the worker pool (workers.h). Its own header so
// that the scratch structs of the stages can hold one without including the pool.
#pragma once

namespace tumble {

class Workers;

/// Whether a stage's items are worth the pool (issue 53: small scenes never slower with more
/// threads). It times the stage's runs: on one thread, a cost per item a; on the pool, what
/// a run costs beyond a n / threads, its overhead d (handing out the chunks, waking a helper
/// that went to sleep, the threads' share of the caches), first the pool's own measure. A run
/// goes to the pool when a n (1 - 1/threads) is over 1.5 d; a stage not yet timed, and every
/// 16th run, go on this thread (a stays current as the scene changes); one run in 64 goes to
/// the pool when a n (1 - 1/threads) is over d / 4 and over 1.5 times the pool's own measure,
/// so that d is timed again (one slow pooled run kept a stage on one thread for good). Either way the result
/// is the same bit for bit (the chunks' outputs are joined in order); only the time differs.
class PoolGate {
public:
    /// True when n items of this stage should go to `pool` (counts the call).
    bool worthIt(const Workers* pool, int n);
    /// Books a run of n items that took `seconds`, on the pool (`pooled`) or not.
    void record(const Workers* pool, int n, double seconds, bool pooled);

private:
    double perItem_ = -1.0;  // a: s an item takes on one thread; < 0: not timed yet
    double overhead_ = -1.0;  // d: s a pooled run costs beyond its share of the work; < 0: the pool's measure
    unsigned calls_ = 0;
};

}  // namespace tumble
