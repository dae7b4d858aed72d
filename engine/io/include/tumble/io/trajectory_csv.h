// The trajectory CSV of INTERFACES.md: one row per body per recorded frame,
// time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz with 17 significant digits.
#pragma once

#include <tumble/model.h>

#include <ostream>
#include <string>

namespace tumble::io {

inline constexpr const char* kTrajectoryCsvHeader = "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

/// Writes the rows of one frame: every body in scene order, static ones included.
/// `time` is the frame time k / frame_rate.
void writeCsvFrame(std::ostream& out, const Model& model, const State& state, double time);

/// A body name as a CSV field: quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text);

}  // namespace tumble::io
