// A sweep's results: one file per variant that ran (DIR/results/NAME.json: its status, the
// exit code and message of a failure, its wall time and the measures its run wrote, see
// run_metrics.h), and DIR/summary.csv merged from them, one row per variant.
#pragma once

#include "sweep_plan.h"
#include "sweep_run.h"

#include <filesystem>
#include <string>
#include <vector>

namespace tumble::sweep {

/// Where a variant's run writes its measures, its log and (with --trajectories) its
/// trajectory; its result file is what says it ran (a resumed sweep skips it).
std::filesystem::path metricsFile(const Plan& plan, const std::filesystem::path& dir, int k);
std::filesystem::path logFile(const Plan& plan, const std::filesystem::path& dir, int k);
std::filesystem::path trajectoryFile(const Plan& plan, const std::filesystem::path& dir, int k);
std::filesystem::path resultFile(const Plan& plan, const std::filesystem::path& dir, int k);

/// The process that runs variant k: `EXE --headless VARIANT --quiet --metrics FILE`
/// (with a trajectory CSV when asked), its output into its log.
Job variantJob(const Plan& plan, const std::filesystem::path& dir, int k, bool trajectories, const std::string& exe);

/// Writes a variant's result file from how its process ended: status `ok` (exit 0, its
/// measures read back), `invalid` (exit 2: a value the scene does not accept) or `failed`
/// (any other end; the message is the last line it printed).
void recordOutcome(const Plan& plan, const std::filesystem::path& dir, const Outcome& outcome);

/// The summary's measure columns: every measure (`metrics` empty), or those named: a
/// scene measure (energy_lost_contacts, energy_lost_damping, deepest_overlap), a body
/// measure for every dynamic body (final_x, final_y, final_z, final_speed, highest,
/// rest_time, or final_position for the three) or for one (`ball.highest`). Throws
/// SweepError naming an unknown one.
std::vector<std::string> metricColumns(const Plan& plan, const std::vector<std::string>& metrics);

struct Tally {
    int ok = 0, failed = 0, notRun = 0;
    std::string firstFailure;  // the first failed variant's name and message ("0003: ...")
};

/// Writes DIR/summary.csv (whole or not at all): `variant`, one column per varied path,
/// `status` (ok, invalid, failed, or `not run`), `state_hash`, `wall_s`, the measures,
/// `message`. Returns how many variants ended each way.
Tally writeSummary(const Plan& plan, const std::filesystem::path& dir, const std::vector<std::string>& columns);

/// Several sweeps in one table (`tumble sweep --merge A --merge B --out FILE.csv`): each
/// folder's summary.csv written again (with its measures, `metrics` as --metric gives
/// them: empty for all), and FILE (whole or not at all) with a first column `sweep` (the
/// folder as given), then `variant`, every path any of them varied (a sweep that did not
/// vary one gets its variants' value there, from their scene files), the status columns,
/// every measure any of them has (blank where a sweep has none), and `message`. Throws
/// SweepError for a folder without a sweep, or a FILE that cannot be written. Returns the
/// counts over all of them.
Tally mergeSummaries(const std::vector<std::filesystem::path>& dirs, const std::vector<std::string>& metrics,
                     const std::filesystem::path& file);

}  // namespace tumble::sweep
