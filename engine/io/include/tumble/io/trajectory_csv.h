// The trajectory CSV of INTERFACES.md: one row per body per recorded frame,
// time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz with 17 significant digits.
#pragma once

#include <tumble/model.h>

#include <filesystem>
#include <ostream>
#include <string>

namespace tumble::io {

inline constexpr const char* kTrajectoryCsvHeader = "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

/// The joints' reactions (ExportOptions::jointForces): one row per joint per frame, in the
/// scene's order. fx..fz: the force on body A at its anchor, N, world; tx..tz: the couple on
/// A, N m, world (hinge, slider, fixed; 0 for the others); B takes the opposite of both.
/// broken: 1 from the frame the joint broke at on (its force then 0).
inline constexpr const char* kJointCsvHeader = "time,joint,fx,fy,fz,tx,ty,tz,broken";

/// Where the joints' CSV of a trajectory CSV goes: beside it, "-joints" added to its name
/// (run.csv -> run-joints.csv).
std::filesystem::path jointCsvPath(const std::filesystem::path& trajectory);

/// Writes the rows of one frame: every body in scene order, static ones included.
/// `time` is the frame time k / frame_rate.
void writeCsvFrame(std::ostream& out, const Model& model, const State& state, double time);

/// A body name as a CSV field: quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text);

}  // namespace tumble::io
