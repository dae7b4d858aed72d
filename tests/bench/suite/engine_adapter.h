// One physics engine behind the benchmark (issue 8): Tumble itself or a peer (Bullet, ODE,
// MuJoCo), driven through the same small interface so every scene and every measurement is
// written once. A scene is given as Tumble's own SceneDesc (tumble/scene.h); an adapter
// translates what its engine can do and refuses, with a reason, what it cannot (a shape,
// a force kind), so the tables say "n/a" rather than measuring something else.
#pragma once

#include <tumble/math.h>
#include <tumble/scene.h>

#include <memory>
#include <string>
#include <vector>

namespace tumble::bench {

/// A body's state as every engine can give it: world centre of mass, orientation (body to
/// world), linear and angular velocity, all in world coordinates.
struct BodySample {
    Vec3 x = Vec3::Zero();
    Quat q = Quat::Identity();
    Vec3 v = Vec3::Zero();
    Vec3 w = Vec3::Zero();
};

class EngineAdapter {
public:
    virtual ~EngineAdapter() = default;

    /// "tumble", "bullet", "ode", "mujoco", "jolt".
    virtual std::string name() const = 0;
    /// The settings this engine is measured in, most accurate first ("rk4", "splitting",
    /// "gyroscopic-implicit", "quickstep", "implicit", ...), each documented in
    /// docs/benchmarks.md.
    virtual std::vector<std::string> modes() const = 0;

    /// Builds the scene in `mode` with the fixed step `dt` (s). False, with the reason in
    /// `why`, when the engine cannot represent the scene (the benchmark reports n/a).
    virtual bool load(const SceneDesc& scene, const std::string& mode, double dt, std::string* why) = 0;
    /// One step of dt.
    virtual void step() = 0;
    /// Simulated time since load (s).
    virtual double time() const = 0;

    virtual int bodyCount() const = 0;
    /// Body `i` of the scene (scene order; static bodies included).
    virtual BodySample body(int i) const = 0;
    /// Contact points after the last step (the engine's own count).
    virtual int contactCount() const = 0;
};

/// Each returns null when that engine was not found at build time (the peers are optional).
std::unique_ptr<EngineAdapter> makeTumbleAdapter();
std::unique_ptr<EngineAdapter> makeBulletAdapter();
std::unique_ptr<EngineAdapter> makeOdeAdapter();
std::unique_ptr<EngineAdapter> makeMujocoAdapter();
std::unique_ptr<EngineAdapter> makeJoltAdapter();

}  // namespace tumble::bench
