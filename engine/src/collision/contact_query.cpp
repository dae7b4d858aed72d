#include <tumble/contact_query.h>

#include "collision/detect.h"

#include <algorithm>
#include <cmath>

namespace tumble {

namespace {

constexpr double kTouchTolerance = 1e-5;  // of the largest body's size: contacts this far apart count

}  // namespace

double touchTolerance(const Model& model) {
    double largest = 0.0;
    for (const BodyModel& b : model.bodies) {
        const double r = collision::boundingRadius(b.collider);
        if (std::isfinite(r)) largest = std::max(largest, r);
    }
    return kTouchTolerance * largest;
}

collision::ManifoldList contactsOf(const Model& model, const State& state) {
    if (!needsContacts(model) || state.bodies.size() != model.bodies.size()) return {};
    const double tolerance = touchTolerance(model);
    // Every body awake: a sleeping body does not pair with a static one in the broadphase,
    // but it rests on it all the same.
    State awake;
    awake.time = state.time;
    awake.bodies = state.bodies;
    awake.jointBrokenAt = state.jointBrokenAt;
    DetectScratch s;
    refreshJointPairs(model, awake, s);  // joined bodies do not touch
    bodyPoses(model, awake, s.end);
    s.start = s.end;
    findPairs(model, awake, tolerance, s);
    findContacts(model, s, tolerance);
    return std::move(s.contacts);
}

}  // namespace tumble
