// The command line's overrides of a scene's settings (--duration, --dt, --frame-rate,
// --integrator, --impacts) and of how it runs (--threads): what each changes, what it
// leaves, and a bad value refused with exit 2 and a message naming the flag.
#include <tumble/integrators.h>

#include <QJsonDocument>
#include <QJsonObject>
#include <QtTest>

#include <cmath>

#include "cli_harness.h"

using namespace tumble::clitest;

class TestCliOptions : public QObject, private Harness {
    Q_OBJECT

private slots:
    void init() { makeFolder(); }
    void cleanup() { dir_.reset(); }

    void overrides_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<int>("frames");
        QTest::addColumn<int>("steps");
        QTest::addColumn<double>("time");
        QTest::addColumn<QString>("integrator");
        QTest::addColumn<QString>("note");  // on stderr, when the step used is not dt
        const QString def = tumble::defaultIntegrator().name;
        QTest::newRow("none") << QStringList() << 11 << 100 << 0.5 << def << "";
        QTest::newRow("duration 1, dt 0.01, frame rate 10")
            << QStringList({"--duration", "1", "--dt", "0.01", "--frame-rate", "10"}) << 11 << 100 << 1.0
            << def << "";
        QTest::newRow("duration 2") << QStringList({"--duration", "2"}) << 41 << 400 << 2.0 << def << "";
        QTest::newRow("duration 0") << QStringList({"--duration", "0"}) << 1 << 0 << 0.0 << def << "";
        // 0.05 s frame intervals need 3 steps of at most 0.02 s each: the note says so.
        QTest::newRow("dt 0.02")
            << QStringList({"--dt", "0.02"}) << 11 << 30 << 0.5 << def
            << "tumble: note: --dt 0.02 s does not divide a frame (0.05 s at frame_rate 20): "
               "each frame is 3 equal steps of 0.0166667 s, the fewest no longer than dt\n";
        QTest::newRow("dt=0.01") << QStringList({"--dt=0.01"}) << 11 << 50 << 0.5 << def << "";
        QTest::newRow("frame rate 4") << QStringList({"--frame-rate", "4"}) << 3 << 100 << 0.5 << def << "";
        QTest::newRow("integrator rk4") << QStringList({"--integrator", "rk4"}) << 11 << 100 << 0.5 << "rk4"
                                        << "";
        QTest::newRow("integrator euler, dt 0.05")
            << QStringList({"--integrator", "euler", "--dt", "0.05"}) << 11 << 10 << 0.5 << "euler"
            << "";
    }

    void overrides() {
        QFETCH(QStringList, args);
        QFETCH(int, frames);
        QFETCH(int, steps);
        QFETCH(double, time);
        QFETCH(QString, integrator);
        QFETCH(QString, note);
        RUN(r, QStringList({"--headless", "box.json", "--out", "traj.csv"}) + args);
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, note);
        const QMap<QString, QString> kv = report(r.out);
        QCOMPARE(kv.value("steps"), QString::number(steps));
        QCOMPARE(kv.value("frames"), QString::number(frames));
        QCOMPARE(kv.value("simulated_time").toDouble(), time);
        QCOMPARE(kv.value("integrator"), integrator);
        QCOMPARE(lines(QString::fromUtf8(read("traj.csv"))).size(), 1 + 2 * frames);
    }

    // Issue 47 item 1: a dt longer than a frame steps once a frame. It did so without a word
    // (stdout said dt: 0.0333 for a run at 1/60 s). Now one note names both, stdout's step:
    // is the step used, and the run is the 1/60 s run; a frame rate that fits gives dt.
    void theStepUsedIsTheStepSaid() {
        const QString scene = QStringLiteral(TUMBLE_SCENES_DIR "/bouncing-ball.json");  // 60 frames/s
        RUN(capped, {"--headless", scene, "--duration", "1", "--dt", "0.0333"});
        RUN(frame, {"--headless", scene, "--duration", "1", "--dt", "0.016666666666666666"});
        RUN(fitting,
            {"--headless", scene, "--duration", "1", "--dt", "0.033333333333333333", "--frame-rate", "30"});
        QCOMPARE(capped.code, 0);
        QCOMPARE(capped.err,
                 QString("tumble: note: --dt 0.0333 s is longer than a frame (0.0166667 s at frame_rate "
                         "60): each frame is one step of 0.0166667 s, not 0.0333; for steps of 0.0333 s "
                         "set frame_rate to 30.03 or less\n"));
        const auto c = report(capped.out), f = report(frame.out), fit = report(fitting.out);
        QCOMPARE(c.value("dt"), QString("0.033300000000000003"));
        QCOMPARE(c.value("step").toDouble(), 1.0 / 60.0);
        QCOMPARE(c.value("steps"), QString("60"));
        QCOMPARE(c.value("state_hash"), f.value("state_hash"));  // the same run as at 1/60 s
        QCOMPARE(frame.err, QString());
        QCOMPARE(fitting.err, QString());
        QCOMPARE(fit.value("step").toDouble(), 1.0 / 30.0);
        QVERIFY(fit.value("state_hash") != c.value("state_hash"));
        // --quiet says nothing.
        RUN(quiet, {"--headless", scene, "--duration", "1", "--dt", "0.0333", "--quiet"});
        QCOMPARE(quiet.err, QString());
    }

    // Issue 47 item 7: one meaning per measure name. --metrics's energy_lost_contacts held
    // friction too (963.6 J "lost" of a pile's 776.4 J once position correction was left
    // out); now each ledger name is stdout's, to the bit, and the parts add up.
    void theMetricsLedgerIsStdouts() {
        const QString scene = QStringLiteral(TUMBLE_SCENES_DIR "/sliding-block.json");
        RUN(r, {"--headless", scene, "--duration", "1", "--metrics", "m.json"});
        QCOMPARE(r.code, 0);
        const auto kv = report(r.out);
        const QJsonObject m = QJsonDocument::fromJson(read("m.json")).object()["scene"].toObject();
        for (const char* name : {"energy_lost_contacts", "energy_lost_friction", "energy_position_correction",
                                 "energy_lost_joints", "energy_by_kinematic"})
            QCOMPARE(m[name].toDouble(), kv.value(name).toDouble());
        QVERIFY(kv.value("energy_lost_friction").toDouble() != 0.0);  // the two names differ here
        const double start = kv.value("energy_start").toDouble(), end = kv.value("energy_end").toDouble();
        const double parts = m["energy_lost_contacts"].toDouble() + m["energy_lost_friction"].toDouble() +
                             m["energy_lost_joints"].toDouble() + m["energy_lost_damping"].toDouble() -
                             m["energy_position_correction"].toDouble() - m["energy_by_kinematic"].toDouble();
        QVERIFY(std::abs(start - end - parts) <= 1e-9 * std::abs(start));
    }

    // Issue 47 item 9: splitting-4 steps a mechanism alone at fourth order and other jointed
    // scenes at second; it said splitting-4 either way. A pendulum alone is composed (no
    // note); given a limit, it is not, and a note says so.
    void splitting4SaysWhenItsJointsAreSecondOrder() {
        const QByteArray pendulum = R"({"format": "tumble-scene", "version": 1, "settings": {"duration": 0.2},
            "bodies": [{"name": "bob", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [1, 0, 0]}],
            "joints": [{"name": "pin", "type": "hinge", "body_a": "bob", "anchor_a": [-1, 0, 0],
                        "axis_a": [0, 0, 1], "anchor_b": [0, 0, 0]LIMITS}]})";
        write("alone.json", QByteArray(pendulum).replace("LIMITS", ""));
        write("limited.json", QByteArray(pendulum).replace("LIMITS", R"(, "limits": [-1, 1])"));
        RUN(alone, {"--headless", "alone.json", "--integrator", "splitting-4"});
        RUN(limited, {"--headless", "limited.json", "--integrator", "splitting-4"});
        QCOMPARE(alone.code, 0);
        QCOMPARE(alone.err, QString());
        QCOMPARE(limited.code, 0);
        QVERIFY2(
            limited.err.startsWith("tumble: note: splitting-4: the joints here are stepped at second order"),
            qPrintable(limited.err));
        QCOMPARE(report(limited.out).value("integrator"), QString("splitting-4"));
    }

    // Each integrator gives its own result, and the same one on every run.
    void integratorOverrideChangesResult() {
        QSet<QString> hashes;
        for (const tumble::IntegratorInfo& info : tumble::integrators()) {
            RUN(r, {"--headless", "box.json", "--integrator", info.name});
            QCOMPARE(r.code, 0);
            const QString hash = report(r.out).value("state_hash");
            QVERIFY(!hash.isEmpty());
            QVERIFY2(!hashes.contains(hash), info.name);
            hashes.insert(hash);
        }
    }

    // --impacts end-of-step: the bouncing ball's impacts are resolved where the steps end
    // (no moment of impact found within a step), the run differs from the exact one, and
    // the scene saved as run says so. Two seconds, while the ball still bounces: by the
    // scene's five both runs have brought it to rest at the same place, to the bit.
    void impactsOverride() {
        const QString scene = QStringLiteral(TUMBLE_SCENES_DIR "/bouncing-ball.json");
        RUN(exact, {"--headless", scene, "--duration", "2"});
        RUN(late, {"--headless", scene, "--duration", "2", "--impacts", "end-of-step", "--save-scene", "saved.json"});
        QCOMPARE(exact.code, 0);
        QCOMPARE(late.code, 0);
        const auto e = report(exact.out), l = report(late.out);
        QVERIFY2(e.value("impacts").toInt() > 0, qPrintable(exact.out));
        QCOMPARE(l.value("impacts"), QString("0"));
        QVERIFY(e.value("state_hash") != l.value("state_hash"));
        QFile saved(path("saved.json"));
        QVERIFY(saved.open(QIODevice::ReadOnly));
        QVERIFY(saved.readAll().contains(R"("impacts": "end-of-step")"));
        RUN(again, {"--headless", scene, "--duration", "2", "--impacts", "exact"});
        QCOMPARE(report(again.out).value("state_hash"), e.value("state_hash"));
    }

    // --threads spreads the step over threads; the run is the same bit for bit.
    void threadsGiveTheSameRun() {
        const QString scene = QStringLiteral(TUMBLE_SCENES_DIR "/tower-20.json");
        RUN(one, {"--headless", scene, "--duration", "1"});
        RUN(two, {"--headless", scene, "--duration", "1", "--threads", "2"});
        RUN(four, {"--headless", scene, "--duration=1", "--threads=4"});
        QCOMPARE(one.code, 0);
        QCOMPARE(two.code, 0);
        QCOMPARE(four.code, 0);
        const auto r1 = report(one.out), r2 = report(two.out), r4 = report(four.out);
        QCOMPARE(r1.value("threads"), QString("1"));
        QCOMPARE(r2.value("threads"), QString("2"));
        QCOMPARE(r4.value("threads"), QString("4"));
        QVERIFY(r1.value("contact_points").toLong() > 0);
        QCOMPARE(r2.value("state_hash"), r1.value("state_hash"));
        QCOMPARE(r4.value("state_hash"), r1.value("state_hash"));
        QCOMPARE(r2.value("contact_points"), r1.value("contact_points"));
    }

    // Issue 47 item 2: typos are refused with exit 2 and the nearest known word, never by
    // opening the editor (without a display it aborted with status 134); the editor opens
    // only for no argument or one scene. Run without a display, as a CI job would.
    void typosAreRefusedWithTheNearestWord_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("--headles")
            << QStringList({"--headles", "box.json"})
            << "tumble: unknown option '--headles'; did you mean --headless? (see --help)";
        QTest::newRow("--bogus") << QStringList({"--bogus"})
                                 << "tumble: unknown option '--bogus' (see --help)";
        QTest::newRow("help")
            << QStringList({"help"})
            << "tumble: 'help' is neither a scene file nor a command; did you mean tumble --help?";
        QTest::newRow("swep")
            << QStringList({"swep", "box.json", "--vary", "box.mass=1,2", "--out", "s"})
            << "tumble: 'swep' is neither a scene file nor a command; did you mean tumble sweep?";
        QTest::newRow("scene with options, no --headless")
            << QStringList({"box.json", "--quiet"})
            << "tumble: options run a scene without a window and need --headless: tumble --headless box.json "
               "... "
               "(tumble box.json alone opens it in the editor)";
        QTest::newRow("--qiuet") << QStringList({"--headless", "box.json", "--qiuet"})
                                 << "tumble: unknown option '--qiuet'; did you mean --quiet? (see --help)";
        QTest::newRow("--dt swallowing a flag")
            << QStringList({"--headless", "box.json", "--dt", "--quiet"}) << "tumble: --dt: needs a value";
        QTest::newRow("sweep --vry")
            << QStringList({"sweep", "box.json", "--vry", "box.mass=1,2", "--out", "s"})
            << "tumble: sweep: unknown option '--vry'; did you mean --vary? (see tumble sweep --help)";
    }

    void typosAreRefusedWithTheNearestWord() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        const QByteArray display = qgetenv("DISPLAY");
        qunsetenv("DISPLAY");
        const Run r = run(args);
        qputenv("DISPLAY", display);
        QCOMPARE(r.code, 2);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, message + "\n");
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    // A negative number is a value, not a flag.
    void aNegativeValueIsAValue() {
        RUN(r, {"--headless", "box.json", "--dt", "-0.1"});
        QCOMPARE(r.code, 2);
        QCOMPARE(r.err, QString("tumble: --dt: must be greater than 0\n"));
    }

    // tumble sweep --quiet prints nothing on success (it was refused as unknown).
    void sweepQuiet() {
        RUN(r, {"sweep", "box.json", "--vary", "settings.duration=0.1,0.2", "--out", "s", "--quiet"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, QString());
        QVERIFY(QFile::exists(path("s/summary.csv")));
    }

    // Issue 47 item 6: values whose energy or momentum double precision cannot carry
    // through a run are refused when the scene is read, naming the field, with one message
    // whatever the options (a velocity of 1e308 loaded, then "ran away ... -nan J"; a mass
    // of 1e308 at 1e300 m said "became non-finite" without --out and "a non-finite number
    // cannot be written" with it).
    void magnitudesARunCannotCarry_data() {
        QTest::addColumn<QByteArray>("body");
        QTest::addColumn<QString>("message");
        QTest::newRow("velocity 1e308") << QByteArray(R"("mass": 1, "velocity": [1e308, 0, 0])")
                                        << "big.json: bodies[0].velocity: gives a momentum of 1e+308 kg m/s "
                                           "(mass 1 kg), more than a run can "
                                           "carry in double precision (at most 1e150)";
        QTest::newRow("mass 1e308 at 1e300 m") << QByteArray(R"("mass": 1e308, "position": [0, 1e300, 0])")
                                               << "big.json: bodies[0].position: gives a potential energy "
                                                  "over the run of inf J (mass 1e+308 kg), more "
                                                  "than a run can carry in double precision (at most 1e150)";
        QTest::newRow("spin 1e200") << QByteArray(R"("mass": 1, "angular_velocity": [0, 1e200, 0])")
                                    << "big.json: bodies[0].angular_velocity: gives a kinetic energy of "
                                       "turning of inf J, more than a run "
                                       "can carry in double precision (at most 1e150)";
    }

    void magnitudesARunCannotCarry() {
        QFETCH(QByteArray, body);
        QFETCH(QString, message);
        write("big.json", R"({"format": "tumble-scene", "version": 1, "bodies": [{"name": "ball", "shape": )"
                          R"({"type": "sphere", "radius": 0.1}, )" +
                              body + "}]}");
        for (const QStringList& more : {QStringList(), QStringList({"--out", "x.csv"})}) {
            RUN(r, QStringList({"--headless", "big.json"}) + more);
            QCOMPARE(r.code, 2);
            QCOMPARE(r.err, message + "\n");
            QVERIFY(!QFileInfo::exists(path("x.csv")));
        }
        // A large but carried value still runs.
        write("fine.json",
              R"({"format": "tumble-scene", "version": 1, "settings": {"duration": 0.1}, "bodies": [)"
              R"({"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, )"
              R"("velocity": [1e6, 0, 0]}]})");
        RUN(fine, {"--headless", "fine.json"});
        QCOMPARE(fine.code, 0);
    }

    void badOverride_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("dt 0") << QStringList({"--dt", "0"}) << "tumble: --dt: must be greater than 0";
        QTest::newRow("dt -0.1") << QStringList({"--dt", "-0.1"}) << "tumble: --dt: must be greater than 0";
        QTest::newRow("dt abc") << QStringList({"--dt", "abc"}) << "tumble: --dt: 'abc' is not a number";
        QTest::newRow("dt 0.01x") << QStringList({"--dt", "0.01x"})
                                  << "tumble: --dt: '0.01x' is not a number";
        QTest::newRow("dt empty") << QStringList({"--dt="}) << "tumble: --dt: '' is not a number";
        QTest::newRow("dt inf") << QStringList({"--dt", "inf"}) << "tumble: --dt: must be a finite number";
        QTest::newRow("dt nan") << QStringList({"--dt", "nan"}) << "tumble: --dt: must be a finite number";
        QTest::newRow("dt without value") << QStringList({"--dt"}) << "tumble: --dt: needs a value";
        QTest::newRow("duration -1") << QStringList({"--duration", "-1"})
                                     << "tumble: --duration: must be 0 or greater";
        QTest::newRow("frame rate 0")
            << QStringList({"--frame-rate", "0"}) << "tumble: --frame-rate: must be greater than 0";
        QTest::newRow("integrator nope")
            << QStringList({"--integrator", "nope"})
            << "tumble: --integrator: unknown integrator 'nope' (see --list-integrators)";
        QTest::newRow("impacts later")
            << QStringList({"--impacts", "later"}) << "tumble: --impacts: 'later' is not one of exact, end-of-step";
        QTest::newRow("threads 0") << QStringList({"--threads", "0"})
                                   << "tumble: --threads: '0' is not a whole number from 1 to 256";
        QTest::newRow("threads 2.5") << QStringList({"--threads", "2.5"})
                                     << "tumble: --threads: '2.5' is not a whole number from 1 to 256";
        QTest::newRow("threads 1000") << QStringList({"--threads", "1000"})
                                      << "tumble: --threads: '1000' is not a whole number from 1 to 256";
    }

    void badOverride() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        RUN(r, QStringList({"--headless", "box.json", "--out", "traj.csv", "--save-scene", "saved.json"}) +
                   args);
        QCOMPARE(r.code, 2);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, message + "\n");
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }
};

QTEST_GUILESS_MAIN(TestCliOptions)
#include "tst_options.moc"
