// The cycles of the editor soak (tests/ui/window/tst_soak.cpp and the leak check's helper
// soak_leaks.cpp): a large scene file opened, simulated to the end of its duration, its last
// frame shown, and closed: by the main window (cycle) or by a document and its timeline
// (timelineCycle); opened again in the same shown main window (reopenCycle); a viewport
// made and destroyed unshown (viewportCycle).
#pragma once

#include "document/document.h"
#include "window/main_window.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"

#include <tumble/io/scene_file.h>

#include <QCoreApplication>
#include <QDeadlineTimer>
#include <QEvent>
#include <QString>
#include <QThread>

#include <malloc.h>

#include <algorithm>
#include <array>

#include <string>

namespace tumble::soak {

/// Heap in use: bytes handed out by malloc, in the arenas and in mmapped chunks.
inline std::size_t heapInUse() {
    const struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

/// The heap in use once what is pending has been handled: the median of five readings a
/// few tens of milliseconds apart, the events handled in between (Qt 3D's render thread
/// frees and makes again a few hundred KiB around each frame it draws).
inline std::size_t settledHeapInUse() {
    std::array<std::size_t, 5> readings{};
    for (std::size_t& r : readings) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
        QThread::msleep(40);
        r = heapInUse();
    }
    std::sort(readings.begin(), readings.end());
    return readings[2];
}

/// A large scene: a ground and `count` boxes and spheres in a grid, dropped from up to a few
/// metres (they land and bounce within the second the scene lasts), written to `path`.
inline void writeLargeScene(const std::string& path, int count) {
    SceneDesc s;
    s.settings.duration = 1.0;
    BodyDesc ground;
    ground.name = "ground";
    ground.motion = Motion::Static;
    ground.shape.type = ShapeType::Plane;
    s.bodies.push_back(ground);
    const int side = 10;
    for (int i = 0; i < count; ++i) {
        BodyDesc b;
        b.name = "body-" + std::to_string(i);
        if (i % 2) {
            b.shape.type = ShapeType::Sphere;
            b.shape.radius = 0.3;
        } else {
            b.shape.type = ShapeType::Box;
            b.shape.halfExtents = Vec3(0.3, 0.2, 0.25);
        }
        b.mass = 1.0;
        b.position = Vec3((i % side) * 1.0, 0.5 + (i / (side * side)) * 1.0, ((i / side) % side) * 1.0);
        b.angularVelocity = Vec3(0.1 * (i % 7), 0.2, 0.1 * (i % 5));
        s.bodies.push_back(b);
    }
    io::writeSceneFile(s, path);
}

/// Deletes what was deleted later (deleteLater) and handles what is pending.
inline void settle() {
    for (int i = 0; i < 3; ++i) {
        QCoreApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);
        QCoreApplication::processEvents(QEventLoop::AllEvents, 10);
    }
}

/// Waits for the timeline's run to complete; false with the reason in `error` if it did not.
inline bool waitForRun(ui::Timeline* t, const QString& path, QString* error) {
    QDeadlineTimer deadline(120 * 1000);
    while (t->status() != ui::Timeline::Status::Complete && !deadline.hasExpired()) {
        QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
        QThread::msleep(5);
    }
    if (t->status() == ui::Timeline::Status::Complete) return true;
    *error = QString("%1: the run did not complete (%2 of %3 frames): %4")
                 .arg(path)
                 .arg(t->framesDone())
                 .arg(t->frameCount())
                 .arg(t->errorMessage());
    return false;
}

/// The main window opens the scene (shown or not), simulates it, shows its last frame, and
/// is closed and destroyed; false with the reason in `error` when a step did not happen.
inline bool cycle(const QString& path, bool show, QString* error) {
    {
        ui::MainWindow w;
        if (!w.openScene(path, error)) return false;
        if (show) w.show();
        w.timeline()->simulate();
        if (!waitForRun(w.timeline(), path, error)) return false;
        w.timeline()->toEnd();
        QCoreApplication::processEvents();
        w.close();
    }
    settle();
    return true;
}

/// The same with the document and its timeline only.
inline bool timelineCycle(const QString& path, QString* error) {
    {
        ui::Document doc;
        if (!doc.open(path, error)) return false;
        ui::Timeline t(&doc);
        t.simulate();
        if (!waitForRun(&t, path, error)) return false;
        t.toEnd();
        State last;
        if (!t.frameState(t.frameCount() - 1, &last)) {
            *error = path + ": the last frame is not readable";
            return false;
        }
    }
    settle();
    return true;
}

/// A viewport of the document made and destroyed without ever being shown (as an image
/// export's or a test's may be).
inline void viewportCycle(ui::Document* doc) {
    { ui::Viewport view(doc); }
    settle();
}

/// The shown main window `w` opens the scene again (as File > Open does: the document
/// replaces its scene, the viewport and the docks follow), simulates it and shows its last
/// frame; false with the reason in `error` when a step did not happen.
inline bool reopenCycle(ui::MainWindow* w, const QString& path, QString* error) {
    if (!w->openScene(path, error)) return false;
    w->timeline()->simulate();
    if (!waitForRun(w->timeline(), path, error)) return false;
    w->timeline()->toEnd();
    settle();
    return true;
}

}  // namespace tumble::soak
