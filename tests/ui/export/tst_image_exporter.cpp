// The image exporter over a simulated sample (the projectile): frames 0..10 step 2 at
// 320 x 240 give exactly six PNGs of that size, named frame_0000 to frame_0005, each showing
// the ball where the recording has it at that frame (and not where it is at the other end);
// the playhead comes back; the selection is not drawn in the images; cancel mid-way leaves the folder as it
// was and says "cancelled"; a folder that cannot be made is named in the failure; frames not recorded are
// refused; asked for a video without ffmpeg the images are still saved and the message says ffmpeg is
// missing; with ffmpeg installed (optional at run time) the MP4 has one frame per image.
#include "document/document.h"
#include "export/image_exporter.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QImage>
#include <QProcess>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <memory>

using namespace tumble;
using namespace tumble::ui;

namespace {

constexpr int kWaitMs = 120000;

// Every entry of a folder, hidden ones too, sorted.
QStringList entries(const QString& folder) {
    return QDir(folder).entryList(QDir::AllEntries | QDir::Hidden | QDir::System | QDir::NoDotAndDotDot,
                                  QDir::Name);
}

bool samePixel(QRgb a, QRgb b) {
    return std::abs(qRed(a) - qRed(b)) + std::abs(qGreen(a) - qGreen(b)) + std::abs(qBlue(a) - qBlue(b)) < 24;
}

}  // namespace

class TestImageExporter : public QObject {
    Q_OBJECT
    Document doc;
    std::unique_ptr<Timeline> timeline;
    std::unique_ptr<Viewport> view;

    // Runs an export to its end; false when finished() did not come.
    bool run(ImageExporter& exporter, const ImageExportOptions& options, bool* ok, QString* message) {
        QSignalSpy done(&exporter, &ImageExporter::finished);
        exporter.start(options);
        if (!done.isEmpty()) return false;  // finished() only after start() returned
        if (!done.wait(kWaitMs)) return false;
        *ok = done.at(0).at(0).toBool();
        *message = done.at(0).at(1).toString();
        return done.size() == 1 && !exporter.isRunning();
    }

    // Where body `body` is drawn at frame k in an image of `size` taken with the user's camera
    // (the user's view and the images share the camera and, here, the aspect ratio).
    QPoint drawnAt(int body, int k, const QSize& size) {
        State s;
        if (!timeline->frameState(k, &s)) return {};
        const Vec3 x = s.bodies[size_t(body)].x;
        const QVector3D p = view->projectToWidget(QVector3D(float(x.x()), float(x.y()), float(x.z())));
        return QPoint(qRound(p.x() * size.width() / view->width()),
                      qRound(p.y() * size.height() / view->height()));
    }

private slots:
    void initTestCase() {
        QString error;
        QVERIFY2(doc.open(":/scenes/projectile.json", &error), qPrintable(error));
        timeline = std::make_unique<Timeline>(&doc);
        view = std::make_unique<Viewport>(&doc);
        view->resize(640, 480);
        view->show();
        view->setTimeline(timeline.get());
        // Side on, close: the ball (r = 0.11 m) is some 10 pixels across at 320 x 240, and in
        // view from frame 0 (0, 1, 0) to frame 10 (2.67, 3.73, 0).
        view->setCamera(QVector3D(1.3f, 2.3f, 0.0f), 6.0f, 0.0f, 0.0f);
        timeline->simulate();
        QVERIFY(QTest::qWaitFor([&] { return timeline->status() == Timeline::Status::Complete; }, kWaitMs));
        QVERIFY(timeline->framesDone() > 20);
    }

    void imageSequence() {
        QTemporaryDir dir;
        const QString folder = dir.filePath("images");  // made by the export
        timeline->seek(7);
        ImageExporter exporter(view.get(), timeline.get());
        QSignalSpy progress(&exporter, &ImageExporter::progress);
        ImageExportOptions o;
        o.folder = folder;
        o.size = QSize(320, 240);
        o.firstFrame = 0;
        o.lastFrame = 10;
        o.frameStep = 2;
        bool ok = false;
        QString message;
        QElapsedTimer clock;
        clock.start();
        QVERIFY(run(exporter, o, &ok, &message));
        if (qEnvironmentVariableIsSet("TUMBLE_KEEP_IMAGES")) {
            QDir().mkpath(qEnvironmentVariable("TUMBLE_KEEP_IMAGES"));
            for (const QString& name : entries(folder)) {
                QFile::copy(QDir(folder).filePath(name),
                            qEnvironmentVariable("TUMBLE_KEEP_IMAGES") + "/" + name);
            }
        }
        qInfo("6 frames at 320 x 240 in %lld ms (window set-up included)", clock.elapsed());
        QVERIFY2(ok, qPrintable(message));
        QCOMPARE(entries(folder), QStringList({"frame_0000.png", "frame_0001.png", "frame_0002.png",
                                               "frame_0003.png", "frame_0004.png", "frame_0005.png"}));
        QCOMPARE(progress.size(), 6);
        QCOMPARE(progress.last().at(0).toInt(), 6);
        QCOMPARE(progress.last().at(1).toInt(), 6);
        QCOMPARE(timeline->currentFrame(), 7);  // the playhead is put back

        QList<QImage> images;
        for (const QString& name : entries(folder)) {
            QImage image(QDir(folder).filePath(name));
            QVERIFY(!image.isNull());
            QCOMPARE(image.size(), QSize(320, 240));
            images.append(image);
        }
        QVERIFY(images.first() != images.last());
        // Image i is frame 2i: the ball is drawn where frame 2i has it, which is background
        // in the image of the frame at the other end of the range.
        for (int i : {0, 5}) {
            const int other = 5 - i;
            const QPoint at = drawnAt(1, 2 * i, o.size);
            QVERIFY2(QRect(QPoint(0, 0), o.size).contains(at),
                     qPrintable(QString("ball at %1, %2").arg(at.x()).arg(at.y())));
            QVERIFY2(!samePixel(images[i].pixel(at), images[other].pixel(at)),
                     qPrintable(QString("image %1 at %2, %3: %4 vs %5")
                                    .arg(i)
                                    .arg(at.x())
                                    .arg(at.y())
                                    .arg(images[i].pixel(at), 0, 16)
                                    .arg(images[other].pixel(at), 0, 16)));
        }
        // A pixel far from the ball's path is the same in every image.
        for (const QImage& image : images) QCOMPARE(image.pixel(310, 5), images.first().pixel(310, 5));
    }

    // The pictures show the scene, not the editing: a selection (highlight, handles at
    // frame 0) is drawn in the user's view but not in the images.
    void selectionIsNotDrawn() {
        auto exportFrame0 = [&](const QList<int>& selection, QImage* image) {
            doc.setSelection(selection);
            QTemporaryDir dir;
            ImageExporter exporter(view.get(), timeline.get());
            ImageExportOptions o;
            o.folder = dir.path();
            o.size = QSize(320, 240);
            o.lastFrame = 0;
            bool ok = false;
            QString message;
            QVERIFY(run(exporter, o, &ok, &message));
            QVERIFY2(ok, qPrintable(message));
            *image = QImage(dir.filePath("frame_0000.png"));
        };
        timeline->seek(0);  // handles are drawn at frame 0 only
        QImage plain, selected;
        exportFrame0({}, &plain);
        exportFrame0({1}, &selected);
        QVERIFY(view->handlesVisible());  // the user's view does show it
        QVERIFY(!plain.isNull());
        QCOMPARE(selected.size(), plain.size());
        // Two views draw the ground grid's lines where they meet the ground plane a little
        // differently (a few tens of pixels of z-fighting); the handles (three arrows some 40
        // pixels long) and the highlighted ball would change hundreds.
        int differ = 0;
        for (int y = 0; y < plain.height(); ++y) {
            for (int x = 0; x < plain.width(); ++x)
                differ += !samePixel(plain.pixel(x, y), selected.pixel(x, y));
        }
        QVERIFY2(differ < 100, qPrintable(QString("%1 pixels differ").arg(differ)));
        doc.setSelection({});

        // The switch itself.
        Viewport other(&doc);
        doc.setSelection({1});
        QVERIFY(other.selectionShown());
        QVERIFY(other.handlesVisible());
        other.setSelectionShown(false);
        QVERIFY(!other.handlesVisible());
        other.setSelectionShown(true);
        QVERIFY(other.handlesVisible());
        doc.setSelection({});
    }

    void cancelLeavesNothing() {
        QTemporaryDir dir;
        QFile keep(dir.filePath("keep.txt"));
        QVERIFY(keep.open(QIODevice::WriteOnly));
        keep.write("mine");
        keep.close();
        ImageExporter exporter(view.get(), timeline.get());
        connect(&exporter, &ImageExporter::progress, &exporter, [&](int done, int) {
            if (done == 2) exporter.cancel();
        });
        QSignalSpy progress(&exporter, &ImageExporter::progress);
        ImageExportOptions o;
        o.folder = dir.path();
        o.size = QSize(320, 240);
        o.lastFrame = 20;
        bool ok = true;
        QString message;
        QVERIFY(run(exporter, o, &ok, &message));
        QVERIFY(!ok);
        QVERIFY2(message.contains("cancelled", Qt::CaseInsensitive), qPrintable(message));
        QCOMPARE(progress.size(), 2);
        QCOMPARE(entries(dir.path()), QStringList({"keep.txt"}));

        // A folder the export made is removed again.
        const QString made = dir.filePath("new/images");
        o.folder = made;
        QVERIFY(run(exporter, o, &ok, &message));
        QVERIFY(!ok);
        QCOMPARE(entries(dir.path()), QStringList({"keep.txt"}));  // neither new/images nor new
    }

    void unwritableFolder() {
        QTemporaryDir dir;
        QFile blocker(dir.filePath("blocker"));  // a file where a folder should be
        QVERIFY(blocker.open(QIODevice::WriteOnly));
        blocker.close();
        ImageExporter exporter(view.get(), timeline.get());
        ImageExportOptions o;
        o.folder = dir.filePath("blocker/images");
        o.size = QSize(320, 240);
        o.lastFrame = 2;
        bool ok = true;
        QString message;
        QVERIFY(run(exporter, o, &ok, &message));
        QVERIFY(!ok);
        QVERIFY2(message.contains(QDir::toNativeSeparators(o.folder)), qPrintable(message));
        QCOMPARE(entries(dir.path()), QStringList({"blocker"}));
    }

    void framesNotRecordedAreRefused() {
        QTemporaryDir dir;
        ImageExporter exporter(view.get(), timeline.get());
        ImageExportOptions o;
        o.folder = dir.path();
        o.size = QSize(320, 240);
        o.firstFrame = 5;
        o.lastFrame = timeline->framesDone();
        bool ok = true;
        QString message;
        QVERIFY(run(exporter, o, &ok, &message));
        QVERIFY(!ok);
        QVERIFY2(message.contains(QString::number(timeline->framesDone() - 1)), qPrintable(message));
        QCOMPARE(entries(dir.path()), QStringList());
    }

    // ffmpeg hidden (PATH without it): the video cannot be made, the images still are.
    void videoWithoutFfmpegKeepsImages() {
        QTemporaryDir dir, emptyBin;
        const QByteArray path = qgetenv("PATH");
        qputenv("PATH", emptyBin.path().toLocal8Bit());
        const QString found = ImageExporter::ffmpegPath();
        ImageExporter exporter(view.get(), timeline.get());
        ImageExportOptions o;
        o.folder = dir.filePath("images");
        o.size = QSize(320, 240);
        o.lastFrame = 3;
        o.video = true;
        o.videoFile = dir.filePath("motion.mp4");
        bool ok = true;
        QString message;
        const bool ran = run(exporter, o, &ok, &message);
        qputenv("PATH", path);
        QVERIFY(found.isEmpty());
        QVERIFY(ran);
        QVERIFY(!ok);
        QVERIFY2(message.startsWith("ffmpeg is not installed"), qPrintable(message));
        QCOMPARE(entries(o.folder),
                 QStringList({"frame_0000.png", "frame_0001.png", "frame_0002.png", "frame_0003.png"}));
        QCOMPARE(entries(dir.path()), QStringList({"images"}));  // no video, no partial one
    }

    void video() {
        const QString ffmpeg = ImageExporter::ffmpegPath();
        // Optional for users, installed for the tests by ./dev.sh: the video path is tested, not skipped.
        QVERIFY2(!ffmpeg.isEmpty(), "ffmpeg is not installed (./dev.sh test installs it)");
        const QString ffprobe = QStandardPaths::findExecutable("ffprobe");
        QVERIFY2(!ffprobe.isEmpty(), "ffmpeg is installed without ffprobe");
        QTemporaryDir dir;
        ImageExporter exporter(view.get(), timeline.get());
        ImageExportOptions o;
        o.folder = dir.filePath("images");
        o.size = QSize(320, 240);
        o.firstFrame = 0;
        o.lastFrame = 20;
        o.frameStep = 1;
        o.video = true;
        o.videoFile = dir.filePath("motion.mp4");
        bool ok = false;
        QString message;
        QVERIFY(run(exporter, o, &ok, &message));
        QVERIFY2(ok, qPrintable(message));
        QCOMPARE(entries(dir.path()), QStringList({"images", "motion.mp4"}));  // no temporary video left
        QCOMPARE(entries(o.folder).size(), 21);
        // The video's mode is a plain write's (it was the temporary file's 0600), as the images'.
        QFile plain(dir.filePath("plain.txt"));
        QVERIFY(plain.open(QIODevice::WriteOnly));
        plain.close();
        QCOMPARE(QFileInfo(o.videoFile).permissions(), QFileInfo(plain.fileName()).permissions());
        QCOMPARE(QFileInfo(o.videoFile).permissions(), QFileInfo(o.folder + "/" + entries(o.folder).first()).permissions());
        QFile::remove(plain.fileName());

        QProcess probe;
        probe.start(ffprobe,
                    {"-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                     "stream=nb_read_frames,width,height,avg_frame_rate", "-of", "csv=p=0", o.videoFile});
        QVERIFY(probe.waitForFinished(60000));
        QCOMPARE(probe.exitCode(), 0);
        const QString out = QString::fromLatin1(probe.readAllStandardOutput()).trimmed();
        // width, height, frame rate (the recording's 30 fps, step 1), frames read.
        QCOMPARE(out, QString("320,240,30/1,21"));
    }
};

QTEST_MAIN(TestImageExporter)
#include "tst_image_exporter.moc"
