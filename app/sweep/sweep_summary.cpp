#include "sweep_summary.h"

#include <tumble/io/atomic_file.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

namespace tumble::sweep {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

const std::vector<std::string> kSceneMeasures = {
    "energy_lost_contacts", "energy_lost_friction", "energy_position_correction",
    "energy_lost_joints",   "energy_by_kinematic",  "energy_lost_damping",
    "deepest_overlap"};
const std::vector<std::string> kBodyMeasures = {"final_x", "final_y", "final_z", "final_speed", "highest", "rest_time"};

ojson readJson(const fs::path& file) {
    std::ifstream in(file);
    if (!in) return nullptr;
    try {
        return ojson::parse(in);
    } catch (const std::exception&) {
        return nullptr;
    }
}

std::string csvText(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
    return q + "\"";
}

std::string csvValue(const ojson& v) {
    if (v.is_null()) return {};
    if (v.is_number_float()) {
        char buf[64];
        const auto r = std::to_chars(buf, buf + sizeof buf, v.get<double>());
        return std::string(buf, r.ptr);
    }
    if (v.is_string()) return csvText(v.get<std::string>());
    return v.dump();
}

// A measure column's value in a result's measures: "scene measure" or "body.measure".
ojson measure(const ojson& metrics, const std::string& column) {
    if (!metrics.is_object()) return nullptr;
    if (metrics.contains("scene") && metrics["scene"].contains(column)) return metrics["scene"][column];
    const auto dot = column.rfind('.');
    if (dot == std::string::npos || !metrics.contains("bodies")) return nullptr;
    const std::string body = column.substr(0, dot), kind = column.substr(dot + 1);
    const ojson& bodies = metrics["bodies"];
    if (!bodies.contains(body) || !bodies[body].contains(kind)) return nullptr;
    return bodies[body][kind];
}

}  // namespace

fs::path metricsFile(const Plan& plan, const fs::path& dir, int k) {
    return dir / "results" / (plan.name(k) + ".metrics.json");
}
fs::path logFile(const Plan& plan, const fs::path& dir, int k) { return dir / "results" / (plan.name(k) + ".log"); }
fs::path trajectoryFile(const Plan& plan, const fs::path& dir, int k) {
    return dir / "trajectories" / (plan.name(k) + ".csv");
}
fs::path resultFile(const Plan& plan, const fs::path& dir, int k) { return dir / "results" / (plan.name(k) + ".json"); }

Job variantJob(const Plan& plan, const fs::path& dir, int k, bool trajectories, const std::string& exe) {
    Job job;
    job.variant = k;
    job.argv = {exe, "--headless", variantFile(plan, dir, k).string(), "--quiet", "--metrics",
                metricsFile(plan, dir, k).string()};
    if (trajectories) {
        job.argv.push_back("--out");
        job.argv.push_back(trajectoryFile(plan, dir, k).string());
    }
    job.log = logFile(plan, dir, k);
    return job;
}

void recordOutcome(const Plan& plan, const fs::path& dir, const Outcome& o) {
    ojson r;
    const ojson metrics = o.exitCode == 0 ? readJson(metricsFile(plan, dir, o.variant)) : ojson(nullptr);
    if (o.exitCode == 0 && metrics.is_object()) {
        r["status"] = "ok";
    } else {
        r["status"] = o.exitCode == 2 ? "invalid" : "failed";
        std::string message = o.message.empty() ? lastLine(logFile(plan, dir, o.variant)) : o.message;
        if (o.signal != 0) message = "killed by signal " + std::to_string(o.signal);
        else if (o.exitCode == 0) message = "its measures were not written";
        else if (message.empty())
            message = "exit status " + std::to_string(o.exitCode) + ", it printed nothing";
        r["message"] = message;
    }
    r["exit"] = o.exitCode;
    r["wall_s"] = o.wall;
    r["metrics"] = metrics;
    io::writeFileAtomically(resultFile(plan, dir, o.variant), r.dump(2) + "\n");
}

std::vector<std::string> metricColumns(const Plan& plan, const std::vector<std::string>& metrics) {
    const std::vector<std::string>& bodies = plan.bodies;
    std::vector<std::string> columns;
    auto add = [&](const std::string& c) {
        if (std::find(columns.begin(), columns.end(), c) == columns.end()) columns.push_back(c);
    };
    auto addKind = [&](const std::string& body, const std::string& kind) {
        if (kind == "final_position") {
            for (const char* axis : {"final_x", "final_y", "final_z"}) add(body + "." + axis);
            return true;
        }
        if (std::find(kBodyMeasures.begin(), kBodyMeasures.end(), kind) == kBodyMeasures.end()) return false;
        add(body + "." + kind);
        return true;
    };
    if (metrics.empty()) {
        for (const std::string& m : kSceneMeasures) add(m);
        for (const std::string& b : bodies)
            for (const std::string& k : kBodyMeasures) addKind(b, k);
        return columns;
    }
    for (const std::string& m : metrics) {
        if (std::find(kSceneMeasures.begin(), kSceneMeasures.end(), m) != kSceneMeasures.end()) {
            add(m);
            continue;
        }
        const auto dot = m.rfind('.');
        bool known = false;
        if (dot == std::string::npos) {
            known = !bodies.empty();
            for (const std::string& b : bodies) known = addKind(b, m) && known;
        } else {
            const std::string body = m.substr(0, dot);
            known = std::find(bodies.begin(), bodies.end(), body) != bodies.end() && addKind(body, m.substr(dot + 1));
        }
        if (!known) {
            std::string all;
            for (const std::string& s : kSceneMeasures) all += s + ", ";
            for (const std::string& s : kBodyMeasures) all += s + ", ";
            throw SweepError{"--metric " + m + ": not a measure (" + all +
                             "final_position; a body's alone as BODY.MEASURE, BODY a dynamic body)"};
        }
    }
    return columns;
}

namespace {

// One sweep's summary: the header's names and a row of CSV-ready cells per variant.
struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

Table summaryTable(const Plan& plan, const fs::path& dir, const std::vector<std::string>& columns,
                   Tally& tally) {
    Table t;
    t.header = {"variant"};
    for (const Vary& v : plan.vary) t.header.push_back(v.path);
    for (const char* c : {"status", "state_hash", "trajectory_hash", "wall_s"}) t.header.push_back(c);
    t.header.insert(t.header.end(), columns.begin(), columns.end());
    t.header.push_back("message");
    for (int k = 0; k < plan.count; ++k) {
        const ojson r = readJson(resultFile(plan, dir, k));
        std::vector<std::string> row = {plan.name(k)};
        const std::vector<int> c = plan.choice(k);
        for (std::size_t i = 0; i < plan.vary.size(); ++i) row.push_back(csvText(plan.vary[i].values[c[i]]));
        const std::string status = r.is_object() ? r.value("status", std::string("failed")) : "not run";
        (status == "ok" ? tally.ok : status == "not run" ? tally.notRun : tally.failed) += 1;
        if (status != "ok" && status != "not run" && tally.firstFailure.empty())
            tally.firstFailure = plan.name(k) + ": " + r.value("message", std::string("failed"));
        const ojson metrics = r.is_object() && r.contains("metrics") ? r["metrics"] : ojson(nullptr);
        const ojson run = metrics.is_object() && metrics.contains("run") ? metrics["run"] : ojson(nullptr);
        row.push_back(status);
        row.push_back(run.is_object() ? csvValue(run["state_hash"]) : "");
        row.push_back(run.is_object() && run.contains("trajectory_hash") ? csvValue(run["trajectory_hash"])
                                                                         : "");
        row.push_back(r.is_object() ? csvValue(r["wall_s"]) : "");
        for (const std::string& col : columns) row.push_back(csvValue(measure(metrics, col)));
        row.push_back(r.is_object() && r.contains("message") ? csvValue(r["message"]) : "");
        t.rows.push_back(std::move(row));
    }
    return t;
}

std::string csvOf(const Table& t) {
    std::ostringstream csv;
    for (std::size_t i = 0; i < t.header.size(); ++i) csv << (i ? "," : "") << csvText(t.header[i]);
    csv << '\n';
    for (const auto& row : t.rows) {
        for (std::size_t i = 0; i < row.size(); ++i) csv << (i ? "," : "") << row[i];
        csv << '\n';
    }
    return csv.str();
}

void writeAtomically(const fs::path& file, const std::string& text) {
    try {
        io::writeFileAtomically(file, text);
    } catch (const std::runtime_error& e) {
        throw SweepError{e.what()};
    }
}

}  // namespace

Tally writeSummary(const Plan& plan, const fs::path& dir, const std::vector<std::string>& columns) {
    Tally tally;
    writeAtomically(dir / "summary.csv", csvOf(summaryTable(plan, dir, columns, tally)));
    return tally;
}

Tally mergeSummaries(const std::vector<fs::path>& dirs, const std::vector<std::string>& metrics,
                     const fs::path& file) {
    struct Part {
        fs::path dir;
        Plan plan;
        Table table;
    };
    std::vector<Part> parts;
    Tally total;
    for (const fs::path& dir : dirs) {
        Part p{dir, readPlan(dir), {}};
        Tally t;
        p.table = summaryTable(p.plan, dir, metricColumns(p.plan, metrics), t);
        writeAtomically(dir / "summary.csv", csvOf(p.table));
        total.ok += t.ok;
        total.failed += t.failed;
        total.notRun += t.notRun;
        if (total.firstFailure.empty() && !t.firstFailure.empty())
            total.firstFailure = dir.string() + " " + t.firstFailure;
        parts.push_back(std::move(p));
    }
    // The merged header: the varied paths of all, then the measures of all, each once.
    std::vector<std::string> paths, measures;
    auto addOnce = [](std::vector<std::string>& list, const std::string& name) {
        if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
    };
    for (const Part& p : parts) {
        for (const Vary& v : p.plan.vary) addOnce(paths, v.path);
        const std::size_t first = 1 + p.plan.vary.size() + 4;
        for (std::size_t i = first; i + 1 < p.table.header.size(); ++i) addOnce(measures, p.table.header[i]);
    }
    Table merged;
    merged.header = {"sweep", "variant"};
    merged.header.insert(merged.header.end(), paths.begin(), paths.end());
    for (const char* c : {"status", "state_hash", "trajectory_hash", "wall_s"}) merged.header.push_back(c);
    merged.header.insert(merged.header.end(), measures.begin(), measures.end());
    merged.header.push_back("message");
    for (const Part& p : parts) {
        auto column = [&](const std::string& name) -> int {
            const auto it = std::find(p.table.header.begin(), p.table.header.end(), name);
            return it == p.table.header.end() ? -1 : static_cast<int>(it - p.table.header.begin());
        };
        for (int k = 0; k < p.plan.count; ++k) {
            const std::vector<std::string>& row = p.table.rows[k];
            std::vector<std::string> out = {csvText(p.dir.string()), row[0]};
            for (const std::string& path : paths) {
                const int c = column(path);
                out.push_back(c >= 0 ? row[c] : csvText(valueInVariant(p.plan, p.dir, k, path)));
            }
            for (const char* c : {"status", "state_hash", "trajectory_hash", "wall_s"})
                out.push_back(row[column(c)]);
            for (const std::string& m : measures) {
                const int c = column(m);
                out.push_back(c >= 0 ? row[c] : "");
            }
            out.push_back(row.back());
            merged.rows.push_back(std::move(out));
        }
    }
    writeAtomically(file, csvOf(merged));
    return total;
}

}  // namespace tumble::sweep
