// What `tumble --headless SCENE --metrics FILE` writes: the measures of one run that a sweep
// puts in its summary (docs/sweeps.md), taken at every recorded frame.
//
// Per dynamic body: where its frame ends (final_x, final_y, final_z: the position the
// trajectory CSV gives), how fast its centre of mass moves then (final_speed), its highest
// point (its frame's height along -gravity; y without gravity) and when it came to rest (rest_time: the first
// frame from which its centre and its fastest surface point stay below 1 cm/s to the end; empty if it is
// still moving). For the scene, the energy ledger with stdout's names and meanings: what the normal impulses
// took (energy_lost_contacts), friction (energy_lost_friction), the joints (energy_lost_joints), what placing
// bodies in contact gave (energy_position_correction), and damping (energy_lost_damping: what the start less
// the end leaves once those are booked; damping's, as long as no applied force or spring does work); and the
// deepest overlap of two bodies seen at a frame.
#pragma once

#include <tumble/world.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tumble::cli {

class RunMetrics {
public:
    explicit RunMetrics(const World& world);
    /// After each recorded frame.
    void frame(const World& world);
    /// The measures as JSON text (what --metrics FILE holds): the run's figures (`run`:
    /// state_hash, trajectory_hash, steps, simulated_time, wall_seconds), `scene` and
    /// `bodies` (by name).
    std::string json(const World& world, long steps, double wall, double energyStart) const;

private:
    struct Body {
        int index = 0;
        double highest = 0.0;
        std::optional<double> restingSince;
    };
    std::vector<Body> bodies_;
    Vec3 up_ = Vec3::UnitY();
    // Every recorded frame's state hash folded in: two runs that end alike but moved
    // differently (a ball at rest after other bounces) differ here.
    std::uint64_t trajectory_ = 0xcbf29ce484222325ull;
    double deepest_ = 0.0;
};

}  // namespace tumble::cli
