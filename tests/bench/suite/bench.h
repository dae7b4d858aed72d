// The benchmark program's parts: options, the engines to run, and the four measurements
// (work-precision, speed, skips as speed variants, stress, export), each writing rows the report
// turns into CSV, plots and Markdown tables.
#pragma once

#include "engine_adapter.h"

#include <filesystem>
#include <string>
#include <vector>

namespace tumble::bench {

struct Options {
    bool quick = false;
    std::string scene;  ///< empty: all
    std::vector<std::string> engines{"tumble", "bullet", "ode", "mujoco", "jolt"};
    std::filesystem::path out = "bench-out";
    int runs = 3;  ///< timed runs of each accuracy point (the minimum is kept)
    /// Runs of each speed row, the fastest kept with its own figures (a single run on a
    /// shared 2-core machine varies by up to 20 %).
    int speedRuns = 1;
};

/// Adapters for the engines named in `opt` that were built; prints "not built" for others.
std::vector<std::unique_ptr<EngineAdapter>> makeEngines(const Options& opt);
std::unique_ptr<EngineAdapter> makeEngine(const std::string& name);

double wallNow();
/// This program's own path (/proc/self/exe), to run parts of it in a child process.
std::string selfPath();

// --- work-precision -------------------------------------------------------------------
struct AccuracyRow {
    std::string scene, engine, mode;
    double dt = 0;
    long steps = 0;
    double wall = 0;  ///< s, the whole run, minimum of the runs
    std::string errorName;
    double error = 0;
};
/// Runs the sweep; false when a run crashed or threw where it must not.
bool runAccuracy(const Options& opt, std::vector<AccuracyRow>& rows);

// --- speed ----------------------------------------------------------------------------
struct SpeedRow {
    std::string scene, engine, mode;
    int bodies = 0;
    int steps = 0;
    double msPerStep = 0;
    double msMaxStep = 0;
    double contactsPerStep = 0;
    double peakMB = 0;  ///< peak resident memory of the child process that ran it
    double baseMB = 0;  ///< the same process before building the scene
    int movingAtEnd = 0;  ///< dynamic bodies faster than 1 cm/s after the last step
    int fellThrough = 0;  ///< dynamic bodies ending 1 m below the lowest static body
    double jointGap = -1.0;  ///< scenes with joints: the largest joint gap over the run (m); else -1
    // Tumble only: ms per step in each stage, pairs and awake bodies per step.
    double forces = 0, integrate = 0, broadphase = 0, narrowphase = 0, toi = 0, impact = 0, solve = 0,
           sleep = 0;
    double pairsPerStep = 0, awakePerStep = 0;
    double cutsPerStep = 0, parkedPerStep = 0, restartsPerStep = 0;  ///< impact moments, parked bodies, restarts
    std::string note;  ///< n/a reason or failure
    bool ok = true;
};
bool runSpeed(const Options& opt, std::vector<SpeedRow>& rows);
/// `tumble-bench --child speed SCENE ENGINE MODE [--quick]`: one speed run, one "RESULT" line.
int childMain(int argc, char** argv);

// --- stress ---------------------------------------------------------------------------
struct StressRow {
    std::string test, engine;
    bool pass = false;
    std::string figure;
    bool broken = false;  ///< the run threw or left a non-finite state
    /// A stack's run (`stands`): its step and its largest move (drift or sink, m) for the
    /// stability-against-step plot; 0 when the test is not a stack.
    double dt = 0.0, largestMove = 0.0;
};
bool runStress(const Options& opt, std::vector<StressRow>& rows);

// --- export ---------------------------------------------------------------------------
struct ExportRow {
    int bodies = 0;
    std::string format;  ///< the file's extension: csv, json, gltf, glb
    int frames = 0;
    double seconds = 0;            ///< the writer alone, the fastest of three
    unsigned long long bytes = 0;  ///< a .gltf with its .bin
    std::string note;              ///< why it failed
};
/// Times each trajectory writer on runs of 250 to 2 000 bodies (250 and 500 when quick),
/// each write in a fresh child process (as a user's run meets the allocator).
bool runExport(const Options& opt, std::vector<ExportRow>& rows);
/// `tumble-bench --child export BODIES FILE`: one timed write, one "RESULT" line.
int exportChildMain(int argc, char** argv);
void writeExport(const Options& opt, const std::vector<ExportRow>& rows);

// --- convex parts (convex_parts_speed.cpp) -------------------------------------------
struct ConvexPartsRow {
    std::string mesh;
    bool turned = false;
    int triangles = 0, parts = 0;
    double volumeOver = 0.0;  ///< % the parts' hulls hold beyond the mesh's volume
    double reachOut = 0.0, tolerance = 0.0, seconds = 0.0;
    std::string note;  ///< why it failed, if it did
};
bool runConvexParts(const Options& opt, std::vector<ConvexPartsRow>& rows);
void writeConvexParts(const Options& opt, const std::vector<ConvexPartsRow>& rows);

// --- report ---------------------------------------------------------------------------
void writeAccuracy(const Options& opt, const std::vector<AccuracyRow>& rows);
void writeSpeed(const Options& opt, const std::vector<SpeedRow>& rows);
void writeStress(const Options& opt, const std::vector<StressRow>& rows);

/// Every scene name, by kind, for --list and --scene.
std::vector<std::string> accuracySceneNames();
std::vector<std::string> speedSceneNames();
std::vector<std::string> stressTestNames();

}  // namespace tumble::bench
