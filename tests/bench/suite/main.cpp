// tumble-bench (issue 8): Tumble against its peers on one library of scenes.
//   tumble-bench                      everything: work-precision, speed, stress
//   tumble-bench --quick              a reduced set in under a minute (the CI smoke run):
//                                     steps 1/60 and 1/240, a few steps of each speed scene,
//                                     shorter stress runs on Tumble alone
//   tumble-bench --scene NAME         one scene or stress test (see --list), or a whole part:
//                                     accuracy, speed, stress or export (the trajectory
//                                     writers' time against the bodies) or convex-parts (the
//                                     split of concave meshes, timed); or stacks (the stress tests
//                                     STACK@1/N, with the stability-against-step plot)
//   tumble-bench --engines tumble,bullet,ode,mujoco,jolt   which engines (default: all built)
//   tumble-bench --out DIR            where the CSV, plots and summary.md go (bench-out)
//   tumble-bench --runs N             timed runs per accuracy point, the minimum kept (3)
//   tumble-bench --speed-runs N       runs of each speed row, the fastest kept (1)
//   tumble-bench --list               the scenes and the engines built
// Exit status: 0, or 1 when a run crashed, threw or left a non-finite state, or Tumble
// failed a stress test. Timing never decides it.
#include "bench.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <unistd.h>

namespace tumble::bench {

double wallNow() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string selfPath() {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    return n > 0 ? std::string(buf, n) : "tumble-bench";
}

std::unique_ptr<EngineAdapter> makeEngine(const std::string& name) {
    if (name == "tumble") return makeTumbleAdapter();
    if (name == "bullet") return makeBulletAdapter();
    if (name == "ode") return makeOdeAdapter();
    if (name == "mujoco") return makeMujocoAdapter();
    if (name == "jolt") return makeJoltAdapter();
    return nullptr;
}

std::vector<std::unique_ptr<EngineAdapter>> makeEngines(const Options& opt) {
    std::vector<std::unique_ptr<EngineAdapter>> out;
    for (const std::string& name : opt.engines) {
        if (auto e = makeEngine(name)) {
            out.push_back(std::move(e));
        } else {
            static std::vector<std::string> told;
            if (std::find(told.begin(), told.end(), name) == told.end()) {
                std::printf("%s: not built, skipped\n", name.c_str());
                told.push_back(name);
            }
        }
    }
    return out;
}

}  // namespace tumble::bench

using namespace tumble::bench;

namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

void list() {
    std::printf("accuracy scenes (work-precision):\n");
    for (const auto& n : accuracySceneNames()) std::printf("  %s\n", n.c_str());
    std::printf("speed scenes:\n");
    for (const auto& n : speedSceneNames()) std::printf("  %s\n", n.c_str());
    std::printf("stress tests:\n");
    for (const auto& n : stressTestNames()) std::printf("  %s\n", n.c_str());
    std::printf("engines:\n");
    for (const char* n : {"tumble", "bullet", "ode", "mujoco", "jolt"}) {
        auto e = makeEngine(n);
        std::string modes;
        if (e)
            for (const auto& m : e->modes()) modes += (modes.empty() ? "" : ", ") + m;
        std::printf("  %-7s %s\n", n, e ? modes.c_str() : "not built");
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 2 && std::strcmp(argv[1], "--child") == 0 && std::strcmp(argv[2], "export") == 0)
        return exportChildMain(argc, argv);
    if (argc > 1 && std::strcmp(argv[1], "--child") == 0) return childMain(argc, argv);
    Options opt;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--quick") {
            opt.quick = true;
        } else if (a == "--list") {
            list();
            return 0;
        } else if (a == "--scene" && more) {
            opt.scene = argv[++i];
        } else if (a == "--engines" && more) {
            opt.engines.clear();
            std::stringstream in(argv[++i]);
            for (std::string e; std::getline(in, e, ',');) opt.engines.push_back(e);
        } else if (a == "--out" && more) {
            opt.out = argv[++i];
        } else if (a == "--runs" && more) {
            opt.runs = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--speed-runs" && more) {
            opt.speedRuns = std::max(1, std::atoi(argv[++i]));
        } else {
            std::fprintf(stderr,
                         "usage: tumble-bench [--quick] [--scene NAME] [--engines tumble,bullet,ode,mujoco,jolt] "
                         "[--out DIR] [--runs N] [--speed-runs N] [--list]\n");
            return 2;
        }
    }
    // A part's name runs the whole part (the speed part's stage plot shows every scene).
    const bool part = opt.scene == "accuracy" || opt.scene == "speed" || opt.scene == "stress" ||
                      opt.scene == "export" || opt.scene == "convex-parts";
    const std::string only = part ? opt.scene : std::string();
    if (part) opt.scene.clear();
    const bool all = opt.scene.empty() && !part;
    if (!all && !part && opt.scene != "stacks" && !contains(accuracySceneNames(), opt.scene) && !contains(speedSceneNames(), opt.scene) &&
        !contains(stressTestNames(), opt.scene)) {
        std::fprintf(stderr, "no scene or test named %s (see --list)\n", opt.scene.c_str());
        return 2;
    }
    std::filesystem::create_directories(opt.out);
    std::filesystem::remove(opt.out / "summary.md");
    const double t0 = wallNow();
    bool ok = true;

    std::vector<AccuracyRow> accuracy;
    if (all || only == "accuracy" || contains(accuracySceneNames(), opt.scene)) {
        std::printf("# Work-precision%s\n", opt.quick ? " (quick: steps 1/60 and 1/240, one run)" : "");
        ok = runAccuracy(opt, accuracy) && ok;
        writeAccuracy(opt, accuracy);
        std::printf("(work-precision: %.1f s)\n", wallNow() - t0);
    }
    std::vector<SpeedRow> speed;
    if (all || only == "speed" || contains(speedSceneNames(), opt.scene)) {
        std::printf("\n# Speed%s\n", opt.quick ? " (quick: a few steps each)" : "");
        ok = runSpeed(opt, speed) && ok;
        writeSpeed(opt, speed);
        std::printf("(so far: %.1f s)\n", wallNow() - t0);
    }
    std::vector<StressRow> stress;
    if (all || only == "stress" || opt.scene == "stacks" || contains(stressTestNames(), opt.scene)) {
        std::printf("\n# Stability stress%s\n", opt.quick ? " (quick: shorter runs, Tumble alone)" : "");
        ok = runStress(opt, stress) && ok;
        writeStress(opt, stress);
    }
    if (all || only == "export") {
        std::printf("\n# Trajectory export%s\n", opt.quick ? " (quick: 250 and 500 bodies)" : "");
        std::vector<ExportRow> exports;
        ok = runExport(opt, exports) && ok;
        writeExport(opt, exports);
    }
    if ((all && !opt.quick) || only == "convex-parts") {
        std::printf("\n# Convex parts\n");
        std::vector<ConvexPartsRow> parts;
        ok = runConvexParts(opt, parts) && ok;
        writeConvexParts(opt, parts);
    }
    std::printf("\n%s in %.1f s; CSV, plots and summary.md in %s\n", ok ? "done" : "FAILED", wallNow() - t0,
                opt.out.c_str());
    return ok ? 0 : 1;
}
