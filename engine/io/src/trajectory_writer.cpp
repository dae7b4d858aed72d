#include <tumble/io/atomic_file.h>
#include <tumble/io/gltf_export.h>
#include <tumble/io/trajectory_csv.h>
#include <tumble/io/trajectory_json.h>
#include <tumble/io/trajectory_writer.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tumble::io {

namespace fs = std::filesystem;

bool trajectoryFormatFor(const fs::path& file, TrajectoryFormat& format) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".csv")
        format = TrajectoryFormat::Csv;
    else if (ext == ".json")
        format = TrajectoryFormat::Json;
    else if (ext == ".gltf")
        format = TrajectoryFormat::Gltf;
    else if (ext == ".glb")
        format = TrajectoryFormat::Glb;
    else
        return false;
    return true;
}

std::string trajectoryFormatsText() {
    return "the trajectory formats are .csv, .json, .gltf and .glb";
}

TrajectoryWriter::TrajectoryWriter(fs::path file, ExportOptions options)
    : file_(std::move(file)), options_(std::move(options)) {}

void TrajectoryWriter::begin(const Model& model, const SceneDesc& scene, int frames, double frameRate) {
    if (scene.bodies.size() != model.bodies.size()) {
        throw std::invalid_argument("export: the scene and the model differ in their bodies");
    }
    if (options_.frameStep < 1) throw std::invalid_argument("export: the frame step must be at least 1");
    first_ = options_.firstFrame;
    last_ = options_.lastFrame < 0 ? frames - 1 : options_.lastFrame;
    if (first_ < 0 || first_ > last_ || last_ >= frames) {
        throw std::invalid_argument("export: frames " + std::to_string(first_) + " to " +
                                    std::to_string(last_) + " are not within the run's 0 to " +
                                    std::to_string(frames - 1));
    }
    bodies_ = options_.bodies;
    if (bodies_.empty()) {
        for (size_t i = 0; i < model.bodies.size(); ++i) bodies_.push_back(static_cast<int>(i));
    }
    for (int b : bodies_) {
        if (b < 0 || b >= static_cast<int>(model.bodies.size())) {
            throw std::invalid_argument("export: there is no body " + std::to_string(b));
        }
    }
    model_ = &model;
    scene_ = &scene;
    frameRate_ = frameRate;
    written_ = 0;
    lastWritten_ = -1;
    open();
}

bool TrajectoryWriter::selected(int k) const {
    return model_ && k >= first_ && k <= last_ && (k - first_) % options_.frameStep == 0;
}

int TrajectoryWriter::selectedFrameCount() const {
    return model_ ? (last_ - first_) / options_.frameStep + 1 : 0;
}

void TrajectoryWriter::frame(int k, const State& state) {
    if (!model_) throw std::logic_error("TrajectoryWriter::frame before begin");
    if (state.bodies.size() != model_->bodies.size()) {
        throw std::invalid_argument("export: the state does not fit the model");
    }
    if (!selected(k)) return;
    if (k <= lastWritten_) throw std::invalid_argument("export: frames must come in order");
    writeFrame(k, state);
    lastWritten_ = k;
    ++written_;
}

void TrajectoryWriter::finish() {
    if (!model_) throw std::logic_error("TrajectoryWriter::finish before begin");
    if (finished_) return;
    if (written_ != selectedFrameCount()) {
        throw std::runtime_error(file_.string() + ": " + std::to_string(written_) + " of " +
                                 std::to_string(selectedFrameCount()) + " frames given; not written");
    }
    close();
    finished_ = true;
}

namespace {

std::string num(double v) {
    if (!std::isfinite(v)) throw std::runtime_error("export: a non-finite number cannot be written");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// Joint k's reaction in `state` (zero before the first step).
struct Reaction {
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
    bool broken = false;
};
Reaction reactionOf(const State& state, int k) {
    Reaction r;
    const auto at = static_cast<size_t>(k);
    if (at < state.jointForces.size()) r.force = state.jointForces[at];
    if (at < state.jointCouples.size()) r.torque = state.jointCouples[at];
    r.broken = state.jointBroken(k);
    return r;
}

class CsvWriter : public TrajectoryWriter {
public:
    CsvWriter(fs::path file, ExportOptions options)
        : TrajectoryWriter(std::move(file), options), joints_(options.jointForces) {}

protected:
    void open() override {
        out_ = std::make_unique<AtomicFile>(file());
        out_->stream() << kTrajectoryCsvHeader << "\n";
        if (joints_) {
            jointsOut_ = std::make_unique<AtomicFile>(jointCsvPath(file()));
            jointsOut_->stream() << kJointCsvHeader << "\n";
        }
    }
    void writeFrame(int k, const State& state) override {
        const std::string time = num(k / frameRate());
        std::ostream& out = out_->stream();
        for (int i : bodies()) {
            const BodyModel& b = model().bodies[i];
            const BodyState& s = state.bodies[i];
            const Derived d = derive(b, s);
            const Vec3 p = bodyFramePosition(b, s);
            out << time << ',' << csvField(b.name);
            for (double v : {p.x(), p.y(), p.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z(), d.v.x(), d.v.y(),
                             d.v.z(), d.omega.x(), d.omega.y(), d.omega.z()}) {
                out << ',' << num(v);
            }
            out << '\n';
        }
        if (!joints_) return;
        std::ostream& rows = jointsOut_->stream();
        for (const JointModel& j : model().joints) {
            const Reaction r = reactionOf(state, j.index);
            rows << time << ',' << csvField(j.name);
            for (double v : {r.force.x(), r.force.y(), r.force.z(), r.torque.x(), r.torque.y(), r.torque.z()})
                rows << ',' << num(v);
            rows << ',' << (r.broken ? 1 : 0) << '\n';
        }
    }
    void close() override {
        // Both written out before either replaces its old file (a full disk leaves both
        // old); then the joints' file first.
        if (jointsOut_) jointsOut_->ready();
        out_->ready();
        if (jointsOut_) jointsOut_->commit();
        out_->commit();
    }

private:
    bool joints_;
    std::unique_ptr<AtomicFile> out_, jointsOut_;
};

// Streamed: the frames are written as they come, never held.
class JsonWriter : public TrajectoryWriter {
public:
    JsonWriter(fs::path file, ExportOptions options)
        : TrajectoryWriter(std::move(file), options), joints_(options.jointForces) {}

protected:
    void open() override {
        out_ = std::make_unique<AtomicFile>(file());
        std::ostream& out = out_->stream();
        out << "{\n  \"format\": \"" << kTrajectoryJsonFormat
            << "\",\n  \"version\": " << kTrajectoryJsonVersion << ",\n  \"frame_rate\": " << num(frameRate())
            << ",\n  \"frame_count\": " << selectedFrameCount() << ",\n  \"bodies\": [";
        for (size_t n = 0; n < bodies().size(); ++n) {
            const BodyModel& b = model().bodies[bodies()[n]];
            const std::string name =
                nlohmann::json(b.name).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
            out << (n ? ",\n" : "\n") << "    {\"name\": " << name << ", \"motion\": \""
                << (b.path ? toString(Motion::Animated) : toString(b.motion)) << "\"}";
        }
        out << (bodies().empty() ? "],\n" : "\n  ],\n");
        if (joints_) {
            out << "  \"joints\": [";
            const auto& joints = model().joints;
            for (size_t n = 0; n < joints.size(); ++n) {
                const JointModel& j = joints[n];
                auto name = [&](const std::string& text) {
                    return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
                };
                out << (n ? ",\n" : "\n") << "    {\"name\": " << name(j.name) << ", \"type\": \""
                    << toString(j.type) << "\", \"body_a\": " << name(model().bodies[j.a].name)
                    << ", \"body_b\": " << (j.b < 0 ? std::string("null") : name(model().bodies[j.b].name)) << "}";
            }
            out << (joints.empty() ? "],\n" : "\n  ],\n");
        }
        out << "  \"frames\": [";
    }
    void writeFrame(int k, const State& state) override {
        std::ostream& out = out_->stream();
        out << (framesOut_++ ? ",\n" : "\n") << "    {\"frame\": " << k
            << ", \"time\": " << num(k / frameRate()) << ", \"bodies\": [";
        for (size_t n = 0; n < bodies().size(); ++n) {
            const int i = bodies()[n];
            const BodyModel& b = model().bodies[i];
            const BodyState& s = state.bodies[i];
            const Derived d = derive(b, s);
            const Vec3 p = bodyFramePosition(b, s);
            auto list = [&](std::initializer_list<double> values) {
                const char* sep = "[";
                for (double v : values) {
                    out << sep << num(v);
                    sep = ", ";
                }
                out << ']';
            };
            out << (n ? ",\n" : "\n") << "      {\"position\": ";
            list({p.x(), p.y(), p.z()});
            out << ", \"orientation\": ";
            list({s.q.w(), s.q.x(), s.q.y(), s.q.z()});
            out << ", \"velocity\": ";
            list({d.v.x(), d.v.y(), d.v.z()});
            out << ", \"angular_velocity\": ";
            list({d.omega.x(), d.omega.y(), d.omega.z()});
            out << "}";
        }
        out << (bodies().empty() ? "]" : "\n    ]");
        if (joints_) {
            out << ", \"joints\": [";
            for (size_t n = 0; n < model().joints.size(); ++n) {
                const Reaction r = reactionOf(state, model().joints[n].index);
                out << (n ? ",\n" : "\n") << "      {\"force\": [" << num(r.force.x()) << ", " << num(r.force.y())
                    << ", " << num(r.force.z()) << "], \"torque\": [" << num(r.torque.x()) << ", "
                    << num(r.torque.y()) << ", " << num(r.torque.z()) << "], \"broken\": "
                    << (r.broken ? "true" : "false") << "}";
            }
            out << (model().joints.empty() ? "]" : "\n    ]");
        }
        out << "}";
    }
    void close() override {
        out_->stream() << (framesOut_ ? "\n  ]\n}\n" : "]\n}\n");
        out_->commit();
    }

private:
    bool joints_;
    std::unique_ptr<AtomicFile> out_;
    int framesOut_ = 0;
};

}  // namespace

std::unique_ptr<TrajectoryWriter> makeTrajectoryWriter(TrajectoryFormat format, const fs::path& file,
                                                       const ExportOptions& options) {
    const bool gltf = format == TrajectoryFormat::Gltf || format == TrajectoryFormat::Glb;
    if (gltf && options.jointForces)
        throw std::invalid_argument("joint forces are written with a .csv or .json trajectory, not glTF");
    switch (format) {
        case TrajectoryFormat::Csv: return std::make_unique<CsvWriter>(file, options);
        case TrajectoryFormat::Json: return std::make_unique<JsonWriter>(file, options);
        case TrajectoryFormat::Gltf: return std::make_unique<GltfTrajectoryWriter>(file, false, options);
        case TrajectoryFormat::Glb: return std::make_unique<GltfTrajectoryWriter>(file, true, options);
    }
    throw std::invalid_argument("unknown trajectory format");
}

std::unique_ptr<TrajectoryWriter> makeTrajectoryWriter(const fs::path& file, const ExportOptions& options) {
    TrajectoryFormat format;
    if (!trajectoryFormatFor(file, format))
        throw std::invalid_argument(file.string() + ": " + trajectoryFormatsText());
    return makeTrajectoryWriter(format, file, options);
}

}  // namespace tumble::io
