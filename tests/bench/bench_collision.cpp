// Collision benchmarks (run by hand, not a test; figures go to docs/benchmarks.md):
// - broadphase: update time and pair count for n boxes spread at constant density (the
//   volume grows with n), the first full update from scratch and steady-state updates with
//   small motion, with the number of heap allocations per steady update;
// - triangle BVH: build and mesh-mesh pair query on sphere meshes;
// - narrowphase: collide() calls per second for each pair type on random near-contact poses.
// Times are process CPU time (std::clock), not wall time: the machines this runs on are
// shared, and CPU time does not count the time other processes hold the core. Every figure
// is the median of several runs. Usage: tumble-bench-collision [--quick]
#include <tumble/convex_hull.h>
#include "collision/broadphase.h"
#include "collision/bvh.h"
#include "collision/narrowphase.h"

#include <algorithm>
#include <atomic>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <numbers>
#include <random>
#include <vector>

using namespace tumble;
using namespace tumble::collision;

// Counts heap allocations, to show that steady-state broadphase updates make none.
namespace {
std::atomic<long> allocations{0};
}

void* operator new(std::size_t size) {
    ++allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t align) {
    ++allocations;
    const std::size_t a = static_cast<std::size_t>(align);
    if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace {

struct Clock {
    using time_point = std::clock_t;
    static time_point now() { return std::clock(); }
};

double secondsSince(Clock::time_point start) {
    return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// ---------------------------------------------------------------------------------------
// Broadphase

struct Scene {
    std::vector<Aabb> bounds;
    std::vector<std::uint8_t> moving;
};

// n bodies: boxes of half-sides 0.25..0.75 at one body per 8 volume units, 10 % static, and
// a static ground plane (an infinite box) as body 0.
Scene spreadScene(int n, std::mt19937& rng) {
    const double side = 2.0 * std::cbrt(static_cast<double>(n));
    std::uniform_real_distribution<double> pos(0.0, side), half(0.25, 0.75), unit(0.0, 1.0);
    Scene s;
    s.bounds.reserve(n);
    s.moving.reserve(n);
    const double inf = std::numeric_limits<double>::infinity();
    s.bounds.push_back({Vec3::Constant(-inf), Vec3::Constant(inf)});
    s.moving.push_back(0);
    for (int i = 1; i < n; ++i) {
        const Vec3 c(pos(rng), pos(rng), pos(rng));
        const Vec3 h(half(rng), half(rng), half(rng));
        s.bounds.push_back({c - h, c + h});
        s.moving.push_back(unit(rng) < 0.1 ? 0 : 1);
    }
    return s;
}

// Every moving body takes a random step of up to 0.02 per axis (1/50 of a body's size:
// about 1 m/s at 60 Hz for a 1 m body).
void smallMotion(Scene& s, std::mt19937& rng) {
    std::uniform_real_distribution<double> step(-0.02, 0.02);
    for (std::size_t i = 0; i < s.bounds.size(); ++i) {
        if (!s.moving[i] || !s.bounds[i].min.allFinite()) continue;
        const Vec3 d(step(rng), step(rng), step(rng));
        s.bounds[i].min += d;
        s.bounds[i].max += d;
    }
}

void benchBroadphase(bool quick) {
    std::printf("Broadphase (dynamic AABB trees), boxes at constant density, 10%% static + a plane\n");
    std::printf("%8s %9s %11s %12s %10s %14s %10s %11s %11s\n", "bodies", "pairs", "first [ms]",
                "steady [ms]", "max [ms]", "per body [ns]", "reinserts", "allocs/upd", "brute [ms]");
    for (int n : {1000, 10000, 100000}) {
        std::mt19937 rng(12345u + static_cast<unsigned>(n));
        Scene scene = spreadScene(n, rng);
        const int runs = quick ? 3 : (n >= 100000 ? 5 : 9);

        std::vector<double> first;
        std::size_t pairs = 0;
        for (int r = 0; r < runs; ++r) {
            Broadphase bp;
            const auto t = Clock::now();
            bp.update(scene.bounds, scene.moving);
            first.push_back(secondsSince(t));
            pairs = bp.pairs().size();
        }

        Broadphase bp;
        bp.update(scene.bounds, scene.moving);
        // Warm up: let fat boxes and buffers settle before measuring the steady state.
        for (int k = 0; k < 10; ++k) {
            smallMotion(scene, rng);
            bp.update(scene.bounds, scene.moving);
        }
        std::vector<double> steady;
        double reinserts = 0.0;
        long allocs = 0;
        // Enough steps that a tree rebuild (every few hundred steps here) may fall inside.
        const int steps = quick ? 5 : 101;
        for (int k = 0; k < steps; ++k) {
            smallMotion(scene, rng);
            const long before = allocations.load();
            const auto t = Clock::now();
            bp.update(scene.bounds, scene.moving);
            const double seconds = secondsSince(t);
            allocs += allocations.load() - before;
            steady.push_back(seconds);
            reinserts += bp.reinserted();
        }

        double brute = std::nan("");
        if (n <= 10000) {
            std::vector<double> b;
            for (int r = 0; r < (n <= 1000 ? 5 : 1); ++r) {
                const auto t = Clock::now();
                const auto ref = bruteForcePairs(scene.bounds, scene.moving);
                b.push_back(secondsSince(t));
                if (ref != bp.pairs()) std::printf("  MISMATCH with brute force at n = %d\n", n);
            }
            brute = median(b);
        }
        const double s = median(steady);
        std::printf("%8d %9zu %11.2f %12.2f %10.2f %14.0f %10.0f %11.2f %11.1f\n", n, pairs,
                    1e3 * median(first), 1e3 * s, 1e3 * *std::max_element(steady.begin(), steady.end()),
                    1e9 * s / n, reinserts / steps, static_cast<double>(allocs) / steps, 1e3 * brute);
    }
    std::printf("first: a fresh Broadphase's first update; steady: median of later updates after\n"
                "small motion, max: the slowest of them; reinserts: bodies re-inserted per steady\n"
                "update; allocs/upd: heap allocations per steady update; brute: bruteForcePairs\n\n");
}

// ---------------------------------------------------------------------------------------
// Triangle BVH

struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<int, 3>> triangles;
};

Mesh uvSphere(double r, int rings, int segments) {
    using std::numbers::pi;
    Mesh m;
    for (int i = 0; i <= rings; ++i) {
        const double phi = pi * i / rings - pi / 2;
        for (int s = 0; s < segments; ++s) {
            const double a = 2 * pi * s / segments;
            m.vertices.emplace_back(r * std::cos(phi) * std::cos(a), r * std::sin(phi),
                                    -r * std::cos(phi) * std::sin(a));
        }
    }
    auto id = [&](int i, int s) { return i * segments + s % segments; };
    for (int i = 0; i < rings; ++i) {
        for (int s = 0; s < segments; ++s) {
            m.triangles.push_back({id(i, s), id(i, s + 1), id(i + 1, s + 1)});
            m.triangles.push_back({id(i, s), id(i + 1, s + 1), id(i + 1, s)});
        }
    }
    return m;
}

void benchBvh(bool quick) {
    std::printf("Triangle BVH: two unit UV spheres, the second turned and offset by 0.5\n");
    std::printf("%10s %12s %14s %12s\n", "triangles", "build [ms]", "pairs query [ms]", "pairs");
    for (int rings : {32, 64, 128}) {
        const Mesh m = uvSphere(1.0, rings, 2 * rings);
        std::vector<double> build, query;
        long pairs = 0;
        for (int r = 0; r < (quick ? 3 : 7); ++r) {
            auto t = Clock::now();
            const TriangleBvh bvh(m.vertices, m.triangles);
            build.push_back(secondsSince(t));
            Pose pose;
            pose.R = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
            pose.p = Vec3(0.5, 0.0, 0.0);
            pairs = 0;
            t = Clock::now();
            bvh.queryPairs(bvh, pose, [&](int, int) { ++pairs; });
            query.push_back(secondsSince(t));
        }
        std::printf("%10zu %12.3f %14.3f %12ld\n", m.triangles.size(), 1e3 * median(build),
                    1e3 * median(query), pairs);
    }
    std::printf("\n");
}

// ---------------------------------------------------------------------------------------
// Narrowphase: collide() calls per second for each pair type, over a fixed list of random
// poses near contact: random orientations, A moved along a random direction (up, for a
// plane) to where the pair just touches (bisection), then in by -2 % to 5 % of the smaller
// bounding radius: mostly resting-contact depths, some just apart. "touching" is the share
// of calls that return a manifold, "points" the mean points per touching call.

Shape meshShape(const Mesh& m) {
    auto s = std::make_shared<MeshShape>();
    s->vertices = m.vertices;
    s->triangles = m.triangles;
    s->closed = true;
    s->bvh = std::make_shared<const TriangleBvh>(s->vertices, s->triangles);
    Shape shape;
    shape.kind = Kind::Mesh;
    shape.mesh = s;
    return shape;
}

Shape hullShape(std::mt19937& rng, int n) {
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.push_back(Vec3(g(rng), g(rng), g(rng)).normalized().cwiseProduct(Vec3(0.8, 0.5, 0.6)));
    Shape s;
    s.kind = Kind::Hull;
    s.hull = std::make_shared<const ConvexHull>(mesh::convexHull(pts));
    return s;
}

Mat3 randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    return Quat(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

struct PairCase {
    const char* name;
    Shape a, b;
};

void benchNarrowphase(bool quick) {
    std::mt19937 rng(777u);
    const Shape ground = Shape::plane(Vec3(0, 1, 0), 0.0);
    const Shape sphere = Shape::sphere(0.5), box = Shape::box(Vec3(0.6, 0.4, 0.5));
    const Shape capsule = Shape::capsule(0.3, 0.5), cylinder = Shape::cylinder(0.4, 0.5);
    const Shape hull = hullShape(rng, 24), ball = meshShape(uvSphere(0.7, 16, 32));
    const Shape bigBall = meshShape(uvSphere(0.7, 64, 128));
    const std::vector<PairCase> cases = {
        {"sphere-sphere", sphere, sphere},     {"sphere-plane", sphere, ground},
        {"sphere-box", sphere, box},           {"sphere-capsule", sphere, capsule},
        {"capsule-capsule", capsule, capsule}, {"capsule-box", capsule, box},
        {"box-plane", box, ground},            {"box-box", box, box},
        {"cylinder-plane", cylinder, ground},  {"cylinder-box", cylinder, box},
        {"hull-plane", hull, ground},          {"hull-hull", hull, hull},
        {"box-hull", box, hull},               {"sphere-mesh (1k tris)", sphere, ball},
        {"box-mesh (1k tris)", box, ball},     {"hull-mesh (1k tris)", hull, ball},
        {"box-mesh (16k tris)", box, bigBall}, {"mesh-plane (1k tris)", ball, ground},
        {"mesh-mesh (1k tris)", ball, ball},
    };
    std::printf("Narrowphase: collide() on %d random poses near contact per pair type (200 with a mesh)\n", quick ? 200 : 2000);
    std::printf("%-24s %14s %10s %8s\n", "pair", "pairs/s", "touching", "points");
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    for (const auto& c : cases) {
        const bool mesh = c.a.kind == Kind::Mesh || c.b.kind == Kind::Mesh;
        const int n = quick || mesh ? 200 : 2000;
        std::vector<std::pair<Pose, Pose>> poses;
        ManifoldList out;
        const double ra = boundingRadius(c.a);
        const double small = c.b.kind == Kind::Plane ? ra : std::min(ra, boundingRadius(c.b));
        for (int k = 0; k < n; ++k) {
            Pose pa, pb;
            pa.R = randomRotation(rng);
            pb.R = c.b.kind == Kind::Plane ? Mat3::Identity() : randomRotation(rng);
            const Vec3 d = c.b.kind == Kind::Plane ? Vec3(0, 1, 0) : Vec3(g(rng), g(rng), g(rng)).normalized();
            // The distance along d at which the pair just touches, by bisection on collide().
            double lo = 0.0, hi = ra + boundingRadius(c.b);
            if (c.b.kind == Kind::Plane) lo = -ra, hi = ra;
            for (int it = 0; it < 20; ++it) {
                const double mid = 0.5 * (lo + hi);
                pa.p = mid * d;
                out.clear();
                collide(c.a, pa, c.b, pb, 0.0, out);
                bool deep = false;
                for (const auto& m : out) deep = deep || m.maxDepth() > 0.0;
                (deep ? lo : hi) = mid;
            }
            pa.p = (hi - small * (-0.02 + 0.07 * unit(rng))) * d;
            poses.emplace_back(pa, pb);
        }
        long calls = 0, touching = 0, points = 0;
        std::vector<double> rates;
        for (int r = 0; r < (quick ? 1 : 5); ++r) {
            calls = touching = points = 0;
            const auto t = Clock::now();
            double seconds = 0.0;
            do {
                for (const auto& [pa, pb] : poses) {
                    out.clear();
                    collide(c.a, pa, c.b, pb, 0.0, out);
                    ++calls;
                    touching += out.empty() ? 0 : 1;
                    for (const auto& m : out) points += m.count;
                }
                seconds = secondsSince(t);
            } while (seconds < (quick ? 0.02 : 0.2));
            rates.push_back(static_cast<double>(calls) / seconds);
        }
        std::printf("%-24s %14.0f %9.0f%% %8.2f\n", c.name, median(rates), 100.0 * touching / calls,
                    touching ? static_cast<double>(points) / touching : 0.0);
    }
    std::printf("pairs/s: median of 5 runs of at least 0.2 s CPU each; a mesh pair may return\n"
                "several manifolds (one per contact region), points counts them all\n\n");
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    benchBroadphase(quick);
    benchBvh(quick);
    benchNarrowphase(quick);
    return 0;
}
