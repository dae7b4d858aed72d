// The benchmark's scenes (issue 8), one library with the tests and the editor's samples
// (DESIGN.md, principle 10): where resources/scenes/ has the scene it is read from there,
// the rest is built here in code. Accuracy scenes carry an observer that turns a run into
// errors against a closed-form answer; speed scenes are plain SceneDescs.
#pragma once

#include "engine_adapter.h"

#include <tumble/scene.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tumble::bench {

/// resources/scenes, found from the working directory or the build's source tree.
std::filesystem::path scenesDir();
/// A sample scene file of resources/scenes (throws io::InputError).
SceneDesc sampleScene(const std::string& fileName);

/// Mass of a body as given (mass, or density times the primitive's volume).
double bodyMass(const BodyDesc& body);
/// Kinetic plus gravitational energy of body `i` of `scene` in the state `s` (J). Primitives only.
double bodyEnergy(const SceneDesc& scene, int i, const BodySample& s);
/// Angular momentum about the centre of mass, world axes. Primitives only.
Vec3 angularMomentum(const BodyDesc& body, const BodySample& s);

/// Watches a run step by step and gives its errors against the closed form.
class Observer {
public:
    virtual ~Observer() = default;
    /// After load, before the first step.
    virtual void start(const EngineAdapter& engine) = 0;
    /// After each step.
    virtual void observe(const EngineAdapter& engine) = 0;
    /// (error name, error) at the end; the first is the scene's main error.
    virtual std::vector<std::pair<std::string, double>> errors() const = 0;
};

struct AccuracyScene {
    std::string name;
    std::string about;  ///< what runs and what the closed form says
    SceneDesc scene;
    double duration = 1.0;  ///< simulated seconds, a whole number of every swept step
    std::function<std::unique_ptr<Observer>()> observer;
};

std::vector<AccuracyScene> accuracyScenes();

struct SpeedScene {
    std::string name;
    std::string about;
    std::function<SceneDesc()> build;  ///< built only when run (the big ones take memory)
    double dt = 1.0 / 60.0;
    int steps = 120;      ///< full run
    int quickSteps = 10;  ///< --quick
};

/// Built in scenes_speed.cpp. Each "skip" variant is its own scene (name suffixes
/// "-sleep-on"/"-sleep-off", "-far-ground").
std::vector<SpeedScene> speedScenes();

/// A square pyramid of unit boxes (half extent h, mass m): `layers` layers, the bottom one
/// layers x layers, each on the gaps of the one below; plus a ground plane.
SceneDesc boxPyramid(int layers, double h, double m, const Vec3& offset);

}  // namespace tumble::bench
