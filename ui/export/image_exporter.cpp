#include "export/image_exporter.h"

#include <tumble/io/atomic_file.h>

#include "timeline/timeline.h"
#include "viewport/viewport.h"

#include <Qt3DRender/QRenderCapture>

#include <QBuffer>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QLoggingCategory>
#include <QPointer>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTemporaryFile>
#include <QTimer>
#include <QWindow>
#include <QtMath>

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <vector>

namespace tumble::ui {

namespace {

// The system's (or ffmpeg's) words for the usual causes of a failed write, said plainly
// first: "the disk is full (… No space left on device)".
QString plainly(const QString& why) {
    static const std::pair<const char*, int> known[] = {
        {"No space left on device", ENOSPC}, {"Read-only file system", EROFS}, {"Permission denied", EACCES}};
    for (const auto& [text, err] : known)
        if (why.contains(QLatin1String(text)))
            return QString::fromStdString(io::plainReason(err)) + QStringLiteral(" (") + why.trimmed() + ')';
    return why;
}

// The process's umask, read from /proc (umask() reads it only by setting it, which the other
// threads would see in between); 022 when it cannot be read.
mode_t processUmask() {
    QFile status(QStringLiteral("/proc/self/status"));
    if (status.open(QIODevice::ReadOnly)) {
        for (const QByteArray& line : status.readAll().split('\n')) {
            bool ok = false;
            const uint mask = line.startsWith("Umask:") ? line.mid(6).trimmed().toUInt(&ok, 8) : 0;
            if (ok) return static_cast<mode_t>(mask & 0777);
        }
    }
    return 022;
}

}  // namespace

namespace {

Q_LOGGING_CATEGORY(lcExport, "tumble.export")

// How long the export view may take to appear, and a frame to be drawn (llvmpipe at a large
// size is slow, but not this slow).
constexpr int kShowTimeoutMs = 20000;
constexpr int kFrameTimeoutMs = 60000;
// Captures of one frame at most (see onCaptured).
constexpr int kMaxCaptures = 6;
// After this long without an answer a capture is requested again.
constexpr int kRetryMs = 3000;
// How long ffmpeg may take per image (an encoder stuck on a bad input is stopped).
constexpr int kEncodeMsPerImage = 2000;
constexpr int kEncodeMinMs = 60000;

QString tail(const QByteArray& text, int lines) {
    QStringList all = QString::fromLocal8Bit(text).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    if (all.size() > lines) all = all.mid(all.size() - lines);
    return all.join(QLatin1Char('\n'));
}

// The size the export view is drawn at: the image size, or a multiple of it when that is
// below the viewport's minimum (200 x 150), scaled down after the capture.
QSize renderSize(const QSize& image) {
    const double s = std::max({1.0, 200.0 / image.width(), 150.0 / image.height()});
    return QSize(int(std::ceil(image.width() * s)), int(std::ceil(image.height() * s)));
}

// Whether Qt3D's render capture comes bottom row first. Qt3D 6's RHI renderer on its OpenGL
// backend reads the framebuffer back with glReadPixels and hands the rows over as they come,
// bottom-up (seen with Qt 6.4 under Xvfb/llvmpipe and checked by tst_image_exporter, which
// finds the ball where the camera projects it). The old OpenGL renderer
// (QT3D_RENDERER=opengl) and the RHI's other backends (Vulkan, Metal, Direct3D: top-left
// origin) are not flipped. TUMBLE_CAPTURE_FLIP=0 or 1 overrides.
bool captureIsBottomUp() {
    bool set = false;
    const int forced = qEnvironmentVariableIntValue("TUMBLE_CAPTURE_FLIP", &set);
    if (set) return forced != 0;
    const QString renderer = qEnvironmentVariable("QT3D_RENDERER").toLower();
    if (!renderer.isEmpty() && renderer != QLatin1String("rhi")) return false;
    const QString api = qEnvironmentVariable("QT3D_RHI_DEFAULT_API").toLower();
#ifdef Q_OS_MACOS
    return api == QLatin1String("opengl") || api == QLatin1String("gl");
#else
    return api.isEmpty() || api == QLatin1String("opengl") || api == QLatin1String("gl");
#endif
}

}  // namespace

struct ImageExporter::Impl {
    enum class Stage { Idle, Showing, Rendering, Probing, Encoding };

    QPointer<Viewport> source;
    QPointer<Timeline> timeline;
    Stage stage = Stage::Idle;
    bool running = false;
    int generation = 0;  // bumped at every start and finish: stale callbacks are dropped

    ImageExportOptions opt;
    QString folder;       // absolute
    QString createdRoot;  // the outermost folder the export made (empty: none)
    std::vector<int> frames;
    int next = 0;      // index of the frame being taken
    int captures = 0;  // captures taken of the frame so far
    QImage previous;   // the last of them
    std::unique_ptr<QTemporaryDir> temp;
    std::unique_ptr<QTemporaryFile> tempVideo;

    QPointer<Viewport> view;  // the export view, a top-level window of the chosen size
    QPointer<Qt3DRender::QRenderCapture> capture;
    QPointer<Qt3DRender::QRenderCaptureReply> reply;
    QTimer* watchdog = nullptr;
    QTimer* poll = nullptr;
    QTimer* retry = nullptr;  // a capture request that has not completed is made again
    QElapsedTimer clock;
    QPointer<QProcess> process;

    int restoreFrame = 0;
    std::vector<QMetaObject::Connection> connections;

    QString tempImage(int index) const {
        return temp->filePath(imageFileName(opt.prefix, index, int(frames.size())));
    }
};

ImageExporter::ImageExporter(Viewport* viewport, Timeline* timeline, QObject* parent)
    : QObject(parent), d_(std::make_unique<Impl>()) {
    d_->source = viewport;
    d_->timeline = timeline;
    d_->watchdog = new QTimer(this);
    d_->watchdog->setSingleShot(true);
    d_->poll = new QTimer(this);
    d_->poll->setInterval(10);
    connect(d_->poll, &QTimer::timeout, this, &ImageExporter::waitForView);
    d_->retry = new QTimer(this);
    d_->retry->setSingleShot(true);
    connect(d_->retry, &QTimer::timeout, this, [this] {
        if (d_->stage != Impl::Stage::Rendering) return;
        qCDebug(lcExport) << "capture of frame" << d_->frames[size_t(d_->next)]
                          << "not answered: asked again";
        requestCapture();
    });
}

ImageExporter::~ImageExporter() {
    if (d_->running) {
        const QSignalBlocker block(this);
        finish(false, tr("Export cancelled"));
    }
}

QString ImageExporter::ffmpegPath() {
    return QStandardPaths::findExecutable(QStringLiteral("ffmpeg"));
}

QString ImageExporter::imageFileName(const QString& prefix, int index, int count) {
    const int digits = std::max(4, int(QString::number(std::max(0, count - 1)).size()));
    return prefix + QStringLiteral("%1.png").arg(index, digits, 10, QLatin1Char('0'));
}

bool ImageExporter::isRunning() const {
    return d_->running;
}

void ImageExporter::start(const ImageExportOptions& options) {
    if (d_->running) return;
    Impl& d = *d_;
    d.running = true;
    ++d.generation;
    d.opt = options;
    d.frames.clear();
    d.next = 0;
    d.createdRoot.clear();
    d.temp.reset();
    d.tempVideo.reset();
    d.clock.start();

    // Every refusal is reported from the event loop, after start() has returned.
    auto refuse = [this](const QString& message) {
        QTimer::singleShot(0, this, [this, message, gen = d_->generation] {
            if (d_->generation == gen && d_->running) fail(message);
        });
    };
    if (!d.source || !d.timeline) return refuse(tr("No viewport or timeline to export from"));
    const int done = d.timeline->framesDone();
    if (done <= 0) return refuse(tr("Nothing is recorded: simulate the scene first"));
    if (!options.size.isValid() || options.size.width() < 2 || options.size.height() < 2 ||
        options.size.width() > 16384 || options.size.height() > 16384) {
        return refuse(tr("Image size %1 x %2 is not possible (2 to 16384 pixels a side)")
                          .arg(options.size.width())
                          .arg(options.size.height()));
    }
    const int last = options.lastFrame < 0 ? done - 1 : options.lastFrame;
    if (options.frameStep < 1) return refuse(tr("The frame step must be at least 1"));
    if (options.firstFrame < 0 || options.firstFrame > last || last >= done) {
        return refuse(tr("Frames %1 to %2 are not all recorded (frames 0 to %3 are)")
                          .arg(options.firstFrame)
                          .arg(last)
                          .arg(done - 1));
    }
    for (int k = options.firstFrame; k <= last; k += options.frameStep) d.frames.push_back(k);
    if (options.folder.isEmpty()) return refuse(tr("No folder given for the images"));
    if (options.prefix.contains(QLatin1Char('/')) || options.prefix.contains(QLatin1Char('%'))) {
        return refuse(tr("The file name prefix \"%1\" may not contain '/' or '%'").arg(options.prefix));
    }
    if (options.video && options.videoFile.isEmpty()) return refuse(tr("No file given for the video"));

    // The target folder, and a hidden temporary folder inside it (same file system: the
    // images are moved into place by renames).
    d.folder = QDir(options.folder).absolutePath();
    if (!QFileInfo(d.folder).isDir()) {
        // The outermost folder that does not exist yet: removed again if the export fails.
        QString root = d.folder;
        while (!QFileInfo::exists(QFileInfo(root).path())) root = QFileInfo(root).path();
        std::error_code ec;
        if (QFileInfo::exists(d.folder))
            ec = std::make_error_code(std::errc::not_a_directory);
        else
            std::filesystem::create_directories(QFile::encodeName(d.folder).toStdString(), ec);
        if (ec) {
            return refuse(tr("Cannot create the folder %1: %2")
                              .arg(QDir::toNativeSeparators(d.folder),
                                   QString::fromStdString(io::plainReason(ec.value()))));
        }
        d.createdRoot = root;
    }
    d.temp = std::make_unique<QTemporaryDir>(d.folder + QStringLiteral("/.tumble-export-XXXXXX"));
    if (!d.temp->isValid()) {
        const QString why = d.temp->errorString();
        return refuse(
            tr("Cannot write to the folder %1: %2").arg(QDir::toNativeSeparators(d.folder), plainly(why)));
    }
    if (options.video) {
        // The video's temporary name, taken now so an unwritable place fails before any work.
        const QFileInfo target(options.videoFile);
        d.tempVideo =
            std::make_unique<QTemporaryFile>(target.absolutePath() + QStringLiteral("/.") +
                                             target.completeBaseName() + QStringLiteral("-XXXXXX.mp4"));
        if (!d.tempVideo->open()) {
            return refuse(tr("Cannot write the video %1: %2")
                              .arg(QDir::toNativeSeparators(target.absoluteFilePath()),
                                   plainly(d.tempVideo->errorString())));
        }
        d.tempVideo->close();
    }

    // The playhead is put back at the end; playback would move it under the export.
    d.restoreFrame = d.timeline->currentFrame();
    d.timeline->pause();
    d.connections.push_back(connect(d.timeline, &Timeline::recordingReset, this, [this] {
        if (d_->stage == Impl::Stage::Showing || d_->stage == Impl::Stage::Rendering) {
            fail(tr("The recording was reset (the scene was edited) during the export"));
        }
    }));
    d.connections.push_back(connect(d.timeline, &QObject::destroyed, this, [this] {
        if (d_->stage == Impl::Stage::Showing || d_->stage == Impl::Stage::Rendering) {
            fail(tr("The timeline was closed during the export"));
        }
    }));

    // The export view: the user's camera, overlays and collision shapes, at the chosen size
    // (in device-independent pixels: the capture is in device pixels, scaled if they differ).
    Viewport* view = new Viewport(d.timeline->document(), nullptr);
    d.view = view;
    view->setWindowFlags(Qt::Tool | Qt::FramelessWindowHint | Qt::WindowDoesNotAcceptFocus);
    view->setAttribute(Qt::WA_ShowWithoutActivating);
    view->setWindowTitle(tr("Tumble: exporting images"));
    view->setSelectionShown(false);
    view->setTimeline(d.timeline);
    for (int i = 0; i < Viewport::kOverlayCount; ++i) {
        const auto o = Viewport::Overlay(i);
        view->setOverlay(o, d.source->overlay(o));
    }
    view->setShowCollisionShapes(d.source->showCollisionShapes());
    const QVector3D target = d.source->cameraTarget();
    const float distance = d.source->cameraDistance();
    const QVector3D dir = (d.source->cameraPosition() - target) / std::max(distance, 1e-6f);
    const float pitch = qRadiansToDegrees(std::asin(std::clamp(dir.y(), -1.0f, 1.0f)));
    const float yaw = qRadiansToDegrees(std::atan2(dir.x(), dir.z()));
    view->setCamera(target, distance, yaw, pitch);
    view->setFixedSize(renderSize(options.size));
    view->show();

    d.capture = view->addRenderCapture();

    d.stage = Impl::Stage::Showing;
    d.watchdog->disconnect();
    connect(d.watchdog, &QTimer::timeout, this, [this] {
        const QSize size = renderSize(d_->opt.size);
        fail(tr("The export view could not be shown at %1 x %2 within %3 s (a size larger than the window "
                "system allows?)")
                 .arg(size.width())
                 .arg(size.height())
                 .arg(kShowTimeoutMs / 1000));
    });
    d.watchdog->start(kShowTimeoutMs);
    d.poll->start();
}

// Polled until the export view's window is on screen at its size.
void ImageExporter::waitForView() {
    Impl& d = *d_;
    if (d.stage != Impl::Stage::Showing || !d.view) return d.poll->stop();
    QWindow* w = d.view->renderWindow();
    if (!w || !w->isExposed() || w->size() != d.view->size()) return;
    d.poll->stop();
    d.watchdog->stop();
    d.stage = Impl::Stage::Rendering;
    beginFrame();
}

// Shows frame frames[next] and starts taking it.
void ImageExporter::beginFrame() {
    Impl& d = *d_;
    if (!d.timeline) return fail(tr("The timeline was closed during the export"));
    const int frame = d.frames[size_t(d.next)];
    d.captures = 0;
    d.previous = QImage();
    d.timeline->seek(frame);
    d.watchdog->disconnect();
    connect(d.watchdog, &QTimer::timeout, this, [this, frame] {
        fail(tr("The viewport did not draw frame %1 within %2 s").arg(frame).arg(kFrameTimeoutMs / 1000));
    });
    d.watchdog->start(kFrameTimeoutMs);
    requestCapture();
}

void ImageExporter::requestCapture() {
    Impl& d = *d_;
    if (!d.view || !d.capture || !d.timeline) return fail(tr("The export view was closed"));
    if (d.reply) d.reply->deleteLater();
    d.reply = d.capture->requestCapture();
    // Now and then a request is never answered (the on-demand renderer misses it): it is
    // made again after a while; the frame's watchdog still bounds the whole.
    d.retry->start(kRetryMs);
    // The reply is taken from the event loop, never inside its completed() signal: Qt3D
    // emits that from its frame processing (Renderer::jobsDone), and what follows a capture
    // (a cancel from a progress slot, the view hidden and deleted) must not run in there.
    if (d.reply->isComplete()) {
        QTimer::singleShot(0, this, [this, gen = d.generation] {
            if (d_->generation == gen) onCaptured();
        });
    } else {
        connect(d.reply, &Qt3DRender::QRenderCaptureReply::completed, this, &ImageExporter::onCaptured,
                Qt::QueuedConnection);
    }
}

void ImageExporter::onCaptured() {
    Impl& d = *d_;
    // Only the reply asked for last counts (an earlier one answered late is dropped with it).
    Qt3DRender::QRenderCaptureReply* reply = d.reply;
    if (d.stage != Impl::Stage::Rendering || !reply || !reply->isComplete()) return;
    d.retry->stop();
    QImage image = reply->image();
    reply->deleteLater();
    d.reply = nullptr;
    // A capture can show the frame before the last change (the instance buffers reach the
    // render thread a frame late): captures are repeated until two in a row agree.
    ++d.captures;
    if (d.captures < 2 || (image != d.previous && d.captures < kMaxCaptures)) {
        d.previous = image;
        QTimer::singleShot(0, this, [this, gen = d.generation] {
            if (d_->generation == gen) requestCapture();
        });
        return;
    }
    d.watchdog->stop();
    const int total = int(d.frames.size());
    const int frame = d.frames[size_t(d.next)];
    if (image.isNull()) return fail(tr("The viewport gave no image of frame %1").arg(frame));
    image = image.convertToFormat(QImage::Format_RGB32);
    if (captureIsBottomUp()) image.mirror(false, true);
    if (image.size() != d.opt.size) {
        image = image.scaled(d.opt.size, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
    }
    const QString path = d.tempImage(d.next);
    // Encoded in memory and written with every write checked: QImage::save into a file
    // reported success on a full disk and left empty images. (The image goes into the
    // hidden folder, moved into place whole at the end: no temporary of its own needed.)
    QByteArray png;
    QBuffer buffer(&png);
    if (!buffer.open(QIODevice::WriteOnly) || !image.save(&buffer, "PNG"))
        return fail(tr("Cannot encode the image of frame %1").arg(frame));
    QFile out(path);
    bool written = out.open(QIODevice::WriteOnly) && out.write(png) == png.size() && out.flush();
    out.close();
    written = written && out.error() == QFileDevice::NoError;
    if (!written) {
        return fail(tr("Cannot write the image %1: %2")
                        .arg(QDir::toNativeSeparators(path), plainly(out.errorString())));
    }
    ++d.next;
    const int gen = d.generation;
    emit progress(d.next, total);
    if (d.generation != gen) return;  // cancelled from a slot
    if (d.next < total) {
        QTimer::singleShot(0, this, [this, gen] {
            if (d_->generation == gen) beginFrame();
        });
    } else {
        QTimer::singleShot(0, this, [this, gen] {
            if (d_->generation == gen) framesDone();
        });
    }
}

void ImageExporter::framesDone() {
    Impl& d = *d_;
    const int n = int(d.frames.size());
    deleteView();
    if (d.timeline) d.timeline->seek(d.restoreFrame);
    const QString where = QDir::toNativeSeparators(d.folder);
    if (!d.opt.video) {
        const QString error = moveImagesIntoPlace();
        if (!error.isEmpty()) return fail(error);
        return finish(true, tr("%n image(s) saved in %1", nullptr, n).arg(where));
    }
    if (ffmpegPath().isEmpty()) {
        const QString error = moveImagesIntoPlace();
        if (!error.isEmpty()) return fail(error);
        return finish(false, tr("ffmpeg is not installed: no video was made (install ffmpeg and put it on "
                                "PATH for MP4); the %n image(s) were saved in %1",
                                nullptr, n)
                                 .arg(where));
    }
    probeEncoders();
}

// Asks ffmpeg which encoders it has: H.264 through libx264 when there, else MPEG-4 part 2
// (built into every ffmpeg).
void ImageExporter::probeEncoders() {
    Impl& d = *d_;
    d.stage = Impl::Stage::Probing;
    auto* p = new QProcess(this);
    d.process = p;
    p->setProcessChannelMode(QProcess::MergedChannels);
    connect(p, &QProcess::finished, this, [this, p] {
        if (d_->process != p || d_->stage != Impl::Stage::Probing) return;
        const QByteArray out = p->readAll();
        p->deleteLater();
        d_->process = nullptr;
        encode(out.contains(" libx264 ") ? QStringLiteral("libx264") : QStringLiteral("mpeg4"));
    });
    connect(p, &QProcess::errorOccurred, this, [this, p](QProcess::ProcessError e) {
        if (e != QProcess::FailedToStart || d_->process != p || d_->stage != Impl::Stage::Probing) return;
        p->deleteLater();
        d_->process = nullptr;
        encode(QStringLiteral("mpeg4"));
    });
    p->start(ffmpegPath(), {QStringLiteral("-hide_banner"), QStringLiteral("-encoders")});
}

void ImageExporter::encode(const QString& codec) {
    Impl& d = *d_;
    d.stage = Impl::Stage::Encoding;
    const int n = int(d.frames.size());
    const int digits = int(imageFileName(QString(), 0, n).size()) - 4;  // less ".png"
    const double fps = d.timeline ? d.timeline->frameRate() / d.opt.frameStep : 30.0 / d.opt.frameStep;
    QStringList args = {QStringLiteral("-hide_banner"), QStringLiteral("-loglevel"), QStringLiteral("error"),
                        QStringLiteral("-y"), QStringLiteral("-framerate"), QString::number(fps, 'g', 10),
                        QStringLiteral("-start_number"), QStringLiteral("0"), QStringLiteral("-i"),
                        d.temp->filePath(d.opt.prefix + QStringLiteral("%0") + QString::number(digits) +
                                         QStringLiteral("d.png")),
                        // yuv420p needs even dimensions: an odd size gets one black row or column.
                        QStringLiteral("-vf"), QStringLiteral("pad=ceil(iw/2)*2:ceil(ih/2)*2"),
                        QStringLiteral("-c:v"), codec};
    if (codec == QLatin1String("libx264")) {
        args << QStringLiteral("-crf") << QStringLiteral("18");
    } else {
        args << QStringLiteral("-q:v") << QStringLiteral("2");
    }
    args << QStringLiteral("-pix_fmt") << QStringLiteral("yuv420p") << QStringLiteral("-movflags")
         << QStringLiteral("+faststart") << QStringLiteral("-f") << QStringLiteral("mp4")
         << d.tempVideo->fileName();

    auto* p = new QProcess(this);
    d.process = p;
    p->setProcessChannelMode(QProcess::MergedChannels);
    connect(p, &QProcess::finished, this, [this, p] {
        if (d_->process == p && d_->stage == Impl::Stage::Encoding) onEncoded();
    });
    connect(p, &QProcess::errorOccurred, this, [this, p](QProcess::ProcessError e) {
        if (e == QProcess::FailedToStart && d_->process == p && d_->stage == Impl::Stage::Encoding)
            onEncoded();
    });
    d.watchdog->disconnect();
    connect(d.watchdog, &QTimer::timeout, this, [this, p] {
        if (d_->process == p) p->kill();  // finished() follows, with a crash exit
    });
    d.watchdog->start(std::max(kEncodeMinMs, kEncodeMsPerImage * n));
    p->start(ffmpegPath(), args);
}

void ImageExporter::onEncoded() {
    Impl& d = *d_;
    d.watchdog->stop();
    QProcess* p = d.process;
    d.process = nullptr;
    const bool ok = p->exitStatus() == QProcess::NormalExit && p->exitCode() == 0 &&
                    QFileInfo(d.tempVideo->fileName()).size() > 0;
    QString why;
    if (!ok) {
        why = p->error() == QProcess::FailedToStart ? p->errorString() : tail(p->readAll(), 6);
        if (why.isEmpty()) why = tr("exit code %1").arg(p->exitCode());
        why = plainly(why);
    }
    p->deleteLater();
    const int n = int(d.frames.size());
    const QString where = QDir::toNativeSeparators(d.folder);
    const QString video = QDir::toNativeSeparators(QFileInfo(d.opt.videoFile).absoluteFilePath());
    const QString error = moveImagesIntoPlace();
    if (!error.isEmpty()) return fail(error);
    if (!ok) {
        return finish(
            false, tr("ffmpeg could not make the video %1 (%2); the %n image(s) were saved in %3", nullptr, n)
                       .arg(video, why, where));
    }
    // The video gets the mode a plain write would give it (a temporary file is made 0600):
    // the replaced file's, or 0666 less the umask for a new one.
    const QByteArray target = QFile::encodeName(d.opt.videoFile);
    struct stat old {};
    const bool replacing = ::stat(target.constData(), &old) == 0 && S_ISREG(old.st_mode);
    QFile::remove(d.opt.videoFile);
    if (!d.tempVideo->rename(d.opt.videoFile)) {
        return finish(false, tr("Cannot write the video %1: %2; the %n image(s) were saved in %3", nullptr, n)
                                 .arg(video, d.tempVideo->errorString(), where));
    }
    d.tempVideo->setAutoRemove(false);
    ::chmod(target.constData(), replacing ? (old.st_mode & 07777) : (0666 & ~processUmask()));
    finish(true, tr("%n image(s) saved in %1 and the video %2", nullptr, n).arg(where, video));
}

QString ImageExporter::moveImagesIntoPlace() {
    Impl& d = *d_;
    const int n = int(d.frames.size());
    QStringList moved;
    for (int i = 0; i < n; ++i) {
        const QString name = imageFileName(d.opt.prefix, i, n);
        const QString to = QDir(d.folder).filePath(name);
        if (QFileInfo::exists(to)) QFile::remove(to);
        if (!QFile::rename(d.tempImage(i), to)) {
            for (const QString& m : moved) QFile::remove(m);
            return tr("Cannot write the image %1").arg(QDir::toNativeSeparators(to));
        }
        moved << to;
    }
    return {};
}

void ImageExporter::cancel() {
    if (d_->running) fail(tr("Export cancelled"));
}

void ImageExporter::fail(const QString& message) {
    finish(false, message);
}

// The export view goes now, not later: a deferred delete ran in whatever event loop came
// next, in the tests the next export's, where it tore down this view's Qt3D engine (its
// renderer, its GL context) while the new view's engine was starting: a SIGSEGV at a freed
// object's address in about 1 of 40 runs of tst_image_exporter under load. Every caller
// runs from the event loop (capture replies arrive queued), never inside Qt3D's frame.
void ImageExporter::deleteView() {
    Impl& d = *d_;
    d.capture = nullptr;
    if (Viewport* view = d.view) {
        d.view = nullptr;
        view->hide();
        delete view;
    }
}

void ImageExporter::finish(bool ok, const QString& message) {
    Impl& d = *d_;
    if (!d.running) return;
    const bool rendering = d.stage == Impl::Stage::Showing || d.stage == Impl::Stage::Rendering;
    d.running = false;
    d.stage = Impl::Stage::Idle;
    ++d.generation;
    d.poll->stop();
    d.retry->stop();
    d.watchdog->stop();
    d.watchdog->disconnect();
    for (const auto& c : d.connections) disconnect(c);
    d.connections.clear();
    if (d.reply) d.reply->deleteLater();
    d.reply = nullptr;
    deleteView();
    if (d.process) {
        QProcess* p = d.process;
        d.process = nullptr;
        p->disconnect(this);
        p->kill();
        p->waitForFinished(2000);
        p->deleteLater();
    }
    d.temp.reset();       // removes whatever images were not moved into place
    d.tempVideo.reset();  // removes the partial video unless it was renamed into place
    if (!ok && !d.createdRoot.isEmpty()) {
        // The folders the export made, from the innermost, while empty.
        for (QString f = d.folder; f.size() >= d.createdRoot.size(); f = QFileInfo(f).path()) {
            if (!QDir(f).isEmpty(QDir::AllEntries | QDir::Hidden | QDir::System | QDir::NoDotAndDotDot) ||
                !QDir().rmdir(f)) {
                break;
            }
        }
    }
    if (rendering && d.timeline) d.timeline->seek(d.restoreFrame);
    emit finished(ok, message);
}

}  // namespace tumble::ui
