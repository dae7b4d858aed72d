// A child process for tests/ui/window/tst_crash_safety.cpp, killed (SIGKILL) by the test at a
// moment of its choosing:
//   crash_child save-loop SCENE OUT   opens SCENE and saves it to OUT again and again, each
//                                     time with the first dynamic body moved, printing
//                                     "saved N" after each save;
//   crash_child autosave SCENE        opens SCENE in the editor's main window, makes an edit,
//                                     autosaves, prints "autosaved", then waits to be killed;
//   crash_child save-once SCENE OUT   opens SCENE and saves it to OUT, then exits;
//   crash_child hold OUT              starts a save of OUT (an io::AtomicFile, the editor's
//                                     way), writes part of it, prints "holding", then waits
//                                     to be killed before the commit.
//   crash_child save-meshes-once SCENE OUT   File > Save with Meshes of SCENE to OUT.
//   crash_child autosave-once SCENE   writes SCENE as this editor's autosave (its data folder
//                                     from XDG_DATA_HOME) and prints the file's path.
// A write that fails prints the editor's message on stderr and exits with status 1.
// (tests/ui/window/tst_write_faults.cpp runs the last three under faults.)
#include "document/document.h"
#include "window/autosave.h"
#include "window/main_window.h"

#include <tumble/io/atomic_file.h>

#include <QApplication>
#include <QThread>

#include <cstdio>
#include <cstring>

using namespace tumble;
using namespace tumble::ui;

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setApplicationName("Tumble");
    QApplication::setOrganizationName("Tumble");
    if (argc == 4 && !std::strcmp(argv[1], "save-loop")) {
        Document doc;
        QString error;
        if (!doc.open(argv[2], &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 2;
        }
        const int moved = doc.bodyCount() - 1;
        for (long n = 1;; ++n) {
            BodyDesc b = doc.body(moved);
            b.position.x() = double(n);
            doc.setBody(moved, b, "Move");
            if (!doc.saveAs(argv[3], &error)) {
                std::fprintf(stderr, "%s\n", qPrintable(error));
                return 1;
            }
            std::printf("saved %ld\n", n);
            std::fflush(stdout);
        }
    }
    if (argc == 3 && !std::strcmp(argv[1], "autosave")) {
        MainWindow w;
        QString error;
        if (!w.openScene(argv[2], &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 2;
        }
        BodyDesc b = w.document()->body(1);
        b.restitution = 0.123;
        w.document()->setBody(1, b, "Restitution");
        w.autosave();
        std::printf("autosaved\n");
        std::fflush(stdout);
        for (;;) QThread::sleep(1);
    }
    if (argc == 4 && !std::strcmp(argv[1], "save-once")) {
        Document doc;
        QString error;
        if (!doc.open(argv[2], &error) || !doc.saveAs(argv[3], &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 1;
        }
        return 0;
    }
    if (argc == 4 && !std::strcmp(argv[1], "save-meshes-once")) {
        Document doc;
        QString error;
        if (!doc.open(argv[2], &error) || !doc.saveWithMeshes(argv[3], &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 1;
        }
        return 0;
    }
    if (argc == 3 && !std::strcmp(argv[1], "autosave-once")) {
        Document doc;
        QString error;
        if (!doc.open(argv[2], &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 2;
        }
        Autosave autosave;
        std::printf("%s\n", qPrintable(autosave.file()));
        std::fflush(stdout);
        if (!autosave.write(doc.scene(), doc.filePath(), &error)) {
            std::fprintf(stderr, "%s\n", qPrintable(error));
            return 1;
        }
        return 0;
    }
    if (argc == 3 && !std::strcmp(argv[1], "hold")) {
        io::AtomicFile file(argv[2]);
        file.stream() << R"({"format": "tumble-scene", "version": 1, "bodies": [)" << std::flush;
        std::printf("holding\n");
        std::fflush(stdout);
        for (;;) QThread::sleep(1);
    }
    std::fprintf(stderr,
                 "usage: crash_child save-loop SCENE OUT | autosave SCENE | save-once SCENE OUT | hold OUT | "
                 "save-meshes-once SCENE OUT | autosave-once SCENE\n");
    return 2;
}
