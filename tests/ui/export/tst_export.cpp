// File > Export from the editor: a trajectory written from the recording reads back equal
// to it; a cancelled export leaves no file; the dialog checks its choices and remembers
// them.
#include "document/document.h"
#include "export/export_dialog.h"
#include "window/main_window.h"
#include "timeline/timeline.h"

#include <tumble/io/trajectory_csv.h>
#include <tumble/io/trajectory_json.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

bool openAndRecord(MainWindow& w, const QString& sample) {
    QString error;
    if (!w.openScene(sample, &error)) return false;
    return QTest::qWaitFor(
        [&] { return w.timeline()->status() == Timeline::Status::Complete && !w.timeline()->isStale(); },
        60000);
}

}  // namespace

class TestExport : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName("tumble-tests");
        QSettings().remove("export");
    }

    // Frames 0..10 step 2 of the projectile, the ball only, as JSON: six frames equal to
    // the recording to the last bit.
    void aTrajectoryFromTheRecording() {
        MainWindow w;
        QVERIFY(openAndRecord(w, ":/scenes/projectile.json"));
        QTemporaryDir dir;
        const QString file = dir.filePath("ball.json");
        io::ExportOptions o;
        o.firstFrame = 0;
        o.lastFrame = 10;
        o.frameStep = 2;
        o.bodies = {1};
        QSignalSpy finished(&w, &MainWindow::exportFinished);
        QString error;
        QVERIFY2(w.startExport(int(ExportDialog::Kind::Json), file, o, QSize(), &error), qPrintable(error));
        QVERIFY(finished.wait(30000));
        QVERIFY2(finished.first().at(0).toBool(), qPrintable(finished.first().at(1).toString()));
        const io::Trajectory t = io::readTrajectoryJson(file.toStdString());
        QCOMPARE(int(t.frames.size()), 6);
        QCOMPARE(int(t.bodies.size()), 1);
        QCOMPARE(t.bodies[0].name, std::string("ball"));
        const auto model = w.timeline()->model();
        for (int i = 0; i < 6; ++i) {
            State s;
            QVERIFY(w.timeline()->frameState(2 * i, &s));
            const Vec3 x = bodyFramePosition(model->bodies[1], s.bodies[1]);
            QCOMPARE(t.frames[i].time, 2 * i / 30.0);
            QCOMPARE(t.frames[i].bodies[0].position, x);
            QCOMPARE(t.frames[i].bodies[0].orientation.coeffs(), s.bodies[1].q.coeffs());
        }
    }

    // The door sample with its joint's reactions: the trajectory CSV as ever and the
    // hinge's rows in door-joints.csv beside it, a row a frame. The dialog offers them
    // for a scene with joints, for CSV and JSON only.
    void jointForcesBesideTheTrajectory() {
        MainWindow w;
        QVERIFY(openAndRecord(w, ":/scenes/hinged-door.json"));
        QTemporaryDir dir;
        io::ExportOptions o;
        o.jointForces = true;
        QSignalSpy finished(&w, &MainWindow::exportFinished);
        QString error;
        QVERIFY2(w.startExport(int(ExportDialog::Kind::Csv), dir.filePath("door.csv"), o, QSize(), &error),
                 qPrintable(error));
        QVERIFY(finished.wait(30000));
        QVERIFY2(finished.first().at(0).toBool(), qPrintable(finished.first().at(1).toString()));
        QFile joints(dir.filePath("door-joints.csv"));
        QVERIFY(joints.open(QIODevice::ReadOnly));
        const QStringList rows = QString::fromUtf8(joints.readAll()).split('\n', Qt::SkipEmptyParts);
        QCOMPARE(rows.value(0), QString(io::kJointCsvHeader));
        QCOMPARE(rows.size(), 1 + w.timeline()->framesDone());
        QVERIFY(rows.value(2).startsWith(QString::number(1 / 60.0, 'g', 17) + ",hinge,"));

        ExportDialog d({"ground", "post", "door"}, 181, 60.0, "hinged-door.json");
        auto* check = d.findChild<QCheckBox*>("jointForces");
        QVERIFY(check && !check->isVisibleTo(&d));  // no joints said yet
        d.setHasJoints(true);
        QVERIFY(check->isVisibleTo(&d));
        d.setJointForces(true);
        d.setKind(ExportDialog::Kind::Json);
        QVERIFY(d.options().jointForces);
        d.setKind(ExportDialog::Kind::Glb);
        QVERIFY(!check->isEnabled());
        QVERIFY(!d.options().jointForces);
    }

    // Cancel as soon as it starts: finished(false) and nothing on disk.
    void aCancelledExportLeavesNoFile() {
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(":/scenes/pyramid-15.json", &error));
        SceneDesc s = w.scene();
        s.settings.duration = 30.0;
        w.document()->setSettings(s.settings, "Longer");
        QVERIFY(QTest::qWaitFor(
            [&] { return w.timeline()->status() == Timeline::Status::Complete && !w.timeline()->isStale(); },
            120000));
        QTemporaryDir dir;
        const QString file = dir.filePath("pyramid.glb");
        QSignalSpy finished(&w, &MainWindow::exportFinished);
        QVERIFY2(w.startExport(int(ExportDialog::Kind::Glb), file, {}, QSize(), &error), qPrintable(error));
        QVERIFY(w.isExporting());
        w.cancelExport();
        QVERIFY(finished.wait(60000));
        QVERIFY(!finished.first().at(0).toBool());
        QVERIFY2(finished.first().at(1).toString().contains("cancelled"),
                 qPrintable(finished.first().at(1).toString()));
        QVERIFY(QDir(dir.path()).entryList(QDir::NoDotAndDotDot | QDir::AllEntries | QDir::Hidden).isEmpty());
    }

    // Images and a video through the same entry point as the dialog's Export button.
    void imagesAndVideoFromTheWindow() {
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        QVERIFY(openAndRecord(w, ":/scenes/projectile.json"));
        QTemporaryDir dir;
        io::ExportOptions o;
        o.lastFrame = 4;
        QSignalSpy finished(&w, &MainWindow::exportFinished);
        QString error;
        const QString video = dir.filePath("throw.mp4");
        QVERIFY2(w.startExport(int(ExportDialog::Kind::Video), video, o, QSize(320, 240), &error),
                 qPrintable(error));
        QVERIFY(finished.wait(120000));
        QVERIFY2(finished.first().at(0).toBool(), qPrintable(finished.first().at(1).toString()));
        QVERIFY(QFileInfo(video).size() > 0);
        const QDir frames(dir.filePath("throw-frames"));
        QCOMPARE(frames.entryList({"*.png"}, QDir::Files).size(), 5);
        QCOMPARE(QImage(frames.filePath("frame_0004.png")).size(), QSize(320, 240));
    }

    void aBadTargetIsRefusedWithItsName() {
        MainWindow w;
        QVERIFY(openAndRecord(w, ":/scenes/projectile.json"));
        QString error;
        QVERIFY(
            !w.startExport(int(ExportDialog::Kind::Csv), "/nonexistent-folder/x.csv", {}, QSize(), &error));
        QVERIFY2(error.contains("/nonexistent-folder/x.csv"), qPrintable(error));
    }

    // Issue 21 item 5: on a fresh machine (no ~/Documents, nothing remembered) the dialog
    // starts in a folder that exists and the first export writes its file; a saved scene's
    // export starts beside its file.
    void theFirstExportFromAFreshHomeWritesItsFile() {
        QTemporaryDir home;
        const QByteArray oldHome = qgetenv("HOME");
        qputenv("HOME", home.path().toLocal8Bit());
        QSettings().remove("export/folder");
        MainWindow w;
        QVERIFY(openAndRecord(w, ":/scenes/projectile.json"));
        ExportDialog d({"ground", "ball"}, w.timeline()->framesDone(), 60.0, "projectile.json");
        d.setKind(ExportDialog::Kind::Csv);
        QVERIFY2(d.problem().isEmpty(), qPrintable(d.problem()));
        QCOMPARE(QFileInfo(d.target()).absolutePath(), QFileInfo(home.path()).absoluteFilePath());
        QString error;
        QVERIFY2(w.startExport(int(ExportDialog::Kind::Csv), d.target(), d.options(), QSize(), &error),
                 qPrintable(error));
        QTRY_VERIFY_WITH_TIMEOUT(QFileInfo(d.target()).size() > 0, 10000);
        // Documents, once there is one.
        QVERIFY(QDir(home.path()).mkdir("Documents"));
        QCOMPARE(ExportDialog::startFolder({}, "projectile.json"), QDir(home.path()).filePath("Documents"));
        // Beside a saved scene; the last export's folder first while it is there.
        QTemporaryDir work;
        const QString saved = QDir(work.path()).filePath("mine.json");
        QCOMPARE(ExportDialog::startFolder({}, saved), QFileInfo(saved).absolutePath());
        QCOMPARE(ExportDialog::startFolder(home.path(), saved), home.path());
        QCOMPARE(ExportDialog::startFolder(home.path() + "/gone", saved), QFileInfo(saved).absolutePath());
        qputenv("HOME", oldHome);
    }

    void theDialogChecksAndRemembers() {
        QTemporaryDir dir;
        {
            ExportDialog d({"ground", "ball"}, 61, 30.0, "projectile.json");
            d.setKind(ExportDialog::Kind::Json);
            QCOMPARE(QFileInfo(d.target()).fileName(), QString("projectile.json"));
            d.setTarget(dir.filePath("out.csv"));
            QVERIFY2(d.problem().contains(".json"), qPrintable(d.problem()));
            d.setTarget(dir.filePath("out.json"));
            QVERIFY2(d.problem().isEmpty(), qPrintable(d.problem()));
            d.setBodiesChecked({});
            QVERIFY(!d.problem().isEmpty());
            d.setBodiesChecked({1});
            QCOMPARE(d.options().bodies, std::vector<int>({1}));
            d.setFrameRange(20, 10, 1);
            QVERIFY(!d.problem().isEmpty());
            d.setFrameRange(0, 60, 3);
            QVERIFY(d.problem().isEmpty());
            QCOMPARE(d.options().frameStep, 3);
            d.setTarget(dir.filePath("missing/out.json"));
            QVERIFY(d.problem().contains("no such folder"));
            d.setTarget(dir.filePath("out.json"));
            d.accept();
        }
        ExportDialog again({"ground", "ball"}, 61, 30.0, "projectile.json");
        QCOMPARE(again.kind(), ExportDialog::Kind::Json);
        QCOMPARE(again.options().frameStep, 3);
        QCOMPARE(QFileInfo(again.target()).absolutePath(), QFileInfo(dir.path()).absoluteFilePath());
    }
};

QTEST_MAIN(TestExport)
#include "tst_export.moc"
