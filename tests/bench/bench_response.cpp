// Collision response benchmarks (run by hand, not a test; figures go to docs/benchmarks.md):
// - sleeping on and off on tower-20, pyramid-15, mass-ratio-stack and a pile of 200 random
//   boxes and spheres dropped on the ground: CPU time per simulated second, the profile's
//   time per stage, awake body steps, and what the stacks did (drift, tilt, energy);
// - solver iterations 5, 10, 20, 40 on tower-20 and pyramid-15 with sleeping off (the
//   solver works every step): cost against drift, the trade-off of the default 20;
// - the contact stages skipped: one body alone (nothing can touch, the stages are skipped)
//   against the same body above a ground it never reaches (the stages run, find nothing).
// Total times are process CPU time (std::clock): the machines this runs on are shared, and
// CPU time does not count the time other processes hold the core. The per-stage times are
// World::profile()'s, which are wall time (steady_clock) inside the step. Every time is
// the median of several runs where a run is cheap; the physics figures are the same in
// every run (the engine is deterministic).
// Usage: tumble-bench-response [--quick] [--scenes DIR]
//   --quick   2 simulated seconds instead of 10, one run each (a smoke run)
//   --scenes  the folder of the sample scenes (default: resources/scenes, found from the
//             working directory or from this source file's place)
#include <tumble/io/scene_file.h>
#include <tumble/world.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using namespace tumble;

namespace {

double cpuNow() {
    return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

double wallNow() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::filesystem::path scenesDir(const std::string& given) {
    if (!given.empty()) return given;
    if (std::filesystem::exists("resources/scenes/tower-20.json")) return "resources/scenes";
    // tests/bench/bench_response.cpp -> resources/scenes
    return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "resources" / "scenes";
}

// ---------------------------------------------------------------------------------------
// One run of a scene and what it did

struct RunFigures {
    double cpu = 0.0;   // process CPU seconds for the whole run
    double wall = 0.0;  // wall seconds
    Profile profile;
    // Of the dynamic bodies, from the start to the end of the run:
    double maxHorizontal = 0.0;  // largest horizontal (x, z) displacement of a centre of mass (m)
    double maxVertical = 0.0;    // largest |vertical displacement| (m)
    double maxTilt = 0.0;        // largest rotation from the start orientation (degrees)
    double maxSpeed = 0.0;       // fastest centre of mass at the end (m/s)
    double maxDepth = 0.0;       // deepest overlap of the contacts at the end, any pair (m)
    int asleep = 0;              // dynamic bodies asleep at the end
    int moving = 0;              // dynamic bodies faster than 1 cm/s at the end
    double kineticEnd = 0.0;     // kinetic energy at the end (J)
    std::string fastest;         // the fastest body at the end: shape, place, speeds
    std::string movingNote;      // which bodies are moving at the end
    double energyStart = 0.0, energyEnd = 0.0;
    double ledgerResidual = 0.0;  // energyEnd - (energyStart - lost + positionCorrection)
};

RunFigures runOnce(const SceneDesc& scene, double seconds) {
    World world(scene);
    const Model& model = world.model();
    const State start = world.state();
    const double h = model.settings.dt;
    const long steps = std::lround(seconds / h);

    RunFigures f;
    f.energyStart = energy(model, start).total();
    const double c0 = cpuNow(), w0 = wallNow();
    for (long k = 0; k < steps; ++k) world.step(h);
    f.cpu = cpuNow() - c0;
    f.wall = wallNow() - w0;
    f.profile = world.profile();

    const State& end = world.state();
    int fastest = -1;
    for (int i : model.dynamicBodies) {
        const BodyState &a = start.bodies[i], &b = end.bodies[i];
        const Vec3 d = b.x - a.x;
        f.maxHorizontal = std::max(f.maxHorizontal, std::hypot(d.x(), d.z()));
        f.maxVertical = std::max(f.maxVertical, std::abs(d.y()));
        const double angle = Eigen::AngleAxisd(b.q * a.q.conjugate()).angle();
        f.maxTilt =
            std::max(f.maxTilt, std::min(angle, 2 * std::numbers::pi - angle) * 180.0 / std::numbers::pi);
        const double speed = b.P.norm() * model.bodies[i].invMass;
        if (speed > f.maxSpeed) f.maxSpeed = speed, fastest = i;
        f.moving += speed > 0.01 ? 1 : 0;
        f.asleep += end.isAsleep(i) ? 1 : 0;
    }
    for (const auto& m : world.contacts()) f.maxDepth = std::max(f.maxDepth, m.maxDepth());
    const Energy e = energy(model, end);
    f.energyEnd = e.total();
    f.kineticEnd = e.kinetic;
    if (fastest >= 0) {
        const BodyModel& b = model.bodies[fastest];
        const BodyState& bs = end.bodies[fastest];
        const Derived d = derive(b, bs);
        char text[300];
        std::snprintf(
            text, sizeof text, "%s at (%.2f, %.4f, %.2f) m, v (%.3f, %.3f, %.3f) m/s, |omega| %.3f rad/s",
            toString(b.shape.type), bs.x.x(), bs.x.y(), bs.x.z(), d.v.x(), d.v.y(), d.v.z(), d.omega.norm());
        f.fastest = text;
        if (b.shape.type == ShapeType::Sphere) {
            // Speed of the sphere's lowest point: 0 when it rolls without slipping.
            const Vec3 slip = d.v + d.omega.cross(Vec3(0, -b.shape.radius, 0));
            std::snprintf(text, sizeof text, ", radius %.4f m, slip at the lowest point %.2e m/s",
                          b.shape.radius, slip.norm());
            f.fastest += text;
        }
    }
    int spheres = 0, far = 0;
    for (int i : model.dynamicBodies) {
        const BodyState& b = end.bodies[i];
        if (b.P.norm() * model.bodies[i].invMass <= 0.01) continue;
        spheres += model.bodies[i].shape.type == ShapeType::Sphere ? 1 : 0;
        far += std::hypot(b.x.x(), b.x.z()) > 5.0 ? 1 : 0;
    }
    f.movingNote = std::to_string(f.moving) + " moving: " + std::to_string(spheres) + " spheres, " +
                   std::to_string(f.moving - spheres) + " others; " + std::to_string(far) +
                   " of them more than 5 m from the middle";
    const EnergyLedger& l = world.ledger();
    f.ledgerResidual =
        f.energyEnd - (f.energyStart - l.lostInContacts - l.lostInFriction - l.lostInJoints + l.positionCorrection);
    return f;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The figures of `runs` runs: CPU time, wall time and each stage's time are medians, each
// taken on its own (a stage's wall time is inflated when another process takes the core
// during it, so the median of each filters that better than the median run's profile);
// the rest is the same in every run.
RunFigures runMedian(const SceneDesc& scene, double seconds, int runs) {
    std::vector<RunFigures> all;
    for (int r = 0; r < runs; ++r) all.push_back(runOnce(scene, seconds));
    RunFigures f = all.front();
    auto med = [&](auto field) {
        std::vector<double> v;
        for (const auto& r : all) v.push_back(field(r));
        return median(v);
    };
    f.cpu = med([](const RunFigures& r) { return r.cpu; });
    f.wall = med([](const RunFigures& r) { return r.wall; });
    for (double Profile::*stage :
         {&Profile::forces, &Profile::integrate, &Profile::broadphase, &Profile::narrowphase,
          &Profile::timeOfImpact, &Profile::impactSolve, &Profile::solve, &Profile::sleep})
        f.profile.*stage = med([stage](const RunFigures& r) { return r.profile.*stage; });
    return f;
}

// ---------------------------------------------------------------------------------------
// Scenes

// 200 bodies, half boxes and half spheres, of 0.2 to 0.5 m (half extents, radius) in random
// orientations on a jittered 5 x 5 lattice of 1.25 m, 8 layers from 1 m up, dropped at
// rest onto a ground plane. Fixed seed: the same pile every run.
SceneDesc pileScene() {
    std::mt19937 rng(20261129u);
    std::uniform_real_distribution<double> size(0.2, 0.5), jitter(-0.1, 0.1);
    std::normal_distribution<double> g(0.0, 1.0);
    SceneDesc s;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.restitution = 0.2;
    ground.friction = 0.6;
    s.bodies.push_back(ground);
    const double spacing = 1.25;
    for (int k = 0; k < 200; ++k) {
        const int layer = k / 25, row = (k % 25) / 5, col = k % 5;
        BodyDesc b;
        b.name = "body-" + std::to_string(k);
        if (k % 2 == 0) {
            b.shape.type = ShapeType::Box;
            b.shape.halfExtents = Vec3(size(rng), size(rng), size(rng));
        } else {
            b.shape.type = ShapeType::Sphere;
            b.shape.radius = size(rng);
        }
        b.density = 500.0;
        b.position = Vec3((col - 2) * spacing + jitter(rng), 1.0 + layer * spacing + jitter(rng),
                          (row - 2) * spacing + jitter(rng));
        b.orientation = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
        b.restitution = 0.2;
        b.friction = 0.6;
        s.bodies.push_back(b);
    }
    return s;
}

struct NamedScene {
    std::string name;
    SceneDesc scene;
    bool stack;  // starts at rest: drift and tilt mean something
};

// ---------------------------------------------------------------------------------------
// 1. Sleeping on and off

void benchSleeping(const std::vector<NamedScene>& scenes, double seconds, bool quick) {
    std::printf("Sleeping on and off, %.0f simulated s, dt from the scene, %s\n", seconds,
                quick ? "one run" : "median of 3 runs (1 for the pile)");
    std::printf("%-18s %5s %10s %10s %11s %7s %6s %8s %8s %8s %8s %9s %11s %10s %9s\n", "scene", "sleep",
                "cpu [s/s]", "wall [s/s]", "awake b.st", "asleep", "moving", "dx [mm]", "dy [mm]", "tilt [°]",
                "v [m/s]", "depth[mm]", "dE [J]", "ledger [J]", "KE [J]");
    std::vector<std::pair<std::string, Profile>> profiles;
    std::vector<std::string> notes;
    for (const auto& s : scenes) {
        for (bool sleeping : {false, true}) {
            SceneDesc d = s.scene;
            d.settings.sleeping = sleeping;
            const int runs = quick ? 1 : (s.stack ? 3 : 1);
            const RunFigures f = runMedian(d, seconds, runs);
            char drift[64] = "       -        -        -";
            if (s.stack)
                std::snprintf(drift, sizeof drift, "%8.3f %8.3f %8.3f", 1e3 * f.maxHorizontal,
                              1e3 * f.maxVertical, f.maxTilt);
            std::printf("%-18s %5s %10.4f %10.4f %11ld %7d %6d %s %8.4f %9.3f %11.3f %10.3f %9.4f\n",
                        s.name.c_str(), sleeping ? "on" : "off", f.cpu / seconds, f.wall / seconds,
                        f.profile.awakeBodySteps, f.asleep, f.moving, drift, f.maxSpeed, 1e3 * f.maxDepth,
                        f.energyEnd - f.energyStart, f.ledgerResidual, f.kineticEnd);
            profiles.emplace_back(s.name + (sleeping ? " on" : " off"), f.profile);
            if (f.maxSpeed > 0.01)
                notes.push_back(s.name + (sleeping ? " on" : " off") + ": " + f.movingNote + "; fastest " +
                                f.fastest);
        }
    }
    for (const auto& n : notes) std::printf("%s\n", n.c_str());
    std::printf(
        "cpu, wall: seconds per simulated second; awake b.st: dynamic bodies integrated,\n"
        "summed over steps; asleep, moving: bodies asleep, faster than 1 cm/s at the end;\n"
        "dx, dy: largest horizontal and vertical displacement of a body's centre from its\n"
        "start, tilt: largest rotation from its start orientation (stacks only); v: fastest\n"
        "body at the end; depth: deepest contact overlap at the end; dE: energy(end) -\n"
        "energy(start); ledger: dE + lost in contacts and friction - position correction\n"
        "(0 when the ledger accounts for every joule); KE: kinetic energy at the end\n\n");

    std::printf("Time per stage (profile, wall ms per simulated second)\n");
    std::printf("%-22s %8s %9s %8s %8s %8s %8s %8s %8s %9s %9s %9s %9s %8s\n", "scene, sleeping", "forces",
                "integr.", "broad", "narrow", "toi", "impact", "solve", "sleep", "pairs/st", "points/st",
                "impacts", "moments", "limited");
    for (const auto& [name, p] : profiles) {
        const double k = 1e3 / seconds;
        const double st = static_cast<double>(std::max(1L, p.steps));
        std::printf("%-22s %8.2f %9.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %9.1f %9.1f %9ld %9ld %8ld\n",
                    name.c_str(), k * p.forces, k * p.integrate, k * p.broadphase, k * p.narrowphase,
                    k * p.timeOfImpact, k * p.impactSolve, k * p.solve, k * p.sleep, p.pairs / st,
                    p.contactPoints / st, p.impacts, p.impactMoments, p.impactSweepLimits);
    }
    std::printf(
        "pairs/st, points/st: broadphase pairs and contact points per step; impacts: pairs\n"
        "that came into contact within a step, moments: moments of impact a step was cut at,\n"
        "limited: impact loops stopped by their bound, all over the run\n\n");
}

// ---------------------------------------------------------------------------------------
// 2. Solver iterations

void benchIterations(const std::vector<NamedScene>& scenes, double seconds, bool quick) {
    std::printf("Solver iterations, sleeping off, %.0f simulated s, %s\n", seconds,
                quick ? "one run" : "median of 3 runs");
    std::printf("%-18s %6s %11s %11s %8s %9s %9s %8s %10s %10s %10s\n", "scene", "iter.", "cpu [s/s]",
                "solve [s/s]", "dx [mm]", "dy [mm]", "tilt [°]", "v [m/s]", "depth [mm]", "dE [J]",
                "ledger [J]");
    for (const auto& s : scenes) {
        for (int iterations : {5, 10, 20, 40}) {
            SceneDesc d = s.scene;
            d.settings.sleeping = false;
            d.settings.solverIterations = iterations;
            const RunFigures f = runMedian(d, seconds, quick ? 1 : 3);
            std::printf("%-18s %6d %11.4f %11.4f %8.3f %9.3f %9.3f %8.4f %10.3f %10.3f %10.3f\n",
                        s.name.c_str(), iterations, f.cpu / seconds, f.profile.solve / seconds,
                        1e3 * f.maxHorizontal, 1e3 * f.maxVertical, f.maxTilt, f.maxSpeed, 1e3 * f.maxDepth,
                        f.energyEnd - f.energyStart, f.ledgerResidual);
        }
    }
    std::printf("solve: the contact solver's share (profile, wall); other columns as above\n\n");
}

// ---------------------------------------------------------------------------------------
// 3. Contact stages skipped

void benchSkip(bool quick) {
    // A 1 x 0.6 x 0.4 m box tumbling in free fall; every simulated second it is put back
    // at the start (setState), so it never falls farther than 4.9 m. With the ground at
    // y = -10 it never comes near it.
    SceneDesc alone;
    BodyDesc box;
    box.name = "box";
    box.shape.type = ShapeType::Box;
    box.shape.halfExtents = Vec3(0.5, 0.3, 0.2);
    box.mass = 1.0;
    box.angularVelocity = Vec3(1.0, 2.0, 3.0);
    alone.bodies.push_back(box);
    SceneDesc withGround = alone;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    ground.shape.distance = -10.0;
    withGround.bodies.insert(withGround.bodies.begin(), ground);

    const int perReset = 240;  // one simulated second at the default dt
    const int resets = quick ? 100 : 500;
    const int runs = quick ? 1 : 5;
    std::printf("Contact stages skipped: one tumbling box in free fall, %d steps a run, %s\n",
                perReset * resets, quick ? "one run" : "median of 5 runs");
    std::printf("%-26s %14s %8s %8s %8s %8s %8s %9s %10s\n", "scene", "per step [ns]", "forces", "integr.",
                "broad", "narrow", "toi", "pairs", "lowest y");
    for (const auto* scene : {&alone, &withGround}) {
        std::vector<std::pair<double, Profile>> results;  // CPU s per step, profile
        double lowest = 0.0;
        for (int r = 0; r < runs; ++r) {
            World world(*scene);
            const State start = world.state();
            const double h = world.model().settings.dt;
            double low = start.bodies.back().x.y();
            const double c0 = cpuNow();
            for (int k = 0; k < resets; ++k) {
                world.setState(start);
                for (int j = 0; j < perReset; ++j) world.step(h);
                low = std::min(low, world.state().bodies.back().x.y());
            }
            results.emplace_back((cpuNow() - c0) / (perReset * resets), world.profile());
            lowest = low;
        }
        std::sort(results.begin(), results.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        const auto& [perStep, p] = results[results.size() / 2];
        const double st = static_cast<double>(p.steps);
        std::printf("%-26s %14.1f %8.1f %8.1f %8.1f %8.1f %8.1f %9ld %10.2f\n",
                    scene == &alone ? "box alone" : "box + ground 10 m below", 1e9 * perStep,
                    1e9 * p.forces / st, 1e9 * p.integrate / st, 1e9 * p.broadphase / st,
                    1e9 * p.narrowphase / st, 1e9 * p.timeOfImpact / st, p.pairs, lowest);
    }
    std::printf(
        "per step: process CPU time; the stage columns: profile (wall) ns per step; pairs:\n"
        "broadphase pairs over the run; lowest y: lowest centre of the box (the ground is at -10)\n\n");
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false;
    std::string dir;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0)
            quick = true;
        else if (std::strcmp(argv[i], "--scenes") == 0 && i + 1 < argc)
            dir = argv[++i];
        else {
            std::fprintf(stderr, "usage: tumble-bench-response [--quick] [--scenes DIR]\n");
            return 2;
        }
    }
    const std::filesystem::path scenes = scenesDir(dir);
    std::vector<NamedScene> all;
    try {
        for (const char* name : {"tower-20", "pyramid-15", "mass-ratio-stack"})
            all.push_back({name, io::readSceneFile(scenes / (std::string(name) + ".json")), true});
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    all.push_back({"pile-200", pileScene(), false});

    const double seconds = quick ? 2.0 : 10.0;
    const double t0 = cpuNow();
    benchSleeping(all, seconds, quick);
    benchIterations({all[0], all[1]}, seconds, quick);
    benchSkip(quick);
    std::printf("total CPU time of this benchmark: %.1f s\n", cpuNow() - t0);
    return 0;
}
