// Trajectory export, one interface for every format: the command line's --out and the
// editor's File > Export both drive a TrajectoryWriter frame by frame. Every format writes
// through AtomicFile, so a writer destroyed without finish() (a cancelled export, a run
// that failed) leaves no file behind, and an existing file keeps its old contents.
#pragma once

#include <tumble/model.h>
#include <tumble/scene.h>
#include <tumble/state.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace tumble::io {

/// Which part of a run to export. The defaults take every frame and every body.
struct ExportOptions {
    int firstFrame = 0;       ///< the first frame written
    int lastFrame = -1;       ///< the last frame written, inclusive; negative: the run's last
    int frameStep = 1;        ///< every n-th frame from firstFrame (a lower frame rate); >= 1
    std::vector<int> bodies;  ///< body indices in scene order, written in that order; empty: all
    /// Each joint's reaction as well (CSV and JSON; the glTF export has none): the force it
    /// put on body A at A's anchor and the couple on A over the last step before each frame
    /// (State::jointForces, jointTorques), and whether it has broken. A CSV gets them in a
    /// second file beside it (jointCsvPath), a JSON in each frame's "joints".
    bool jointForces = false;
};

/// The trajectory formats, chosen by the file's extension (case ignored).
enum class TrajectoryFormat { Csv, Json, Gltf, Glb };

/// The format a file name asks for, or false when its extension is none of .csv, .json,
/// .gltf, .glb.
bool trajectoryFormatFor(const std::filesystem::path& file, TrajectoryFormat& format);

/// "the trajectory formats are .csv, .json, .gltf and .glb": for messages.
std::string trajectoryFormatsText();

class TrajectoryWriter {
public:
    virtual ~TrajectoryWriter() = default;
    TrajectoryWriter(const TrajectoryWriter&) = delete;
    TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

    /// Opens the output (throws std::runtime_error when it cannot be written, naming the
    /// file) and writes what comes before the frames. `model` and `scene` are the run's
    /// (the scene gives the render shapes: meshes need shape.meshData); `frames` is the
    /// number of frames of the whole run (frameCount(settings)) and `frameRate` its rate.
    /// Throws std::invalid_argument when the options do not fit the run (a body index out
    /// of range, an empty frame range, frameStep < 1). Both objects must outlive the writer.
    void begin(const Model& model, const SceneDesc& scene, int frames, double frameRate);

    /// Frame k of the run (time k / frameRate). Call it for every frame in order, or for
    /// the selected ones only; those outside the options are skipped here.
    void frame(int k, const State& state);

    /// Writes what remains and makes the file(s) appear; throws std::runtime_error when a
    /// selected frame was not given, or when writing failed (then nothing new is left behind, except that of
    /// a .gltf whose .bin was already in place the .bin stays).
    void finish();

    /// Whether frame k is exported (after begin()).
    bool selected(int k) const;
    /// The frames exported, the bodies exported (after begin()).
    int selectedFrameCount() const;
    const std::vector<int>& bodies() const { return bodies_; }
    const std::filesystem::path& file() const { return file_; }

protected:
    TrajectoryWriter(std::filesystem::path file, ExportOptions options);

    virtual void open() = 0;                                 // AtomicFile(s), header
    virtual void writeFrame(int k, const State& state) = 0;  // a selected frame
    virtual void close() = 0;                                // trailer, commit

    const Model& model() const { return *model_; }
    const SceneDesc& scene() const { return *scene_; }
    double frameRate() const { return frameRate_; }
    int firstFrame() const { return first_; }
    int lastFrame() const { return last_; }
    int frameStep() const { return options_.frameStep; }

private:
    std::filesystem::path file_;
    ExportOptions options_;
    const Model* model_ = nullptr;
    const SceneDesc* scene_ = nullptr;
    double frameRate_ = 0.0;
    int first_ = 0, last_ = -1;
    std::vector<int> bodies_;
    int written_ = 0, lastWritten_ = -1;
    bool finished_ = false;
};

/// A writer for `file` in the format its extension names; throws std::invalid_argument
/// (with trajectoryFormatsText()) for any other extension.
std::unique_ptr<TrajectoryWriter> makeTrajectoryWriter(const std::filesystem::path& file,
                                                       const ExportOptions& options = {});

/// The same, for a format given apart from the file name.
std::unique_ptr<TrajectoryWriter> makeTrajectoryWriter(TrajectoryFormat format,
                                                       const std::filesystem::path& file,
                                                       const ExportOptions& options = {});

}  // namespace tumble::io
