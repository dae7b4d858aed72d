// World::deepestOverlap: how deep two bodies overlap as they stand, the measure a recorded
// frame shows (issue 45). The contacts of the last step were found at the end of its free
// step, before the contact solver placed the bodies again from the step's start, so their
// depths are not the frame's: a box resting on the ground overlaps it there by g h² / 2
// (5.45 mm at 1/30 s) and not at all in the frame.
#include <tumble/world.h>

#include "collision/detect.h"
#include "collision/narrowphase.h"

#include <algorithm>

namespace tumble {

double World::deepestOverlap() const {
    double deepest = 0.0;
    collision::ManifoldList found;
    const collision::ManifoldList& last = contacts();
    for (size_t k = 0; k < last.size(); ++k) {
        const int a = last[k].bodyA, b = last[k].bodyB;
        if (k > 0 && last[k - 1].bodyA == a && last[k - 1].bodyB == b) continue;  // (a pair's next manifold)
        const BodyModel &A = model_.bodies[a], &B = model_.bodies[b];
        found.clear();
        collision::collide(A.collider, bodyPose(A, state_.bodies[a]), B.collider,
                           bodyPose(B, state_.bodies[b]), 0.0, found);
        for (const collision::Manifold& m : found) deepest = std::max(deepest, m.maxDepth());
    }
    return deepest;
}

}  // namespace tumble
