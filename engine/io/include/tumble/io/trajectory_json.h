// The trajectory JSON of docs/export.md: format and version, frame rate, the bodies (name,
// motion) and per frame its time and, per body, the pose of the body frame, the velocity
// of the centre of mass and the angular velocity, numbers that read back exactly; with the
// joints' reactions asked for, the joints (name, type, bodies) and per frame their force,
// couple and whether they have broken.
#pragma once

#include <tumble/math.h>
#include <tumble/scene.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::io {

inline constexpr const char* kTrajectoryJsonFormat = "tumble-trajectory";
inline constexpr int kTrajectoryJsonVersion = 1;

struct TrajectoryBody {
    std::string name;
    Motion motion = Motion::Dynamic;
};

struct TrajectoryPose {
    Vec3 position = Vec3::Zero();         ///< body frame origin, world
    Quat orientation = Quat::Identity();  ///< w, x, y, z; body to world
    Vec3 velocity = Vec3::Zero();         ///< centre of mass, world
    Vec3 angularVelocity = Vec3::Zero();  ///< world
};

/// A joint, when the trajectory carries the joints' reactions (ExportOptions::jointForces).
struct TrajectoryJoint {
    std::string name, type, bodyA;
    std::string bodyB;  ///< empty: the world
};

/// A joint's reaction at a frame: the force on body A at its anchor (N, world) and the
/// couple on A (N m, world) over the last step before the frame; B takes the opposite.
struct TrajectoryReaction {
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
    bool broken = false;
};

struct TrajectoryFrame {
    int frame = 0;                       ///< k of the run
    double time = 0.0;                   ///< k / frame_rate
    std::vector<TrajectoryPose> bodies;  ///< in the order of Trajectory::bodies
    std::vector<TrajectoryReaction> joints;  ///< in the order of Trajectory::joints (or none)
};

struct Trajectory {
    double frameRate = 0.0;
    std::vector<TrajectoryBody> bodies;
    std::vector<TrajectoryJoint> joints;  ///< empty unless the file has "joints"
    std::vector<TrajectoryFrame> frames;
};

/// Parses trajectory JSON; throws InputError (tumble/io/scene_file.h) naming `fileName`
/// and the field for anything malformed.
Trajectory parseTrajectoryJson(std::string_view text, const std::string& fileName);

/// Reads a trajectory JSON file; messages name the file as given.
Trajectory readTrajectoryJson(const std::filesystem::path& path);

}  // namespace tumble::io
