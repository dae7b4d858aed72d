#include "document/body_keys.h"

#include <tumble/key_path.h>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

namespace {

constexpr double kSameTime = 1e-9;  // s: a key this near t is the key at t

bool samePose(const BodyDesc& a, const BodyDesc& b) {
    return a.position == b.position && a.orientation.coeffs() == b.orientation.coeffs();
}

}  // namespace

void insertKey(BodyDesc& b, double t, const Vec3& position, const Quat& orientation) {
    if (b.motion != Motion::Animated) {
        b.motion = Motion::Animated;
        b.mass.reset();
        b.density.reset();
        b.inertia.reset();
        b.centerOfMass.reset();
        b.forces.clear();
        b.velocity = b.angularVelocity = Vec3::Zero();
        b.keys.clear();
    }
    const BodyKey key{t, position, orientation.normalized()};
    auto at = std::find_if(b.keys.begin(), b.keys.end(),
                           [t](const BodyKey& k) { return std::abs(k.time - t) <= kSameTime; });
    if (at != b.keys.end()) {
        *at = key;
    } else {
        b.keys.insert(std::upper_bound(b.keys.begin(), b.keys.end(), t,
                                       [](double time, const BodyKey& k) { return time < k.time; }),
                      key);
    }
}

bool moveKey(BodyDesc& b, int k, double t) {
    if (k < 0 || k >= static_cast<int>(b.keys.size())) return false;
    for (size_t j = 0; j < b.keys.size(); ++j)
        if (static_cast<int>(j) != k && std::abs(b.keys[j].time - t) <= kSameTime) return false;
    BodyKey key = b.keys[static_cast<size_t>(k)];
    key.time = t;
    b.keys.erase(b.keys.begin() + k);
    b.keys.insert(std::upper_bound(b.keys.begin(), b.keys.end(), t,
                                   [](double time, const BodyKey& e) { return time < e.time; }),
                  key);
    return true;
}

bool removeKey(BodyDesc& b, int k) {
    if (b.keys.size() <= 1 || k < 0 || k >= static_cast<int>(b.keys.size())) return false;
    b.keys.erase(b.keys.begin() + k);
    return true;
}

bool keysMakeAPath(const BodyDesc& b) {
    for (size_t k = 0; k < b.keys.size(); ++k) {
        const BodyKey& key = b.keys[k];
        if (!std::isfinite(key.time) || !key.position.allFinite() || !key.orientation.coeffs().allFinite() ||
            !(key.orientation.coeffs().norm() > 1e-12) || (k > 0 && !(key.time > b.keys[k - 1].time)))
            return false;
    }
    return !b.keys.empty();
}

void followKeys(const BodyDesc& before, BodyDesc& after) {
    if (after.motion != Motion::Animated || after.keys.empty()) return;
    const bool moved =
        before.motion == Motion::Animated && before.keys == after.keys && !samePose(before, after);
    if (moved) insertKey(after, 0.0, after.position, after.orientation);
    // Keys that cannot make a path are left for the document's check to refuse; the pose
    // stays as given.
    if (!keysMakeAPath(after)) return;
    const PathPoint p = KeyPath(after.keys, after.interpolation).at(0.0);
    after.position = p.position;
    after.orientation = p.orientation;
}

}  // namespace tumble::ui
