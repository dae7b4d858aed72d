#include "sweep_cli.h"

#include "sweep_plan.h"
#include "sweep_run.h"
#include "sweep_summary.h"

#include <chrono>
#include <cstdio>
#include <ostream>
#include <thread>
#include <unistd.h>

namespace tumble::sweep {

namespace fs = std::filesystem;

namespace {

constexpr int kOk = 0, kFailed = 1, kInvalid = 2, kStopped = 130;

const char* kHelp = R"(Usage:
  tumble sweep SCENE --vary PATH=VALUES [--vary PATH=VALUES ...] --out DIR [options]
  tumble sweep --merge DIR [--metric NAME ...]

Runs every combination of the values given (the full product; the last --vary changes
fastest), each variant its own `tumble --headless` process, and writes:
  DIR/variants/NNNN.json   each variant: a scene file that runs by itself
  DIR/results/NNNN.json    each variant's status, wall time and measures
  DIR/summary.csv          one row per variant: variant, one column per PATH, status,
                           state_hash, wall_s, the measures, message
A variant whose result is there is not run again: a stopped sweep resumes with the same
command. A variant that fails (a value the scene refuses, a run stopped by the energy
guard) is a row with its status and message.

  --vary PATH=VALUES  PATH names a value of the scene: settings.KEY, or a body's or a
                      joint's name then its keys and [index]es: ball.restitution,
                      ball.velocity[1], crate.friction, ball.shape.radius, settings.dt.
                      VALUES is a,b,c or start:stop:count (both ends included)
  --out DIR           the sweep's folder (made if missing)
  --jobs N            variants at once (default: the machine's cores)
  --trajectories      also a trajectory CSV per variant, DIR/trajectories/NNNN.csv
  --metric NAME       the measures the summary keeps (repeat, or a,b; default all):
                      energy_lost_contacts, energy_lost_damping, deepest_overlap, and per
                      dynamic body final_x, final_y, final_z (final_position: the three),
                      final_speed, highest, rest_time; BODY.NAME for one body's
  --merge DIR         write DIR/summary.csv again from the results there

Exit status: 0 every variant ran; 1 one or more failed; 2 bad input (an unknown PATH, an
empty list: nothing is run); 130 stopped (Ctrl-C): run the same command to resume.
)";

struct Options {
    std::string scene, out, merge;
    std::vector<Vary> vary;
    std::vector<std::string> metrics;
    int jobs = 0;
    bool trajectories = false;
};

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::size_t a = 0;
    while (a <= s.size()) {
        const std::size_t b = std::min(s.find(',', a), s.size());
        if (b > a) out.push_back(s.substr(a, b - a));
        a = b + 1;
    }
    return out;
}

Options parse(const std::vector<std::string>& args) {
    Options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string a = args[i], value;
        bool hasValue = false;
        if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
            value = a.substr(a.find('=') + 1);
            a = a.substr(0, a.find('='));
            hasValue = true;
        }
        auto next = [&]() -> std::string {
            if (hasValue) return value;
            if (i + 1 >= args.size()) throw SweepError{a + ": needs a value"};
            return args[++i];
        };
        if (a == "--vary") o.vary.push_back(parseVary(next()));
        else if (a == "--out") o.out = next();
        else if (a == "--merge") o.merge = next();
        else if (a == "--trajectories") o.trajectories = true;
        else if (a == "--metric") {
            for (const std::string& m : splitList(next())) o.metrics.push_back(m);
        } else if (a == "--jobs") {
            const std::string v = next();
            int n = 0;
            char extra = 0;
            if (std::sscanf(v.c_str(), "%d%c", &n, &extra) != 1 || n < 1 || n > 1024)
                throw SweepError{"--jobs: '" + v + "' is not a whole number from 1 to 1024"};
            o.jobs = n;
        } else if (a.rfind("-", 0) == 0 && a.size() > 1) {
            throw SweepError{"sweep: unknown option '" + a + "' (see tumble sweep --help)"};
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            throw SweepError{"sweep: more than one scene given: '" + o.scene + "' and '" + a + "'"};
        }
    }
    if (!o.merge.empty()) {
        if (!o.scene.empty() || !o.vary.empty() || !o.out.empty())
            throw SweepError{"--merge DIR takes no scene, --vary or --out: the folder holds its plan"};
        return o;
    }
    if (o.scene.empty()) throw SweepError{"sweep: needs a scene file (see tumble sweep --help)"};
    if (o.out.empty()) throw SweepError{"sweep: needs --out DIR, the folder for its variants and results"};
    if (o.vary.empty()) throw SweepError{"sweep: nothing varies: give at least one --vary PATH=VALUES"};
    return o;
}

// "done / running / failed / ETA" on stderr: rewritten in place on a terminal, else a line
// at most every two seconds and at the end.
class Progress {
public:
    Progress(std::ostream& err, int total, int alreadyDone)
        : err_(err), total_(total), done_(alreadyDone), tty_(isatty(2) != 0) {}
    void finished(bool ok, double wall) {
        ++done_;
        ++ranHere_;
        failed_ += ok ? 0 : 1;
        wallSum_ += wall;
    }
    void show(int running, int parallel, bool last = false) {
        const auto now = std::chrono::steady_clock::now();
        if (!last && !tty_ && now - shown_ < std::chrono::seconds(2)) return;
        if (!last && !tty_ && done_ == lastDone_) return;
        shown_ = now;
        lastDone_ = done_;
        char line[160];
        std::string eta = "";
        if (ranHere_ > 0 && done_ < total_) {
            const double each = wallSum_ / ranHere_;
            const double s = each * (total_ - done_) / std::max(1, parallel);
            char buf[32];
            std::snprintf(buf, sizeof buf, ", about %.0f s left", s);
            eta = buf;
        }
        std::snprintf(line, sizeof line, "sweep: %d of %d done, %d running, %d failed%s", done_, total_, running,
                      failed_, eta.c_str());
        if (tty_) err_ << '\r' << line << "\x1b[K" << (last ? "\n" : "") << std::flush;
        else err_ << line << '\n' << std::flush;
    }

private:
    std::ostream& err_;
    int total_, done_, failed_ = 0, ranHere_ = 0, lastDone_ = -1;
    double wallSum_ = 0.0;
    bool tty_;
    std::chrono::steady_clock::time_point shown_{};
};

int finish(const Plan& plan, const fs::path& dir, const std::vector<std::string>& columns, bool stopped,
           std::ostream& out, std::ostream& err) {
    const Tally t = writeSummary(plan, dir, columns);
    out << "variants: " << plan.count << "\n"
        << "ok: " << t.ok << "\n"
        << "failed: " << t.failed << "\n"
        << "not_run: " << t.notRun << "\n"
        << "summary: " << (dir / "summary.csv").string() << "\n";
    if (stopped) {
        err << "tumble sweep: stopped; " << t.ok + t.failed << " of " << plan.count
            << " variants have results: run the same command to resume\n";
        return kStopped;
    }
    return t.failed > 0 || t.notRun > 0 ? kFailed : kOk;
}

int sweepLocally(const Options& o, std::ostream& out, std::ostream& err) {
    const fs::path dir = o.out;
    const Plan plan = makePlan(o.scene, o.vary);
    const std::vector<std::string> columns = metricColumns(plan, o.metrics);
    writeVariants(plan, dir);
    std::error_code ec;
    fs::create_directories(dir / "results", ec);
    if (!ec && o.trajectories) fs::create_directories(dir / "trajectories", ec);
    if (ec) throw SweepError{dir.string() + ": " + ec.message()};

    const std::string exe = selfExecutable();
    std::vector<Job> jobs;
    for (int k = 0; k < plan.count; ++k) {
        if (fs::exists(resultFile(plan, dir, k), ec)) continue;
        Job job;
        job.variant = k;
        job.argv = {exe, "--headless", variantFile(plan, dir, k).string(), "--quiet", "--metrics",
                    metricsFile(plan, dir, k).string()};
        if (o.trajectories) {
            job.argv.push_back("--out");
            job.argv.push_back(trajectoryFile(plan, dir, k).string());
        }
        job.log = logFile(plan, dir, k);
        jobs.push_back(std::move(job));
    }
    const int parallel = o.jobs > 0 ? o.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    Progress progress(err, plan.count, plan.count - static_cast<int>(jobs.size()));
    const bool finished = runLocally(
        jobs, parallel,
        [&](const Outcome& outcome) {
            recordOutcome(plan, dir, outcome);
            progress.finished(outcome.exitCode == 0, outcome.wall);
        },
        [&](int running) { progress.show(running, parallel); });
    progress.show(0, parallel, true);
    return finish(plan, dir, columns, !finished, out, err);
}

}  // namespace

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    for (const std::string& a : args)
        if (a == "--help" || a == "-h") {
            out << kHelp;
            return kOk;
        }
    try {
        const Options o = parse(args);
        if (!o.merge.empty()) {
            const Plan plan = readPlan(o.merge);
            return finish(plan, o.merge, metricColumns(plan, o.metrics), false, out, err);
        }
        return sweepLocally(o, out, err);
    } catch (const SweepError& e) {
        err << "tumble: " << e.message << "\n";
        return kInvalid;
    }
}

}  // namespace tumble::sweep
