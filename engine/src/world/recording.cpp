#include <tumble/model.h>
#include <tumble/recording.h>
#include <tumble/world.h>

#include <algorithm>
#include <stdexcept>

namespace tumble {

std::size_t stateBytes(const State& s) {
    return sizeof(State) + s.bodies.capacity() * sizeof(BodyState) + s.restTime.capacity() * sizeof(double) +
           s.asleep.capacity() + s.contacts.capacity() * sizeof(ContactMemory) +
           s.touching.capacity() * sizeof(std::uint64_t);
}

FrameSummary summarize(const Model& model, const State& state, long steps) {
    FrameSummary f;
    f.time = state.time;
    const Energy e = energy(model, state);
    f.kinetic = e.kinetic;
    f.potential = e.potential;
    Vec3 P = Vec3::Zero(), L = Vec3::Zero();
    for (int i : model.dynamicBodies) {
        const BodyState& b = state.bodies[static_cast<std::size_t>(i)];
        P += b.P;
        L += b.x.cross(b.P) + b.L;
    }
    f.momentum = P.norm();
    f.angularMomentum = L.norm();
    f.steps = steps;
    return f;
}

Recording::Recording(std::size_t capBytes) : cap_(capBytes) {}

void Recording::reset(int frames) {
    total_ = frames;
    interval_ = 1;
    bytes_ = 0;
    frames_.clear();
    summaries_.clear();
    cacheStart_ = -1;
    cache_.clear();
}

void Recording::setCapBytes(std::size_t bytes) {
    cap_ = bytes;
    thin();
}

void Recording::append(const State& state, const FrameSummary& summary) {
    if (framesDone() >= total_) throw std::logic_error("Recording::append: past the last frame");
    const int k = framesDone();
    summaries_.push_back(summary);
    if (k % interval_ == 0) {
        frames_.push_back(std::make_unique<State>(state));
        bytes_ += stateBytes(*frames_.back());
        thin();
    } else {
        frames_.emplace_back();
    }
}

// Doubles the interval until the kept snapshots fit; frame 0 and one more always stay.
void Recording::thin() {
    const int before = interval_;
    while (bytes_ > cap_ && storedCount() > 2) {
        interval_ *= 2;
        for (std::size_t k = 0; k < frames_.size(); ++k) {
            if (frames_[k] && k % static_cast<std::size_t>(interval_) != 0) {
                bytes_ -= stateBytes(*frames_[k]);
                frames_[k].reset();
            }
        }
    }
    if (interval_ != before) {  // a cached span no longer matches the keyframes
        cacheStart_ = -1;
        cache_.clear();
    }
}

int Recording::storedCount() const {
    int n = 0;
    for (const auto& f : frames_) n += f ? 1 : 0;
    return n;
}

const State* Recording::stored(int frame) const {
    if (frame < 0 || frame >= framesDone()) return nullptr;
    return frames_[static_cast<std::size_t>(frame)].get();
}

int Recording::keyframeAtOrBefore(int frame) const {
    for (int k = std::min(frame, framesDone() - 1); k >= 0; --k)
        if (frames_[static_cast<std::size_t>(k)]) return k;
    return -1;
}

const State* Recording::state(int frame, World& world) {
    if (const State* s = stored(frame)) return s;
    if (frame < 0 || frame >= framesDone()) return nullptr;
    const int key = keyframeAtOrBefore(frame);
    if (cacheStart_ == key + 1 && frame - cacheStart_ < static_cast<int>(cache_.size()))
        return &cache_[static_cast<std::size_t>(frame - cacheStart_)];
    // Re-simulate the span after the keyframe up to the next kept frame (or the last recorded).
    cache_.clear();
    cacheStart_ = key + 1;
    world.setState(*frames_[static_cast<std::size_t>(key)]);
    for (int k = key + 1; k < framesDone() && !frames_[static_cast<std::size_t>(k)]; ++k) {
        advanceFrame(world, k);
        cache_.push_back(world.state());
    }
    return &cache_[static_cast<std::size_t>(frame - cacheStart_)];
}

}  // namespace tumble
