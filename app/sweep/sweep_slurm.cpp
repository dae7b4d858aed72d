#include "sweep_slurm.h"

#include "stop_signals.h"
#include "sweep_progress.h"
#include "sweep_run.h"
#include "sweep_summary.h"

#include <tumble/io/atomic_file.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>

namespace tumble::sweep {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

constexpr int kMostTasks = 1000;  // Slurm's default MaxArraySize is 1001 (indexes 0 to 1000)

std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

struct Command {
    int status = -1;
    std::string output;  // stdout and stderr together
};

// A Slurm command, through the shell (its arguments quoted), its output captured.
Command shell(const std::string& command) {
    Command c;
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    if (!p) return c;
    char buf[4096];
    std::size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) c.output.append(buf, n);
    const int status = pclose(p);
    c.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return c;
}

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

// The results in the folder: how many variants have one, and how many of those failed.
void countResults(const Plan& plan, const fs::path& dir, int& done, int& failed) {
    done = failed = 0;
    for (int k = 0; k < plan.count; ++k) {
        std::ifstream in(resultFile(plan, dir, k));
        if (!in) continue;
        ++done;
        try {
            if (ojson::parse(in).value("status", std::string()) != "ok") ++failed;
        } catch (const std::exception&) {
            ++failed;
        }
    }
}

}  // namespace

bool runOnSlurm(const Plan& plan, const fs::path& dir, const SlurmOptions& options, std::ostream& out,
                std::ostream& err) {
    std::vector<int> pending;
    std::error_code ec;
    for (int k = 0; k < plan.count; ++k)
        if (!fs::exists(resultFile(plan, dir, k), ec)) pending.push_back(k);
    if (pending.empty()) return true;
    const fs::path abs = fs::absolute(dir).lexically_normal();
    fs::create_directories(abs / "slurm", ec);
    if (ec) throw SweepError{(abs / "slurm").string() + ": cannot be made: " + io::plainReason(ec.value())};

    // This submission's list (a job still running keeps reading its own).
    int n = 0;
    while (fs::exists(abs / "slurm" / ("submit-" + std::to_string(n) + ".json"), ec)) ++n;
    const fs::path list = abs / "slurm" / ("submit-" + std::to_string(n) + ".json");
    const int tasks = std::min({static_cast<int>(pending.size()), kMostTasks,
                                options.tasks > 0 ? options.tasks : kMostTasks});
    try {
        io::writeFileAtomically(
            list, ojson({{"tasks", tasks}, {"trajectories", options.trajectories}, {"variants", pending}}).dump() + "\n");
        std::ostringstream script;
        script << "#!/bin/sh\n"
               << "# tumble sweep: " << pending.size() << " variants of " << plan.scene.string() << " in " << tasks
               << " array tasks (task t runs the entries t, t + " << tasks << ", ... of " << list.filename().string()
               << ")\n"
               << "#SBATCH --job-name=tumble-sweep\n"
               << "#SBATCH --array=0-" << tasks - 1;
        if (options.maxRunning > 0) script << '%' << options.maxRunning;
        script << "\n#SBATCH --output=" << (abs / "slurm" / "task-%A_%a.log").string() << "\n";
        for (const std::string& o : options.sbatch) script << "#SBATCH " << o << "\n";
        script << "exec " << quoted(selfExecutable()) << " sweep --task " << quoted(abs.string()) << ' '
               << quoted(list.string()) << " \"$SLURM_ARRAY_TASK_ID\"\n";
        io::writeFileAtomically(abs / "sweep.sbatch", script.str());
    } catch (const std::runtime_error& e) {
        throw SweepError{e.what()};
    }

    const Command submitted = shell("sbatch --parsable " + quoted((abs / "sweep.sbatch").string()));
    const std::string job = firstLine(submitted.output).substr(0, firstLine(submitted.output).find(';'));
    if (submitted.status != 0 || job.empty() || job.find_first_not_of("0123456789") != std::string::npos)
        throw SweepError{"sbatch: " + (submitted.output.empty() ? std::string("could not be run") : firstLine(submitted.output))};
    out << "job: " << job << "\n" << std::flush;
    if (!options.wait) {
        err << "tumble sweep: job " << job << " submitted (" << pending.size() << " variants in " << tasks
            << " tasks); when it ends: tumble sweep --merge " << dir.string() << "\n";
        return true;
    }

    std::optional<cli::StopSignals> signals(std::in_place);  // (a throw below restores the handlers too)
    int done = 0, failed = 0;
    countResults(plan, dir, done, failed);
    Progress progress(err, plan.count, done);
    int misses = 0;
    bool ended = false;
    while (!cli::StopSignals::received() && !ended) {
        const Command q = shell("squeue -h -j " + job + " -o %T");
        if (q.status != 0) {
            // A just-submitted job can be missing for a moment; a controller that stays away
            // is an error (the job may still run: merge later).
            if (++misses > 5) {
                throw SweepError{"squeue: " + firstLine(q.output) + " (job " + job +
                                 " may still run: tumble sweep --merge " + dir.string() + " when it ends)"};
            }
        } else {
            misses = 0;
            int running = 0, queued = 0;
            std::istringstream states(q.output);
            for (std::string s; std::getline(states, s);) {
                if (s.empty()) continue;
                ++queued;
                running += s == "RUNNING" || s == "COMPLETING";
            }
            countResults(plan, dir, done, failed);
            progress.set(done, failed);
            progress.show(running, 1);
            ended = queued == 0;
        }
        for (int i = 0; i < 10 && !cli::StopSignals::received() && !ended; ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const bool stopped = cli::StopSignals::received() != 0;
    signals.reset();  // the handlers before come back
    if (stopped) {
        shell("scancel " + job);
        err << "tumble sweep: job " << job << " cancelled\n";
        return false;
    }
    countResults(plan, dir, done, failed);
    progress.set(done, failed);
    progress.show(0, 1, true);
    // Tasks that ended without running all their variants (a time limit, a node lost): where
    // accounting is on, sacct says how; their variants stay without a result (`not run`),
    // and the same command runs them again. (Accounting off, as on the test cluster: sacct
    // fails and nothing is said.)
    if (done < plan.count) {
        const Command acct = shell("sacct -n -P -X -j " + job + " -o JobID,State");
        std::istringstream lines(acct.status == 0 ? acct.output : std::string());
        for (std::string line; std::getline(lines, line);) {
            const auto bar = line.find('|');
            if (bar == std::string::npos || line.compare(bar + 1, 9, "COMPLETED") == 0) continue;
            err << "tumble sweep: Slurm task " << line.substr(0, bar) << " ended " << line.substr(bar + 1)
                << "; its variants without a result run again with the same command\n";
        }
    }
    return true;
}

int runTask(const fs::path& dir, const fs::path& list, int task) {
    const Plan plan = readPlan(dir);
    ojson submit;
    try {
        std::ifstream in(list);
        submit = ojson::parse(in);
    } catch (const std::exception& e) {
        throw SweepError{list.string() + ": cannot be read: " + e.what()};
    }
    const int tasks = submit.at("tasks").get<int>();
    const bool trajectories = submit.value("trajectories", false);
    const std::vector<int> variants = submit.at("variants").get<std::vector<int>>();
    std::vector<Job> jobs;
    std::error_code ec;
    const std::string exe = selfExecutable();
    for (std::size_t i = static_cast<std::size_t>(task); i < variants.size(); i += static_cast<std::size_t>(tasks))
        if (!fs::exists(resultFile(plan, dir, variants[i]), ec))
            jobs.push_back(variantJob(plan, dir, variants[i], trajectories, exe));
    if (trajectories) fs::create_directories(dir / "trajectories", ec);
    std::string writeFailure;
    runLocally(
        jobs, 1,
        [&](const Outcome& o) {
            try {
                recordOutcome(plan, dir, o);
                return true;
            } catch (const std::exception& e) {
                writeFailure = e.what();
                return false;
            }
        },
        [](int) {});
    if (!writeFailure.empty()) {
        std::cerr << "tumble sweep: " << writeFailure << "\n";
        return 1;
    }
    return 0;
}

}  // namespace tumble::sweep
