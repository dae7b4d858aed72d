// Speed: each scene, engine by engine, in a child process of its own (this program run
// with --child), so the peak memory it reports is that run's and a crash is reported, not
// suffered. The child prints one line, "RESULT key=value ...", that the parent reads back.
#include "adapter_tumble.h"
#include "bench.h"
#include "scenes.h"

#include <tumble/model.h>

#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace tumble::bench {

std::vector<std::string> speedSceneNames() {
    std::vector<std::string> names;
    for (const SpeedScene& s : speedScenes()) names.push_back(s.name);
    return names;
}

namespace {

double vmKB(const char* key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) return std::atof(line.c_str() + std::strlen(key));
    return 0.0;
}

// With TUMBLE_BENCH_MEMORY set, where the child's memory is (stderr): its peak and resident
// size beyond `base` (kB), malloc's heap (arena, in use, mapped chunks) and the resident
// kB of each mapping by name (the program's code, [heap], each library, anonymous maps).
// Once the scene is loaded and again at the end, so that two engines' growth can be set
// side by side (docs/benchmarks.md, "Where the memory is").
void memoryReport(const char* when, double base) {
    if (!std::getenv("TUMBLE_BENCH_MEMORY")) return;
    const struct mallinfo2 mi = mallinfo2();
    std::fprintf(stderr, "MEMORY %s peak=%.0f rss=%.0f arena=%zu inuse=%zu mapped=%zu (kB above base; bytes)\n",
                 when, vmKB("VmHWM:") - base, vmKB("VmRSS:") - base, mi.arena, mi.uordblks, mi.hblkhd);
    std::ifstream maps("/proc/self/smaps");
    std::map<std::string, long> byName;
    std::string line, name;
    while (std::getline(maps, line)) {
        if (line.rfind("Rss:", 0) == 0) {
            byName[name] += std::atol(line.c_str() + 4);
        } else if (!line.empty() && std::isxdigit(static_cast<unsigned char>(line[0])) &&
                   line.find(' ') < line.find(':')) {  // a mapping's first line: range perms offset dev inode [name]
            std::istringstream fields(line);
            std::string range, perms, offset, dev, inode;
            fields >> range >> perms >> offset >> dev >> inode;
            std::getline(fields >> std::ws, name);
            name = (name.empty() ? "anonymous" : name) + " " + perms;
        }
    }
    for (const auto& [mapping, kb] : byName)
        if (kb > 0) std::fprintf(stderr, "MEMORY %s %6ld kB %s\n", when, kb, mapping.c_str());
}

// How far joint j is from holding in the engine's present state (m): its anchors' distance
// (ball, hinge, fixed), that distance square to the axis (slider), or off the length
// (distance; a rope only when longer).
double jointGap(const JointModel& j, const EngineAdapter& engine) {
    const BodySample a = engine.body(j.a);
    const Vec3 pa = a.x + a.q * j.anchorA;
    Vec3 pb = j.anchorB;
    if (j.b >= 0) {
        const BodySample b = engine.body(j.b);
        pb = b.x + b.q * j.anchorB;
    }
    const Vec3 d = pa - pb;
    switch (j.type) {
        case JointType::Distance: return std::abs(d.norm() - j.length);
        case JointType::Rope: return std::max(0.0, d.norm() - j.length);
        case JointType::Slider: {
            const Vec3 axis = a.q * j.axisA;
            return (d - d.dot(axis) * axis).norm();
        }
        default: return d.norm();
    }
}

}  // namespace

int childMain(int argc, char** argv) {
    const char* usage = "usage: tumble-bench --child speed SCENE ENGINE MODE [--quick] [--substeps N]\n";
    if (argc < 6 || std::strcmp(argv[2], "speed") != 0) {
        std::fprintf(stderr, "%s", usage);
        return 2;
    }
    const std::string sceneName = argv[3], engineName = argv[4], mode = argv[5];
    // --substeps N: each of the scene's frames (its dt) stepped as N steps of dt / N, the
    // time and the joints' gap still per frame. What a peer's accuracy costs: its joints
    // held as Tumble's are (docs/benchmarks.md, "at matched accuracy").
    bool quick = false;
    int substeps = 1;
    for (int i = 6; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else if (std::strcmp(argv[i], "--substeps") == 0 && i + 1 < argc) {
            char* end = nullptr;
            const long n = std::strtol(argv[++i], &end, 10);
            if (*end != '\0' || n < 1 || n > 1000) {
                std::fprintf(stderr, "tumble-bench: --substeps wants a whole number from 1 to 1000, not '%s'\n", argv[i]);
                return 2;
            }
            substeps = static_cast<int>(n);
        } else {
            std::fprintf(stderr, "tumble-bench: unknown option '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
    const double base = vmKB("VmHWM:");
    for (SpeedScene& sc : speedScenes()) {
        if (sc.name != sceneName) continue;
        std::unique_ptr<EngineAdapter> engine = makeEngine(engineName);
        std::string why;
        bool loaded = false;
        // Which bodies move, and the lowest static body's place: a body that ends a metre
        // below it has fallen through the ground.
        std::vector<bool> dynamic;
        double floorY = std::numeric_limits<double>::infinity();
        Model jointed;  // the scene's joints as Tumble reads them (anchors from the centres of mass)
        {
            const SceneDesc scene = sc.build();  // freed once the engine has its own copy
            if (!scene.joints.empty()) jointed = compile(scene);
            for (const BodyDesc& b : scene.bodies) {
                dynamic.push_back(b.motion == Motion::Dynamic);
                if (b.motion == Motion::Static) floorY = std::min(floorY, b.position.y());
            }
            loaded = engine && engine->load(scene, mode, sc.dt / substeps, &why);
        }
        if (!loaded) {
            std::printf("NA %s\n", engine ? why.c_str() : "not built");
            return 0;
        }
        const int steps = quick ? sc.quickSteps : sc.steps;
        memoryReport("loaded", base);
        double total = 0, worst = 0, contacts = 0, gap = 0, deepest = 0;
        auto* tumble = dynamic_cast<TumbleAdapter*>(engine.get());
        try {
            for (int i = 0; i < steps; ++i) {
                const double t0 = wallNow();
                for (int k = 0; k < substeps; ++k) engine->step();
                const double t = wallNow() - t0;
                total += t;
                worst = std::max(worst, t);
                contacts += engine->contactCount();
                // The joints' largest gap over the run (outside the timing).
                for (const JointModel& j : jointed.joints) gap = std::max(gap, jointGap(j, *engine));
                // Tumble's deepest overlap in a step's poses, what a recorded frame would show.
                if (tumble) deepest = std::max(deepest, tumble->world().deepestOverlap());
            }
        } catch (const std::exception& e) {
            std::printf("FAIL %s\n", e.what());
            return 1;
        }
        // How settled the scene is at the end (what the speed bought): the bodies still
        // moving faster than 1 cm/s (a heap that has come to rest has few; rocks that keep
        // jittering or rolling count), and those that fell through the ground.
        memoryReport("end", base);
        int stillMoving = 0, fellThrough = 0;
        for (int i = 0; i < engine->bodyCount(); ++i) {
            if (i >= static_cast<int>(dynamic.size()) || !dynamic[i]) continue;
            const BodySample b = engine->body(i);
            stillMoving += b.v.norm() > 0.01;
            fellThrough += std::isfinite(floorY) && b.x.y() < floorY - 1.0;  // no ground, no falling through
        }
        std::printf("RESULT bodies=%d steps=%d ms=%.6g max=%.6g contacts=%.6g peak=%.6g base=%.6g moving=%d fell=%d",
                    engine->bodyCount(), steps, 1e3 * total / steps, 1e3 * worst, contacts / steps,
                    vmKB("VmHWM:") / 1024, base / 1024, stillMoving, fellThrough);
        if (!jointed.joints.empty()) std::printf(" gap=%.6g", gap);
        if (auto* t = tumble) {
            const Profile& p = t->world().profile();
            const double k = 1e3 / steps;
            std::printf(
                " forces=%.6g integrate=%.6g broadphase=%.6g narrowphase=%.6g toi=%.6g impact=%.6g "
                "solve=%.6g sleep=%.6g pairs=%.6g reused=%.6g apart=%.6g awake=%.6g cuts=%.6g parked=%.6g restarts=%.6g "
                "still=%.6g",
                p.forces * k, p.integrate * k, p.broadphase * k, p.narrowphase * k, p.timeOfImpact * k,
                p.impactSolve * k, p.solve * k, p.sleep * k, double(p.pairs) / steps, double(p.pairsReused) / steps,
                double(p.pairsApart) / steps, double(p.awakeBodySteps) / steps, double(p.impactMoments) / steps,
                double(p.parkedBodySteps) / steps, double(p.islandRestarts) / steps, double(p.stillBodySteps) / steps);
            // The end state's hash: a change meant to leave the results bit for bit as they
            // were shows it here (the parent reads numbers only and skips it).
            if (!jointed.joints.empty()) std::printf(" splits=%.6g", double(p.jointSplits) / steps);
            std::printf(" deep=%.6g settled=%.6g", deepest, double(p.settledBodies) / steps);
            std::printf(" searches=%.6g kept=%.6g", double(p.impactSearches) / steps,
                        double(p.impactSearchesKept) / steps);
            std::printf(" state=%016llx", static_cast<unsigned long long>(hashState(t->world().state())));
        }
        std::printf("\n");
        return 0;
    }
    std::printf("FAIL no speed scene %s\n", sceneName.c_str());
    return 1;
}

namespace {

// One run of a speed row in a child process (a crash is reported, not suffered, and the
// peak memory is the run's own).
SpeedRow speedRun(const std::string& self, const std::string& name, const std::string& engineName,
                  const std::string& mode, bool quick, bool& ok) {
    SpeedRow row;
    row.scene = name;
    row.engine = engineName;
    row.mode = mode;
    // A bound on each run: a peer that takes minutes to build a big model is reported, not waited
    // for.
    const int limit = quick ? 2 : 120;
    const std::string cmd = "timeout " + std::to_string(limit) + " '" + self + "' --child speed " + name +
                            " " + row.engine + " " + row.mode + (quick ? " --quick" : "") + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    std::string out;
    char buf[1024];
    while (pipe && std::fgets(buf, sizeof buf, pipe)) out += buf;
    const int status = pipe ? pclose(pipe) : -1;
    std::map<std::string, double> kv;
    const size_t at = out.find("RESULT ");
    if (at != std::string::npos) {
        std::istringstream in(out.substr(at + 7));
        std::string tok;
        while (in >> tok)
            if (auto eq = tok.find('='); eq != std::string::npos)
                kv[tok.substr(0, eq)] = std::atof(tok.c_str() + eq + 1);
    }
    if (status != 0 || kv.empty()) {
        const size_t na = out.find("NA ");
        if (status == 0 && na != std::string::npos) {
            row.note = "n/a: " + out.substr(na + 3);
        } else if (WIFEXITED(status) && WEXITSTATUS(status) == 124) {
            row.note = "stopped after " + std::to_string(limit) + " s (the time limit of a run)";
        } else {
            // A peer that fails is a finding for the tables (ODE's dWorldStep runs out
            // of memory on pyramid-1240); only Tumble failing fails the benchmark.
            row.ok = false;
            if (row.engine == "tumble") ok = false;
            row.note = "failed (status " + std::to_string(status) + "): " + out.substr(0, 300);
        }
        while (!row.note.empty() && row.note.back() == '\n') row.note.pop_back();
    } else {
        row.bodies = static_cast<int>(kv["bodies"]);
        row.steps = static_cast<int>(kv["steps"]);
        row.msPerStep = kv["ms"];
        row.msMaxStep = kv["max"];
        row.contactsPerStep = kv["contacts"];
        row.peakMB = kv["peak"];
        row.movingAtEnd = static_cast<int>(kv["moving"]);
        row.fellThrough = static_cast<int>(kv["fell"]);
        row.baseMB = kv["base"];
        if (kv.count("gap")) row.jointGap = kv["gap"];
        row.forces = kv["forces"], row.integrate = kv["integrate"], row.broadphase = kv["broadphase"];
        row.narrowphase = kv["narrowphase"], row.toi = kv["toi"], row.impact = kv["impact"];
        row.solve = kv["solve"], row.sleep = kv["sleep"];
        row.pairsPerStep = kv["pairs"], row.awakePerStep = kv["awake"];
        row.cutsPerStep = kv["cuts"], row.parkedPerStep = kv["parked"], row.restartsPerStep = kv["restarts"];
    }
    return row;
}

}  // namespace

bool runSpeed(const Options& opt, std::vector<SpeedRow>& rows) {
    bool ok = true;
    const std::string self = selfPath();
    std::vector<std::unique_ptr<EngineAdapter>> engines = makeEngines(opt);
    for (const std::string& name : speedSceneNames()) {
        if (!opt.scene.empty() && opt.scene != name) continue;
        // Tumble three times: impacts at their moment (the default), then at the end of the
        // step as the peers resolve them, single-threaded (the headline) and on two threads.
        std::vector<std::pair<EngineAdapter*, std::string>> runs;
        for (auto& engine : engines) {
            const std::string first = engine->modes().front();
            runs.emplace_back(engine.get(), first);
            if (engine->name() != "tumble") continue;
            runs.emplace_back(engine.get(), first + kEndOfStep);
            runs.emplace_back(engine.get(), first + kEndOfStep + kTwoThreads);
        }
        for (auto& [engine, mode] : runs) {
            // The fastest of opt.speedRuns runs, with its own figures; a run that failed, was
            // stopped or does not apply is not repeated.
            SpeedRow row;
            for (int k = 0; k < opt.speedRuns; ++k) {
                SpeedRow one = speedRun(self, name, engine->name(), mode, opt.quick, ok);
                const bool first = k == 0;
                const bool faster = one.note.empty() && one.msPerStep < row.msPerStep;
                if (first || faster || !one.note.empty()) row = one;  // a failure is the finding
                if (!row.note.empty()) break;
            }
            const std::string gap =
                row.jointGap >= 0.0 ? "  joint gap " + std::to_string(1e3 * row.jointGap) + " mm" : "";
            std::printf(
                "  %-22s %-8s %-12s %9.3f ms/step (max %.2f)  %8.1f contacts  %7.1f MB  %4d moving %4d "
                "fell%s  %s\n",
                name.c_str(), row.engine.c_str(), row.mode.c_str(), row.msPerStep, row.msMaxStep,
                row.contactsPerStep, row.peakMB - row.baseMB, row.movingAtEnd, row.fellThrough, gap.c_str(),
                row.note.c_str());
            std::fflush(stdout);
            rows.push_back(row);
        }
    }
    return ok;
}

}  // namespace tumble::bench
