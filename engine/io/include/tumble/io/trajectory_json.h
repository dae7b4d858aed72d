// The trajectory JSON of docs/export.md: format and version, frame rate, the bodies (name,
// motion) and per frame its time and, per body, the pose of the body frame, the velocity
// of the centre of mass and the angular velocity, numbers that read back exactly.
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

struct TrajectoryFrame {
    int frame = 0;                       ///< k of the run
    double time = 0.0;                   ///< k / frame_rate
    std::vector<TrajectoryPose> bodies;  ///< in the order of Trajectory::bodies
};

struct Trajectory {
    double frameRate = 0.0;
    std::vector<TrajectoryBody> bodies;
    std::vector<TrajectoryFrame> frames;
};

/// Parses trajectory JSON; throws InputError (tumble/io/scene_file.h) naming `fileName`
/// and the field for anything malformed.
Trajectory parseTrajectoryJson(std::string_view text, const std::string& fileName);

/// Reads a trajectory JSON file; messages name the file as given.
Trajectory readTrajectoryJson(const std::filesystem::path& path);

}  // namespace tumble::io
