// tumble sweep (issue 22, docs/sweeps.md): variants of a scene run as processes of their
// own, their results merged into summary.csv. The physics of a swept value against its
// closed form, a variant that runs alone to the same hash, resuming after a stop and after
// a kill, failed variants as rows, and bad input refused before anything is written.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QtTest>

#include "cli_harness.h"

#include <csignal>

using namespace tumble::clitest;

namespace {

// A ball of radius 0.05 whose bottom is 1 m above a ground that bounces nothing back
// (restitution 0: a pair takes the larger of its two), dropped from rest; frames at 240/s.
const char* const kDrop = R"({
  "format": "tumble-scene",
  "version": 1,
  "settings": {"gravity": [0, -9.81, 0], "dt": 0.004166666666666667, "duration": 1.0, "frame_rate": 240},
  "bodies": [
    {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0},
     "restitution": 0},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.05}, "mass": 0.2, "position": [0, 1.05, 0],
     "restitution": 0.5}
  ]
}
)";

// summary.csv as rows of name -> value (no quoted commas in these sweeps' values).
QList<QMap<QString, QString>> summaryRows(const QByteArray& csv) {
    const QStringList l = lines(QString::fromUtf8(csv));
    QList<QMap<QString, QString>> rows;
    if (l.isEmpty()) return rows;
    const QStringList head = l.first().split(',');
    for (int i = 1; i < l.size(); ++i) {
        const QStringList cells = l[i].split(',');
        QMap<QString, QString> row;
        for (int c = 0; c < head.size() && c < cells.size(); ++c) row.insert(head[c], cells[c]);
        rows.push_back(row);
    }
    return rows;
}

}  // namespace

class TestSweep : public QObject, private Harness {
    Q_OBJECT

private slots:
    void init() {
        makeFolder();
        write("drop.json", kDrop);
    }
    void cleanup() { dir_.reset(); }

    // Issue 47 item 1: varying dt past a frame (1/240 s here) changes nothing, since each
    // frame is one step; the sweep says so for each such variant before anything runs.
    void aStepCappedByTheFrameRateIsNoted() {
        RUN(r, {"sweep", "drop.json", "--vary", "settings.dt=0.001,0.01", "--out", "dt"});
        QCOMPARE(r.code, 0);
        QVERIFY2(r.err.contains(
                     "tumble sweep: note: 0001: settings.dt 0.01 s is longer than a frame (0.00416667 s "
                     "at frame_rate 240): each frame is one step of 0.00416667 s"),
                 qPrintable(r.err));
        QVERIFY2(r.err.contains("tumble sweep: note: 0000: settings.dt 0.001 s does not divide a frame"),
                 qPrintable(r.err));
    }

    // The ball's first rebound rises e² m (its bottom), e swept over five values: the
    // impact at its moment sends it back at e times its landing speed, and the step
    // (constant gravity, Strang splitting) is exact on the parabola. The apex is read from
    // each variant's trajectory at 240 frames/s (within g (1/480)² / 2 = 2e-5 m of the true
    // one); the summary's columns hold the values, ok, and the ball's measures.
    void reboundApexIsESquared() {
        RUN(r, {"sweep", "drop.json", "--vary", "ball.restitution=0.2:1:5", "--out", "sw", "--trajectories",
                "--jobs", "2"});
        QCOMPARE(r.code, 0);
        const QMap<QString, QString> kv = report(r.out);
        QCOMPARE(kv.value("variants"), QString("5"));
        QCOMPARE(kv.value("ok"), QString("5"));
        const auto rows = summaryRows(read("sw/summary.csv"));
        QCOMPARE(rows.size(), 5);
        for (const auto& row : rows) {
            QCOMPARE(row.value("status"), QString("ok"));
            const double e = row.value("ball.restitution").toDouble();
            // The trajectory: time,body,x,y,... (the body by name).
            const QStringList traj = lines(QString::fromUtf8(read("sw/trajectories/" + row.value("variant") + ".csv")));
            // Landed when it first moves up; the apex is the highest frame until it falls again.
            double apex = -1e9;
            bool landed = false;
            for (const QString& line : traj.mid(1)) {
                const QStringList c = line.split(',');
                if (c.value(1) != "ball") continue;
                const double bottom = c.value(3).toDouble() - 0.05, vy = c.value(10).toDouble();
                if (!landed) {
                    landed = vy > 0.0;
                    if (!landed) continue;
                }
                apex = std::max(apex, bottom);
                if (vy < 0.0) break;  // falling again: the first rebound is over
            }
            qInfo("e = %.1f: first rebound apex %.6f m, e^2 = %.6f", e, apex, e * e);
            QVERIFY(landed);
            QVERIFY2(std::abs(apex - e * e) < 1e-4, qPrintable(QString::number(apex)));
            QCOMPARE(row.value("ball.highest").toDouble(), 1.05);  // where it started
            QVERIFY(!row.value("state_hash").isEmpty());
            QVERIFY(row.value("wall_s").toDouble() > 0.0);
        }
    }

    // A variant's file runs by itself to the hash its row records, and that is the hash of
    // the scene edited by hand to the same value: the sweep changes nothing else.
    void aVariantRunsAloneToTheSameHash() {
        RUN(r, {"sweep", "drop.json", "--vary", "ball.restitution=0.3,0.7", "--vary", "ball.velocity[0]=0,1", "--out",
                "sw"});
        QCOMPARE(r.code, 0);
        const auto rows = summaryRows(read("sw/summary.csv"));
        QCOMPARE(rows.size(), 4);
        // The last --vary changes fastest.
        QCOMPARE(rows[1].value("ball.restitution"), QString("0.3"));
        QCOMPARE(rows[1].value("ball.velocity[0]"), QString("1"));
        RUN(alone, {"--headless", "sw/variants/0001.json"});
        QCOMPARE(alone.code, 0);
        QCOMPARE(report(alone.out).value("state_hash"), rows[1].value("state_hash"));
        QByteArray edited = kDrop;
        edited.replace("\"position\": [0, 1.05, 0],", "\"position\": [0, 1.05, 0], \"velocity\": [1, 0, 0],");
        edited.replace("\"restitution\": 0.5", "\"restitution\": 0.3");
        write("edited.json", edited);
        RUN(byHand, {"--headless", "edited.json"});
        QCOMPARE(byHand.code, 0);
        QCOMPARE(report(byHand.out).value("state_hash"), rows[1].value("state_hash"));
        QVERIFY(rows[0].value("state_hash") != rows[1].value("state_hash"));
    }

    // A setting the file leaves at its default (the integrator, the impacts' timing) can be
    // varied too: each variant holds it, and runs as the scene with that setting does.
    void settingsTheFileLeavesOut() {
        RUN(r, {"sweep", "drop.json", "--vary", "settings.integrator=rk4,euler", "--vary",
                "settings.impacts=end-of-step", "--out", "sw"});
        QCOMPARE(r.code, 0);
        const auto rows = summaryRows(read("sw/summary.csv"));
        QCOMPARE(rows.size(), 2);
        RUN(rk4, {"--headless", "drop.json", "--integrator", "rk4", "--impacts", "end-of-step"});
        RUN(euler, {"--headless", "drop.json", "--integrator", "euler", "--impacts", "end-of-step"});
        QCOMPARE(rows[0].value("state_hash"), report(rk4.out).value("state_hash"));
        QCOMPARE(rows[1].value("state_hash"), report(euler.out).value("state_hash"));
        QVERIFY(rows[0].value("state_hash") != rows[1].value("state_hash"));
    }

    // Stopped by SIGINT (as Ctrl-C does) after its first result, the sweep exits 130, keeps
    // what finished, leaves no half-written file, and lists the rest as not run; killed
    // outright (SIGKILL) it leaves what finished too. The same command then runs only what
    // is missing, and the results equal a sweep run in one go.
    void resumesAfterAStopAndAKill_data() {
        QTest::addColumn<int>("signal");
        QTest::newRow("SIGINT") << int(SIGINT);
        QTest::newRow("SIGKILL") << int(SIGKILL);
    }
    void resumesAfterAStopAndAKill() {
        QFETCH(int, signal);
        // Six variants of about a second each, one at a time (a tenth of the steps where a
        // step costs thirty times as much).
#ifdef TUMBLE_TEST_SANITIZED
        const QString dt = "settings.dt=1e-4";
#else
        const QString dt = "settings.dt=1e-5";
#endif
        const QStringList args = {"sweep", "drop.json", "--vary", dt, "--vary",
                                  "ball.restitution=0.1:0.6:6", "--vary", "settings.duration=1.2",
                                  "--out", "sw", "--jobs", "1"};
        QProcess p;
        p.setWorkingDirectory(dir_->path());
        p.start(TUMBLE_EXECUTABLE, args);
        QVERIFY(p.waitForStarted(10000));
        QTRY_VERIFY_WITH_TIMEOUT(QFile::exists(path("sw/results/0000.json")), 60000);
        ::kill(static_cast<pid_t>(p.processId()), signal);
        QVERIFY(p.waitForFinished(30000));
        if (signal == SIGINT) {
            QCOMPARE(p.exitStatus(), QProcess::NormalExit);
            QCOMPARE(p.exitCode(), 130);
            QVERIFY(QString::fromUtf8(p.readAllStandardError()).contains("run the same command to resume"));
            const auto rows = summaryRows(read("sw/summary.csv"));
            QCOMPARE(rows.size(), 6);
            QCOMPARE(rows[0].value("status"), QString("ok"));
            QCOMPARE(rows[5].value("status"), QString("not run"));
        }
        QTest::qWait(signal == SIGKILL ? 3000 : 0);  // (the killed sweep's last variant runs on alone)
        const QStringList before = QDir(path("sw/results")).entryList({"*.json"}, QDir::Files);
        QVERIFY(before.contains("0000.json"));
        QVERIFY(!before.contains("0005.json"));
        for (const QString& f : QDir(path("sw")).entryList(QDir::Files) + QDir(path("sw/results")).entryList(QDir::Files))
            QVERIFY2(!f.contains(".tumble-tmp-"), qPrintable(f));
        const QByteArray first = read("sw/results/0000.json");

        RUN(again, args);
        QCOMPARE(again.code, 0);
        QCOMPARE(read("sw/results/0000.json"), first);  // not run again
        RUN(whole, QStringList(args).replaceInStrings(QRegularExpression("^sw$"), "whole"));
        QCOMPARE(whole.code, 0);
        const auto resumed = summaryRows(read("sw/summary.csv")), once = summaryRows(read("whole/summary.csv"));
        QCOMPARE(resumed.size(), 6);
        for (int k = 0; k < 6; ++k) {
            QCOMPARE(resumed[k].value("status"), QString("ok"));
            QCOMPARE(resumed[k].value("state_hash"), once[k].value("state_hash"));
            QCOMPARE(resumed[k].value("ball.final_y"), once[k].value("ball.final_y"));
        }
    }

    // Issue 47 item 3: Ctrl-C while a big sweep writes its variants (20 000 of them) stops it
    // between two: exit 130, no temporary left, every variant written whole, no plan yet
    // (it is written last, so the same command resumes from the variants there).
    void aStopWhileWritingTheVariants() {
        QProcess p;
        p.setWorkingDirectory(dir_->path());
        p.start(TUMBLE_EXECUTABLE, {"sweep", "drop.json", "--vary", "ball.restitution=0:1:200", "--vary",
                                    "ball.mass=0.1:2:100", "--out", "sw"});
        QVERIFY(p.waitForStarted(10000));
        QTRY_VERIFY_WITH_TIMEOUT(!QDir(path("sw/variants")).entryList(QDir::Files).isEmpty(), 60000);
        ::kill(static_cast<pid_t>(p.processId()), SIGINT);
        QVERIFY(p.waitForFinished(30000));
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 130);
        const QString err = QString::fromUtf8(p.readAllStandardError());
        QVERIFY2(err.contains("stopped while writing the variants; nothing was run"), qPrintable(err));
        QVERIFY(!QFile::exists(path("sw/sweep.json")));
        const QStringList written = QDir(path("sw/variants")).entryList(QDir::Files | QDir::Hidden);
        qInfo("%lld of 20000 variants written before the stop", static_cast<long long>(written.size()));
        QVERIFY2(written.size() < 20000, qPrintable(QString::number(written.size())));
        for (const QString& f : written) {
            QVERIFY2(!f.contains(".tumble-tmp-"), qPrintable(f));
            QJsonParseError error;
            QJsonDocument::fromJson(read("sw/variants/" + f), &error);
            QVERIFY2(error.error == QJsonParseError::NoError, qPrintable(f));
        }
    }

    // A value the scene refuses and a run the energy guard stops are rows with their
    // status and message; the sweep goes on and exits 1.
    // Issue 47 item 5: a wildcard sets one value on every body that has the key
    // ("*.restitution", "bodies[*].friction"); it was refused.
    void aWildcardSetsEveryBody() {
        RUN(r, {"sweep", "drop.json", "--vary", "*.restitution=0.25", "--vary", "bodies[*].friction=0.75",
                "--out", "sw", "--quiet"});
        QCOMPARE(r.code, 0);
        QFile variant(path("sw/variants/0000.json"));
        QVERIFY(variant.open(QIODevice::ReadOnly));
        const QJsonArray bodies = QJsonDocument::fromJson(variant.readAll()).object()["bodies"].toArray();
        QCOMPARE(bodies.size(), 2);
        for (const QJsonValue b : bodies) {
            QCOMPARE(b.toObject()["restitution"].toDouble(), 0.25);
            QCOMPARE(b.toObject()["friction"].toDouble(), 0.75);
        }
        RUN(bad, {"sweep", "drop.json", "--vary", "*.bounce=1", "--out", "bad"});
        QCOMPARE(bad.code, 2);
        QVERIFY2(bad.err.startsWith("tumble: --vary *.bounce: no body has it"), qPrintable(bad.err));
    }

    // Issue 47 item 5: the summary's state_hash is of the final state only: two variants
    // whose ball bounces differently and ends at rest in the same place share it. The
    // trajectory_hash (every recorded frame's state) tells them apart.
    void theTrajectoryHashTellsRunsApart() {
        RUN(r, {"sweep", TUMBLE_SCENES_DIR "/bouncing-ball.json", "--vary", "ground.restitution=0.2,0.3",
                "--vary", "ball.restitution=0.1", "--out", "sw", "--quiet"});
        QCOMPARE(r.code, 0);
        const auto rows = summaryRows(read("sw/summary.csv"));
        QCOMPARE(rows.size(), 2);
        QCOMPARE(rows[0].value("state_hash"), rows[1].value("state_hash"));  // both at rest, alike
        QVERIFY(!rows[0].value("trajectory_hash").isEmpty());
        QVERIFY(rows[0].value("trajectory_hash") != rows[1].value("trajectory_hash"));
    }

    // Issue 47 item 5: a sweep resumed after its scene was edited reused the old variants
    // without a word; the plan keeps the scene's content hash and the resume is refused.
    void aResumeOfAnEditedSceneIsRefused() {
        const QStringList args{"sweep", "drop.json", "--vary", "ball.restitution=0.2,0.4",
                               "--out", "sw",        "--quiet"};
        RUN(first, args);
        QCOMPARE(first.code, 0);
        const QByteArray summary = read("sw/summary.csv");
        write("drop.json", QByteArray(kDrop).replace("\"mass\": 0.2", "\"mass\": 0.3"));
        RUN(again, args);
        QCOMPARE(again.code, 2);
        QVERIFY2(again.err.contains("drop.json changed since this sweep began"), qPrintable(again.err));
        QCOMPARE(read("sw/summary.csv"), summary);
        write("drop.json", kDrop);  // as it was: the resume finds everything done
        RUN(back, args);
        QCOMPARE(back.code, 0);
    }

    // A variant the scene format refuses is refused before anything runs (issue 47 item 5:
    // it was an `invalid` row found when its turn came); one that fails while it runs (the
    // energy guard) is a row with its status and message.
    void failedVariantsAreRows() {
        write("blowup.json", kBlowUp);
        RUN(r, {"sweep", "drop.json", "--vary", "ball.restitution=0.5,1.5", "--out", "sw"});
        QCOMPARE(r.code, 2);
        QCOMPARE(r.err, QString("tumble: variant 0001: bodies[1].restitution: must be between 0 and 1 "
                                "(ball.restitution=1.5); nothing was run\n"));
        QVERIFY(!QFileInfo::exists(path("sw/variants")));

        RUN(b, {"sweep", "blowup.json", "--vary", "ball.forces[0].stiffness=10,1e12", "--out", "blow"});
        QCOMPARE(b.code, 1);
        auto rows = summaryRows(read("blow/summary.csv"));
        QCOMPARE(rows[0].value("status"), QString("ok"));
        QCOMPARE(rows[1].value("status"), QString("failed"));
        QVERIFY2(rows[1].value("message").contains("energy"), qPrintable(rows[1].value("message")));
    }

    // Bad input: exit 2, a message naming what is wrong, and nothing written.
    void badInputIsRefused_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        const QStringList base = {"sweep", "drop.json", "--out", "sw"};
        QTest::newRow("unknown body") << base + QStringList{"--vary", "bal.restitution=1"} << "no body or joint named 'bal'";
        QTest::newRow("unknown key") << base + QStringList{"--vary", "ball.bounce=1"} << "body 'ball' has no 'bounce'";
        QTest::newRow("a list, not a value") << base + QStringList{"--vary", "ball.velocity=1"} << "ball.velocity[N]";
        QTest::newRow("index past the end") << base + QStringList{"--vary", "ball.velocity[3]=1"} << "no [3]";
        QTest::newRow("empty list") << base + QStringList{"--vary", "ball.restitution="} << "an empty list";
        QTest::newRow("empty value") << base + QStringList{"--vary", "ball.restitution=0.1,,0.2"} << "an empty value";
        QTest::newRow("not a number") << base + QStringList{"--vary", "ball.restitution=high"} << "'high' is not a number";
        QTest::newRow("bad range") << base + QStringList{"--vary", "ball.restitution=0:1"} << "is not start:stop:count";
        QTest::newRow("count 0") << base + QStringList{"--vary", "ball.restitution=0:1:0"} << "the count '0'";
        QTest::newRow("not whole") << base + QStringList{"--vary", "settings.solver_iterations=1:10:3"}
                                   << "'5.5' is not a whole number";
        QTest::newRow("not true or false") << base + QStringList{"--vary", "settings.sleeping=yes"}
                                           << "is not true or false";
        QTest::newRow("twice") << base + QStringList{"--vary", "ball.mass=1", "--vary", "ball.mass=2"} << "given twice";
        QTest::newRow("no vary") << base << "nothing varies";
        QTest::newRow("no out") << QStringList{"sweep", "drop.json", "--vary", "ball.mass=1"} << "needs --out";
        QTest::newRow("unknown measure") << base + QStringList{"--vary", "ball.mass=1", "--metric", "apex"}
                                         << "--metric apex: not a measure";
        QTest::newRow("bad scene") << QStringList{"sweep", "missing.json", "--vary", "ball.mass=1", "--out", "sw"}
                                   << "missing.json";
    }
    void badInputIsRefused() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        RUN(r, args);
        QCOMPARE(r.code, 2);
        QVERIFY2(r.err.contains(message), qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(path("sw")));
    }

    // --merge writes the summary again from the results, with the measures asked for; a
    // folder holding another sweep is not overwritten.
    void mergeAndAnotherSweepsFolder() {
        RUN(r, {"sweep", "drop.json", "--vary", "ball.restitution=0.4,0.6", "--out", "sw"});
        QCOMPARE(r.code, 0);
        QVERIFY(QFile::remove(path("sw/summary.csv")));
        RUN(m, {"sweep", "--merge", "sw", "--metric", "ball.highest,rest_time"});
        QCOMPARE(m.code, 0);
        const QStringList l = lines(QString::fromUtf8(read("sw/summary.csv")));
        QCOMPARE(l.first(), QString("variant,ball.restitution,status,state_hash,trajectory_hash,wall_s,ball."
                                    "highest,ball.rest_time,message"));
        QCOMPARE(l.size(), 3);
        RUN(other, {"sweep", "drop.json", "--vary", "ball.mass=1,2", "--out", "sw"});
        QCOMPARE(other.code, 2);
        QVERIFY2(other.err.contains("holds another sweep"), qPrintable(other.err));
    }

    // Issue 47 item 5: two sweeps of the drop, one over the restitution, one over the ball's
    // mass, in one table: a row per variant of each, a column per path either varied (each
    // sweep's own value where it did not vary it: 0.5 and 0.2 from the scene), the highest
    // point of the first rebound e^2 above the ground in every row (the mass changes nothing).
    void severalSweepsMerged() {
        RUN(a, {"sweep", "drop.json", "--vary", "ball.restitution=0.4,0.6", "--out", "sa", "--quiet"});
        RUN(b, {"sweep", "drop.json", "--vary", "ball.mass=1,2", "--vary", "settings.duration=0.5", "--out",
                "sb", "--quiet"});
        QCOMPARE(a.code + b.code, 0);
        RUN(m, {"sweep", "--merge", "sa", "--merge", "sb", "--out", "all.csv", "--metric",
                "ball.rest_time,final_y"});
        QCOMPARE(m.code, 0);
        QCOMPARE(report(m.out).value("variants"), QString("4"));
        QCOMPARE(report(m.out).value("summary"), QString("all.csv"));
        const QStringList l = lines(QString::fromUtf8(read("all.csv")));
        QCOMPARE(l.first(),
                 QString("sweep,variant,ball.restitution,ball.mass,settings.duration,status,state_hash,"
                         "trajectory_hash,wall_s,ball.rest_time,ball.final_y,message"));
        const auto rows = summaryRows(read("all.csv"));
        QCOMPARE(rows.size(), 4);
        const QStringList expected = {"sa 0000 0.4 0.2 1", "sa 0001 0.6 0.2 1", "sb 0000 0.5 1 0.5",
                                      "sb 0001 0.5 2 0.5"};
        for (int i = 0; i < 4; ++i) {
            const auto& row = rows[i];
            QCOMPARE(QStringList({row["sweep"], row["variant"], row["ball.restitution"], row["ball.mass"],
                                  row["settings.duration"]})
                         .join(' '),
                     expected[i]);
            QCOMPARE(row["status"], QString("ok"));
        }
        // Each row the same as its own sweep's summary (written again by the merge).
        for (const char* dir : {"sa", "sb"}) {
            const auto own = summaryRows(read(QString(dir) + "/summary.csv"));
            for (const auto& row : rows) {
                if (row["sweep"] != dir) continue;
                const auto& mine = own[row["variant"].toInt()];
                for (const char* col : {"state_hash", "trajectory_hash", "ball.rest_time", "ball.final_y"})
                    QCOMPARE(row[col], mine[col]);
            }
        }
        // A restitution of 0.4 and 0.6 differ; the two masses are one motion.
        QVERIFY(rows[0]["trajectory_hash"] != rows[1]["trajectory_hash"]);
        QCOMPARE(rows[2]["ball.final_y"], rows[3]["ball.final_y"]);

        RUN(noOut, {"sweep", "--merge", "sa", "--merge", "sb"});
        QCOMPARE(noOut.code, 2);
        QVERIFY2(noOut.err.contains("--out FILE.csv"), qPrintable(noOut.err));
        RUN(twice, {"sweep", "--merge", "sa", "--merge", "sa/", "--out", "x.csv"});
        QCOMPARE(twice.code, 2);
        QVERIFY2(twice.err.contains("given twice"), qPrintable(twice.err));
        RUN(none, {"sweep", "--merge", "sa", "--merge", "nowhere", "--out", "x.csv"});
        QCOMPARE(none.code, 2);
        QVERIFY2(none.err.contains("nowhere/sweep.json: no sweep here"), qPrintable(none.err));
        QVERIFY(!QFile::exists(path("x.csv")));
    }
};

QTEST_GUILESS_MAIN(TestSweep)
#include "tst_sweep.moc"
