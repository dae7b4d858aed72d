// Work-precision: every accuracy scene, engine and mode over a sweep of steps from 1/30 s
// to 1/3840 s. The first run of a point gives its errors (an Observer watches every step);
// the timed runs after it do nothing but step, and the fastest of them is kept.
#include "bench.h"
#include "scenes.h"

#include <cmath>
#include <cstdio>
#include <exception>

namespace tumble::bench {

std::vector<std::string> accuracySceneNames() {
    std::vector<std::string> names;
    for (const AccuracyScene& s : accuracyScenes()) names.push_back(s.name);
    return names;
}

namespace {

// One point of the sweep; false when the engine refused the scene (reason printed).
bool runPoint(EngineAdapter& engine, const AccuracyScene& scene, const std::string& mode, double dt, int runs,
              std::vector<AccuracyRow>& rows) {
    std::string why;
    const long steps = std::lround(scene.duration / dt);
    std::unique_ptr<Observer> obs = scene.observer();
    if (!engine.load(scene.scene, mode, dt, &why)) {
        std::printf("  %-8s %-20s n/a: %s\n", engine.name().c_str(), mode.c_str(), why.c_str());
        return false;
    }
    double best = 1e300;
    std::vector<std::pair<std::string, double>> errors;
    try {
        obs->start(engine);
        double t0 = wallNow();
        for (long i = 0; i < steps; ++i) {
            engine.step();
            obs->observe(engine);
        }
        best = wallNow() - t0;
        errors = obs->errors();
    } catch (const std::exception& e) {
        // A diverging run (non-finite state) is a result, not a failure of the benchmark.
        errors = obs->errors();
        for (auto& [name, err] : errors) err = INFINITY;
        std::printf("  %-8s %-20s dt 1/%.0f: stopped: %s\n", engine.name().c_str(), mode.c_str(), 1 / dt,
                    e.what());
        runs = 0;
    }
    for (int r = 1; r < runs; ++r) {
        engine.load(scene.scene, mode, dt, nullptr);
        const double t0 = wallNow();
        for (long i = 0; i < steps; ++i) engine.step();
        best = std::min(best, wallNow() - t0);
    }
    for (const auto& [name, err] : errors)
        rows.push_back({scene.name, engine.name(), mode, dt, steps, best, name, err});
    std::printf("  %-8s %-17s dt 1/%-5.0f %8.3f ms/sim-s  %s %.3g\n", engine.name().c_str(), mode.c_str(),
                1 / dt, 1e3 * best / scene.duration, errors.front().first.c_str(), errors.front().second);
    return true;
}

}  // namespace

bool runAccuracy(const Options& opt, std::vector<AccuracyRow>& rows) {
    std::vector<double> dts;
    if (opt.quick) {
        dts = {1.0 / 60.0, 1.0 / 240.0};
    } else {
        for (int d = 30; d <= 3840; d *= 2) dts.push_back(1.0 / d);
    }
    const int runs = opt.quick ? 1 : opt.runs;
    std::vector<std::unique_ptr<EngineAdapter>> engines = makeEngines(opt);
    for (const AccuracyScene& scene : accuracyScenes()) {
        if (!opt.scene.empty() && opt.scene != scene.name) continue;
        std::printf("\n== %s: %s\n", scene.name.c_str(), scene.about.c_str());
        for (auto& engine : engines)
            for (const std::string& mode : engine->modes())
                for (double dt : dts)
                    if (!runPoint(*engine, scene, mode, dt, runs, rows)) break;
        std::fflush(stdout);
    }
    return true;
}

}  // namespace tumble::bench
