// The timeline's costs as a user feels them (docs/benchmarks.md "## Timeline"):
//  - how long the UI thread's event loop is held up while a long scene simulates in the
//    worker (the largest and the 99th-percentile gap between ticks of a 5 ms timer), and
//    how fast the worker records;
//  - what a seek costs: a kept frame, and a frame between keyframes under a memory cap
//    (re-simulated), first and again (cached).
// With --window the whole editor is shown (under Xvfb: the viewport draws every frame
// of playback), else the Timeline runs on its own.
//
//   xvfb-run -a -s "-screen 0 1600x1000x24" ./build/tests/bench/tumble-bench-timeline [--window] [--quick]
#include "document/document.h"
#include "window/main_window.h"
#include "timeline/timeline.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QTimer>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

using namespace tumble;
using namespace tumble::ui;

namespace {

struct Gaps {
    double maxMs = 0.0;
    double p99Ms = 0.0;
    double meanMs = 0.0;
    int ticks = 0;
};

// Runs the event loop for `seconds` (or until `done`), timing the gaps between 5 ms ticks.
template <class Done>
Gaps measureGaps(double seconds, Done done) {
    std::vector<double> gaps;
    QElapsedTimer clock, total;
    clock.start();
    total.start();
    QTimer tick;
    tick.setTimerType(Qt::PreciseTimer);
    tick.setInterval(5);
    QObject::connect(&tick, &QTimer::timeout, [&] {
        gaps.push_back(clock.nsecsElapsed() * 1e-6);
        clock.restart();
    });
    tick.start();
    while (total.elapsed() < seconds * 1000 && !done()) QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 5);
    tick.stop();
    Gaps g;
    if (gaps.empty()) return g;
    std::sort(gaps.begin(), gaps.end());
    g.ticks = static_cast<int>(gaps.size());
    g.maxMs = gaps.back();
    g.p99Ms = gaps[static_cast<std::size_t>(0.99 * (gaps.size() - 1))];
    double sum = 0;
    for (double x : gaps) sum += x;
    g.meanMs = sum / gaps.size();
    return g;
}

SceneDesc longScene(Document& doc, const char* sample, int frames, bool sleeping = true) {
    QString error;
    if (!doc.open(QStringLiteral(":/scenes/%1.json").arg(sample), &error)) {
        std::fprintf(stderr, "%s\n", qPrintable(error));
        std::exit(1);
    }
    SceneDesc s = doc.scene();
    s.settings.duration = (frames - 1) / s.settings.frameRate;
    s.settings.sleeping = s.settings.sleeping && sleeping;
    return s;
}

void simulateWhileMeasuring(Document& doc, Timeline& t, const char* sample, int frames, double seconds,
                            bool sleeping = true) {
    const SceneDesc s = longScene(doc, sample, frames, sleeping);
    doc.replaceScene(s, "bench", false);
    t.simulate();
    QElapsedTimer wall;
    wall.start();
    const Gaps g = measureGaps(seconds, [&] { return t.status() != Timeline::Status::Running; });
    const double w = wall.elapsed() * 1e-3;
    const int done = t.framesDone();
    std::printf("%-16s%s %6d frames  %6d done in %6.2f s (%7.1f frames/s, %5.2f× real time)  "
                "UI gaps: max %6.1f ms, p99 %5.1f ms, mean %4.1f ms over %d ticks\n",
                sample, sleeping ? "" : " (no sleeping)", t.frameCount(), done, w, done / w, t.speed(), g.maxMs, g.p99Ms, g.meanMs, g.ticks);
    t.cancel();
    QElapsedTimer c;
    c.start();
    while (t.status() == Timeline::Status::Running && c.elapsed() < 60000)
        QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
}

void seekCosts(Document& doc, Timeline& t, const char* sample, int frames, std::size_t capBytes,
               bool sleeping = true) {
    const SceneDesc s = longScene(doc, sample, frames, sleeping);
    doc.replaceScene(s, "bench", false);
    t.setMemoryCap(capBytes);
    t.simulate();
    while (t.status() == Timeline::Status::Running) QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> pick(0, t.framesDone() - 1);
    const int K = t.keyframeInterval();
    double keptMs = 0, firstMs = 0, againMs = 0;
    int kept = 0, between = 0;
    for (int i = 0; i < 40; ++i) {
        int k = pick(rng);
        QElapsedTimer c;
        if (K > 1) {
            k = k - k % K;
            if (k + 1 >= t.framesDone()) continue;
            c.start();
            t.seek(k);
            keptMs += c.nsecsElapsed() * 1e-6;
            ++kept;
            const int mid = std::min(t.framesDone() - 1, k + std::max(1, K - 1));
            c.restart();
            t.seek(mid);
            firstMs += c.nsecsElapsed() * 1e-6;
            c.restart();
            t.seek(mid - (mid > k + 1 ? 1 : 0));
            againMs += c.nsecsElapsed() * 1e-6;
            ++between;
        } else {
            c.start();
            t.seek(k);
            keptMs += c.nsecsElapsed() * 1e-6;
            ++kept;
        }
    }
    std::printf("%-16s %6d frames, cap %5zu MB: keyframes every %3d, recording %7.1f MB; seek kept %.3f ms",
                sample, t.framesDone(), capBytes >> 20, K, t.recordingBytes() / 1048576.0, kept ? keptMs / kept : 0.0);
    if (between)
        std::printf(", between keyframes %.2f ms first, %.3f ms cached", firstMs / between, againMs / between);
    std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    bool window = false, quick = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--window")) window = true;
        else if (!std::strcmp(argv[i], "--quick")) quick = true;
        else {
            std::fprintf(stderr, "usage: %s [--window] [--quick]\n", argv[0]);
            return 2;
        }
    }
    std::unique_ptr<MainWindow> main;
    std::unique_ptr<Document> ownDoc;
    std::unique_ptr<Timeline> ownTimeline;
    Document* doc;
    Timeline* t;
    if (window) {
        main = std::make_unique<MainWindow>();
        main->show();
        doc = main->document();
        t = main->timeline();
    } else {
        ownDoc = std::make_unique<Document>();
        ownTimeline = std::make_unique<Timeline>(ownDoc.get());
        doc = ownDoc.get();
        t = ownTimeline.get();
    }
    t->setAutoSimulate(false);
    std::printf("UI thread while the worker simulates (%s):\n", window ? "whole editor shown" : "Timeline alone");
    const double seconds = quick ? 3.0 : 10.0;
    simulateWhileMeasuring(*doc, *t, "tumbling-box", 10000, seconds);
    simulateWhileMeasuring(*doc, *t, "sleeping-wake", 10000, seconds);
    simulateWhileMeasuring(*doc, *t, "pyramid-15", 10000, seconds);
    simulateWhileMeasuring(*doc, *t, "pyramid-15", 10000, seconds, false);
    if (window) {
        // Playback at 4× of a finished run: the viewport draws each frame.
        const SceneDesc s = longScene(*doc, "tower-20", 1200);
        doc->replaceScene(s, "bench", false);
        t->simulate();
        while (t->status() == Timeline::Status::Running) QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
        t->setPlaybackSpeed(4.0);
        t->toStart();
        t->play();
        int shown = 0;
        QObject::connect(t, &Timeline::currentFrameChanged, [&] { ++shown; });
        const Gaps g = measureGaps(quick ? 2.0 : 5.0, [&] { return !t->isPlaying(); });
        std::printf("playback 4× of tower-20: %d frames shown, UI gaps max %.1f ms, p99 %.1f ms\n", shown, g.maxMs,
                    g.p99Ms);
        t->pause();
    }
    std::printf("\nSeeking:\n");
    seekCosts(*doc, *t, "sleeping-wake", quick ? 1000 : 3000, std::size_t(512) << 20);
    seekCosts(*doc, *t, "sleeping-wake", quick ? 1000 : 3000, std::size_t(1) << 20);
    seekCosts(*doc, *t, "tower-20", quick ? 600 : 2000, std::size_t(1) << 20);
    seekCosts(*doc, *t, "pyramid-15", quick ? 300 : 1200, std::size_t(8) << 20, false);
    return 0;
}
