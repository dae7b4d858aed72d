// Accuracy scenes and their closed forms. Each observer reads only BodySamples, so the same
// error is computed for every engine.
#include "scenes.h"

#include "adapter_tumble.h"

#include <tumble/io/scene_file.h>
#include <tumble/mass.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace tumble::bench {

std::filesystem::path scenesDir() {
    if (std::filesystem::exists("resources/scenes/tower-20.json")) return "resources/scenes";
#ifdef TUMBLE_BENCH_SCENES_DIR
    return TUMBLE_BENCH_SCENES_DIR;
#else
    return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path().parent_path() /
           "resources" / "scenes";
#endif
}

SceneDesc sampleScene(const std::string& fileName) {
    return io::readSceneFile(scenesDir() / fileName);
}

double bodyMass(const BodyDesc& body) {
    if (body.mass) return *body.mass;
    if (body.density) return *body.density * shapeVolume(body.shape);
    return 0.0;
}

namespace {

Mat3 worldInertia(const BodyDesc& body, const BodySample& s) {
    const Mat3 I = body.inertia ? *body.inertia : primitiveMassProperties(body.shape, bodyMass(body)).inertia;
    const Mat3 R = s.q.normalized().toRotationMatrix();
    return R * I * R.transpose();
}

constexpr double kInf = std::numeric_limits<double>::infinity();

bool finite(const BodySample& s) {
    return s.x.allFinite() && s.v.allFinite() && s.w.allFinite() && s.q.coeffs().allFinite();
}

double angleBetween(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

Vec3 angularMomentum(const BodyDesc& body, const BodySample& s) {
    return worldInertia(body, s) * s.w;
}

double bodyEnergy(const SceneDesc& scene, int i, const BodySample& s) {
    const BodyDesc& b = scene.bodies[i];
    if (b.motion != Motion::Dynamic) return 0.0;
    const double m = bodyMass(b);
    return 0.5 * m * s.v.squaredNorm() + 0.5 * s.w.dot(worldInertia(b, s) * s.w) -
           m * scene.settings.gravity.dot(s.x);
}

namespace {

// Free fall of a ball thrown up and sideways, no ground: x(T) = x0 + v0 T + g T²/2.
class FreeFall : public Observer {
public:
    explicit FreeFall(double T) : T_(T) {}
    void start(const EngineAdapter& e) override { s0_ = e.body(0); }
    void observe(const EngineAdapter& e) override { last_ = e.body(0); }
    std::vector<std::pair<std::string, double>> errors() const override {
        const Vec3 g(0, -9.81, 0);
        const Vec3 exact = s0_.x + s0_.v * T_ + 0.5 * g * T_ * T_;
        return {{"position_error_m", finite(last_) ? (last_.x - exact).norm() : kInf}};
    }

private:
    double T_;
    BodySample s0_, last_;
};

// A torque-free body: energy and |L| must stay; `reference` (optional) the orientation at
// the end from a converged run.
class TorqueFree : public Observer {
public:
    TorqueFree(BodyDesc body, std::function<Quat()> reference, bool axisAngle)
        : body_(std::move(body)), reference_(std::move(reference)), axisAngle_(axisAngle) {}
    void start(const EngineAdapter& e) override {
        const BodySample s = e.body(0);
        E0_ = energy(s);
        L0_ = angularMomentum(body_, s);
        theta0_ = angleBetween(axis(s), L0_);
    }
    void observe(const EngineAdapter& e) override {
        last_ = e.body(0);
        if (!finite(last_)) {
            bad_ = true;
            return;
        }
        dE_ = std::max(dE_, std::abs(energy(last_) - E0_) / E0_);
        dL_ = std::max(dL_, std::abs(angularMomentum(body_, last_).norm() - L0_.norm()) / L0_.norm());
        dTheta_ = std::max(dTheta_, std::abs(angleBetween(axis(last_), L0_) - theta0_));
    }
    std::vector<std::pair<std::string, double>> errors() const override {
        std::vector<std::pair<std::string, double>> out;
        if (reference_) {
            // The angle of the rotation between them, from the difference quaternion's parts
            // (2 acos of the dot product cannot resolve angles below about 2e-8 rad).
            const Quat d = reference_().normalized().conjugate() * last_.q.normalized();
            const double angle = 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
            out.emplace_back("orientation_error_rad", bad_ ? kInf : angle);
        }
        if (axisAngle_) out.emplace_back("axis_angle_error_rad", bad_ ? kInf : dTheta_);
        out.emplace_back("energy_rel_error", bad_ ? kInf : dE_);
        out.emplace_back("L_rel_error", bad_ ? kInf : dL_);
        return out;
    }

private:
    double energy(const BodySample& s) const {
        return 0.5 * bodyMass(body_) * s.v.squaredNorm() + 0.5 * s.w.dot(worldInertia(body_, s) * s.w);
    }
    static Vec3 axis(const BodySample& s) { return s.q.normalized() * Vec3(0, 1, 0); }

    BodyDesc body_;
    std::function<Quat()> reference_;
    bool axisAngle_;
    double E0_ = 0, dE_ = 0, dL_ = 0, theta0_ = 0, dTheta_ = 0;
    Vec3 L0_ = Vec3::Zero();
    BodySample last_;
    bool bad_ = false;
};

// Apexes of a bouncing ball: the n-th bounce returns e^(2n) of the drop height h. Each apex
// is taken ballistically (y + vy²/2g) at the first sample in flight after a bounce.
class Bounce : public Observer {
public:
    Bounce(double radius, double e, int count) : r_(radius), e_(e), count_(count) {}
    void start(const EngineAdapter& eng) override {
        const BodySample s = eng.body(1);
        h_ = s.x.y() - r_;
        vy_ = s.v.y();
    }
    void observe(const EngineAdapter& eng) override {
        const BodySample s = eng.body(1);
        if (!finite(s)) {
            bad_ = true;
            return;
        }
        if (vy_ <= 0.0 && s.v.y() > 0.0) pending_ = true;
        if (pending_ && s.v.y() > 0.0 && s.x.y() - r_ > 1e-4) {
            apexes_.push_back(s.x.y() - r_ + s.v.y() * s.v.y() / (2 * 9.81));
            pending_ = false;
        }
        vy_ = s.v.y();
    }
    std::vector<std::pair<std::string, double>> errors() const override {
        double err = 0.0;
        for (int n = 1; n <= count_; ++n) {
            const double exact = std::pow(e_, 2 * n) * h_;
            const double got = n <= static_cast<int>(apexes_.size()) ? apexes_[n - 1] : 0.0;
            err = std::max(err, std::abs(got - exact));
        }
        return {{"apex_error_m", bad_ ? kInf : err}};
    }

private:
    double r_, e_;
    int count_;
    double h_ = 0, vy_ = 0;
    bool pending_ = false, bad_ = false;
    std::vector<double> apexes_;
};

// Final velocities of a head-on collision of bodies 0 and 1 along x.
class HeadOn : public Observer {
public:
    HeadOn(double m1, double m2, double e) : m1_(m1), m2_(m2), e_(e) {}
    void start(const EngineAdapter& eng) override {
        u1_ = eng.body(0).v;
        u2_ = eng.body(1).v;
    }
    void observe(const EngineAdapter& eng) override {
        a_ = eng.body(0);
        b_ = eng.body(1);
    }
    std::vector<std::pair<std::string, double>> errors() const override {
        const Vec3 p = m1_ * u1_ + m2_ * u2_;
        const Vec3 v1 = (p - m2_ * e_ * (u1_ - u2_)) / (m1_ + m2_);
        const Vec3 v2 = (p + m1_ * e_ * (u1_ - u2_)) / (m1_ + m2_);
        const bool ok = finite(a_) && finite(b_);
        return {{"velocity_error_m_s", ok ? std::max((a_.v - v1).norm(), (b_.v - v2).norm()) : kInf}};
    }

private:
    double m1_, m2_, e_;
    Vec3 u1_ = Vec3::Zero(), u2_ = Vec3::Zero();
    BodySample a_, b_;
};

// A block sliding to a stop: d = v0²/(2 mu g).
class Slide : public Observer {
public:
    explicit Slide(double mu) : mu_(mu) {}
    void start(const EngineAdapter& eng) override { s0_ = eng.body(1); }
    void observe(const EngineAdapter& eng) override { last_ = eng.body(1); }
    std::vector<std::pair<std::string, double>> errors() const override {
        const double d = s0_.v.squaredNorm() / (2 * mu_ * 9.81);
        return {{"stop_distance_error_m", finite(last_) ? std::abs((last_.x - s0_.x).norm() - d) : kInf}};
    }

private:
    double mu_;
    BodySample s0_, last_;
};

// A sphere launched sliding without spin: it rolls from t = 2 v0/(7 mu g) at 5/7 v0.
// The moment it starts to roll is where the slip's straight line (friction is constant
// while it slides) through the last two sliding samples reaches zero: the first sample
// found rolling alone would give every engine the error of its step, whatever its physics.
class SlideToRoll : public Observer {
public:
    SlideToRoll(double radius, double mu) : r_(radius), mu_(mu) {}
    void start(const EngineAdapter& eng) override {
        v0_ = eng.body(1).v.x();
        sliding_[1] = {eng.time(), v0_};
    }
    void observe(const EngineAdapter& eng) override {
        last_ = eng.body(1);
        const double slip = last_.v.x() + last_.w.z() * r_;
        if (tRoll_ >= 0) return;
        if (std::abs(slip) >= 1e-3 * v0_) {
            sliding_[0] = sliding_[1];
            sliding_[1] = {eng.time(), slip};
            ++slides_;
            return;
        }
        tRoll_ = eng.time();
        const auto [t0, s0] = sliding_[0];
        const auto [t1, s1] = sliding_[1];
        if (slides_ >= 1 && s0 > s1 && s1 > 0.0) tRoll_ = t1 + s1 * (t1 - t0) / (s0 - s1);
    }
    std::vector<std::pair<std::string, double>> errors() const override {
        const double tExact = 2 * v0_ / (7 * mu_ * 9.81);
        const bool ok = finite(last_);
        return {{"final_speed_error_m_s", ok ? std::abs(last_.v.norm() - 5.0 / 7.0 * v0_) : kInf},
                {"roll_time_error_s", ok && tRoll_ >= 0 ? std::abs(tRoll_ - tExact) : kInf}};
    }

private:
    double r_, mu_;
    double v0_ = 0, tRoll_ = -1;
    std::pair<double, double> sliding_[2];  // (time, slip) of the last two samples still sliding
    int slides_ = 0;
    BodySample last_;
};

// A box moved along `dir` by constant forces beyond its friction (a push switched on at t0,
// or gravity along a slope): it slides d = ½ a (t − t0)² from where it rested (issue 44).
class ForcedSlide : public Observer {
public:
    ForcedSlide(const Vec3& dir, double a, double t0) : dir_(dir.normalized()), a_(a), t0_(t0) {}
    void start(const EngineAdapter& eng) override { s0_ = eng.body(1); }
    void observe(const EngineAdapter& eng) override {
        last_ = eng.body(1);
        t_ = eng.time();
    }
    std::vector<std::pair<std::string, double>> errors() const override {
        const double d = 0.5 * a_ * (t_ - t0_) * (t_ - t0_);
        return {{"slide_distance_error_m", finite(last_) ? std::abs((last_.x - s0_.x).dot(dir_) - d) : kInf}};
    }

private:
    Vec3 dir_;
    double a_, t0_, t_ = 0.0;
    BodySample s0_, last_;
};

// A 1 kg box (half extents 0.3, 0.2, 0.3) resting on the ground, both of friction mu, under
// gravity g; pushed by `push` from t = 1 s when it is not zero.
SceneDesc boxOnGround(const Vec3& g, const Vec3& push, double mu) {
    SceneDesc s = sampleScene("sliding-block.json");  // its ground plane, then the box
    s.settings.gravity = g;
    s.settings.sleeping = false;
    s.bodies.resize(1);
    s.bodies[0].friction = mu;
    s.bodies[0].restitution = 0.0;
    BodyDesc box;
    box.name = "box";
    box.shape.type = ShapeType::Box;
    box.shape.halfExtents = Vec3(0.3, 0.2, 0.3);
    box.mass = 1.0;
    box.position = Vec3(0, 0.2, 0);
    box.friction = mu;
    box.restitution = 0.0;
    if (!push.isZero()) {
        ForceDesc f;
        f.vector = push;
        f.start = 1.0;
        box.forces.push_back(f);
    }
    s.bodies.push_back(box);
    return s;
}

// The orientation at time T of the tumbling box, from Tumble's RK4 at 1/61440 s (16 times
// below the smallest step swept): its error is far below every swept run's.
Quat tumblingReference(const SceneDesc& scene, double T) {
    static std::map<double, Quat> cache;
    if (auto it = cache.find(T); it != cache.end()) return it->second;
    TumbleAdapter a;
    const double dt = 1.0 / 61440.0;
    a.load(scene, "rk4", dt, nullptr);
    const long n = std::lround(T / dt);
    for (long i = 0; i < n; ++i) a.step();
    return cache[T] = a.body(0).q;
}

}  // namespace

std::vector<AccuracyScene> accuracyScenes() {
    std::vector<AccuracyScene> out;

    SceneDesc fall;
    BodyDesc ball;
    ball.name = "ball";
    ball.shape.type = ShapeType::Sphere;
    ball.shape.radius = 0.1;
    ball.mass = 1.0;
    ball.position = Vec3(0, 10, 0);
    ball.velocity = Vec3(3, 5, 0);
    fall.bodies.push_back(ball);
    out.push_back({"free-fall", "a ball thrown at (3, 5, 0) m/s, no ground, 2 s: x(T) = x0 + v0 T + g T^2/2",
                   fall, 2.0, [] { return std::make_unique<FreeFall>(2.0); }});

    const SceneDesc tumbling = sampleScene("tumbling-box.json");
    out.push_back({"tumbling-box",
                   "tumbling-box.json, 10 s about the intermediate axis: energy and |L| constant; the "
                   "orientation against Tumble's RK4 at 1/61440 s",
                   tumbling, 10.0, [tumbling] {
                       return std::make_unique<TorqueFree>(
                           tumbling.bodies[0], [tumbling] { return tumblingReference(tumbling, 10.0); },
                           false);
                   }});

    SceneDesc rod;
    rod.settings.gravity = Vec3::Zero();
    BodyDesc r;
    r.name = "rod";
    r.shape.type = ShapeType::Box;
    r.shape.halfExtents = Vec3(0.01, 0.5, 0.01);
    r.mass = 1.0;
    r.angularVelocity = Vec3(1, 50, 0);
    rod.bodies.push_back(r);
    out.push_back({"spinning-rod",
                   "a thin rod (1 m x 2 cm) spinning at 50 rad/s about its axis, tumbling at 1 rad/s, 5 s: "
                   "the axis keeps its angle to L",
                   rod, 5.0, [r] { return std::make_unique<TorqueFree>(r, nullptr, true); }});

    out.push_back({"bouncing-ball", "bouncing-ball.json, 3 s: the first 3 apexes of the bottom at 0.64^n m",
                   sampleScene("bouncing-ball.json"), 3.0,
                   [] { return std::make_unique<Bounce>(0.1, 0.8, 3); }});
    out.push_back({"head-on", "head-on.json, 3 s: after the impact -0.85 and +0.95 m/s",
                   sampleScene("head-on.json"), 3.0, [] { return std::make_unique<HeadOn>(1.0, 3.0, 0.9); }});
    out.push_back({"sliding-block", "sliding-block.json, 3 s: stops after v0^2/(2 mu g) = 1.529 m",
                   sampleScene("sliding-block.json"), 3.0, [] { return std::make_unique<Slide>(0.3); }});
    out.push_back({"rolling-sphere",
                   "rolling-sphere.json, 3 s: rolls from 2 v0/(7 mu g) = 0.728 s at 5/7 v0 = 3.571 m/s",
                   sampleScene("rolling-sphere.json"), 3.0,
                   [] { return std::make_unique<SlideToRoll>(0.11, 0.2); }});
    // Sliding driven by a constant force (issue 44): a box at rest pushed from t = 1 s with
    // 1.05 mu m g, and a box let go on a 30° slope (gravity tilted over the flat ground).
    const double mu = 0.5, g = 9.81, theta = std::numbers::pi / 6;
    const double push = 1.05 * mu * g;
    out.push_back({"pushed-box",
                   "a 1 kg box at rest (mu 0.5) pushed from t = 1 s with 1.05 mu m g, 5 s: slides "
                   "(F/m - mu g)(t - 1)^2 / 2 = 1.962 m",
                   boxOnGround(Vec3(0, -g, 0), Vec3(push, 0, 0), mu), 5.0,
                   [=] { return std::make_unique<ForcedSlide>(Vec3::UnitX(), push - mu * g, 1.0); }});
    const Vec3 tilted(g * std::sin(theta), -g * std::cos(theta), 0);
    out.push_back(
        {"slope-slide",
         "a 1 kg box let go on a 30 degree slope (mu 0.5), 3 s: slides g (sin 30 - mu cos 30) t^2 / 2 "
         "= 2.957 m",
         boxOnGround(tilted, Vec3::Zero(), mu), 3.0, [=] {
             return std::make_unique<ForcedSlide>(Vec3::UnitX(), g * (std::sin(theta) - mu * std::cos(theta)),
                                                  0.0);
         }});
    return out;
}

}  // namespace tumble::bench
