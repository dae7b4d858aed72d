#include <tumble/io/scene_file.h>
#include <tumble/io/trajectory_json.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace tumble::io {

namespace {

using nlohmann::json;

struct Reader {
    const std::string& file;

    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        throw InputError(file, field, message);
    }

    const json& member(const json& object, const std::string& path, const char* key) const {
        if (!object.is_object()) fail(path, "must be an object");
        auto it = object.find(key);
        if (it == object.end()) fail(path.empty() ? key : path + "." + key, "missing");
        return *it;
    }

    double number(const json& v, const std::string& path) const {
        if (!v.is_number()) fail(path, "must be a number");
        return v.get<double>();
    }

    template <int N>
    std::array<double, N> numbers(const json& v, const std::string& path) const {
        if (!v.is_array() || v.size() != N)
            fail(path, "must be an array of " + std::to_string(N) + " numbers");
        std::array<double, N> out{};
        for (int i = 0; i < N; ++i) out[i] = number(v[i], path + "[" + std::to_string(i) + "]");
        return out;
    }

    Vec3 vec3(const json& v, const std::string& path) const {
        const auto a = numbers<3>(v, path);
        return Vec3(a[0], a[1], a[2]);
    }
};

}  // namespace

Trajectory parseTrajectoryJson(std::string_view text, const std::string& fileName) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        throw InputError(fileName, "", std::string("not valid JSON: ") + e.what());
    }
    const Reader r{fileName};
    const json& format = r.member(doc, "", "format");
    if (format != kTrajectoryJsonFormat)
        r.fail("format", std::string("must be \"") + kTrajectoryJsonFormat + "\"");
    const json& version = r.member(doc, "", "version");
    if (!version.is_number_integer() || version.get<int>() < 1 ||
        version.get<int>() > kTrajectoryJsonVersion) {
        r.fail("version",
               "must be 1 (this build reads up to version " + std::to_string(kTrajectoryJsonVersion) + ")");
    }
    Trajectory t;
    t.frameRate = r.number(r.member(doc, "", "frame_rate"), "frame_rate");
    if (!(t.frameRate > 0)) r.fail("frame_rate", "must be greater than 0");

    const json& bodies = r.member(doc, "", "bodies");
    if (!bodies.is_array()) r.fail("bodies", "must be an array");
    for (size_t i = 0; i < bodies.size(); ++i) {
        const std::string path = "bodies[" + std::to_string(i) + "]";
        TrajectoryBody b;
        const json& name = r.member(bodies[i], path, "name");
        if (!name.is_string()) r.fail(path + ".name", "must be a string");
        b.name = name.get<std::string>();
        const json& motion = r.member(bodies[i], path, "motion");
        if (motion == "dynamic")
            b.motion = Motion::Dynamic;
        else if (motion == "static")
            b.motion = Motion::Static;
        else if (motion == "kinematic")
            b.motion = Motion::Kinematic;
        else if (motion == "animated")
            b.motion = Motion::Animated;
        else
            r.fail(path + ".motion", "must be dynamic, static, kinematic or animated");
        t.bodies.push_back(std::move(b));
    }

    const bool hasJoints = doc.contains("joints");
    if (hasJoints) {
        const json& joints = doc["joints"];
        if (!joints.is_array()) r.fail("joints", "must be an array");
        for (size_t i = 0; i < joints.size(); ++i) {
            const std::string path = "joints[" + std::to_string(i) + "]";
            auto text = [&](const char* key, bool nullable) -> std::string {
                const json& v = r.member(joints[i], path, key);
                if (nullable && v.is_null()) return {};
                if (!v.is_string()) r.fail(path + "." + key, nullable ? "must be a string or null" : "must be a string");
                return v.get<std::string>();
            };
            t.joints.push_back({text("name", false), text("type", false), text("body_a", false), text("body_b", true)});
        }
    }

    const json& frames = r.member(doc, "", "frames");
    if (!frames.is_array()) r.fail("frames", "must be an array");
    for (size_t k = 0; k < frames.size(); ++k) {
        const std::string path = "frames[" + std::to_string(k) + "]";
        TrajectoryFrame f;
        const json& index = r.member(frames[k], path, "frame");
        if (!index.is_number_integer()) r.fail(path + ".frame", "must be an integer");
        f.frame = index.get<int>();
        f.time = r.number(r.member(frames[k], path, "time"), path + ".time");
        const json& poses = r.member(frames[k], path, "bodies");
        if (!poses.is_array() || poses.size() != t.bodies.size()) {
            r.fail(path + ".bodies",
                   "must be an array with one entry per body (" + std::to_string(t.bodies.size()) + ")");
        }
        for (size_t i = 0; i < poses.size(); ++i) {
            const std::string p = path + ".bodies[" + std::to_string(i) + "]";
            TrajectoryPose pose;
            pose.position = r.vec3(r.member(poses[i], p, "position"), p + ".position");
            const auto q = r.numbers<4>(r.member(poses[i], p, "orientation"), p + ".orientation");
            pose.orientation = Quat(q[0], q[1], q[2], q[3]);
            pose.velocity = r.vec3(r.member(poses[i], p, "velocity"), p + ".velocity");
            pose.angularVelocity = r.vec3(r.member(poses[i], p, "angular_velocity"), p + ".angular_velocity");
            f.bodies.push_back(pose);
        }
        if (hasJoints) {
            const json& reactions = r.member(frames[k], path, "joints");
            if (!reactions.is_array() || reactions.size() != t.joints.size()) {
                r.fail(path + ".joints",
                       "must be an array with one entry per joint (" + std::to_string(t.joints.size()) + ")");
            }
            for (size_t i = 0; i < reactions.size(); ++i) {
                const std::string p = path + ".joints[" + std::to_string(i) + "]";
                TrajectoryReaction reaction;
                reaction.force = r.vec3(r.member(reactions[i], p, "force"), p + ".force");
                reaction.torque = r.vec3(r.member(reactions[i], p, "torque"), p + ".torque");
                const json& broken = r.member(reactions[i], p, "broken");
                if (!broken.is_boolean()) r.fail(p + ".broken", "must be true or false");
                reaction.broken = broken.get<bool>();
                f.joints.push_back(reaction);
            }
        }
        t.frames.push_back(std::move(f));
    }
    return t;
}

Trajectory readTrajectoryJson(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), "", "cannot be read (missing, or no permission)");
    std::ostringstream text;
    text << in.rdbuf();
    return parseTrajectoryJson(text.str(), path.string());
}

}  // namespace tumble::io
