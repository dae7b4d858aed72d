// The frame loop: lands exactly on every frame time and every force switch time, with
// equal steps no longer than dt in between. Frame times are computed as k / frame_rate,
// never accumulated, so a long run does not drift off them.
#include <tumble/world.h>

#include "common/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace tumble {

int frameCount(const Settings& s) {
    return static_cast<int>(std::llround(s.duration * s.frameRate)) + 1;
}

namespace {

// The fewest equal steps no longer than dt over `span`. The slack keeps a span that is a
// whole number of dt up to a part in a billion at that number: a dt typed as 0.0083333333
// (a frame of 1/60 s in 2) is 4e-10 short of 1/120 and took 3 steps with a slack of 1e-12.
long stepsOver(double span, double dt) {
    return std::max(1L, static_cast<long>(std::ceil(span / dt * (1.0 - 1e-9))));
}

// Steps from the world's time to `end` in n equal steps, n the fewest with h <= dt.
long advanceTo(World& world, double end, double dt) {
    const double span = end - world.state().time;
    if (!(span > 0.0)) return 0;
    const long n = stepsOver(span, dt);
    const double start = world.state().time;
    for (long k = 1; k <= n; ++k) {
        world.step((start + span * static_cast<double>(k) / static_cast<double>(n)) - world.state().time);
    }
    world.setTime(end);  // exact, whatever the rounding of the sum of steps
    return n;
}

}  // namespace

long stepsPerFrame(const Settings& s) {
    return stepsOver(1.0 / s.frameRate, s.dt);
}

double stepUsed(const Settings& s) {
    return 1.0 / s.frameRate / static_cast<double>(stepsPerFrame(s));
}

namespace {


}  // namespace

std::string stepNote(const Settings& s) {
    const double h = stepUsed(s);
    if (std::abs(h - s.dt) <= 1e-6 * s.dt) return {};  // (a dt typed to 6 digits is that dt)
    const double frame = 1.0 / s.frameRate;
    const std::string frameText =
        "a frame (" + numberText(frame) + " s at frame_rate " + numberText(s.frameRate) + ")";
    if (s.dt > frame) {
        return "settings.dt " + numberText(s.dt) + " s is longer than " + frameText +
               ": each frame is one step of " + numberText(h) + " s, not " + numberText(s.dt) +
               "; for steps of " + numberText(s.dt) + " s set frame_rate to " + numberText(1.0 / s.dt) +
               " or less";
    }
    const long n = stepsPerFrame(s);
    return "settings.dt " + numberText(s.dt) + " s does not divide " + frameText + ": each frame is " +
           std::to_string(n) + " equal steps of " + numberText(h) + " s, the fewest no longer than dt";
}

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
