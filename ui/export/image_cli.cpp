// The headless command line's image and video output (--out DIR/, --out FILE.mp4): the
// editor's ImageExporter driven without the editor's window. Kept in ui/ because it draws
// with the viewport; app/ reaches it through editor_main.h and sees no Qt header.
#include "document/document.h"
#include "editor_main.h"
#include "export/image_exporter.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"

#include <QApplication>
#include <QEventLoop>
#include <QLoggingCategory>
#include <QTimer>

#include <cstdlib>
#include <memory>

namespace tumble::ui {

std::string renderImages(const SceneDesc& scene, const std::string& folder, const std::string& video,
                         int width, int height, const std::function<bool()>& stop) {
    auto set = [](const char* name) {
        const char* v = std::getenv(name);
        return v && *v;
    };
    if (!set("DISPLAY") && !set("WAYLAND_DISPLAY"))
        return "images and video are drawn with OpenGL and need a display: run under xvfb-run "
               "(xvfb-run -a tumble --headless ...)";
    std::unique_ptr<QApplication> app;
    if (!QCoreApplication::instance()) {
        static int argc = 1;
        static char name[] = "tumble";
        static char* argv[] = {name, nullptr};
        keepFrameMemory();
        app = std::make_unique<QApplication>(argc, argv);
    }
    // Qt3D's start-up chatter is not for a command line's stderr.
    QLoggingCategory::setFilterRules(QStringLiteral("Qt3D.*=false\nqt3d.*=false"));
    Document doc;
    doc.replaceScene(scene, QStringLiteral("Scene"), false);
    Timeline timeline(&doc);
    timeline.setAutoSimulate(false);
    Viewport view(&doc);
    view.resize(width, height);
    view.setTimeline(&timeline);
    view.frameAll();

    QEventLoop loop;
    bool stopped = false;
    QTimer watch;  // a signal (SIGINT, SIGTERM) asks the run or the export to stop
    watch.setInterval(50);
    QObject::connect(&timeline, &Timeline::statusChanged, &loop, [&](Timeline::Status s) {
        if (s != Timeline::Status::Running) loop.quit();
    });
    QObject::connect(&watch, &QTimer::timeout, &loop, [&] {
        if (!stop || !stop()) return;
        stopped = true;
        watch.stop();
        loop.quit();
    });
    watch.start();
    timeline.simulate();
    if (timeline.status() == Timeline::Status::Running) loop.exec();
    if (stopped) {
        timeline.cancel();
        return "stopped";
    }
    if (timeline.status() != Timeline::Status::Complete)
        return "the run failed: " + timeline.errorMessage().toStdString();

    ImageExporter exporter(&view, &timeline);
    QObject::disconnect(&watch, nullptr, &loop, nullptr);
    QObject::connect(&watch, &QTimer::timeout, &exporter, [&] {
        if (!stop || !stop() || stopped) return;
        stopped = true;
        exporter.cancel();  // leaves no image, no video; finished() follows
    });
    watch.start();
    ImageExportOptions o;
    o.folder = QString::fromStdString(folder);
    o.size = QSize(width, height);
    o.video = !video.empty();
    o.videoFile = QString::fromStdString(video);
    bool ok = false;
    QString message;
    QObject::connect(&exporter, &ImageExporter::finished, &loop, [&](bool good, const QString& m) {
        ok = good;
        message = m;
        loop.quit();
    });
    exporter.start(o);
    loop.exec();
    if (stopped) return "stopped";
    return ok ? std::string() : message.toStdString();
}

}  // namespace tumble::ui
