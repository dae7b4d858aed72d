// A sweep as a Slurm job array (`tumble sweep ... --slurm`, docs/sweeps.md): the variants
// still without a result are listed in DIR/slurm/submit-N.txt, DIR/sweep.sbatch runs them as
// an array (`#SBATCH --array=0-(T-1)`, at most 1000 tasks: task t takes the list's entries
// t, t + T, ...), each task with `tumble sweep --task DIR LIST t`, which runs its variants one
// by one exactly as a local sweep does (the same child process, the same result files).
// The sweep then follows the job with squeue, and merges when it has left the queue (a task
// that ended short is named from sacct where accounting is on). Slurm
// is only ever called (sbatch, squeue, scancel): it is the scheduler, Tumble has none.
#pragma once

#include "sweep_plan.h"

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace tumble::sweep {

struct SlurmOptions {
    std::vector<std::string> sbatch;  // more #SBATCH options, each as given ("--partition=short")
    int maxRunning = 0;               // the array's %M (0: no limit)
    int tasks = 0;                    // at most this many array tasks (0: one per variant, up to 1000)
    bool wait = true;                 // false: submit and return
    bool trajectories = false;        // a trajectory CSV per variant too
};

/// Submits the variants of `plan` in `dir` without a result; follows the job unless
/// !options.wait. Returns true when the job left the queue (or was submitted, without
/// waiting); false when stopped by SIGINT or SIGTERM (the job is cancelled). Throws
/// SweepError when Slurm cannot be reached (sbatch or squeue fails; the message is theirs).
bool runOnSlurm(const Plan& plan, const std::filesystem::path& dir, const SlurmOptions& options, std::ostream& out,
                std::ostream& err);

/// `tumble sweep --task DIR LIST T`: runs the variants of task T of a submitted array.
int runTask(const std::filesystem::path& dir, const std::filesystem::path& list, int task);

}  // namespace tumble::sweep
