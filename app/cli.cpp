#include "cli.h"
#include "arg_reader.h"
#include "cli_options.h"
#include "std_streams.h"
#include "stop_signals.h"
#include "sweep/run_metrics.h"
#include "sweep/sweep_cli.h"
#include "version.h"

#include <tumble/convex_parts.h>
#include <tumble/errors.h>
#include <tumble/io/atomic_file.h>
#include <tumble/io/convex_parts_cache.h>
#include <tumble/io/scene_file.h>
#include <tumble/io/trajectory_writer.h>
#include <tumble/world.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <ostream>

#include <unistd.h>

namespace tumble::cli {

namespace {

constexpr int kOk = 0;
constexpr int kFailure = 1;
constexpr int kInvalid = 2;

// The options of --headless (the help's "Options for --headless" is written from it).
const std::vector<OptionSpec>& headlessOptions() {
    static const std::vector<OptionSpec> options = {
        {"--duration", "S",
         "simulated seconds (overrides settings.duration); numbers may be\n"
         "written as fractions, as --dt 1/120"},
        {"--dt", "S",
         "the longest step, seconds (overrides settings.dt); each frame\n"
         "(1/frame_rate) is taken in the fewest equal steps no longer than\n"
         "dt, so a dt longer than a frame steps once a frame (a note says\n"
         "so, and stdout's step: is the step used)"},
        {"--integrator", "NAME", "overrides settings.integrator; see --list-integrators"},
        {"--impacts", "WHEN",
         "exact or end-of-step (overrides settings.impacts): impacts at their\n"
         "moment, or at the end of the step that finds them (faster for piles)"},
        {"--frame-rate", "HZ", "recorded frames per second (overrides settings.frame_rate)"},
        {"--threads", "N",
         "threads to step with, 1 to 256 (default 1): the narrow phase, the\n"
         "time of impact and the integrator's drift spread over them; the\n"
         "result is the same bit for bit for any N"},
        {"--out", "FILE",
         "writes the trajectory; the format follows the extension:\n"
         ".csv, .json (docs/export.md), .gltf (with FILE's .bin beside it) or\n"
         ".glb (glTF 2.0: the bodies' meshes and their motion as an animation);\n"
         "a folder ending in / gets a PNG per frame, FILE.mp4 a video (its\n"
         "frames in FILE-frames/; needs ffmpeg): both drawn by the editor's\n"
         "viewport, so they need a display (xvfb-run -a tumble --headless ...).\n"
         "- writes it to standard output (--format), once the run succeeded"},
        {"--format", "FORMAT", "the format of --out -: csv (default), json or glb"},
        {"--joint-forces", "",
         "with a .csv or .json --out: each joint's reaction too (the force\n"
         "on body A at its anchor and the couple on A, world, over the last\n"
         "step before each frame; a CSV gets them in FILE-joints.csv beside it)"},
        {"--image-size", "WxH", "pixels of the images and video (default 1280x720)"},
        {"--save-scene", "FILE",
         "writes the scene as run (options applied), normalised; - to\n"
         "standard output"},
        {"--metrics", "FILE",
         "writes the run's measures as JSON (what a sweep's summary holds,\n"
         "docs/sweeps.md): per body its final position and speed, highest\n"
         "point and the time it came to rest; the energy contacts and damping\n"
         "took; the deepest overlap; the state hash; - to standard output"},
        {"--quiet", "", "prints nothing but errors"},
        {"--progress", "",
         "a progress line on stderr (frame, simulated time, time left) for a\n"
         "run past two seconds; on by default when stderr is a terminal"},
    };
    return options;
}

// The flags of the command line itself, beside --headless's options.
const std::vector<OptionSpec>& commandFlags() {
    static const std::vector<OptionSpec> flags = {
        {"--headless", "", ""}, {"--help", "", ""}, {"--version", "", ""}, {"--list-integrators", "", ""}};
    return flags;
}

std::vector<OptionSpec> everyFlag() {
    std::vector<OptionSpec> all = commandFlags();
    all.insert(all.end(), headlessOptions().begin(), headlessOptions().end());
    return all;
}

std::string helpText() {
    return R"(Usage:
  tumble [SCENE]                      open the editor, with SCENE or the default sample scene
  tumble --headless SCENE [options]   simulate without a window (SCENE - reads it from
                                      standard input; mesh files from the working folder)
  tumble --help | --version | --list-integrators

Options for --headless:
)" + optionsHelp(headlessOptions()) +
           R"(
  tumble sweep SCENE --vary PATH=VALUES ... --out DIR [options]
                      runs variants of SCENE (tumble sweep --help)

Exit status: 0 success; 2 invalid input (the message names the file and the field);
1 any other failure, such as a state that became non-finite (the message names the
body and the time); 130 or 143 stopped by SIGINT (Ctrl-C) or SIGTERM at the next frame.
On failure or a stop no output file is written, nor any temporary left. When an output
is - (standard output), the key: value report below goes to standard error.

A successful run prints key: value lines: bodies, integrator, dt, step (the step used
between frames: see --dt), frames, steps,
simulated_time, wall_seconds; energy_start and energy_end (kinetic + potential, J) and
where energy went: energy_lost_contacts, energy_lost_friction (taken by impulses),
energy_position_correction (potential energy of placing bodies in contact) and
energy_lost_joints (taken by the joints' impulses and projections; negative when a motor
gives energy), so that energy_end = energy_start - lost + correction when no force drives
the scene; the time
of each stage (forces_seconds, integrate_seconds, broadphase_seconds,
narrowphase_seconds, toi_seconds, impact_seconds, solve_seconds, sleep_seconds); pairs,
contact_points, impacts, impact_moments (the steps were cut there), impact_sweep_limits,
awake_body_steps, parked_body_steps (bodies of islands without an impact, kept out of a
step's cuts) and island_restarts (steps taken again with every body cut) summed over the
steps; threads; and state_hash (the same scene and options give the same hash,
whatever --threads is).
)";
}

struct Options {
    std::string scene;
    std::optional<double> duration, dt, frameRate;
    std::optional<std::string> integrator;
    std::optional<ImpactTiming> impacts;
    std::string out, saveScene, metrics;
    std::optional<io::TrajectoryFormat> format;  // --format, for --out -
    int imageWidth = 1280, imageHeight = 720;
    int threads = 1;
    bool quiet = false;
    bool jointForces = false;
    bool progress = false;  // --progress: even when stderr is not a terminal
};

ImageRenderer& imageRenderer() {
    static ImageRenderer renderer;
    return renderer;
}

// --out DIR/ (a folder: PNG per frame) or --out FILE.mp4 (a video, its frames beside it).
bool isImageOutput(const std::string& out) {
    if (out.empty()) return false;
    if (out.back() == '/') return true;
    const std::string ext = std::filesystem::path(out).extension().string();
    std::string lower;
    for (char c : ext) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower == ".mp4";
}

struct UsageError {
    std::string message;
};

// SIGINT (Ctrl-C) and SIGTERM during a run (StopSignals): the run stops at the next frame
// by throwing Stopped, so that every output being written (each an AtomicFile) is dropped
// with its temporary, and the exit status says which signal it was.
struct Stopped {};

std::string signalName(int signal) {
    return signal == SIGINT    ? "SIGINT (Ctrl-C)"
           : signal == SIGTERM ? "SIGTERM"
                               : "signal " + std::to_string(signal);
}

// A number, or a fraction of two ("--dt 1/60").
double parseNumber(const std::string& flag, const std::string& text) {
    const auto slash = text.find('/');
    if (slash != std::string::npos && slash > 0) {
        const double below = parseNumber(flag, text.substr(slash + 1));
        if (below == 0.0) throw UsageError{flag + ": '" + text + "' divides by 0"};
        const double v = parseNumber(flag, text.substr(0, slash)) / below;
        if (!std::isfinite(v)) throw UsageError{flag + ": must be a finite number"};
        return v;
    }
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw UsageError{flag + ": '" + text + "' is not a number"};
    if (!std::isfinite(v)) throw UsageError{flag + ": must be a finite number"};
    return v;
}

Options parse(const std::vector<std::string>& args) {
    Options o;
    ArgReader reader(args);
    const std::vector<OptionSpec> known = everyFlag();
    while (reader.next()) {
        const std::string& a = reader.flag();
        auto next = [&]() -> std::string {
            if (auto v = reader.value(); v && !looksLikeFlag(*v)) return *v;
            throw UsageError{a + ": needs a value"};
        };
        if (a.rfind("-", 0) == 0 && a.size() > 1 && !findOption(known, a))
            throw UsageError{unknownOption(a, known, " (see --help)")};
        if (a == "--headless") continue;
        if (a == "--quiet") o.quiet = true;
        else if (a == "--progress")
            o.progress = true;
        else if (a == "--joint-forces") o.jointForces = true;
        else if (a == "--duration") o.duration = parseNumber(a, next());
        else if (a == "--dt") o.dt = parseNumber(a, next());
        else if (a == "--frame-rate") o.frameRate = parseNumber(a, next());
        else if (a == "--integrator") o.integrator = next();
        else if (a == "--impacts") {
            const std::string v = next();
            if (v == toString(ImpactTiming::Exact)) o.impacts = ImpactTiming::Exact;
            else if (v == toString(ImpactTiming::EndOfStep)) o.impacts = ImpactTiming::EndOfStep;
            else throw UsageError{"--impacts: '" + v + "' is not one of exact, end-of-step"};
        }
        else if (a == "--threads") {
            const std::string v = next();
            int n = 0;
            char extra = 0;
            if (std::sscanf(v.c_str(), "%d%c", &n, &extra) != 1 || n < 1 || n > 256)
                throw UsageError{"--threads: '" + v + "' is not a whole number from 1 to 256"};
            o.threads = n;
        } else if (a == "--out" || a == "--save-scene" || a == "--metrics") {
            // One file each: a second one silently replaced the first.
            std::string& file = a == "--out" ? o.out : a == "--save-scene" ? o.saveScene : o.metrics;
            const std::string given = next();
            if (!file.empty())
                throw UsageError{a + ": given twice ('" + file + "' and '" + given + "'); a run writes one"};
            file = given;
        } else if (a == "--image-size") {
            const std::string v = next();
            int w = 0, h = 0;
            char extra = 0;
            if (std::sscanf(v.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192)
                throw UsageError{"--image-size: '" + v + "' is not WIDTHxHEIGHT in pixels (16 to 8192 each)"};
            o.imageWidth = w;
            o.imageHeight = h;
        } else if (a == "--format") {
            const std::string v = next();
            io::TrajectoryFormat f;
            if ((v != "csv" && v != "json" && v != "glb") || !io::trajectoryFormatFor("x." + v, f))
                throw UsageError{"--format: '" + v +
                                 "' is not one of csv, json, glb (the formats standard output can carry)"};
            o.format = f;
        } else if (a.rfind("-", 0) == 0 && a.size() > 1)
            throw UsageError{"unknown option '" + a + "' (see --help)"};
        else if (o.scene.empty()) o.scene = a;
        else throw UsageError{"more than one scene given: '" + o.scene + "' and '" + a + "'"};
    }
    if (o.scene.empty()) throw UsageError{"--headless needs a scene file (see --help)"};
    // Standard output carries one file; the report then goes to standard error.
    const int toStdout = (o.out == "-") + (o.saveScene == "-") + (o.metrics == "-");
    if (toStdout > 1)
        throw UsageError{
            "only one of --out, --save-scene and --metrics can be - (standard output carries one file)"};
    if (o.format && o.out != "-")
        throw UsageError{"--format: only for --out - (a file's format follows its extension)"};
    return o;
}

// The command-line flag that overrode a setting, so that a bad value names the flag.
std::string flagFor(const std::string& path, const Options& o) {
    static const std::map<std::string, std::string> flags = {{"settings.duration", "--duration"},
                                                             {"settings.dt", "--dt"},
                                                             {"settings.frame_rate", "--frame-rate"},
                                                             {"settings.integrator", "--integrator"}};
    auto it = flags.find(path);
    if (it == flags.end()) return {};
    const bool given = (it->second == "--duration" && o.duration) || (it->second == "--dt" && o.dt) ||
                       (it->second == "--frame-rate" && o.frameRate) ||
                       (it->second == "--integrator" && o.integrator);
    return given ? it->second : std::string{};
}

std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

int headless(const Options& o, std::ostream& out, std::ostream& err) {
    // From the start: a signal while the outputs are opened is noted too, and the run stops
    // at its first frame with their temporaries removed.
    const StopSignals stopSignals;
    SceneDesc scene;
    const std::string sceneName = o.scene == "-" ? kStdinName : o.scene;  // for messages
    try {
        // From standard input, mesh files are found from the working folder.
        scene = o.scene == "-" ? io::parseScene(readStandardInput(), kStdinName, std::filesystem::path("."))
                               : io::readSceneFile(o.scene);
    } catch (const io::InputError& e) {
        err << e.what() << "\n";
        return kInvalid;
    } catch (const std::runtime_error& e) {
        err << "tumble: " << e.what() << "\n";
        return kInvalid;
    }
    if (o.duration) scene.settings.duration = *o.duration;
    if (o.dt) scene.settings.dt = *o.dt;
    if (o.frameRate) scene.settings.frameRate = *o.frameRate;
    if (o.integrator) scene.settings.integrator = *o.integrator;
    if (o.impacts) scene.settings.impacts = *o.impacts;

    const bool images = isImageOutput(o.out);
    const bool trajectoryToStdout = o.out == "-";
    if (images && !imageRenderer()) {
        err << "tumble: --out: '" << o.out << "': images and video need the editor, which this build has not\n";
        return kInvalid;
    }
    io::TrajectoryFormat format = o.format.value_or(io::TrajectoryFormat::Csv);
    if (!o.out.empty() && !images && !trajectoryToStdout && !io::trajectoryFormatFor(o.out, format)) {
        err << "tumble: --out: '" << o.out << "': " << io::trajectoryFormatsText() << "\n";
        return kInvalid;
    }

    if (o.jointForces && (o.out.empty() || images || (format != io::TrajectoryFormat::Csv &&
                                                        format != io::TrajectoryFormat::Json))) {
        err << "tumble: --joint-forces: needs --out FILE.csv or FILE.json (the joints' reactions are "
               "written with the trajectory)\n";
        return kInvalid;
    }

    if (o.jointForces && trajectoryToStdout && format == io::TrajectoryFormat::Csv) {
        err << "tumble: --joint-forces: with --out - needs --format json (a CSV puts the joints in a "
               "second file)\n";
        return kInvalid;
    }

    if (o.jointForces && scene.joints.empty()) {
        err << "tumble: --joint-forces: " << sceneName << " has no joints (nothing to write)\n";
        return kInvalid;
    }

    // Meshes to split into convex parts that the sidecar did not have: split here, noted,
    // and kept in the sidecar for the next run (not for a scene read from standard input).
    try {
        std::vector<std::pair<ShapeDesc*, std::string>> toMake;
        for (auto& entry : io::convexPartsShapes(scene))
            if (!entry.first->convexParts) toMake.push_back(entry);
        const int made = io::makeConvexParts(scene, sceneName);
        if (made > 0 && !o.quiet) {
            for (auto& [shape, path] : toMake) {
                if (!shape->convexParts) continue;
                const mesh::ConvexParts& p = *shape->convexParts;
                char text[256];
                std::snprintf(
                    text, sizeof text,
                    "%s: %s split into %zu convex parts in %.2f s (their hulls %+.1f %% of its volume, "
                    "reaching out %.3g m at most)",
                    path.c_str(), shape->file.c_str(), p.parts.size(), p.seconds,
                    100.0 * (p.partsVolume / p.meshVolume - 1.0), p.largestPokeOut);
                err << "tumble: note: " << text << "\n";
            }
        }
        if (made > 0 && o.scene != "-") {
            const auto cache = io::convexPartsCachePath(o.scene);
            try {
                io::writeConvexPartsCache(scene, cache);
                if (!o.quiet) err << "tumble: note: the convex parts are kept in " << cache.string() << "\n";
            } catch (const std::runtime_error& e) {
                if (!o.quiet) err << "tumble: note: the convex parts were not kept: " << e.what() << "\n";
            }
        }
    } catch (const io::InputError& e) {
        err << e.what() << "\n";
        return kInvalid;
    }

    std::unique_ptr<World> world;
    try {
        world = std::make_unique<World>(scene);
        world->setThreads(o.threads);
    } catch (const SceneError& e) {
        const std::string flag = flagFor(e.path(), o);
        if (!flag.empty()) err << "tumble: " << flag << ": " << e.message() << "\n";
        else
            err << sceneName << ": " << e.what() << "\n";
        return kInvalid;
    }
    if (!o.quiet) {
        for (std::string note : world->model().notes) {
            if (o.dt && note.rfind("settings.dt ", 0) == 0)
                note.replace(0, 11, "--dt");  // the flag that set it
            err << "tumble: note: " << note << "\n";
        }
    }

    // The output given as -, written to a temporary file and copied out after the run.
    std::unique_ptr<StdoutFile> stdoutFile;
    try {
        // Named after the scene: a .glb names its root node after its file.
        const std::string stem = o.scene == "-" ? "scene" : std::filesystem::path(o.scene).stem().string();
        if (trajectoryToStdout)
            stdoutFile =
                std::make_unique<StdoutFile>(stem + (format == io::TrajectoryFormat::Csv    ? ".csv"
                                                     : format == io::TrajectoryFormat::Json ? ".json"
                                                                                            : ".glb"));
        else if (o.saveScene == "-" || o.metrics == "-")
            stdoutFile = std::make_unique<StdoutFile>("out.json");
    } catch (const std::exception& e) {
        err << "tumble: " << e.what() << "\n";
        return kFailure;
    }
    auto target = [&](const std::string& file) { return file == "-" ? stdoutFile->path().string() : file; };

    std::unique_ptr<io::TrajectoryWriter> trajectory;
    try {
        if (!o.out.empty() && !images) {
            io::ExportOptions options;
            options.jointForces = o.jointForces;
            trajectory = io::makeTrajectoryWriter(format, target(o.out), options);
            trajectory->begin(world->model(), scene, frameCount(world->model().settings),
                              world->model().settings.frameRate);
        }
    } catch (const std::exception& e) {
        err << "tumble: --out: " << e.what() << "\n";
        return kFailure;
    }
    // Opened before the run so that an unwritable path fails at once, and committed with the
    // trajectory so that a failed run leaves none of the files behind.
    std::unique_ptr<io::AtomicFile> savedScene, metricsFile;
    try {
        if (!o.saveScene.empty()) savedScene = std::make_unique<io::AtomicFile>(target(o.saveScene));
    } catch (const std::exception& e) {
        err << "tumble: --save-scene: " << e.what() << "\n";
        return kFailure;
    }
    try {
        if (!o.metrics.empty()) metricsFile = std::make_unique<io::AtomicFile>(target(o.metrics));
    } catch (const std::exception& e) {
        err << "tumble: --metrics: " << e.what() << "\n";
        return kFailure;
    }

    const Energy before = energy(world->model(), world->state());
    std::optional<RunMetrics> metrics;
    if (!o.metrics.empty()) metrics.emplace(*world);
    const auto t0 = std::chrono::steady_clock::now();
    RunResult result;
    const int frames = frameCount(world->model().settings);
    auto stoppedMessage = [&](int frame) {
        err << "tumble: stopped by " << signalName(StopSignals::received())
            << " at t = " << number(world->state().time) << " s (frame " << frame << " of " << frames
            << "); nothing was written\n";
        return 128 + StopSignals::received();
    };
    int frameReached = 0;
    // A long run says how far it is: once past two seconds, about once a second (in place
    // on a terminal), and its last line cleared at the end.
    const bool tty = isatty(2) != 0;
    const bool showProgress = !o.quiet && (o.progress || tty);
    auto lastShown = t0;
    bool shown = false;
    auto progress = [&](int k) {
        const auto now = std::chrono::steady_clock::now();
        if (!showProgress || now - t0 < std::chrono::seconds(2) || now - lastShown < std::chrono::seconds(1))
            return;
        lastShown = now;
        shown = true;
        const double elapsed = std::chrono::duration<double>(now - t0).count();
        char line[160];
        std::snprintf(line, sizeof line, "frame %d of %d, t = %.3g s, about %.0f s left", k, frames,
                      world->state().time, elapsed / std::max(k, 1) * (frames - 1 - k));
        err << (tty ? "\r" : "") << "tumble: " << line << (tty ? "\x1b[K" : "\n") << std::flush;
    };
    try {
        result = simulate(*world, [&](int k, const State& s) {
            frameReached = k;  // the world is at this frame's time
            if (StopSignals::received()) throw Stopped{};
            progress(k);
            if (trajectory) trajectory->frame(k, s);
            if (metrics) metrics->frame(*world);
        });
        if (StopSignals::received()) throw Stopped{};
    } catch (const Stopped&) {
        return stoppedMessage(frameReached);  // the outputs' temporaries go with their writers
    } catch (const SimulationError& e) {
        err << "tumble: " << sceneName << ": " << e.what() << "\n";
        return kFailure;
    } catch (const std::exception& e) {
        err << "tumble: --out: " << e.what() << "\n";
        return kFailure;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (shown && tty) err << "\r\x1b[K" << std::flush;  // the progress line goes

    // Images first (they simulate again and may be stopped), then every other output is
    // committed: a run stopped or failed before here leaves none of them.
    if (images) {
        // The editor's exporter simulates the scene again (the same frames: the engine is
        // deterministic) and draws each one.
        const bool video = o.out.back() != '/';
        const std::filesystem::path out(o.out);
        const std::string folder =
            video ? (out.parent_path() / (out.stem().string() + "-frames")).string() : o.out;
        const std::string message =
            imageRenderer()(scene, folder, video ? o.out : std::string(), o.imageWidth, o.imageHeight,
                            [] { return StopSignals::received() != 0; });
        if (StopSignals::received()) {
            err << "tumble: stopped by " << signalName(StopSignals::received())
                << " while drawing the images; nothing was written\n";
            return 128 + StopSignals::received();
        }
        if (!message.empty()) {
            err << "tumble: --out: " << message << "\n";
            return kFailure;
        }
    }

    try {
        // The small files written out first (a full disk fails them before anything is
        // renamed), then the trajectory, then their renames.
        if (savedScene) {
            savedScene->stream() << io::sceneToJson(scene);
            savedScene->ready();
        }
        if (metricsFile) {
            metricsFile->stream() << metrics->json(*world, result.steps, wall, before.total());
            metricsFile->ready();
        }
        if (trajectory) trajectory->finish();
        if (savedScene) savedScene->commit();
        if (metricsFile) metricsFile->commit();
        if (stdoutFile) stdoutFile->copyTo(out);
    } catch (const std::exception& e) {
        err << "tumble: " << e.what() << "\n";
        return kFailure;
    }
    if (!o.quiet) {
        const Model& m = world->model();
        const Energy after = energy(m, world->state());
        const Profile& p = world->profile();
        // Standard output carries a file: the report goes to standard error.
        std::ostream& report = stdoutFile ? err : out;
        report << "bodies: " << m.bodies.size() << "\n"
               << "integrator: " << m.integrator->name << "\n"
               << "dt: " << number(m.settings.dt) << "\n"
               << "step: " << number(stepUsed(m.settings)) << "\n"
               << "frames: " << result.frames << "\n"
               << "steps: " << result.steps << "\n"
               << "simulated_time: " << number(world->state().time) << "\n"
               << "wall_seconds: " << wall << "\n"
               << "energy_start: " << number(before.total()) << "\n"
               << "energy_end: " << number(after.total()) << "\n"
               << "energy_lost_contacts: " << number(world->ledger().lostInContacts) << "\n"
               << "energy_lost_friction: " << number(world->ledger().lostInFriction) << "\n"
               << "energy_position_correction: " << number(world->ledger().positionCorrection) << "\n"
               << "energy_lost_joints: " << number(world->ledger().lostInJoints) << "\n"
               << "energy_by_kinematic: " << number(world->ledger().doneByKinematic) << "\n"
               << "forces_seconds: " << p.forces << "\n"
               << "integrate_seconds: " << p.integrate << "\n"
               << "broadphase_seconds: " << p.broadphase << "\n"
               << "narrowphase_seconds: " << p.narrowphase << "\n"
               << "toi_seconds: " << p.timeOfImpact << "\n"
               << "impact_seconds: " << p.impactSolve << "\n"
               << "solve_seconds: " << p.solve << "\n"
               << "sleep_seconds: " << p.sleep << "\n"
               << "pairs: " << p.pairs << "\n"
               << "contact_points: " << p.contactPoints << "\n"
               << "impacts: " << p.impacts << "\n"
               << "impact_moments: " << p.impactMoments << "\n"
               << "impact_sweep_limits: " << p.impactSweepLimits << "\n"
               << "awake_body_steps: " << p.awakeBodySteps << "\n"
               << "parked_body_steps: " << p.parkedBodySteps << "\n"
               << "island_restarts: " << p.islandRestarts << "\n"
               << "still_body_steps: " << p.stillBodySteps << "\n"
               << "settled_bodies: " << p.settledBodies << "\n"
               << "threads: " << world->threads() << "\n"
               << "state_hash: " << hashHex(hashState(world->state())) << "\n";
    }
    return kOk;
}

}  // namespace

void setImageRenderer(ImageRenderer renderer) { imageRenderer() = std::move(renderer); }

namespace {

// A scene the editor can be asked to open: a file there, or a name ending in .json (the
// editor says when it is missing).
bool namesAScene(const std::string& arg) {
    if (arg.empty() || arg[0] == '-' || arg == "sweep") return false;
    std::error_code ec;
    if (std::filesystem::exists(arg, ec)) return true;
    std::string ext = std::filesystem::path(arg).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".json";
}

// What a first argument that is neither a flag nor a scene was likely meant to be.
std::string commandFor(const std::string& word) {
    std::string bare = word;
    while (!bare.empty() && bare[0] == '-') bare.erase(0, 1);
    const std::string guess = nearest(bare, {"sweep", "help", "headless", "version", "list-integrators"});
    if (guess.empty()) return {};
    return guess == "sweep" ? "tumble sweep" : "tumble --" + guess;
}

}  // namespace

bool wantsCommandLine(const std::vector<std::string>& args) {
    // The editor: no argument, one scene, or (from an editor's recovery) --recover FILE.
    if (args.empty()) return false;
    if (args.size() == 2 && args[0] == "--recover") return false;
    return !(args.size() == 1 && namesAScene(args[0]));
}

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (!args.empty() && args.front() == "sweep") return sweep::run({args.begin() + 1, args.end()}, out, err);
    for (const std::string& a : args) {
        if (a == "--help" || a == "-h") {
            out << helpText();
            return kOk;
        }
        if (a == "--version") {
            out << versionLine() << "\n";
            return kOk;
        }
        if (a == "--list-integrators") {
            for (const IntegratorInfo& info : integrators()) {
                out << info.name << (&info == &defaultIntegrator() ? " (default)" : "") << "\n    order "
                    << info.order << ", " << info.forceEvaluations << " force evaluation"
                    << (info.forceEvaluations > 1 ? "s" : "") << " per step: " << info.description << "\n";
            }
            return kOk;
        }
    }
    const bool headlessRun = std::find(args.begin(), args.end(), "--headless") != args.end();
    if (!headlessRun && !args.empty() && !args[0].empty() && args[0][0] != '-') {
        // A first word that is no command ("tumble help", "tumble swep ..."), or a scene
        // with options but no --headless.
        const std::string guess = commandFor(args[0]);
        if (namesAScene(args[0]) && guess.empty()) {
            err << "tumble: options run a scene without a window and need --headless: tumble --headless "
                << args[0] << " ... (tumble " << args[0] << " alone opens it in the editor)\n";
        } else {
            err << "tumble: '" << args[0] << "' is neither a scene file nor a command"
                << (guess.empty() ? std::string(" (see --help)") : "; did you mean " + guess + "?") << "\n";
        }
        return kInvalid;
    }
    try {
        return headless(parse(args), out, err);
    } catch (const UsageError& e) {
        err << "tumble: " << e.message << "\n";
        return kInvalid;
    }
}

}  // namespace tumble::cli
