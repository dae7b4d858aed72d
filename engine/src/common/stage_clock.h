// The clock of the stage profile (World::profile): the processor's time-stamp counter where
// there is one, read in about 11 ns on this project's machine against 26 ns for
// steady_clock (kvm-clock's vDSO); a tiny scene reads it some fifteen times a step, and
// steady_clock was a quarter of a rolling ball's step. The profile adds up ticks; World
// turns them into seconds when asked, at the rate the two clocks kept since the World was
// made (constant_tsc: the counter runs at one rate whatever the core's speed).
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace tumble::stage_clock {

inline std::uint64_t now() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
#endif
}

/// Ticks since `t`, as a double (the profile's unit until World converts it).
inline double since(std::uint64_t t) {
    return static_cast<double>(now() - t);
}

/// Both clocks read together: the tick count halfway between two readings that bracket the
/// wall-clock reading, the closest of a few tries (a thread preempted between the readings
/// would pair a wall time with a tick count far from it).
struct Reading {
    std::uint64_t ticks = 0;
    std::chrono::steady_clock::time_point wall;

    static Reading take() {
        Reading best;
        std::uint64_t gap = ~std::uint64_t{0};
        for (int i = 0; i < 5; ++i) {
            const std::uint64_t a = now();
            const auto w = std::chrono::steady_clock::now();
            const std::uint64_t b = now();
            if (b - a < gap) gap = b - a, best = {a + (b - a) / 2, w};
        }
        return best;
    }
};

/// Seconds per tick: the two clocks' rates between a reading at construction and now.
struct Rate {
    Reading start = Reading::take();

    double secondsPerTick() const {
#if defined(__x86_64__) || defined(__i386__)
        const Reading r = Reading::take();
        const double s = std::chrono::duration<double>(r.wall - start.wall).count();
        return r.ticks > start.ticks && s > 0.0 ? s / static_cast<double>(r.ticks - start.ticks) : 0.0;
#else
        using Period = std::chrono::steady_clock::period;
        return static_cast<double>(Period::num) / static_cast<double>(Period::den);
#endif
    }
};

}  // namespace tumble::stage_clock
