#include "run_metrics.h"

#include <tumble/collision.h>

#include <nlohmann/json.hpp>

#include <algorithm>

namespace tumble::cli {

namespace {

constexpr double kRestSpeed = 0.01;  // m/s: a body slower than this at every point is at rest

}  // namespace

RunMetrics::RunMetrics(const World& world) {
    const Model& m = world.model();
    const double g = m.settings.gravity.norm();
    if (g > 0.0) up_ = -m.settings.gravity / g;
    for (int i : m.dynamicBodies) {
        Body b;
        b.index = i;
        b.highest = up_.dot(bodyFramePosition(m.bodies[i], world.state().bodies[i]));
        bodies_.push_back(b);
    }
}

void RunMetrics::frame(const World& world) {
    const Model& m = world.model();
    const State& s = world.state();
    trajectory_ = (trajectory_ ^ hashState(s)) * 0x100000001b3ull;
    for (Body& b : bodies_) {
        const BodyModel& model = m.bodies[b.index];
        const BodyState& state = s.bodies[b.index];
        b.highest = std::max(b.highest, up_.dot(bodyFramePosition(model, state)));
        const Derived d = derive(model, state);
        const double fastest = d.v.norm() + d.omega.norm() * boundingRadius(model.collider);
        if (fastest >= kRestSpeed)
            b.restingSince.reset();
        else if (!b.restingSince)
            b.restingSince = s.time;
    }
    deepest_ = std::max(deepest_, world.deepestOverlap());
}

std::string RunMetrics::json(const World& world, long steps, double wall, double energyStart) const {
    using ojson = nlohmann::ordered_json;
    const Model& m = world.model();
    const State& s = world.state();
    const EnergyLedger& l = world.ledger();
    const double energyEnd = energy(m, s).total();
    ojson j;
    j["run"] = {{"state_hash", hashHex(hashState(s))},
                {"trajectory_hash", hashHex(trajectory_)},
                {"steps", steps},
                {"simulated_time", s.time},
                {"wall_seconds", wall}};
    // The ledger's names mean here what they mean on stdout (issue 47 item 7: contacts
    // were normal impulses and friction here, normal impulses alone there), and its parts
    // add up: start - end = contacts + friction + joints + damping - position correction
    // - work by kinematic bodies.
    j["scene"] = {{"energy_lost_contacts", l.lostInContacts},
                  {"energy_lost_friction", l.lostInFriction},
                  {"energy_position_correction", l.positionCorrection},
                  {"energy_lost_joints", l.lostInJoints},
                  {"energy_by_kinematic", l.doneByKinematic},
                  {"energy_lost_damping", energyStart - energyEnd - l.lostInContacts - l.lostInFriction -
                                              l.lostInJoints + l.positionCorrection + l.doneByKinematic},
                  {"deepest_overlap", deepest_}};
    ojson& bodies = j["bodies"];
    bodies = ojson::object();
    for (const Body& b : bodies_) {
        const BodyModel& model = m.bodies[b.index];
        const BodyState& state = s.bodies[b.index];
        const Derived d = derive(model, state);
        ojson& o = bodies[model.name];
        const Vec3 x = bodyFramePosition(model, state);
        o["final_x"] = x.x();
        o["final_y"] = x.y();
        o["final_z"] = x.z();
        o["final_speed"] = d.v.norm();
        o["highest"] = b.highest;
        o["rest_time"] = b.restingSince ? ojson(*b.restingSince) : ojson(nullptr);
    }
    return j.dump(2) + "\n";
}

}  // namespace tumble::cli
