// A soak: a busy scene (a square pyramid of 285 boxes, each on the four below it, the layers
// a little apart so that it drops into place; sleeping off, so every contact is found and
// solved every step) run at the scenes' default step for 4.5 s. Every step leaves every
// body's state finite; the contacts are as many as claimed (about 1 700 points a step); the
// heap in use stops growing once the pile has landed (the contact caches have their size),
// so that a leak of even one 64-byte block a step fails; the energy never exceeds the
// start's and the pile stays a pile (its kinetic energy after the warm-up is under 5% of its
// potential energy above the ground).
//
// Not asserted, because it does not hold (see the report of issue 9): that a settled pile
// with sleeping off stays at rest. It gains energy in bursts (here up to 63 J of kinetic
// energy after 0.04 J at 2 s); at 1/60 s a 10-layer pyramid gains more than it started with.
//
// Environment (for a longer run by hand, not in ctest):
//   TUMBLE_SOAK_SECONDS   simulated seconds (default 4.5); a long run also needs
//                         QTEST_FUNCTION_TIMEOUT (ms, Qt Test stops a test after 300 s)
//   TUMBLE_SOAK_LEAK      bytes leaked on purpose every step (default 0): shows the heap
//                         check failing, as it must on a leak
// A run prints the heap in use (warm-up maximum, maximum after, at the end), the peak
// resident size, the steps per second, the contact points and the energies.
#include "scene_builders.h"

#include <QtTest>

#include <malloc.h>

#include <sys/resource.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace tumble;
using namespace tumble::test;

namespace {

constexpr double kHalf = 0.4;        // box half extent (m)
constexpr int kLayers = 9;           // a square pyramid of 9 x 9, 8 x 8, ... 1 x 1 boxes: 285
constexpr double kGap = 0.05;        // m between layers at the start: the pile drops into place
constexpr double kDt = 1.0 / 240.0;  // the scenes' default step

// Heap in use: bytes handed out by malloc, in the arenas and in mmapped chunks.
std::size_t heapInUse() {
    const struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

long peakRssKiB() {
    struct rusage r {};
    getrusage(RUSAGE_SELF, &r);
    return r.ru_maxrss;
}

double envOr(const char* name, double fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::atof(v) : fallback;
}

// A square pyramid of boxes on the ground, each box on the four below it (every contact
// between layers a face on four faces), the layers a little apart and each box turned a
// little about the vertical at random: dropped, the pile lands layer on layer and settles.
SceneDesc busyScene() {
    std::vector<BodyDesc> bodies;
    bodies.push_back(groundPlane(0.3, 0.6));
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> yaw(-0.05, 0.05);
    for (int l = 0; l < kLayers; ++l) {
        const int n = kLayers - l;
        for (int i = 0; i < n; ++i)
            for (int k = 0; k < n; ++k) {
                std::string name = "b";
                name += std::to_string(bodies.size());
                BodyDesc b = material(boxBody(name, Vec3(kHalf, kHalf, kHalf), 1.0), 0.3, 0.6);
                b.position = Vec3((2 * i - n + 1) * kHalf, kHalf + l * (2 * kHalf + kGap) + kGap,
                                  (2 * k - n + 1) * kHalf);
                b.orientation = Quat(Eigen::AngleAxisd(yaw(rng), Vec3::UnitY()));
                bodies.push_back(b);
            }
    }
    SceneDesc s = sceneOf(std::move(bodies));
    s.settings.sleeping = false;  // every body is simulated every step: the contacts stay busy
    s.settings.dt = kDt;
    return s;
}

bool finite(const BodyState& b) {
    return b.x.allFinite() && b.q.coeffs().allFinite() && b.P.allFinite() && b.L.allFinite();
}

long contactPoints(const World& w) {
    long n = 0;
    for (const collision::Manifold& m : w.contacts()) n += m.count;
    return n;
}

}  // namespace

class TestSoak : public QObject {
    Q_OBJECT
private slots:
    void busyPileStaysFiniteBoundedAndSettles() {
        const double seconds = envOr("TUMBLE_SOAK_SECONDS", 4.5);
        const auto leak = static_cast<std::size_t>(envOr("TUMBLE_SOAK_LEAK", 0.0));
        const double warmUp = 1.5;  // s: the pile has landed; the contact caches have their size
        QVERIFY(seconds >= 3 * warmUp);

        World w(busyScene());
        const Energy start = energy(w.model(), w.state());
        // The scale of the energies: the potential energy of the pile above the ground.
        double height = 0;
        for (int i : w.model().dynamicBodies)
            height += w.model().bodies[i].mass * 9.81 * (w.state().bodies[i].x.y() - kHalf);

        const long steps = std::lround(seconds / kDt);
        const long warmSteps = std::lround(warmUp / kDt);
        std::size_t heapWarm = 0, heapMax = 0;  // max in the second half of the warm-up, max after
        long minPoints = -1, maxPoints = 0, sumPoints = 0;
        double maxTotal = start.total(), maxKineticLate = 0;
        std::vector<char*> leaked;
        QElapsedTimer clock;
        clock.start();
        for (long n = 1; n <= steps; ++n) {
            w.step(kDt);
            if (leak) leaked.push_back(new char[leak]);
            for (std::size_t i = 0; i < w.state().bodies.size(); ++i)
                if (!finite(w.state().bodies[i]))
                    QFAIL(qPrintable(QString("step %1: body %2 is not finite").arg(n).arg(i)));
            const Energy e = energy(w.model(), w.state());
            maxTotal = std::max(maxTotal, e.total());
            if (n >= warmSteps / 2 && n <= warmSteps) heapWarm = std::max(heapWarm, heapInUse());
            if (n <= warmSteps) continue;
            const long points = contactPoints(w);
            minPoints = minPoints < 0 ? points : std::min(minPoints, points);
            maxPoints = std::max(maxPoints, points);
            sumPoints += points;
            maxKineticLate = std::max(maxKineticLate, e.kinetic);
            heapMax = std::max(heapMax, heapInUse());
        }
        const double elapsed = clock.elapsed() / 1000.0;
        const Energy end = energy(w.model(), w.state());
        const long after = steps - warmSteps;
        std::printf(
            "soak: %zu bodies, %ld steps of %.4g s in %.1f s (%.1f steps/s); contact points after "
            "the warm-up %ld..%ld, mean %ld; heap in use: warm-up max %zu B, max after %zu B, at the "
            "end %zu B; peak RSS %ld KiB; energy at the "
            "start %.6g J, max %.6g J, at the end %.6g J; kinetic after the warm-up max %.3g J, at "
            "the end %.3g J\n",
            w.state().bodies.size(), steps, kDt, elapsed, steps / elapsed, minPoints, maxPoints,
            sumPoints / after, heapWarm, heapMax, heapInUse(), peakRssKiB(), start.total(), maxTotal,
            end.total(), maxKineticLate, end.kinetic);
        for (char* p : leaked) delete[] p;

        // As busy as claimed: over 1 500 contact points a step after the warm-up (1 701 on average,
        // up to 2 508).
        QVERIFY2(sumPoints / after >= 1500,
                 qPrintable(QString("only %1 contact points a step").arg(sumPoints / after)));
        // The heap does not grow once the contact caches have their size (it follows the
        // number of contacts a little: the bound is on the maximum after the warm-up against
        // the maximum in its second half). One 64-byte block leaked a step (80 bytes with
        // malloc's header) over the 720 steps after the warm-up is 56 KiB, above the bound.
        const std::size_t bound = 16 * 1024;
        QVERIFY2(
            heapMax <= heapWarm + bound,
            qPrintable(
                QString("heap in use grew from %1 B to %2 B after the warm-up").arg(heapWarm).arg(heapMax)));
        // Energy never exceeds the start's (up to the integrator's rounding in the first steps
        // of the fall, 1e-6 of the pile's potential energy), and the pile stays a pile: after
        // the warm-up its motion is a small fraction of its potential energy above the ground.
        QVERIFY2(maxTotal <= start.total() + 1e-6 * height,
                 qPrintable(QString("energy rose to %1 J from %2 J (by %3 J)")
                                .arg(maxTotal, 0, 'g', 12)
                                .arg(start.total(), 0, 'g', 12)
                                .arg(maxTotal - start.total())));
        QVERIFY2(maxKineticLate < 0.05 * height,
                 qPrintable(QString("kinetic energy %1 J after the warm-up, the pile's potential %2 J")
                                .arg(maxKineticLate)
                                .arg(height)));
    }
};

QTEST_GUILESS_MAIN(TestSoak)
#include "tst_soak.moc"
