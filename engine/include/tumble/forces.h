// Stage: forces. Accumulates the force F and torque τ about the centre of mass of every
// dynamic body at time t: gravity, applied forces (torque (10)), torques, springs to
// world anchors, and linear and angular damping.
#pragma once

#include <tumble/model.h>

#include <vector>

namespace tumble {

struct Wrench {
    Vec3 force = Vec3::Zero();
    Vec3 torque = Vec3::Zero();
};

/// Fills `out` (one entry per body; entries of non-dynamic bodies stay zero) for the
/// body states `bodies`, with the applied forces active at time t.
void accumulateForces(const Model& model, const std::vector<BodyState>& bodies, double t,
                      std::vector<Wrench>& out);

}  // namespace tumble
