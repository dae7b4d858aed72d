#include "model/compile_keys.h"

#include <tumble/errors.h>

#include "common/number_text.h"
#include "model/compile_shape.h"

#include <cmath>

namespace tumble {

using namespace compiling;

void validateKeys(const BodyDesc& b, const std::string& p) {
    if (b.motion != Motion::Animated) {
        if (!b.keys.empty())
            throw SceneError(p + ".keys", std::string("only an animated body has keys (this one is ") +
                                              toString(b.motion) +
                                              "); set motion to animated or remove them");
        return;
    }
    if (b.keys.empty())
        throw SceneError(p + ".keys",
                         "an animated body needs at least one key (time, position, orientation)");
    if (b.velocity != Vec3::Zero())
        throw SceneError(p + ".velocity", "an animated body moves as its keys say; remove its velocity");
    if (b.angularVelocity != Vec3::Zero())
        throw SceneError(p + ".angular_velocity", "an animated body turns as its keys say; remove it");
    for (size_t k = 0; k < b.keys.size(); ++k) {
        const BodyKey& key = b.keys[k];
        const std::string at = p + ".keys[" + std::to_string(k) + "]";
        requireFinite(key.time, at + ".time");
        if (k > 0 && !(key.time > b.keys[k - 1].time)) {
            throw SceneError(at + ".time", "must be later than the key before (" +
                                               numberText(b.keys[k - 1].time) + " s); this one is at " +
                                               numberText(key.time) + " s");
        }
        requireFinite(key.position, at + ".position");
        if (!(key.position.stableNorm() <= kLargestHeld))
            throw SceneError(at + ".position",
                             "is farther than a run can carry in double precision (1e150 m)");
        if (!key.orientation.coeffs().allFinite())
            throw SceneError(at + ".orientation", "must be finite numbers");
        if (!(key.orientation.coeffs().stableNorm() > 1e-12))
            throw SceneError(at + ".orientation", "must not be the zero quaternion");
    }
}

void compileAnimated(const BodyDesc& d, BodyModel& b, std::vector<double>& switchTimes) {
    b.motion = Motion::Kinematic;
    b.path = std::make_shared<const KeyPath>(d.keys, d.interpolation);
    for (const BodyKey& k : d.keys) switchTimes.push_back(k.time);
}

}  // namespace tumble
