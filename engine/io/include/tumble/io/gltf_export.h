// glTF 2.0 export (.gltf with its .bin beside it, or one .glb), written directly (JSON by
// nlohmann-json, one binary buffer; linear in bodies x frames): one node per exported body
// carrying its render mesh (tessellate.h), placed at the body's pose in the first exported
// frame, and one animation "simulation" with a
// translation and a rotation channel (LINEAR, times in seconds) per moving body, sampled at
// every exported frame. Static bodies, and kinematic ones at zero velocity, get no channel.
// Units metres, +Y up, right-handed: glTF's convention is Tumble's, nothing is converted.
#pragma once

#include <tumble/io/trajectory_writer.h>

#include <array>
#include <vector>

namespace tumble::io {

class GltfTrajectoryWriter : public TrajectoryWriter {
public:
    /// `binary`: one .glb; else `file` (.gltf) and its buffer, `file` with the extension
    /// .bin, which the .gltf names by its file name alone.
    GltfTrajectoryWriter(std::filesystem::path file, bool binary, ExportOptions options = {});
    ~GltfTrajectoryWriter() override;

    /// Segments around the axis of round shapes (default 32); before begin().
    void setSegments(int segments) { segments_ = segments; }

protected:
    void open() override;
    void writeFrame(int k, const State& state) override;
    void close() override;

private:
    struct Outputs;
    bool binary_;
    int segments_ = 32;
    std::unique_ptr<Outputs> outputs_;
    std::vector<double> times_;
    // Per exported body: per frame the body frame's position and orientation (w, x, y, z).
    std::vector<std::vector<std::array<double, 7>>> poses_;
};

}  // namespace tumble::io
