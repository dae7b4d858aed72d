// Speed scenes (issue 8), built in code: they are too large to be useful as sample files,
// except the ones read from resources/scenes. Each skip of DESIGN.md's "Speed and accuracy"
// has its on and off variant here.
#include "scenes.h"

#include "../../engine/chair_pile.h"

#include <tumble/mass.h>

#include <cmath>
#include <random>

namespace tumble::bench {

namespace {

BodyDesc ground() {
    BodyDesc g;
    g.name = "ground";
    g.motion = Motion::Static;
    g.shape.type = ShapeType::Plane;
    return g;
}

BodyDesc box(const std::string& name, const Vec3& half, double mass, const Vec3& at) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = half;
    b.mass = mass;
    b.position = at;
    return b;
}

// 3 008 boxes (half extent 1, mass 2) in 47 layers of 8 x 8, 0.5 m apart, dropped.
SceneDesc drop3000() {
    SceneDesc s;
    s.bodies.push_back(ground());
    for (int l = 0; l < 47; ++l)
        for (int i = 0; i < 8; ++i)
            for (int k = 0; k < 8; ++k)
                s.bodies.push_back(
                    box("b", Vec3(1, 1, 1), 2.0, Vec3((i - 3.5) * 2.5, 1.5 + l * 2.5, (k - 3.5) * 2.5)));
    return s;
}

// Boxes with random spins far enough apart never to touch; with a far ground the contact
// stages must run (something static exists) but find nothing.
SceneDesc freeBodies(int n, bool farGround) {
    SceneDesc s;
    s.settings.gravity = Vec3::Zero();
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(n))));
    for (int i = 0; i < n; ++i) {
        BodyDesc b =
            box("b", Vec3(0.5, 0.3, 0.2), 1.0, Vec3(i % side, (i / side) % side, i / (side * side)) * 4.0);
        b.angularVelocity = Vec3(u(rng), u(rng), u(rng));
        s.bodies.push_back(b);
    }
    if (farGround) {
        BodyDesc g = ground();
        g.shape.distance = -1e4;
        s.bodies.push_back(g);
    }
    return s;
}

// Towers of 5 boxes in a grid; the top box of tower k is pushed sideways at t = k + 0.5 s.
SceneDesc piles(int count, bool sleeping) {
    SceneDesc s;
    s.settings.sleeping = sleeping;
    s.bodies.push_back(ground());
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    for (int p = 0; p < count; ++p) {
        const Vec3 base((p % side) * 4.0, 0, (p / side) * 4.0);
        for (int l = 0; l < 5; ++l) {
            BodyDesc b = box("b", Vec3(0.5, 0.5, 0.5), 10.0, base + Vec3(0, 0.5 + l, 0));
            if (l == 4) {
                ForceDesc f;
                f.vector = Vec3(200, 0, 0);
                f.start = p + 0.5;
                f.end = p + 0.6;
                b.forces.push_back(f);
            }
            s.bodies.push_back(b);
        }
    }
    return s;
}

// A jittered octahedron (convex: one vertex on each half axis), closed.
std::shared_ptr<const TriangleMesh> rock(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.25, 0.5);
    auto m = std::make_shared<TriangleMesh>();
    m->vertices = {{u(rng), 0, 0},  {-u(rng), 0, 0}, {0, u(rng), 0},
                   {0, -u(rng), 0}, {0, 0, u(rng)},  {0, 0, -u(rng)}};
    m->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}

// A 40 m square of 2 x 20 x 20 triangles with gentle bumps, as a static triangle mesh.
std::shared_ptr<const TriangleMesh> terrain() {
    auto m = std::make_shared<TriangleMesh>();
    const int n = 20;
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k) {
            const double x = -20.0 + 40.0 * i / n, z = -20.0 + 40.0 * k / n;
            m->vertices.emplace_back(x, 0.3 * std::sin(0.5 * x) * std::cos(0.4 * z), z);
        }
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const int a = i * (n + 1) + k, b = a + 1, c = a + n + 1, d = c + 1;
            m->triangles.push_back({a, b, c});
            m->triangles.push_back({b, d, c});
        }
    return m;
}

SceneDesc hullRain(int count, bool sleeping) {
    SceneDesc s;
    s.settings.sleeping = sleeping;
    BodyDesc g;
    g.name = "terrain";
    g.motion = Motion::Static;
    g.shape.type = ShapeType::Mesh;
    g.shape.file = "generated-terrain";
    g.shape.collision = MeshCollision::Triangles;
    g.shape.meshData = terrain();
    s.bodies.push_back(g);
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-8.0, 8.0), h(2.0, 20.0);
    for (int i = 0; i < count; ++i) {
        BodyDesc b;
        b.name = "rock";
        b.shape.type = ShapeType::Mesh;
        b.shape.file = "generated-rock";
        b.shape.meshData = rock(rng);
        b.density = 1000.0;
        b.position = Vec3(u(rng), h(rng), u(rng));
        s.bodies.push_back(b);
    }
    return s;
}

// Static boxes overlapping their neighbours (many static-static pairs that must never be
// tested) with a few dynamic boxes resting on them.
SceneDesc staticField() {
    SceneDesc s;
    for (int i = 0; i < 30; ++i)
        for (int k = 0; k < 30; ++k) {
            BodyDesc b = box("floor", Vec3(0.6, 0.5, 0.6), 1.0, Vec3(i, -0.5, k));
            b.mass.reset();
            b.motion = Motion::Static;
            s.bodies.push_back(b);
        }
    for (int i = 0; i < 10; ++i) s.bodies.push_back(box("b", Vec3(0.3, 0.3, 0.3), 1.0, Vec3(3 * i, 0.3, 15)));
    s.settings.sleeping = false;
    return s;
}

// A chain of `links` box links (0.2 m long, 0.5 kg) joined end to end by ball joints, the
// first hung from a fixed point, laid out level: it falls and swings (joints only, no
// contacts, no ground).
SceneDesc hangingChain(int links) {
    SceneDesc s;
    s.settings.sleeping = false;
    const double half = 0.1, top = 25.0;
    for (int k = 0; k < links; ++k) {
        s.bodies.push_back(box("link-" + std::to_string(k), Vec3(half, 0.025, 0.025), 0.5, Vec3(half + 2 * half * k, top, 0.0)));
        JointDesc j;
        j.name = "joint-" + std::to_string(k);
        j.type = JointType::Ball;
        j.bodyA = "link-" + std::to_string(k);
        j.anchorA = Vec3(-half, 0.0, 0.0);
        if (k == 0) {
            j.anchorB = Vec3(0.0, top, 0.0);
        } else {
            j.bodyB = "link-" + std::to_string(k - 1);
            j.anchorB = Vec3(half, 0.0, 0.0);
        }
        s.joints.push_back(j);
    }
    return s;
}

// The sample ragdoll (resources/scenes/ragdoll.json: 10 bodies, ball joints and limited
// hinges) `count` times, in columns of five dropped onto each other and the ground.
SceneDesc ragdollPile(int count) {
    const SceneDesc one = sampleScene("ragdoll.json");
    SceneDesc s;
    s.settings = one.settings;
    s.settings.sleeping = false;
    for (const BodyDesc& b : one.bodies)
        if (b.motion == Motion::Static) s.bodies.push_back(b);
    for (int r = 0; r < count; ++r) {
        const int column = r / 5, level = r % 5;
        const Vec3 offset(1.6 * (column % 2), 1.2 * level, 1.6 * (column / 2));  // apart: one spans 1.05 m high
        const std::string tag = "-" + std::to_string(r);
        for (BodyDesc b : one.bodies) {
            if (b.motion == Motion::Static) continue;
            b.name += tag;
            b.position += offset;
            s.bodies.push_back(b);
        }
        for (JointDesc j : one.joints) {
            j.name += tag;
            j.bodyA += tag;
            if (!j.bodyB.empty()) j.bodyB += tag;
            s.joints.push_back(j);
        }
    }
    return s;
}

// `count` chairs (resources/scenes/chair.json's) piled as tests/engine/chair_pile.h says.
SceneDesc chairPile(int count) {
    return test::chairPile(sampleScene("chair.json"), count);
}

// Body names must be unique: the builders above name by kind, this numbers them.
// Jolt's PerformanceTest "Pyramid" scene (PyramidScene.h) as Tumble describes it: 1 240 boxes
// of 2 m (density 1 000 kg/m³, Jolt's default friction 0.2 and restitution 0) in 15 square
// layers, each layer 0.5 m above the last and odd layers shifted by half a box, on a static
// 100 x 2 x 100 m box whose top is at y = 0; sleeping off. For checking the Jolt peer's times
// against Jolt's own program on the same scene.
SceneDesc joltPyramid() {
    SceneDesc s;
    s.settings.sleeping = false;
    BodyDesc floor = box("floor", Vec3(50, 1, 50), 1.0, Vec3(0, -1, 0));
    floor.motion = Motion::Static;
    floor.mass.reset();
    s.bodies.push_back(floor);
    const int height = 15;
    for (int i = 0; i < height; ++i)
        for (int j = i / 2; j < height - (i + 1) / 2; ++j)
            for (int k = i / 2; k < height - (i + 1) / 2; ++k) {
                const double shift = (i & 1) ? 1.0 : 0.0;
                BodyDesc b = box("b", Vec3(1, 1, 1), 1.0,
                                 Vec3(-height + 2.0 * j + shift, 1.0 + 2.5 * i, -height + 2.0 * k + shift));
                b.mass.reset();
                b.density = 1000.0;
                b.friction = 0.2;
                b.restitution = 0.0;
                s.bodies.push_back(b);
            }
    for (BodyDesc& b : s.bodies) b.friction = 0.2, b.restitution = 0.0;
    return s;
}

SceneDesc named(SceneDesc s) {
    for (size_t i = 0; i < s.bodies.size(); ++i)
        if (s.bodies[i].motion != Motion::Static || s.bodies[i].shape.type != ShapeType::Plane)
            s.bodies[i].name += "-" + std::to_string(i);
    return s;
}

}  // namespace

SceneDesc boxPyramid(int layers, double h, double m, const Vec3& offset) {
    SceneDesc s;
    BodyDesc g = ground();
    g.shape.distance = offset.y();
    s.bodies.push_back(g);
    for (int l = 0; l < layers; ++l) {
        const int n = layers - l;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < n; ++k)
                s.bodies.push_back(
                    box("b", Vec3(h, h, h), m,
                        offset + Vec3((2 * i - n + 1) * h, h + 2 * h * l, (2 * k - n + 1) * h)));
    }
    return s;
}

std::vector<SpeedScene> speedScenes() {
    std::vector<SpeedScene> out;
    out.push_back({"drop-3000",
                   "3 008 boxes (half extent 1, 2 kg) in 47 layers of 8 x 8 dropped on the ground",
                   [] { return named(drop3000()); }, 1.0 / 60.0, 180, 3});
    out.push_back({"pyramid-1240", "a 15-layer square pyramid of 1 240 unit boxes, sleeping off",
                   [] {
                       SceneDesc pyr = boxPyramid(15, 0.5, 1.0, Vec3::Zero());
                       pyr.settings.sleeping = false;
                       return named(pyr);
                   },
                   1.0 / 60.0, 120, 2});
    out.push_back({"jolt-pyramid",
                   "Jolt's PerformanceTest pyramid: 1 240 boxes of 2 m in 15 layers dropped 0.5 m apart, "
                   "sleeping off (to check the Jolt peer against Jolt's own program)",
                   [] { return named(joltPyramid()); }, 1.0 / 60.0, 500, 1});
    out.push_back({"free-10000", "10 000 boxes tumbling, no gravity, no contacts, nothing static",
                   [] { return named(freeBodies(10000, false)); }, 1.0 / 60.0, 120, 5});
    out.push_back({"free-10000-far-ground",
                   "free-10000 with a ground plane 10 km below: the contact stages run",
                   [] { return named(freeBodies(10000, true)); }, 1.0 / 60.0, 120, 5});
    out.push_back({"piles-sleep-on", "100 towers of 5 boxes, the top of one pushed each second, sleeping on",
                   [] { return named(piles(100, true)); }, 1.0 / 60.0, 600, 20});
    out.push_back({"piles-sleep-off", "piles-sleep-on with sleeping off",
                   [] { return named(piles(100, false)); }, 1.0 / 60.0, 600, 20});
    out.push_back({"hull-rain", "300 convex hulls (jittered octahedra) raining on a 800-triangle mesh ground",
                   [] { return named(hullRain(300, true)); }, 1.0 / 60.0, 300, 10});
    out.push_back({"hull-rain-sleep-off", "hull-rain with sleeping off (every engine steps every rock)",
                   [] { return named(hullRain(300, false)); }, 1.0 / 60.0, 300, 10});
    out.push_back({"static-field",
                   "900 overlapping static boxes (3 000+ static pairs) under 10 resting boxes",
                   [] { return named(staticField()); }, 1.0 / 60.0, 120, 5});
    out.push_back({"chain-100",
                   "a chain of 100 box links on ball joints hung from one end, falling from level and "
                   "swinging (joints only)",
                   [] { return hangingChain(100); }, 1.0 / 60.0, 300, 10});
    out.push_back({"ragdoll-pile",
                   "20 ragdolls (10 bodies, 9 joints each: balls and limited hinges) dropped in four "
                   "columns of five onto the ground",
                   [] { return ragdollPile(20); }, 1.0 / 60.0, 300, 10});
    out.push_back({"ragdoll-stairs",
                   "the sample ragdoll with swing cones and twist limits at its ball joints, tumbling down "
                   "six steps (sleeping off)",
                   [] {
                       SceneDesc s = sampleScene("ragdoll-stairs.json");
                       s.settings.sleeping = false;
                       return s;
                   },
                   1.0 / 60.0, 300, 10});
    out.push_back({"robot-arm",
                   "the sample two-link arm driven by servos through its keyed targets, pushing three "
                   "blocks aside",
                   [] { return sampleScene("robot-arm.json"); }, 1.0 / 60.0, 300, 10});
    out.push_back({"chair-pile",
                   "200 chairs (compound bodies of six boxes) dropped in eight layers of 5 x 5 onto the "
                   "floor, impacts at the end of the step",
                   [] { return chairPile(200); }, 1.0 / 60.0, 240, 10});
    return out;
}

}  // namespace tumble::bench
