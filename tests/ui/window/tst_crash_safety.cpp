// Crash safety with real kills (SIGKILL, no chance to clean up): a save interrupted at any
// moment leaves the previous file whole, what the killed saves left beside it is removed by
// the next save, and an autosave survives the killed editor and is recovered by the next one.
#include "document/document.h"
#include "window/autosave.h"
#include "window/main_window.h"

#include <tumble/io/atomic_file.h>
#include <tumble/io/scene_file.h>

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QRandomGenerator>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QThread>
#include <QUndoStack>
#include <QtTest>

#include <fcntl.h>
#include <sys/stat.h>

#include <cmath>

using namespace tumble;
using namespace tumble::ui;

namespace {

// A scene of ~2 000 bodies (a few hundred kB of JSON) so that each save takes a while.
QByteArray bigScene() {
    QByteArray bodies =
        R"({"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}})";
    for (int i = 0; i < 2000; ++i)
        bodies +=
            QStringLiteral(
                R"(, {"name": "box%1", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "mass": 1, "position": [%2, 0.1, %3]})")
                .arg(i)
                .arg(i % 50)
                .arg(i / 50)
                .toUtf8();
    return R"({"format": "tumble-scene", "version": 1, "bodies": [)" + bodies + "]}";
}

// Sets a file's modification time `seconds` into the past.
bool age(const QString& path, int seconds) {
    timespec times[2];
    clock_gettime(CLOCK_REALTIME, &times[0]);
    times[0].tv_sec -= seconds;
    times[1] = times[0];
    return utimensat(AT_FDCWD, QFile::encodeName(path).constData(), times, 0) == 0;
}

// An editor process (the crash child) with its data under `home` opens `scene`, makes an
// edit, autosaves and is killed with SIGKILL; then this process takes the same home, as the
// next editor of the same user. False (with a message) if the child did not get that far.
bool killAfterAutosave(const QTemporaryDir& home, const QString& scene) {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("XDG_DATA_HOME", home.filePath("data"));
    env.insert("XDG_CONFIG_HOME", home.filePath("config"));
    QProcess child;
    child.setProcessEnvironment(env);
    child.start(TUMBLE_CRASH_CHILD, {"autosave", scene});
    if (!child.waitForStarted(10000)) return false;
    const bool autosaved = QTest::qWaitFor(
        [&] {
            return child.readAllStandardOutput().contains("autosaved") || child.state() != QProcess::Running;
        },
        60000);
    if (!autosaved || child.state() != QProcess::Running) {
        qWarning("the crash child did not autosave: %s", child.readAllStandardError().constData());
        return false;
    }
    child.kill();
    child.waitForFinished(10000);
    qputenv("XDG_DATA_HOME", home.filePath("data").toLocal8Bit());
    qputenv("XDG_CONFIG_HOME", home.filePath("config").toLocal8Bit());
    QCoreApplication::setApplicationName("Tumble");
    QCoreApplication::setOrganizationName("Tumble");
    return true;
}

}  // namespace

class TestCrashSafety : public QObject {
    Q_OBJECT
private slots:
    void killedDuringSavesLeavesAWholeFile() {
        QTemporaryDir dir;
        const QString scene = dir.filePath("big.json");
        QFile f(scene);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(bigScene());
        f.close();
        const QString out = dir.filePath("saved.json");
        QRandomGenerator rng(12345);
        long lastSeen = 0;
        for (int round = 0; round < 12; ++round) {
            QProcess child;
            child.start(TUMBLE_CRASH_CHILD, {"save-loop", scene, out});
            QVERIFY(child.waitForStarted(10000));
            // Wait for a first save, then kill at a random moment among the next ones.
            QVERIFY2(child.waitForReadyRead(60000), qPrintable(child.readAllStandardError()));
            QThread::msleep(rng.bounded(5, 120));
            child.kill();  // SIGKILL
            QVERIFY(child.waitForFinished(10000));
            QCOMPARE(child.exitStatus(), QProcess::CrashExit);
            const QString said = QString::fromUtf8(child.readAllStandardOutput()).trimmed();
            const long saves = said.section('\n', -1).section(' ', 1).toLong();
            QVERIFY(saves >= 1);
            lastSeen = std::max(lastSeen, saves);
            // Whatever the moment, the file is a whole scene: one of the saves, every body there.
            SceneDesc read;
            try {
                read = io::readSceneFile(out.toStdString());
            } catch (const std::exception& e) {
                QFAIL(qPrintable(QString("round %1: the file is broken: %2").arg(round).arg(e.what())));
            }
            QCOMPARE(int(read.bodies.size()), 2001);
            const double x = read.bodies.back().position.x();
            QVERIFY2(x >= saves && x <= saves + 1 && x == std::floor(x),
                     qPrintable(QString("round %1: moved to %2 after save %3").arg(round).arg(x).arg(saves)));
        }
        QVERIFY(lastSeen >= 1);

        // One more killed for sure between writing and committing, so that at least one
        // temporary is left beside the scene.
        QProcess holder;
        holder.start(TUMBLE_CRASH_CHILD, {"hold", out});
        QVERIFY(holder.waitForStarted(10000));
        QVERIFY2(holder.waitForReadyRead(60000), qPrintable(holder.readAllStandardError()));
        holder.kill();
        QVERIFY(holder.waitForFinished(10000));
        // Beside the scene: nothing but the kills' temporaries, each named as AtomicFile
        // names them. They are made older than the threshold (a save leaves a dead
        // process's temporary alone for a minute, in case it is another machine's).
        QStringList leftovers = QDir(dir.path()).entryList(QDir::Files | QDir::NoDotAndDotDot);
        leftovers.removeAll("big.json");
        leftovers.removeAll("saved.json");
        QVERIFY(!leftovers.isEmpty());
        for (const QString& name : leftovers) {
            QVERIFY2(io::isTemporaryOf(name.toStdString(), "saved.json"), qPrintable(name));
            QVERIFY(age(dir.filePath(name), 2 * 60));
        }
        // The next save, by a fresh editor process, leaves exactly the scene file.
        QProcess next;
        next.start(TUMBLE_CRASH_CHILD, {"save-once", scene, out});
        QVERIFY(next.waitForFinished(60000));
        QVERIFY2(next.exitStatus() == QProcess::NormalExit && next.exitCode() == 0,
                 qPrintable(next.readAllStandardError()));
        QCOMPARE(QDir(dir.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot, QDir::Name),
                 QStringList({"big.json", "saved.json"}));
        QCOMPARE(int(io::readSceneFile(out.toStdString()).bodies.size()), 2001);
    }

    void anAutosaveSurvivesAKilledEditor() {
        QTemporaryDir home;
        QVERIFY(killAfterAutosave(home, ":/scenes/bouncing-ball.json"));
        // The next editor, same user: the autosave is there and comes back as one undo step.
        const QList<AutosaveLeftover> left = Autosave::leftovers();
        QCOMPARE(left.size(), 1);
        QVERIFY(left.first().scenePath.isEmpty());  // a sample: untitled
        QVERIFY(left.first().savedAt.secsTo(QDateTime::currentDateTime()) < 120);
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(":/scenes/bouncing-ball.json", &error));
        QVERIFY(w.document()->body(1).restitution != 0.123);
        QVERIFY2(w.recoverAutosave(&error), qPrintable(error));
        QCOMPARE(w.document()->body(1).restitution, 0.123);
        QVERIFY(w.isWindowModified());
    }

    // Issue 46: unsaved work on a.json, the editor killed; the next editor is started on
    // b.json and Recover is chosen. The recovered scene opens as a.json in another editor,
    // never into b.json's document; saving it writes a.json and b.json stays as it was.
    void recoveryNeverWritesIntoAnotherFile() {
        QTemporaryDir home, dir;
        const QString a = dir.filePath("a.json"), b = dir.filePath("b.json");
        {
            Document doc;
            QString error;
            QVERIFY(doc.open(":/scenes/bouncing-ball.json", &error));
            QVERIFY2(doc.saveAs(a, &error), qPrintable(error));
            QVERIFY2(doc.saveAs(b, &error), qPrintable(error));
        }
        auto bytesOf = [](const QString& path) {
            QFile f(path);
            return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
        };
        const QByteArray bBefore = bytesOf(b), aBefore = bytesOf(a);
        QVERIFY(killAfterAutosave(home, a));
        const QList<AutosaveLeftover> left = Autosave::leftovers();
        QCOMPARE(left.size(), 1);
        QCOMPARE(QFileInfo(left.first().scenePath).absoluteFilePath(), QFileInfo(a).absoluteFilePath());

        // The editor of b.json: Recover starts another editor with the autosave.
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(b, &error));
        QStringList started;
        w.startEditor = [&](const QStringList& args) {
            started = args;
            return true;
        };
        QVERIFY2(w.recover(left.first(), &error), qPrintable(error));
        QCOMPARE(started, QStringList({"--recover", left.first().file}));
        QCOMPARE(w.document()->filePath(), b);
        QVERIFY(!w.isWindowModified());
        QCOMPARE(w.document()->body(1).restitution, io::readSceneFile(b.toStdString()).bodies[1].restitution);

        // That editor (tumble --recover FILE): a.json, unsaved, with the killed editor's edit.
        MainWindow other;
        QVERIFY2(other.recoverFile(left.first().file, &error), qPrintable(error));
        QCOMPARE(QFileInfo(other.document()->filePath()).absoluteFilePath(), QFileInfo(a).absoluteFilePath());
        QVERIFY(other.isWindowModified());
        QVERIFY(other.windowTitle().contains("a.json"));
        QCOMPARE(other.document()->body(1).restitution, 0.123);
        QVERIFY(Autosave::leftovers().isEmpty());  // taken over by that editor
        QCOMPARE(bytesOf(a), aBefore);             // nothing written until the user saves
        other.document()->undoStack()->undo();     // back to a.json as it is on disk
        QVERIFY(other.document()->body(1).restitution != 0.123);
        other.document()->undoStack()->redo();
        QVERIFY2(other.document()->saveAs(other.document()->filePath(), &error), qPrintable(error));
        QCOMPARE(io::readSceneFile(a.toStdString()).bodies[1].restitution, 0.123);
        QCOMPARE(bytesOf(b), bBefore);  // b.json untouched throughout
    }
};

QTEST_MAIN(TestCrashSafety)
#include "tst_crash_safety.moc"
