// The frame loop: lands exactly on every frame time and every force switch time, with
// equal steps no longer than dt in between. Frame times are computed as k / frame_rate,
// never accumulated, so a long run does not drift off them.
#include <tumble/world.h>

#include <algorithm>
#include <cmath>

namespace tumble {

int frameCount(const Settings& s) {
    return static_cast<int>(std::llround(s.duration * s.frameRate)) + 1;
}

namespace {

// Steps from the world's time to `end` in n equal steps, n the fewest with h <= dt.
long advanceTo(World& world, double end, double dt) {
    const double span = end - world.state().time;
    if (!(span > 0.0)) return 0;
    // The small slack keeps a span that is a whole number of dt, up to rounding, at that number.
    const long n = std::max(1L, static_cast<long>(std::ceil(span / dt * (1.0 - 1e-12))));
    const double start = world.state().time;
    for (long k = 1; k <= n; ++k) {
        world.step((start + span * static_cast<double>(k) / static_cast<double>(n)) -
                   world.state().time);
    }
    world.setTime(end);  // exact, whatever the rounding of the sum of steps
    return n;
}

}  // namespace

long advanceFrame(World& world, int frame) {
    const Settings& s = world.model().settings;
    const std::vector<double>& switches = world.model().forceSwitchTimes;
    const double frameTime = static_cast<double>(frame) / s.frameRate;
    long steps = 0;
    auto it = std::upper_bound(switches.begin(), switches.end(), world.state().time);
    for (; it != switches.end() && *it < frameTime; ++it) steps += advanceTo(world, *it, s.dt);
    return steps + advanceTo(world, frameTime, s.dt);
}

RunResult simulate(World& world, const std::function<void(int, const State&)>& onFrame) {
    RunResult r;
    r.frames = frameCount(world.model().settings);
    onFrame(0, world.state());
    for (int k = 1; k < r.frames; ++k) {
        r.steps += advanceFrame(world, k);
        onFrame(k, world.state());
    }
    return r;
}

}  // namespace tumble
