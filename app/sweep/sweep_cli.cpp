#include "sweep_cli.h"

#include "arg_reader.h"
#include "cli_options.h"

#include "stop_signals.h"
#include "sweep_plan.h"
#include "sweep_progress.h"
#include "sweep_run.h"
#include "sweep_slurm.h"
#include "sweep_summary.h"

#include <tumble/io/atomic_file.h>

#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <thread>

namespace tumble::sweep {

namespace fs = std::filesystem;

namespace {

constexpr int kOk = 0, kFailed = 1, kInvalid = 2, kStopped = 130;

// The sweep's options on this machine and on Slurm (the help is written from them).
const std::vector<cli::OptionSpec>& sweepOptions() {
    static const std::vector<cli::OptionSpec> options = {
        {"--vary", "PATH=VALUES",
         "PATH names a value of the scene: settings.KEY, or a body's or a\n"
         "joint's name then its keys and [index]es: ball.restitution,\n"
         "ball.velocity[1], crate.friction, ball.shape.radius, settings.dt.\n"
         "VALUES is a,b,c or start:stop:count (both ends included)"},
        {"--out", "DIR", "the sweep's folder (made if missing)"},
        {"--jobs", "N", "variants at once (default: the machine's cores)"},
        {"--trajectories", "", "also a trajectory CSV per variant, DIR/trajectories/NNNN.csv"},
        {"--metric", "NAME",
         "the measures the summary keeps (repeat, or a,b; default all):\n"
         "energy_lost_contacts, energy_lost_damping, deepest_overlap, and per\n"
         "dynamic body final_x, final_y, final_z (final_position: the three),\n"
         "final_speed, highest, rest_time; BODY.NAME for one body's"},
        {"--merge", "DIR",
         "write DIR/summary.csv again from the results there; repeated, with\n"
         "--out FILE.csv, several sweeps in one table (a column `sweep` names\n"
         "the folder; the paths and measures of all of them)"},
        {"--quiet", "", "prints nothing but errors (no progress, notes or counts)"},
    };
    return options;
}

const std::vector<cli::OptionSpec>& slurmOptionSpecs() {
    static const std::vector<cli::OptionSpec> options = {
        {"--slurm", "",
         "run the variants as a job array: writes DIR/sweep.sbatch (at most\n"
         "1000 tasks; each runs its share of the variants), submits it with\n"
         "sbatch, follows it with squeue and merges when it ends; Ctrl-C\n"
         "cancels the job (scancel). The same command resumes what is missing"},
        {"--sbatch", "OPTION", "one more #SBATCH line, e.g. --sbatch=--partition=short (repeat)"},
        {"--max-running", "M", "at most M tasks at once (the array's %M)"},
        {"--tasks", "T",
         "at most T array tasks, each running its share of the variants one\n"
         "after another (default: a task per variant, up to 1000): for\n"
         "variants of a fraction of a second, which a task per variant would\n"
         "spend mostly waiting for the scheduler"},
        {"--no-wait", "", "submit and return; tumble sweep --merge DIR when the job has ended"},
    };
    return options;
}

std::string helpText() {
    return R"(Usage:
  tumble sweep SCENE --vary PATH=VALUES [--vary PATH=VALUES ...] --out DIR [options]
  tumble sweep --merge DIR [--metric NAME ...]
  tumble sweep --merge DIR --merge DIR ... --out FILE.csv [--metric NAME ...]

Runs every combination of the values given (the full product; the last --vary changes
fastest), each variant its own `tumble --headless` process, and writes:
  DIR/variants/NNNN.json   each variant: a scene file that runs by itself
  DIR/results/NNNN.json    each variant's status, wall time and measures
  DIR/summary.csv          one row per variant: variant, one column per PATH, status,
                           state_hash, wall_s, the measures, message
A variant whose result is there is not run again: a stopped sweep resumes with the same
command. A variant that fails (a value the scene refuses, a run stopped by the energy
guard) is a row with its status and message.

)" + cli::optionsHelp(sweepOptions()) +
           "\nOn a Slurm cluster (DIR on a file system the nodes share):\n" +
           cli::optionsHelp(slurmOptionSpecs()) +
           R"(
Exit status: 0 every variant ran; 1 one or more failed; 2 bad input (an unknown PATH, an
empty list: nothing is run); 130 stopped (Ctrl-C): run the same command to resume.
)";
}

struct Options {
    std::string scene, out;
    std::vector<std::string> merge;
    std::vector<Vary> vary;
    std::vector<std::string> metrics;
    int jobs = 0;
    bool trajectories = false;
    bool slurm = false;
    bool quiet = false;
    SlurmOptions slurmOptions;
};

int wholeNumber(const std::string& flag, const std::string& v, int most) {
    int n = 0;
    char extra = 0;
    if (std::sscanf(v.c_str(), "%d%c", &n, &extra) != 1 || n < 1 || n > most)
        throw SweepError{flag + ": '" + v + "' is not a whole number from 1 to " + std::to_string(most)};
    return n;
}

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
    cli::ArgReader reader(args);
    std::vector<cli::OptionSpec> known = sweepOptions();
    known.insert(known.end(), slurmOptionSpecs().begin(), slurmOptionSpecs().end());
    while (reader.next()) {
        const std::string& a = reader.flag();
        auto next = [&]() -> std::string {
            if (auto v = reader.value(); v && (!cli::looksLikeFlag(*v) || a == "--sbatch")) return *v;
            throw SweepError{a + ": needs a value"};
        };
        if (a.rfind("-", 0) == 0 && a.size() > 1 && !cli::findOption(known, a))
            throw SweepError{"sweep: " + cli::unknownOption(a, known, " (see tumble sweep --help)")};
        if (a == "--vary") o.vary.push_back(parseVary(next()));
        else if (a == "--quiet")
            o.quiet = true;
        else if (a == "--out") o.out = next();
        else if (a == "--merge")
            o.merge.push_back(next());
        else if (a == "--trajectories") o.trajectories = true;
        else if (a == "--metric") {
            for (const std::string& m : splitList(next())) o.metrics.push_back(m);
        } else if (a == "--jobs") {
            o.jobs = wholeNumber(a, next(), 1024);
        } else if (a == "--slurm") {
            o.slurm = true;
        } else if (a == "--sbatch") {
            o.slurmOptions.sbatch.push_back(next());
        } else if (a == "--max-running") {
            o.slurmOptions.maxRunning = wholeNumber(a, next(), 1000000);
        } else if (a == "--tasks") {
            o.slurmOptions.tasks = wholeNumber(a, next(), 1000);
        } else if (a == "--no-wait") {
            o.slurmOptions.wait = false;
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            throw SweepError{"sweep: more than one scene given: '" + o.scene + "' and '" + a + "'"};
        }
    }
    if (!o.merge.empty()) {
        if (!o.scene.empty() || !o.vary.empty())
            throw SweepError{"--merge DIR takes no scene or --vary: the folder holds its plan"};
        if (o.merge.size() > 1 && o.out.empty())
            throw SweepError{
                "--merge: several sweeps need --out FILE.csv, the file for the table of them all"};
        if (!o.out.empty() && fs::path(o.out).extension() != ".csv")
            throw SweepError{"--merge: --out '" + o.out + "': the merged table is a .csv file"};
        for (std::size_t i = 0; i < o.merge.size(); ++i)
            for (std::size_t j = 0; j < i; ++j)
                if (fs::weakly_canonical(o.merge[i]) == fs::weakly_canonical(o.merge[j]))
                    throw SweepError{"--merge: '" + o.merge[i] + "' is given twice"};
        return o;
    }
    if (o.scene.empty()) throw SweepError{"sweep: needs a scene file (see tumble sweep --help)"};
    if (o.scene == "-")
        throw SweepError{
            "sweep: the scene must be a file, not - (a resumed sweep reads it again, and its "
            "variants find their meshes beside it)"};
    if (o.out.empty()) throw SweepError{"sweep: needs --out DIR, the folder for its variants and results"};
    if (o.vary.empty()) throw SweepError{"sweep: nothing varies: give at least one --vary PATH=VALUES"};
    if (!o.slurm && (!o.slurmOptions.sbatch.empty() || o.slurmOptions.maxRunning > 0 || o.slurmOptions.tasks > 0 ||
                     !o.slurmOptions.wait))
        throw SweepError{"--sbatch, --max-running, --tasks and --no-wait go with --slurm"};
    if (o.slurm && o.jobs > 0) throw SweepError{"--jobs is for a sweep on this machine; with --slurm, --max-running"};
    o.slurmOptions.trajectories = o.trajectories;
    return o;
}

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
    if (t.failed > 0)
        err << "tumble sweep: " << t.failed << " of " << plan.count
            << " variants failed (summary.csv says why); "
            << "the first, " << t.firstFailure << "\n";
    return t.failed > 0 || t.notRun > 0 ? kFailed : kOk;
}

// The variants whose step is not their dt (writeVariants' notes), a line each up to five,
// before anything runs.
void noteSteps(const std::vector<std::string>& notes, std::ostream& err) {
    for (std::size_t k = 0; k < notes.size() && k < 5; ++k) err << "tumble sweep: note: " << notes[k] << "\n";
    if (notes.size() > 5)
        err << "tumble sweep: note: and " << notes.size() - 5
            << " more variants whose step is not their dt\n";
}

// Several sweeps' summaries in one table (--merge A --merge B --out FILE.csv).
int mergeSweeps(const Options& o, std::ostream& out, std::ostream& err) {
    const std::vector<fs::path> dirs(o.merge.begin(), o.merge.end());
    const Tally t = mergeSummaries(dirs, o.metrics, o.out);
    if (!o.quiet) {
        out << "sweeps: " << dirs.size() << "\n"
            << "variants: " << t.ok + t.failed + t.notRun << "\n"
            << "ok: " << t.ok << "\n"
            << "failed: " << t.failed << "\n"
            << "not_run: " << t.notRun << "\n"
            << "summary: " << o.out << "\n";
    }
    if (t.failed > 0)
        err << "tumble sweep: " << t.failed << " variants failed; the first, " << t.firstFailure << "\n";
    return t.failed > 0 || t.notRun > 0 ? kFailed : kOk;
}

int sweepInFolder(const Options& o, std::ostream& realOut, std::ostream& err) {
    // --quiet: no progress, notes or counts; errors still go to err.
    std::ostream silent(nullptr);
    std::ostream& out = o.quiet ? silent : realOut;
    std::ostream& chatter = o.quiet ? silent : err;
    const fs::path dir = o.out;
    // Ctrl-C while the variants are written stops between two of them (each file whole).
    const cli::StopSignals signals;
    const Plan plan = makePlan(o.scene, o.vary);
    const std::vector<std::string> columns = metricColumns(plan, o.metrics);
    std::vector<std::string> stepNotes;
    try {
        stepNotes = writeVariants(plan, dir, [] { return cli::StopSignals::received() != 0; });
    } catch (const SweepStopped&) {
        err << "tumble sweep: stopped while writing the variants; nothing was run: run the same command "
               "to resume\n";
        return 128 + cli::StopSignals::received();
    }
    std::error_code ec;
    fs::create_directories(dir / "results", ec);
    if (!ec && o.trajectories) fs::create_directories(dir / "trajectories", ec);
    if (ec) throw SweepError{dir.string() + ": cannot be made: " + io::plainReason(ec.value())};

    if (o.slurm) {
        const bool ended = runOnSlurm(plan, dir, o.slurmOptions, out, chatter);
        if (!o.slurmOptions.wait) return kOk;
        return finish(plan, dir, columns, !ended, out, err);
    }
    const std::string exe = selfExecutable();
    std::vector<Job> jobs;
    for (int k = 0; k < plan.count; ++k) {
        if (fs::exists(resultFile(plan, dir, k), ec)) continue;
        jobs.push_back(variantJob(plan, dir, k, o.trajectories, exe));
    }
    noteSteps(stepNotes, chatter);
    const int parallel = o.jobs > 0 ? o.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    Progress progress(chatter, plan.count, plan.count - static_cast<int>(jobs.size()));
    // A result that cannot be written (a full disk, the folder gone) stops the sweep: nothing
    // more is started, and the same command resumes once there is room.
    std::string writeFailure;
    const bool finished = runLocally(
        jobs, parallel,
        [&](const Outcome& outcome) {
            try {
                recordOutcome(plan, dir, outcome);
            } catch (const std::exception& e) {
                if (writeFailure.empty()) writeFailure = e.what();
                return false;
            }
            progress.finished(outcome.exitCode == 0, outcome.wall);
            return writeFailure.empty();
        },
        [&](int running) { progress.show(running, parallel); });
    progress.show(0, parallel, true);
    if (!writeFailure.empty()) {
        err << "tumble sweep: " << writeFailure
            << "; the sweep stopped (the results written are kept): run the same command to resume\n";
        return kFailed;
    }
    return finish(plan, dir, columns, !finished, out, err);
}

}  // namespace

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    for (const std::string& a : args)
        if (a == "--help" || a == "-h") {
            out << helpText();
            return kOk;
        }
    try {
        // (Internal: one task of a Slurm array, sweep_slurm.h.)
        if (args.size() == 4 && args[0] == "--task") {
            int task = -1;
            char extra = 0;
            if (std::sscanf(args[3].c_str(), "%d%c", &task, &extra) != 1 || task < 0)
                throw SweepError{"--task: '" + args[3] + "' is not a task index"};
            return runTask(args[1], args[2], task);
        }
        const Options o = parse(args);
        if (o.merge.size() == 1 && o.out.empty()) {
            const Plan plan = readPlan(o.merge[0]);
            return finish(plan, o.merge[0], metricColumns(plan, o.metrics), false, out, err);
        }
        if (!o.merge.empty()) return mergeSweeps(o, out, err);
        return sweepInFolder(o, out, err);
    } catch (const SweepError& e) {
        err << "tumble: " << e.message << "\n";
        return kInvalid;
    }
}

}  // namespace tumble::sweep
