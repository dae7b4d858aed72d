// A recorded run: a State snapshot per frame (principle 4 of DESIGN.md), bounded in memory.
//
// While the snapshots fit in the cap every frame is kept. Past it the recording thins
// itself: the keyframe interval K doubles and only frames k with k % K == 0 stay. A frame
// in between is re-simulated on demand from the keyframe before it (advanceFrame repeats
// the recorded steps bit for bit), so any frame of a run of any length is reachable by at
// most K - 1 frames of simulation, and memory stays under the cap (plus one cached span
// of re-simulated frames). The per-frame summary (energy, momentum) is kept for every
// frame: a few numbers each.
#pragma once

#include <tumble/state.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace tumble {

class World;
struct Model;

/// Numbers every frame keeps, whatever is thinned: what the plots draw.
struct FrameSummary {
    double time = 0.0;
    double kinetic = 0.0;          ///< J
    double potential = 0.0;        ///< J: gravity and springs
    double momentum = 0.0;         ///< |sum P| of the dynamic bodies, kg·m/s
    double angularMomentum = 0.0;  ///< |sum (x × P + L)| about the origin, kg·m²/s
    long steps = 0;                ///< steps taken since the previous frame
};

/// Approximate heap and inline bytes of one snapshot.
std::size_t stateBytes(const State& state);

class Recording {
public:
    /// `capBytes`: the most the kept snapshots may take (at least two are always kept).
    explicit Recording(std::size_t capBytes = std::size_t(512) << 20);

    /// Forgets every frame; the next append is frame 0 of a run of `frames` frames.
    void reset(int frames);
    /// Adds the next frame.
    void append(const State& state, const FrameSummary& summary);

    /// Frames of the whole run (as reset), and how many are recorded so far.
    int frameCount() const { return total_; }
    int framesDone() const { return static_cast<int>(summaries_.size()); }
    bool complete() const { return framesDone() == total_; }

    /// 1 while every frame is kept; else frames are kept only at multiples of it.
    int keyframeInterval() const { return interval_; }
    std::size_t capBytes() const { return cap_; }
    void setCapBytes(std::size_t bytes);
    /// Bytes the kept snapshots take.
    std::size_t bytes() const { return bytes_; }
    int storedCount() const;

    const FrameSummary& summary(int frame) const { return summaries_.at(static_cast<std::size_t>(frame)); }
    /// The kept snapshot of `frame`, or null when it was thinned out (or is not recorded).
    const State* stored(int frame) const;
    /// The nearest kept frame at or before `frame`.
    int keyframeAtOrBefore(int frame) const;

    /// The state of any recorded frame: kept, or re-simulated with `world` (a World of the
    /// same model; its state is overwritten) from the keyframe before it. Re-simulated
    /// frames up to the next keyframe are cached, so scrubbing nearby costs nothing more.
    /// Returns null when `frame` is not recorded.
    const State* state(int frame, World& world);

private:
    void thin();

    std::size_t cap_;
    int total_ = 0;
    int interval_ = 1;
    std::size_t bytes_ = 0;
    std::vector<std::unique_ptr<State>> frames_;  // one slot per recorded frame; null when thinned
    std::vector<FrameSummary> summaries_;
    int cacheStart_ = -1;  // first frame of the cached span of re-simulated frames
    std::vector<State> cache_;
};

/// The summary of a state (energy of the model, momentum of its dynamic bodies).
FrameSummary summarize(const Model& model, const State& state, long steps);

}  // namespace tumble
