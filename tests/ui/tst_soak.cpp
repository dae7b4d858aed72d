// The editor soak, heap: a large scene (a ground and 600 bodies) opened by a document,
// simulated to the end by its timeline (the worker thread, the recording) and closed, 16
// times. Once Qt's and glibc's per-thread caches have filled (by the 8th cycle), the heap
// in use no longer grows: a leak of even one small block a cycle fails the test. The main
// window's cycles (viewport and docks included) are checked for leaks by LeakSanitizer in
// helpers/soak_leaks.cpp (ctest: ui/soak_leaks).
//
// Environment: TUMBLE_SOAK_CYCLES (default 16, at least 10); TUMBLE_SOAK_LEAK: bytes leaked
// on purpose every cycle (default 0), to see the check fail.
#include "helpers/soak_cycle.h"

#include <QApplication>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace tumble;

class TestSoak : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

    void openSimulateCloseManyTimesWithoutGrowth() {
        const char* c = std::getenv("TUMBLE_SOAK_CYCLES");
        const int cycles = c && *c ? std::atoi(c) : 16;
        const char* l = std::getenv("TUMBLE_SOAK_LEAK");
        const std::size_t leak = l && *l ? std::strtoul(l, nullptr, 10) : 0;
        const int warm = 8;  // cycles that fill the caches
        QVERIFY(cycles >= warm + 2);
        QTemporaryDir dir;
        const QString path = dir.filePath("large.json");
        soak::writeLargeScene(path.toStdString(), 600);

        std::vector<std::size_t> heap;
        std::vector<char*> leaked;
        QElapsedTimer clock;
        clock.start();
        for (int k = 0; k < cycles; ++k) {
            QString error;
            QVERIFY2(soak::timelineCycle(path, &error), qPrintable(error));
            if (leak) leaked.push_back(new char[leak]);
            heap.push_back(soak::heapInUse());
            std::printf("cycle %d: heap in use %zu B (%+lld B since the first), %.1f s\n", k + 1, heap.back(),
                        static_cast<long long>(heap.back()) - static_cast<long long>(heap.front()),
                        clock.elapsed() / 1000.0);
        }
        for (char* p : leaked) delete[] p;
        // A block of 1 KiB leaked every cycle is more than twice this over the 8 cycles after
        // the warm ones.
        const std::size_t bound = 4 * 1024;
        const std::size_t warmHeap = heap[warm - 1];
        QVERIFY2(heap.back() <= warmHeap + bound,
                 qPrintable(QString("heap in use grew from %1 B after cycle %2 to %3 B after cycle %4")
                                .arg(warmHeap)
                                .arg(warm)
                                .arg(heap.back())
                                .arg(cycles)));
    }
};

QTEST_MAIN(TestSoak)
#include "tst_soak.moc"
