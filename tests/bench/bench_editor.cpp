// Editor benchmark (run by hand, not a test; figures go to docs/benchmarks.md): how the
// editor copes with scenes of many bodies. For scenes of N boxes and spheres in a grid (and
// the ground plane), built in code and loaded with Document::replaceScene, it measures in
// wall time (QElapsedTimer), each the median of several runs:
// - load: replaceScene until the event queue is drained (processEvents), and until the first
//   frame of the new scene has been rendered;
// - frame: the camera orbits by 1 degree (Viewport::setCamera) and we wait until a frame
//   with it has been rendered;
// - selection of one body (Document::setSelection) and a move of one body (Document::setBody
//   with a new position) until processed, and until the next frame has been rendered;
// - pick: Viewport::bodyAt at the centre of the viewport;
// - idle: process CPU time (all threads) over 2 s of wall time in which nothing changes.
//
// "Rendered" is detected with a Qt3DRender::QRenderCapture put at the root of the
// viewport's frame graph (above the default forward renderer, which is otherwise unchanged)
// asking for a 1 x 1 pixel capture: its reply completes on the main thread once the
// render thread has drawn the frame and read that pixel back, which it can only do after
// the whole frame was drawn. Qt3DWindow is a plain QWindow and has no frameSwapped signal.
// The time from a change to the completed capture is what a user waits to see the change.
//
// Two set-ups: the whole editor (ui::MainWindow: viewport, scene tree, properties, settings
// and undo history docks), and the viewport alone (a Document and a Viewport of the same
// size as the main window's viewport), so the docks' share of a cost can be told apart.
//
// Usage: tumble-bench-editor [--quick] [--pieces] [--viewport-only] [--sizes 100,1000,5000] [--runs R]
//                            [--frames F]
//   --quick   100 and 1000 bodies, fewer runs (a smoke run)
//   --viewport-only  only the viewport alone (888 x 959, the editor's viewport at 1600 x 1000)
//   --pieces  also the property dock alone and the scene tree dock alone (with a Document,
//             no viewport): their share of load, selection and move
#include "document/document.h"
#include "editor_main.h"
#include "window/main_window.h"
#include "panels/property_dock.h"
#include "panels/scene_tree_dock.h"
#include "viewport/viewport.h"

#include <Qt3DExtras/Qt3DWindow>
#include <Qt3DRender/QFrameGraphNode>
#include <Qt3DRender/QRenderCapture>

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QFile>
#include <QMainWindow>
#include <QStandardPaths>
#include <QTimer>
#include <QWindow>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace tumble;
using namespace tumble::ui;

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double maxOf(const std::vector<double>& v) {
    return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}

// N bodies, boxes and spheres alternating, on a square grid 1.5 m apart resting on the
// ground (the ground plane of the empty scene is body 0).
SceneDesc gridScene(int n) {
    SceneDesc scene = emptyScene();
    const int side = int(std::ceil(std::sqrt(double(n))));
    const double spacing = 1.5;
    const double offset = 0.5 * spacing * (side - 1);
    for (int i = 0; i < n; ++i) {
        BodyDesc b;
        const bool box = i % 2 == 0;
        b.name = (box ? "box-" : "sphere-") + std::to_string(i);
        b.shape.type = box ? ShapeType::Box : ShapeType::Sphere;
        b.shape.radius = 0.4;
        b.shape.halfExtents = Vec3(0.4, 0.4, 0.4);
        b.mass = 1.0;
        b.position = Vec3(spacing * (i % side) - offset, 0.4, spacing * (i / side) - offset);
        scene.bodies.push_back(b);
    }
    return scene;
}

// What the editor is measured in: the whole main window, or a Document and a Viewport.
struct Setup {
    std::string name;
    std::unique_ptr<MainWindow> window;
    std::unique_ptr<Document> ownDoc;
    std::unique_ptr<Viewport> ownView;
    std::unique_ptr<QMainWindow> ownWindow;  // a dock alone
    Document* doc = nullptr;
    Viewport* view = nullptr;
    QWidget* top = nullptr;
    Qt3DRender::QRenderCapture* capture = nullptr;
};

void drain() {
    QCoreApplication::sendPostedEvents();
    QCoreApplication::processEvents(QEventLoop::AllEvents);
}

// Waits until a frame rendered from now on has been drawn; false after 60 s. Without a
// viewport (a dock alone), returns at once.
bool waitFrame(Setup& s) {
    if (!s.capture) return true;
    std::unique_ptr<Qt3DRender::QRenderCaptureReply> reply(s.capture->requestCapture(QRect(0, 0, 1, 1)));
    if (reply->isComplete()) return true;
    QEventLoop loop;
    QObject::connect(reply.get(), &Qt3DRender::QRenderCaptureReply::completed, &loop, &QEventLoop::quit);
    QTimer::singleShot(60000, &loop, &QEventLoop::quit);
    loop.exec();
    return reply->isComplete();
}

// Puts a render capture at the root of the viewport's frame graph.
void installCapture(Setup& s) {
    auto* window = static_cast<Qt3DExtras::Qt3DWindow*>(s.view->renderWindow());
    Qt3DRender::QFrameGraphNode* graph = window->activeFrameGraph();
    s.capture = new Qt3DRender::QRenderCapture();
    graph->setParent(s.capture);
    window->setActiveFrameGraph(s.capture);
}

bool showAndWait(Setup& s) {
    s.top->show();
    QElapsedTimer t;
    t.start();
    QWindow* w = s.view ? s.view->renderWindow() : s.top->windowHandle();
    while ((!w || !w->isExposed()) && t.elapsed() < 10000) {
        drain();
        if (!w) w = s.top->windowHandle();
    }
    return w && w->isExposed();
}

std::unique_ptr<Setup> makeWindow() {
    auto s = std::make_unique<Setup>();
    s->name = "editor";
    s->window = std::make_unique<MainWindow>();
    s->window->resize(1600, 1000);
    s->doc = s->window->document();
    s->view = s->window->viewport();
    s->top = s->window.get();
    return s;
}

std::unique_ptr<Setup> makeViewportOnly(const QSize& size) {
    auto s = std::make_unique<Setup>();
    s->name = "viewport only";
    s->ownDoc = std::make_unique<Document>();
    s->ownView = std::make_unique<Viewport>(s->ownDoc.get());
    s->ownView->resize(size);
    s->doc = s->ownDoc.get();
    s->view = s->ownView.get();
    s->top = s->ownView.get();
    return s;
}

// A Document and one dock in a main window of the editor's size (the time a dock takes).
template <class Dock>
std::unique_ptr<Setup> makeDockOnly(const char* name) {
    auto s = std::make_unique<Setup>();
    s->name = name;
    s->ownDoc = std::make_unique<Document>();
    s->ownWindow = std::make_unique<QMainWindow>();
    s->ownWindow->addDockWidget(Qt::LeftDockWidgetArea, new Dock(s->ownDoc.get(), s->ownWindow.get()));
    s->ownWindow->setCentralWidget(new QWidget);
    s->ownWindow->resize(1600, 1000);
    s->doc = s->ownDoc.get();
    s->top = s->ownWindow.get();
    return s;
}

struct Figures {
    double loadDrained = NAN, loadFrame = NAN;
    double frame = NAN, frameMax = NAN;
    double select = NAN, selectFrame = NAN;
    double edit = NAN, editFrame = NAN;
    double pick = NAN;
    double idleCpu = NAN;  // process CPU time over wall time while nothing changes (%)
    int entities = 0;
};

double msSince(const QElapsedTimer& t) {
    return double(t.nsecsElapsed()) * 1e-6;
}

Figures measure(Setup& s, int n, int runs, int frames) {
    Figures f;
    const SceneDesc scene = gridScene(n);
    const SceneDesc empty = emptyScene();
    QElapsedTimer t;

    // Load: from an empty scene each time.
    std::vector<double> drained, shown;
    for (int r = 0; r < runs; ++r) {
        s.doc->replaceScene(empty, QString(), false);
        drain();
        waitFrame(s);
        t.start();
        s.doc->replaceScene(scene, QString(), false);
        drain();
        drained.push_back(msSince(t));
        waitFrame(s);
        shown.push_back(msSince(t));
    }
    f.loadDrained = median(drained);
    f.loadFrame = median(shown);
    f.entities = s.view ? s.view->entityCount() : 0;

    // Frames: orbit 1 degree a frame around everything.
    if (s.view) s.view->frameAll();
    drain();
    waitFrame(s);
    const QVector3D target = s.view ? s.view->cameraTarget() : QVector3D();
    const float distance = s.view ? s.view->cameraDistance() : 0.0f;
    std::vector<double> frameTimes;
    for (int i = 0; s.view && i < frames; ++i) {
        t.start();
        s.view->setCamera(target, distance, 30.0f + float(i), 35.0f);
        waitFrame(s);
        frameTimes.push_back(msSince(t));
    }
    f.frame = median(frameTimes);
    f.frameMax = maxOf(frameTimes);

    // Idle: nothing changes for 2 s; does the viewport keep the processors busy?
    if (s.view) {
        const std::clock_t c0 = std::clock();
        t.start();
        QEventLoop idle;
        QTimer::singleShot(2000, &idle, &QEventLoop::quit);
        idle.exec();
        f.idleCpu = 100.0 * (double(std::clock() - c0) / CLOCKS_PER_SEC) / (msSince(t) * 1e-3);
    }

    // Selection of one body (alternating between two, so each is a change).
    const int a = n / 2, b = n / 2 + 1;
    std::vector<double> sel, selShown;
    for (int r = 0; r < runs; ++r) {
        t.start();
        s.doc->setSelection({r % 2 ? a : b});
        drain();
        sel.push_back(msSince(t));
        waitFrame(s);
        selShown.push_back(msSince(t));
    }
    f.select = median(sel);
    f.selectFrame = median(selShown);

    // A property edit: body `a` (selected or not) moves up by 1 cm each time.
    std::vector<double> edit, editShown;
    for (int r = 0; r < runs; ++r) {
        BodyDesc body = s.doc->body(a);
        body.position.y() += 0.01;
        t.start();
        s.doc->setBody(a, body, QStringLiteral("Move"), 0);
        drain();
        edit.push_back(msSince(t));
        waitFrame(s);
        editShown.push_back(msSince(t));
    }
    f.edit = median(edit);
    f.editFrame = median(editShown);

    // Picking at the centre of the viewport.
    if (!s.view) {
        s.doc->replaceScene(empty, QString(), false);
        drain();
        return f;
    }
    const QPoint centre(s.view->width() / 2, s.view->height() / 2);
    std::vector<double> picks;
    int hit = -2;
    for (int r = 0; r < 20; ++r) {
        t.start();
        hit = s.view->bodyAt(centre);
        picks.push_back(msSince(t));
    }
    f.pick = median(picks);
    std::printf("    (%s, %d bodies: pick at the centre hit body %d)\n", s.name.c_str(), n, hit);

    s.doc->replaceScene(empty, QString(), false);
    drain();
    waitFrame(s);
    return f;
}

std::string loadAverage() {
    QFile f("/proc/loadavg");
    if (!f.open(QIODevice::ReadOnly)) return "?";
    return f.readLine().trimmed().toStdString();
}

void printRow(const Setup& s, int n, const Figures& f) {
    std::printf(
        "| %-13s | %5d | %8d | %9.1f | %9.1f | %8.1f | %8.1f | %8.2f | %8.1f | %8.2f | %8.1f | %8.3f | %5.0f "
        "|\n",
        s.name.c_str(), n, f.entities, f.loadDrained, f.loadFrame, f.frame, f.frameMax, f.select,
        f.selectFrame, f.edit, f.editFrame, f.pick, f.idleCpu);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    tumble::ui::keepFrameMemory();  // as the editor does (editor_main.h)
    QApplication app(argc, argv);
    // Keep the bench's window geometry, recent files and autosave away from the user's.
    QApplication::setOrganizationName("TumbleBench");
    QApplication::setApplicationName("tumble-bench-editor");
    QStandardPaths::setTestModeEnabled(true);

    std::vector<int> sizes = {100, 1000, 5000};
    int runs = 3, frames = 15;
    bool pieces = false;
    bool viewportOnly = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--quick")) {
            sizes = {100, 1000};
            runs = 3;
            frames = 10;
        } else if (!std::strcmp(argv[i], "--pieces")) {
            pieces = true;
        } else if (!std::strcmp(argv[i], "--viewport-only")) {
            viewportOnly = true;
        } else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
            sizes.clear();
            for (const QString& part : QString(argv[++i]).split(',')) sizes.push_back(part.toInt());
        } else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) {
            runs = std::atoi(argv[++i]);
        } else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) {
            frames = std::atoi(argv[++i]);
        } else {
            std::fprintf(
                stderr,
                "usage: %s [--quick] [--pieces] [--viewport-only] [--sizes 100,1000,5000] [--runs R] "
                "[--frames F]\n",
                argv[0]);
            return 2;
        }
    }

    std::printf("Load average at the start: %s\n", loadAverage().c_str());
    std::printf("Times in ms, wall (QElapsedTimer), median of %d runs (frames: median and largest of %d).\n",
                runs, frames);
    std::printf(
        "| set-up        |     N | entities | load: drained | load: first frame | frame | slowest frame "
        "| select | select: frame | move | move: frame | pick | idle CPU %% |\n");
    std::printf("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");

    QSize viewportSize(888, 959);  // the editor's, at 1600 x 1000
    if (!viewportOnly) {
        auto s = makeWindow();
        if (!showAndWait(*s)) {
            std::fprintf(stderr, "the viewport never became exposed (is there a display?)\n");
            return 1;
        }
        installCapture(*s);
        s->doc->replaceScene(emptyScene(), QString(), false);
        drain();
        waitFrame(*s);  // the first frame: shaders, the grid
        viewportSize = s->view->size();
        std::printf("    (editor window %dx%d, its viewport %dx%d)\n", s->top->width(), s->top->height(),
                    viewportSize.width(), viewportSize.height());
        for (int n : sizes) printRow(*s, n, measure(*s, n, runs, frames));
    }
    {
        auto s = makeViewportOnly(viewportSize);
        if (!showAndWait(*s)) return 1;
        std::printf("    (GL renderer: %s; samples per pixel: %d)\n", qPrintable(Viewport::glRenderer()),
                    s->view->samples());
        installCapture(*s);
        drain();
        waitFrame(*s);
        for (int n : sizes) printRow(*s, n, measure(*s, n, runs, frames));
    }
    if (pieces) {
        std::vector<std::function<std::unique_ptr<Setup>()>> makers = {
            [] { return makeDockOnly<PropertyDock>("properties"); },
            [] { return makeDockOnly<SceneTreeDock>("scene tree"); }};
        for (const auto& make : makers) {
            auto s = make();
            if (!showAndWait(*s)) return 1;
            drain();
            for (int n : sizes) printRow(*s, n, measure(*s, n, runs, frames));
        }
    }
    std::printf("Load average at the end: %s\n", loadAverage().c_str());
    return 0;
}
