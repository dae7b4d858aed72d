// The headless command line of INTERFACES.md, run as the real executable in a fresh
// folder: exit statuses, the key: value report, one-line errors naming the file and field,
// no output left behind on failure, determinism and the exports. The overrides of the
// scene's settings (--dt, --integrator, --impacts, --threads ...) are in tst_options.cpp.
#include <tumble/integrators.h>
#include <tumble/io/scene_file.h>
#include <tumble/io/trajectory_csv.h>
#include <tumble/io/trajectory_json.h>
#include <tumble/io/trajectory_writer.h>
#include <tumble/world.h>

#include <QDir>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QtTest>

#include <sys/stat.h>

#include "../io/gltf_validator.h"
#include "cli_harness.h"

#include <sstream>

namespace {

using namespace tumble::clitest;

// A spring that rk4 holds only for dt < 2√2/√(k/m) = 0.00894 s, at dt = 0.01 s.
const char* const kStiff = R"({
  "format": "tumble-scene",
  "version": 1,
  "settings": {"dt": 0.01, "duration": 10, "integrator": "rk4", "frame_rate": 50},
  "bodies": [
    {"name": "bob", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, -0.1, 0],
     "forces": [{"type": "spring", "anchor": [0, 1, 0], "stiffness": 1e5, "rest_length": 1}]}
  ]
}
)";

// The hash and the CSV of the same run done in this process, through the engine.
struct Reference {
    QString hash;
    std::string csv;
};

Reference reference(const std::string& scenePath) {
    tumble::World world(tumble::io::readSceneFile(scenePath));
    std::ostringstream csv;
    csv << tumble::io::kTrajectoryCsvHeader << "\n";
    const double frameRate = world.model().settings.frameRate;
    tumble::simulate(world, [&](int k, const tumble::State& s) {
        tumble::io::writeCsvFrame(csv, world.model(), s, k / frameRate);
    });
    return {QString::fromStdString(tumble::hashHex(tumble::hashState(world.state()))), csv.str()};
}

}  // namespace

class TestCli : public QObject, private Harness {
    Q_OBJECT

private slots:
    void init() { makeFolder(); }

    void cleanup() { dir_.reset(); }

    // A mesh split into convex parts: the first run splits it, says so and keeps the parts
    // beside the scene; the second takes them from there, with the same run to the bit.
    void convexPartsMadeOnceAndKept() {
        // A closed L-shaped prism (concave): two boxes' worth of parts.
        write("l.obj",
              "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
              "v 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n"
              "f 1 6 5 4\nf 1 4 3 2\nf 7 8 9 10\nf 7 10 11 12\n"
              "f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n");
        write("l.json", R"({"format": "tumble-scene", "version": 1, "settings": {"duration": 0.5},
  "bodies": [{"name": "floor", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0]}},
             {"name": "l", "shape": {"type": "mesh", "file": "l.obj", "collision": "convex-parts", "max_parts": 4},
              "density": 500, "position": [0, 0.5, 0]}]})");
        RUN(first, {"--headless", "l.json"});
        QCOMPARE(first.code, 0);
        QVERIFY2(first.err.contains("tumble: note: bodies[1].shape: l.obj split into 2 convex parts in "),
                 qPrintable(first.err));
        QVERIFY2(first.err.contains("the convex parts are kept in l.convex-parts.json"),
                 qPrintable(first.err));
        QVERIFY(QFile::exists(path("l.convex-parts.json")));
        RUN(second, {"--headless", "l.json"});
        QCOMPARE(second.code, 0);
        QVERIFY2(!second.err.contains("split into"), qPrintable(second.err));
        QCOMPARE(second.out.section("state_hash:", 1), first.out.section("state_hash:", 1));
    }

    void help() {
        RUN(r, {"--help"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        QVERIFY(r.out.startsWith("Usage:"));
        for (const char* flag : {"--headless", "--duration", "--dt", "--integrator", "--impacts", "--frame-rate",
                                 "--threads", "--out", "--save-scene", "--quiet", "--help", "--version", "--list-integrators"}) {
            QVERIFY2(r.out.contains(flag), flag);
        }
    }

    void version() {
        RUN(r, {"--version"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        // The version and the commit the build was made from (a build outside git: unknown).
        QVERIFY2(QRegularExpression("^tumble \\d+\\.\\d+\\.\\d+ \\(commit ([0-9a-f]{7,40}(-dirty)?|unknown)\\)\\n$")
                     .match(r.out)
                     .hasMatch(),
                 qPrintable(r.out));
    }

    void listIntegrators() {
        RUN(r, {"--list-integrators"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        const QStringList all = lines(r.out);
        QCOMPARE(r.out.count("(default)"), 1);
        for (const tumble::IntegratorInfo& info : tumble::integrators()) {
            const QString name = info.name;
            const bool isDefault = &info == &tumble::defaultIntegrator();
            const QString expected = isDefault ? name + " (default)" : name;
            QVERIFY2(all.contains(expected), qPrintable("no line '" + expected + "' in\n" + r.out));
        }
    }

    void headlessRun() {
        RUN(r, {"--headless", "box.json"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        const QMap<QString, QString> kv = report(r.out);
        QVERIFY2(!kv.isEmpty(), qPrintable("not key: value lines:\n" + r.out));
        for (const char* key : {"bodies", "steps", "simulated_time", "wall_seconds", "state_hash"}) {
            QVERIFY2(kv.contains(key), key);
        }
        QCOMPARE(kv["bodies"], QString("2"));
        QCOMPARE(kv["steps"], QString("100"));  // 10 frame intervals of 0.05 s in steps of 0.005 s
        QCOMPARE(kv["simulated_time"].toDouble(), 0.5);
        bool ok = false;
        QVERIFY(kv["wall_seconds"].toDouble(&ok) >= 0.0 && ok);
        QVERIFY2(QRegularExpression("^[0-9a-f]{16}$").match(kv["state_hash"]).hasMatch(),
                 qPrintable(kv["state_hash"]));
        QCOMPARE(kv["state_hash"], reference(path("box.json").toStdString()).hash);
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));  // wrote nothing
    }

    // The collision samples (no driving force) run headless and report where their energy
    // went: energy_end = energy_start - lost + correction, and the end is never above the start.
    void samplesBalanceTheirEnergy_data() {
        QTest::addColumn<QString>("scene");
        for (const char* name : {"bouncing-ball", "head-on", "tilted-box-impact", "newtons-cradle",
                                 "sliding-block", "rolling-sphere", "incline", "mass-ratio-stack",
                                 "sleeping-wake", "chain", "newtons-cradle-strings", "sieve"})
            QTest::newRow(name) << QString(TUMBLE_SCENES_DIR "/%1.json").arg(name);
    }
    void samplesBalanceTheirEnergy() {
        QFETCH(QString, scene);
        RUN(r, {"--headless", scene, "--duration", "3"});
        QCOMPARE(r.code, 0);
        const QMap<QString, QString> kv = report(r.out);
        for (const char* key :
             {"energy_start", "energy_end", "energy_lost_contacts", "energy_lost_friction",
              "energy_position_correction", "energy_lost_joints", "impact_moments", "solve_seconds", "awake_body_steps",
              "parked_body_steps", "island_restarts", "still_body_steps", "settled_bodies"})
            QVERIFY2(kv.contains(key), key);
        const double start = kv["energy_start"].toDouble(), end = kv["energy_end"].toDouble();
        const double lost = kv["energy_lost_contacts"].toDouble() + kv["energy_lost_friction"].toDouble() +
                            kv["energy_lost_joints"].toDouble();
        const double correction = kv["energy_position_correction"].toDouble();
        // (A resting stack books nothing but the rounding of its positions, 1e-15 of its
        // weight times height a step: mass-ratio-stack -1e-11 J of 1e3 J in 3 s.)
        QVERIFY2(lost >= -1e-11 * std::abs(start), qPrintable(r.out));
        // The ledger balances to 1e-6 of the energy that moved (the integrators' own error in
        // these scenes is far below that).
        const double scale = std::abs(start) + lost + std::abs(correction);
        QVERIFY2(std::abs(end - (start - lost + correction)) <= 1e-6 * scale, qPrintable(r.out));
        QVERIFY2(end <= start + 1e-9 * std::abs(start), qPrintable(r.out));
    }

    void quiet() {
        RUN(r, {"--headless", "box.json", "--quiet"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, QString());
        RUN(withOut, {"--headless", "--quiet", "--out", "traj.csv", "box.json"});
        QCOMPARE(withOut.code, 0);
        QCOMPARE(withOut.out, QString());
        QCOMPARE(withOut.err, QString());
        QCOMPARE(lines(QString::fromUtf8(read("traj.csv"))).size(), 1 + 2 * 11);
    }

    void outCsv() {
        RUN(r, {"--headless", "box.json", "--out", "traj.csv"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        const QByteArray csv = read("traj.csv");
        const QStringList rows = lines(QString::fromUtf8(csv));
        QCOMPARE(rows.value(0), QString("time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz"));
        QCOMPARE(rows.size(), 1 + 2 * 11);  // header, 2 bodies x 11 frames
        QCOMPARE(csv.toStdString(), reference(path("box.json").toStdString()).csv);
        QCOMPARE(entries(), QStringList({"blow.json", "box.json", "traj.csv"}));  // no temporary left
    }

    // --joint-forces: the door sample's hinge in traj-joints.csv beside the trajectory, a row
    // per frame, its weight carried (20 kg x 9.81 m/s^2) from the first step on.
    void outJointForces() {
        RUN(r, {"--headless", TUMBLE_SCENES_DIR "/hinged-door.json", "--duration", "0.5", "--out", "traj.csv",
                "--joint-forces"});
        QCOMPARE(r.code, 0);
        const QStringList rows = lines(QString::fromUtf8(read("traj-joints.csv")));
        QCOMPARE(rows.value(0), QString("time,joint,fx,fy,fz,tx,ty,tz,broken"));
        QCOMPARE(rows.size(), 1 + 31);  // header, 1 joint x 31 frames
        QCOMPARE(rows.value(1), QString("0,hinge,0,0,0,0,0,0,0"));
        const QStringList last = rows.last().split(',');
        QCOMPARE(last.value(1), QString("hinge"));
        QVERIFY(std::abs(last.value(3).toDouble() - 196.2) < 1e-9);
        QCOMPARE(lines(QString::fromUtf8(read("traj.csv"))).size(), 1 + 3 * 31);  // unchanged: ground, post, door
    }

    void saveScene() {
        RUN(r, {"--headless", "box.json", "--duration", "0.3", "--save-scene", "saved.json"});
        QCOMPARE(r.code, 0);
        const tumble::SceneDesc saved = tumble::io::readSceneFile(path("saved.json").toStdString());
        QCOMPARE(saved.settings.duration, 0.3);                               // as run, the override applied
        QVERIFY(std::abs(saved.bodies[1].orientation.norm() - 1.0) < 1e-15);  // normalised
        RUN(again, {"--headless", "saved.json", "--save-scene", "saved-again.json"});
        QCOMPARE(again.code, 0);
        QCOMPARE(report(again.out).value("state_hash"), report(r.out).value("state_hash"));
        QVERIFY(!report(r.out).value("state_hash").isEmpty());
        QCOMPARE(read("saved-again.json"), read("saved.json"));
        QCOMPARE(entries(), QStringList({"blow.json", "box.json", "saved-again.json", "saved.json"}));
    }

    void invalidScene_data() {
        QTest::addColumn<QString>("scene");    // the file given on the command line
        QTest::addColumn<QByteArray>("text");  // written to bad.json
        QTest::addColumn<QString>("message");
        const QByteArray box = kBox;
        auto broken = [&](const char* from, const char* to) {
            QByteArray t = box;
            return t.replace(from, to);
        };
        QTest::newRow("radius") << "bad.json"
                                << broken(R"("half_extents": [0.5, 0.25, 0.1])",
                                          R"("half_extents": [0.5, 0, 0.1])")
                                << "bad.json: bodies[1].shape.half_extents[1]: must be greater than 0";
        QTest::newRow("mass") << "bad.json" << broken(R"("mass": 2)", R"("mass": -2)")
                              << "bad.json: bodies[1].mass: must be greater than 0";
        QTest::newRow("1e999") << "bad.json" << broken(R"("mass": 2)", R"("mass": 2e999)")
                               << "bad.json: bodies[1].mass: must be a finite number";
        QTest::newRow("missing key") << "bad.json" << broken(R"("format": "tumble-scene",)", "")
                                     << "bad.json: format: is missing";
        QTest::newRow("unknown key") << "bad.json"
                                     << broken(R"("mass": 2,)", R"("mass": 2, "colour": "red",)")
                                     << "bad.json: bodies[1].colour: unknown key";
        QTest::newRow("energy_guard a string")
            << "bad.json" << broken(R"("frame_rate": 20})", R"("frame_rate": 20, "energy_guard": "off"})")
            << "bad.json: settings.energy_guard: must be true or false";
        QTest::newRow("dt 1e-300") << "bad.json" << broken(R"("dt": 0.005)", R"("dt": 1e-300)")
                                   << "bad.json: settings.dt: 1e-300 s is too small: 5e+299 steps for the "
                                      "duration of 0.5 s (at most 10^10)";
        QTest::newRow("version 2") << "bad.json" << broken(R"("version": 1)", R"("version": 2)")
                                   << "bad.json: version: version 2 is not one this build reads (it reads 1)";
        QTest::newRow("truncated")
            << "bad.json" << QByteArray(R"({"format": "tumble-scene",)")
            << "bad.json: malformed JSON: parse error at line 1, column 27: syntax error "
               "while parsing object key - unexpected end of input; expected string literal";
        QTest::newRow("missing file")
            << "nope.json" << QByteArray() << "nope.json: cannot be read (missing, or no permission)";
        QTest::newRow("directory") << "folder.json" << QByteArray()
                                   << "folder.json: is a directory, not a scene file";
        // Opening a FIFO for reading waits for a writer: it used to hang the run.
        QTest::newRow("fifo")
            << "pipe.json" << QByteArray()
            << "pipe.json: is not a regular file (a pipe, socket or device), not a scene file";
    }

    void invalidScene() {
        QFETCH(QString, scene);
        QFETCH(QByteArray, text);
        QFETCH(QString, message);
        if (scene == "bad.json") write("bad.json", text);
        if (scene == "folder.json") QVERIFY(QDir(dir_->path()).mkdir("folder.json"));
        if (scene == "pipe.json")
            QVERIFY(::mkfifo(QDir(dir_->path()).filePath("pipe.json").toLocal8Bit(), 0600) == 0);
        const QStringList before = entries();
        RUN(r, {"--headless", scene, "--out", "traj.csv", "--save-scene", "saved.json"});
        QCOMPARE(r.code, 2);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, message + "\n");  // exactly one line: FILE: FIELD: MESSAGE
        QCOMPARE(entries(), before);      // no output, no temporary
    }

    // With the energy guard off, the state overflows; the message names the body, the
    // time and the likely cause.
    void nonFiniteState() {
        QByteArray unguarded = kBlowUp;
        unguarded.replace(R"("frame_rate": 10})", R"("frame_rate": 10, "energy_guard": false})");
        write("blow.json", unguarded);
        RUN(r, {"--headless", "blow.json", "--out", "traj.csv", "--save-scene", "saved.json"});
        QCOMPARE(r.code, 1);
        QCOMPARE(r.out, QString());
        QCOMPARE(lines(r.err).size(), 1);
        const QRegularExpressionMatch m =
            QRegularExpression(
                "^tumble: blow\\.json: body 'ball' \\(bodies\\[0\\]\\) became non-finite at t = "
                "([0-9.e+-]+) s; likely cause: explicit euler gains energy on spring forces\\[0\\] of body "
                "'ball' \\(k = 1e\\+12 N/m, m = 1 kg: undamped, at any step\\); use rk4")
                .match(r.err);
        QVERIFY2(m.hasMatch(), qPrintable(r.err));
        const double t = m.captured(1).toDouble();
        QVERIFY2(t > 0.0 && t <= 2.0, qPrintable(m.captured(1)));
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));  // no partial CSV, no temporary
    }

    // A run whose energy runs away stops while the state is still finite: exit 1, one line
    // naming the body, the time and the likely cause, no output left behind.
    void energyRunaway_data() {
        QTest::addColumn<QByteArray>("scene");
        QTest::addColumn<QString>("pattern");
        QTest::newRow("rk4, step too large")
            << QByteArray(kStiff)
            << "^tumble: blow\\.json: body 'bob' \\(bodies\\[0\\]\\) ran away "
               "at t = ([0-9.e+-]+) s: .*; likely cause: dt = 0\\.01 s is too "
               "large for spring forces\\[0\\] of body 'bob' \\(k = 1e\\+05 N/m, "
               "m = 1 kg: needs dt < 0\\.00894 s with rk4\\)$";
        QTest::newRow("explicit euler")
            << QByteArray(kBlowUp)
            << "^tumble: blow\\.json: body 'ball' \\(bodies\\[0\\]\\) ran away at "
               "t = ([0-9.e+-]+) s: .*; likely cause: explicit euler gains energy on "
               "spring forces\\[0\\] of body 'ball' .*use rk4 .* or symplectic-euler";
    }

    void energyRunaway() {
        QFETCH(QByteArray, scene);
        QFETCH(QString, pattern);
        write("blow.json", scene);
        RUN(r, {"--headless", "blow.json", "--out", "traj.csv", "--save-scene", "saved.json"});
        QCOMPARE(r.code, 1);
        QCOMPARE(r.out, QString());
        QCOMPARE(lines(r.err).size(), 1);
        const QRegularExpressionMatch m = QRegularExpression(pattern).match(lines(r.err).at(0));
        QVERIFY2(m.hasMatch(), qPrintable(r.err));
        const double t = m.captured(1).toDouble();
        QVERIFY2(t > 0.0 && t < 0.5, qPrintable(m.captured(1)));      // early: an overflow takes seconds
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));  // no partial CSV, no temporary

        // The guard switched off in the file: the same scene runs on past that time.
        QByteArray off = scene;
        QVERIFY(off.contains(R"("frame_rate": )"));
        off.replace(R"("settings": {)", R"("settings": {"energy_guard": false, )");
        write("blow.json", off);
        RUN(unguarded, {"--headless", "blow.json", "--save-scene", "saved.json"});
        QCOMPARE(unguarded.code, 1);
        QVERIFY2(unguarded.err.contains("became non-finite"), qPrintable(unguarded.err));
        const QRegularExpressionMatch later =
            QRegularExpression("at t = ([0-9.e+-]+) s").match(unguarded.err);
        QVERIFY(later.hasMatch());
        QVERIFY2(later.captured(1).toDouble() > t, qPrintable(unguarded.err));
    }

    // The setting is read, kept by --save-scene and written in every saved scene.
    void energyGuardSettingRoundTrips() {
        QByteArray off = kBox;
        off.replace(R"("frame_rate": 20})", R"("frame_rate": 20, "energy_guard": false})");
        write("off.json", off);
        RUN(r, {"--headless", "off.json", "--save-scene", "saved.json"});
        QCOMPARE(r.code, 0);
        QVERIFY(!tumble::io::readSceneFile(path("saved.json").toStdString()).settings.energyGuard);
        QVERIFY(read("saved.json").contains(R"("energy_guard": false)"));
        RUN(on, {"--headless", "box.json", "--save-scene", "saved.json"});
        QCOMPARE(on.code, 0);
        QVERIFY(tumble::io::readSceneFile(path("saved.json").toStdString()).settings.energyGuard);
        QVERIFY(read("saved.json").contains(R"("energy_guard": true)"));
    }

    void usageErrors_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("unknown option") << QStringList({"--headless", "box.json", "--bogus"})
                                        << "tumble: unknown option '--bogus' (see --help)";
        QTest::newRow("unknown short option")
            << QStringList({"--headless", "-x", "box.json"}) << "tumble: unknown option '-x' (see --help)";
        QTest::newRow("missing scene")
            << QStringList({"--headless"}) << "tumble: --headless needs a scene file (see --help)";
        QTest::newRow("missing scene with options") << QStringList({"--headless", "--out", "traj.csv"})
                                                    << "tumble: --headless needs a scene file (see --help)";
        QTest::newRow("two scenes") << QStringList({"--headless", "box.json", "blow.json"})
                                    << "tumble: more than one scene given: 'box.json' and 'blow.json'";
        QTest::newRow("out without value")
            << QStringList({"--headless", "box.json", "--out"}) << "tumble: --out: needs a value";
        const QString jointForces =
            "tumble: --joint-forces: needs --out FILE.csv or FILE.json (the joints' reactions are written "
            "with the trajectory)";
        QTest::newRow("joint forces without out") << QStringList({"--headless", "box.json", "--joint-forces"})
                                                  << jointForces;
        QTest::newRow("joint forces in glTF")
            << QStringList({"--headless", "box.json", "--joint-forces", "--out", "t.glb"}) << jointForces;
    }

    void usageErrors() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        RUN(r, args);
        QCOMPARE(r.code, 2);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, message + "\n");
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    // Refused before simulating: the scene given would otherwise fail with status 1.
    void outExtension_data() {
        QTest::addColumn<QString>("out");
        QTest::newRow("txt") << "traj.txt";
        QTest::newRow("none") << "traj";
        QTest::newRow("csv.bak") << "traj.csv.bak";
    }

    void outExtension() {
        QFETCH(QString, out);
        RUN(r, {"--headless", "blow.json", "--out", out});
        QCOMPARE(r.code, 2);
        QCOMPARE(r.out, QString());
        QCOMPARE(lines(r.err).size(), 1);
        QVERIFY2(r.err.startsWith("tumble: --out: '" + out + "': "), qPrintable(r.err));
        QVERIFY2(r.err.contains(".csv"), qPrintable(r.err));  // says what is accepted
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    // An output that cannot be written fails before the run (the scene given would otherwise
    // fail with another message) and leaves the other output unwritten.
    void unwritableOutput_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("out") << QStringList({"--out", "nodir/traj.csv", "--save-scene", "saved.json"})
                             << "tumble: --out: nodir/traj.csv: cannot be written: no such folder";
        QTest::newRow("save-scene")
            << QStringList({"--out", "traj.csv", "--save-scene", "nodir/saved.json"})
            << "tumble: --save-scene: nodir/saved.json: cannot be written: no such folder";
        // Issue 47 item 4: --metrics was checked after the run, when the trajectory was
        // already written.
        QTest::newRow("metrics") << QStringList({"--out", "traj.csv", "--metrics", "nodir/m.json"})
                                 << "tumble: --metrics: nodir/m.json: cannot be written: no such folder";
    }

    // Issue 47 item 4: a second --out (or --save-scene, --metrics) silently replaced the
    // first; --joint-forces on a scene without joints wrote a header-only file.
    void outputsGivenOnceAndForAReason_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("--out twice") << QStringList({"box.json", "--out", "a.csv", "--out", "b.csv"})
                                     << "tumble: --out: given twice ('a.csv' and 'b.csv'); a run writes one";
        QTest::newRow("--metrics twice")
            << QStringList({"box.json", "--metrics", "a.json", "--metrics=b.json"})
            << "tumble: --metrics: given twice ('a.json' and 'b.json'); a run writes one";
        QTest::newRow("--joint-forces without joints")
            << QStringList({"box.json", "--out", "a.csv", "--joint-forces"})
            << "tumble: --joint-forces: box.json has no joints (nothing to write)";
    }

    void outputsGivenOnceAndForAReason() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        RUN(r, QStringList({"--headless"}) + args);
        QCOMPARE(r.code, 2);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, message + "\n");
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    void unwritableOutput() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        RUN(r, QStringList({"--headless", "blow.json"}) + args);
        QCOMPARE(r.code, 1);
        QCOMPARE(r.out, QString());
        QCOMPARE(r.err, message + "\n");
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    void outExtensionIgnoresCase() {
        RUN(r, {"--headless", "box.json", "--out", "TRAJ.CSV"});
        QCOMPARE(r.code, 0);
        QCOMPARE(lines(QString::fromUtf8(read("TRAJ.CSV"))).size(), 1 + 2 * 11);
    }

    void deterministic() {
        RUN(a, {"--headless", "box.json", "--out", "a.csv"});
        RUN(b, {"--headless", "box.json", "--out", "b.csv"});
        QCOMPARE(a.code, 0);
        QCOMPARE(b.code, 0);
        const QString hash = report(a.out).value("state_hash");
        QVERIFY(!hash.isEmpty());
        QCOMPARE(report(b.out).value("state_hash"), hash);
        QVERIFY(!read("a.csv").isEmpty());
        QCOMPARE(read("b.csv"), read("a.csv"));
    }

    // --out with the other formats (docs/export.md): the same run as in this process, the
    // glTF files valid and complete, no temporary left.
    void outJson() {
        RUN(r, {"--headless", "box.json", "--out", "traj.json"});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        QCOMPARE(entries(), QStringList({"blow.json", "box.json", "traj.json"}));
        const tumble::io::Trajectory t = tumble::io::readTrajectoryJson(path("traj.json").toStdString());
        QCOMPARE(t.frameRate, 20.0);
        QCOMPARE(t.bodies.size(), size_t(2));
        QCOMPARE(t.bodies[1].name, std::string("box"));
        QCOMPARE(t.frames.size(), size_t(11));
        // Byte for byte what the writer gives for the same run in this process.
        const tumble::SceneDesc scene = tumble::io::readSceneFile(path("box.json").toStdString());
        tumble::World world(scene);
        const std::string expected = path("expected.json").toStdString();
        auto writer = tumble::io::makeTrajectoryWriter(expected);
        writer->begin(world.model(), scene, tumble::frameCount(world.model().settings), 20);
        tumble::simulate(world, [&](int k, const tumble::State& s) { writer->frame(k, s); });
        writer->finish();
        QCOMPARE(read("traj.json"), read("expected.json"));
        QCOMPARE(report(r.out).value("state_hash"),
                 QString::fromStdString(tumble::hashHex(tumble::hashState(world.state()))));
    }

    void outGltf_data() {
        QTest::addColumn<QString>("out");
        QTest::addColumn<QStringList>("files");
        QTest::newRow("gltf") << "traj.gltf"
                              << QStringList({"blow.json", "box.json", "traj.bin", "traj.gltf"});
        QTest::newRow("glb") << "traj.glb" << QStringList({"blow.json", "box.json", "traj.glb"});
        QTest::newRow("GLB") << "TRAJ.GLB" << QStringList({"TRAJ.GLB", "blow.json", "box.json"});
    }

    void outGltf() {
        QFETCH(QString, out);
        QFETCH(QStringList, files);
        RUN(r, {"--headless", "box.json", "--out", out});
        QCOMPARE(r.code, 0);
        QCOMPARE(r.err, QString());
        QCOMPARE(entries(), files);
        TUMBLE_VERIFY_GLTF_VALID(path(out));
        // The JSON of the file (a .glb's first chunk): both bodies, the box animated.
        QByteArray json = read(out);
        if (out.endsWith("glb", Qt::CaseInsensitive)) {
            QVERIFY(json.startsWith("glTF"));
            const quint32 length = qFromLittleEndian<quint32>(json.constData() + 12);
            json = json.mid(20, length);
        }
        const QJsonObject doc = QJsonDocument::fromJson(json).object();
        QStringList names;
        for (const QJsonValue& n : doc.value("nodes").toArray())
            names << n.toObject().value("name").toString();
        QVERIFY2(names.contains("ground") && names.contains("box"), qPrintable(names.join(", ")));
        const QJsonArray channels =
            doc.value("animations").toArray().at(0).toObject().value("channels").toArray();
        QCOMPARE(channels.size(), 2);  // translation and rotation of the box; the ground is static
        for (const QJsonValue& c : channels) {
            const int node = c.toObject().value("target").toObject().value("node").toInt();
            QCOMPARE(doc.value("nodes").toArray().at(node).toObject().value("name").toString(),
                     QString("box"));
        }
    }

    // Issue 47 item 8: a .glb of many moving bodies holds each thing once: the frame times in
    // one accessor that every sampler shares, and a buffer no larger than the meshes and the
    // keys (assimp's exporter, before, stored the times once per sampler and took 17.6 s for
    // 2 000 bodies: tumble-bench --scene export times it).
    void outGlbManyBodies() {
        const int moving = 300;
        QByteArray bodies = R"({"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0]}})";
        for (int i = 0; i < moving; ++i) {
            const QByteArray shape =
                i % 2 ? R"({"type": "sphere", "radius": 0.3})" : R"({"type": "box", "half_extents": [0.3, 0.3, 0.3]})";
            bodies += ",\n{\"name\": \"b" + QByteArray::number(i) + "\", \"mass\": 1, \"shape\": " + shape +
                      ", \"position\": [" + QByteArray::number(1.5 * (i % 20)) + ", 2, " +
                      QByteArray::number(1.5 * (i / 20)) + "], \"angular_velocity\": [0, 1, 0]}";
        }
        write("many.json", R"({"format": "tumble-scene", "version": 1,
                             "settings": {"duration": 0.5, "frame_rate": 60}, "bodies": [)" +
                               bodies + "]}");
        RUN(r, {"--headless", "many.json", "--out", "many.glb", "--quiet"});
        QCOMPARE(r.code, 0);
        TUMBLE_VERIFY_GLTF_VALID(path("many.glb"));
        const QByteArray glb = read("many.glb");
        const QJsonObject doc =
            QJsonDocument::fromJson(glb.mid(20, qFromLittleEndian<quint32>(glb.constData() + 12))).object();
        const QJsonArray samplers = doc["animations"].toArray().at(0).toObject()["samplers"].toArray();
        QCOMPARE(samplers.size(), 2 * moving);
        QSet<int> inputs;
        for (const QJsonValue& s : samplers) inputs.insert(s.toObject()["input"].toInt());
        QCOMPARE(inputs.size(), 1);
        const QJsonArray accessors = doc["accessors"].toArray();
        const int frames = accessors.at(*inputs.begin()).toObject()["count"].toInt();
        QCOMPARE(frames, 31);
        // Three meshes (box, sphere, the ground's square), three accessors each.
        QCOMPARE(doc["meshes"].toArray().size(), 3);
        QCOMPARE(accessors.size(), 3 * 3 + 1 + 2 * moving);
        qint64 meshBytes = 0;
        for (const QJsonValue& m : doc["meshes"].toArray()) {
            const QJsonObject p = m.toObject()["primitives"].toArray().at(0).toObject();
            const int vertices = accessors.at(p["attributes"].toObject()["POSITION"].toInt()).toObject()["count"].toInt();
            const int indices = accessors.at(p["indices"].toInt()).toObject()["count"].toInt();
            meshBytes += 2 * 12 * vertices + 4 * indices;
        }
        const qint64 keyBytes = 4 * frames + qint64(moving) * frames * (12 + 16);
        QCOMPARE(qint64(doc["buffers"].toArray().at(0).toObject()["byteLength"].toInteger()), meshBytes + keyBytes);
    }

    // A run that fails leaves none of the files behind (a .gltf's .bin included).
    void failedRunLeavesNoExport_data() {
        QTest::addColumn<QString>("out");
        for (const char* out : {"traj.json", "traj.gltf", "traj.glb"}) QTest::newRow(out) << QString(out);
    }

    void failedRunLeavesNoExport() {
        QFETCH(QString, out);
        RUN(r, {"--headless", "blow.json", "--out", out});
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains("ran away"), qPrintable(r.err));
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    void outNamesEveryFormat() {
        RUN(bad, {"--headless", "box.json", "--out", "traj.obj"});
        QCOMPARE(bad.code, 2);
        QCOMPARE(
            bad.err,
            QString("tumble: --out: 'traj.obj': the trajectory formats are .csv, .json, .gltf and .glb\n"));
        RUN(help, {"--help"});
        for (const char* ext : {".csv", ".json", ".gltf", ".glb"}) QVERIFY2(help.out.contains(ext), ext);
        RUN(unwritable, {"--headless", "box.json", "--out", "nodir/traj.gltf"});
        QCOMPARE(unwritable.code, 1);
        QCOMPARE(unwritable.err,
                 QString("tumble: --out: nodir/traj.gltf: cannot be written: no such folder\n"));
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

#ifdef TUMBLE_HAVE_UI
    // --out DIR/ draws a PNG per frame, --out FILE.mp4 a video with its frames beside it;
    // both through the editor's viewport, so they need a display (the tests have Xvfb's).
    void outImagesAndVideo() {
        write("box.json", kBox);  // 0.5 s at 20 frames/s: 11 frames
        RUN(images, {"--headless", "box.json", "--out", "frames/", "--image-size", "160x120", "--quiet"});
        QCOMPARE(images.code, 0);
        const QStringList pngs = QDir(path("frames")).entryList({"*.png"}, QDir::Files, QDir::Name);
        QCOMPARE(pngs.size(), 11);
        QCOMPARE(pngs.first(), QString("frame_0000.png"));
        QCOMPARE(pngSize(path("frames/frame_0010.png")), QSize(160, 120));
        RUN(video, {"--headless", "box.json", "--out", "box.mp4", "--image-size", "160x120", "--quiet"});
        QCOMPARE(video.code, 0);
        QVERIFY(QFileInfo(path("box.mp4")).size() > 0);
        QCOMPARE(QDir(path("box-frames")).entryList({"*.png"}, QDir::Files).size(), 11);
        RUN(size, {"--headless", "box.json", "--out", "more/", "--image-size", "160by120"});
        QCOMPARE(size.code, 2);
        QVERIFY2(size.err.contains("--image-size: '160by120'"), qPrintable(size.err));
        QVERIFY(!QFileInfo::exists(path("more")));
    }

    void outImagesNeedADisplay() {
        write("box.json", kBox);
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.remove("DISPLAY");
        env.remove("WAYLAND_DISPLAY");
        p.setProcessEnvironment(env);
        p.setWorkingDirectory(dir_->path());
        p.start(TUMBLE_EXECUTABLE, {"--headless", "box.json", "--out", "frames/", "--quiet"});
        QVERIFY(p.waitForFinished(120000));
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 1);
        QVERIFY2(QString::fromUtf8(p.readAllStandardError()).contains("need a display: run under xvfb-run"),
                 "the message says why");
        QVERIFY(!QFileInfo::exists(path("frames")));
    }
#else
    // A build without the editor (TUMBLE_BUILD_UI=OFF, e.g. the sanitizer build) cannot
    // draw: it says so and writes nothing.
    void outImagesNeedTheEditor() {
        for (const char* out : {"frames/", "box.mp4"}) {
            RUN(r, {"--headless", "box.json", "--out", out, "--quiet"});
            QCOMPARE(r.code, 2);
            QCOMPARE(r.err, QString("tumble: --out: '%1': images and video need the editor, which this build "
                                    "has not\n")
                                .arg(out));
        }
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }
#endif
};

QTEST_GUILESS_MAIN(TestCli)
#include "tst_cli.moc"
