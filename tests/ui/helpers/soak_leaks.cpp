// The editor soak's leak check (ctest: ui/soak_leaks): opens a large scene in a main window,
// simulates it to the end and closes it, a few times (helpers/soak_cycle.h), and ends
// cleanly, under LeakSanitizer (gcc's liblsan preloaded into this uninstrumented program,
// tests/ui/lsan.supp for what Qt, Mesa and fontconfig keep until exit), which reports every
// block still allocated and unreachable at exit and fails the run.
//
//   soak_leaks CYCLES [--leak-on-purpose]
//
// --leak-on-purpose leaks a block from a slot the event loop calls (Qt's frames below it on
// the stack), as a leak in the editor would be: ui/soak_leaks_caught expects the report to
// name it, so the suppressions cannot hide a leak in Tumble's code. Refuses to run (exit 3)
// when LeakSanitizer is not loaded, so the check cannot pass by not running.
#include "soak_cycle.h"

#include <QApplication>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTimer>

#include <dlfcn.h>
#include <link.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

// Kept from inlining so that its name is on the report's stack.
__attribute__((noinline)) void* soakLeakOnPurpose() {
    static void* volatile sink;
    sink = std::malloc(4096);
    void* p = sink;
    sink = nullptr;  // nothing refers to it any more
    return p;
}

// Keeps Mesa's driver loaded to the end (it is unloaded at exit otherwise), so that what it
// keeps is reported under its name, which the suppressions name, not an unknown module.
void pinDrivers() {
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void*) {
            if (info->dlpi_name && std::strstr(info->dlpi_name, "/dri/"))
                dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
}

int main(int argc, char** argv) {
    if (!dlsym(RTLD_DEFAULT, "__lsan_do_leak_check")) {
        std::fprintf(stderr, "soak_leaks: LeakSanitizer is not loaded (LD_PRELOAD=liblsan.so.0)\n");
        return 3;
    }
    const int cycles = argc > 1 ? std::atoi(argv[1]) : 3;
    const bool leak = argc > 2 && !std::strcmp(argv[2], "--leak-on-purpose");
    QApplication app(argc, argv);
    QStandardPaths::setTestModeEnabled(true);
    QApplication::setQuitOnLastWindowClosed(false);
    QTemporaryDir dir;
    const QString path = dir.filePath("large.json");
    tumble::soak::writeLargeScene(path.toStdString(), 600);
    for (int k = 0; k < cycles; ++k) {
        QString error;
        if (!tumble::soak::cycle(path, true, &error)) {
            std::fprintf(stderr, "soak_leaks: %s\n", qPrintable(error));
            return 1;
        }
        std::printf("cycle %d done\n", k + 1);
        std::fflush(stdout);
    }
    pinDrivers();
    if (leak) {
        QTimer::singleShot(0, [] { soakLeakOnPurpose(); });
        tumble::soak::settle();
    }
    return 0;
}
