#include <tumble/io/trajectory_csv.h>

#include <cstdio>

namespace tumble::io {

std::filesystem::path jointCsvPath(const std::filesystem::path& trajectory) {
    std::filesystem::path p = trajectory;
    p.replace_filename(trajectory.stem().string() + "-joints" + trajectory.extension().string());
    return p;
}

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

void writeCsvFrame(std::ostream& out, const Model& model, const State& state, double time) {
    char buf[512];
    for (size_t i = 0; i < model.bodies.size(); ++i) {
        const BodyModel& b = model.bodies[i];
        const BodyState& s = state.bodies[i];
        const Derived d = derive(b, s);
        const Vec3 p = bodyFramePosition(b, s);
        std::snprintf(buf, sizeof buf, "%.17g,", time);
        out << buf << csvField(b.name);
        std::snprintf(buf, sizeof buf,
                      ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                      p.x(), p.y(), p.z(), s.q.w(), s.q.x(), s.q.y(), s.q.z(), d.v.x(), d.v.y(), d.v.z(),
                      d.omega.x(), d.omega.y(), d.omega.z());
        out << buf;
    }
}

}  // namespace tumble::io
