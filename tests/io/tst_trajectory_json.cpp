// The trajectory writers of tumble/io/trajectory_writer.h in their text formats: the JSON
// of docs/export.md reads back equal to the run bit for bit, with frame and body selection;
// the CSV writer writes the rows of writeCsvFrame; a cancelled or incomplete export leaves
// no file; the JSON reader names the field of a malformed file.
#include <tumble/io/scene_file.h>
#include <tumble/io/trajectory_csv.h>
#include <tumble/io/trajectory_json.h>
#include <tumble/io/trajectory_writer.h>
#include <tumble/world.h>

#include <QTemporaryDir>
#include "trajectory_scene.h"

#include <QtTest>

#include <bit>
#include <cstdint>
#include <fstream>
#include <sstream>

using namespace tumble;
namespace fs = std::filesystem;

namespace {

std::uint64_t bits(double d) {
    return std::bit_cast<std::uint64_t>(d);
}

// Every motion, a name that JSON must escape, an offset centre of mass (the body frame's
// position differs from x) and a spin.
SceneDesc scene() {
    return test::trajectoryScene("say \"hi\"\\ ball \xc3\xa9\n");
}

// Runs the scene through `writer` (when given) and returns every frame's state.
std::vector<State> run(const SceneDesc& s, io::TrajectoryWriter* writer) {
    World world(s);
    std::vector<State> frames;
    if (writer)
        writer->begin(world.model(), s, frameCount(world.model().settings), world.model().settings.frameRate);
    simulate(world, [&](int k, const State& st) {
        frames.push_back(st);
        if (writer) writer->frame(k, st);
    });
    return frames;
}

std::string readAll(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

QStringList entries(const QTemporaryDir& dir) {
    return QDir(dir.path()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

// The pose of frame k, body i, equal bit for bit to the state's.
void checkPose(const io::TrajectoryPose& pose, const Model& model, const State& state, int i,
               const QByteArray& where) {
    const BodyModel& b = model.bodies[i];
    const BodyState& s = state.bodies[i];
    const Derived d = derive(b, s);
    const Vec3 p = bodyFramePosition(b, s);
    const double expected[13] = {p.x(),   p.y(),   p.z(),   s.q.w(),     s.q.x(),     s.q.y(),    s.q.z(),
                                 d.v.x(), d.v.y(), d.v.z(), d.omega.x(), d.omega.y(), d.omega.z()};
    const double read[13] = {pose.position.x(),       pose.position.y(),        pose.position.z(),
                             pose.orientation.w(),    pose.orientation.x(),     pose.orientation.y(),
                             pose.orientation.z(),    pose.velocity.x(),        pose.velocity.y(),
                             pose.velocity.z(),       pose.angularVelocity.x(), pose.angularVelocity.y(),
                             pose.angularVelocity.z()};
    for (int c = 0; c < 13; ++c) {
        QVERIFY2(bits(read[c]) == bits(expected[c]), where + ": value " + QByteArray::number(c) + " reads " +
                                                         QByteArray::number(read[c], 'g', 17) + ", state " +
                                                         QByteArray::number(expected[c], 'g', 17));
    }
}

}  // namespace

class TestTrajectoryJson : public QObject {
    Q_OBJECT

private slots:
    void roundTrip() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "run.json";
        const SceneDesc s = scene();
        auto writer = io::makeTrajectoryWriter(file);
        const std::vector<State> frames = run(s, writer.get());
        QVERIFY(!fs::exists(file));  // nothing visible before finish()
        writer->finish();
        QCOMPARE(entries(dir), QStringList({"run.json"}));

        const Model model = compile(s);
        const io::Trajectory t = io::readTrajectoryJson(file);
        QCOMPARE(t.frameRate, 20.0);
        QCOMPARE(t.bodies.size(), s.bodies.size());
        for (size_t i = 0; i < s.bodies.size(); ++i) {
            QCOMPARE(t.bodies[i].name, s.bodies[i].name);
            QCOMPARE(int(t.bodies[i].motion), int(s.bodies[i].motion));
        }
        QCOMPARE(t.frames.size(), size_t(11));  // round(0.5 * 20) + 1
        QCOMPARE(t.frames.size(), frames.size());
        for (size_t k = 0; k < frames.size(); ++k) {
            QCOMPARE(t.frames[k].frame, int(k));
            QCOMPARE(bits(t.frames[k].time), bits(double(k) / 20.0));
            QCOMPARE(bits(t.frames[k].time), bits(frames[k].time));
            QCOMPARE(t.frames[k].bodies.size(), s.bodies.size());
            for (size_t i = 0; i < s.bodies.size(); ++i) {
                checkPose(t.frames[k].bodies[i], model, frames[k], int(i),
                          "frame " + QByteArray::number(qulonglong(k)) + ", body " +
                              QByteArray::number(qulonglong(i)));
                if (QTest::currentTestFailed()) return;
            }
        }
        // The fields mean what docs/export.md says, checked without the engine's helpers:
        // the kinematic carousel moves at its constant velocity and spins about y.
        const double t10 = 0.5;
        const io::TrajectoryPose& c = t.frames[10].bodies[3];
        QVERIFY(std::abs(c.position.x() - (-1 + 0.25 * t10)) < 1e-12);
        QVERIFY(std::abs(c.velocity.x() - 0.25) < 1e-12);
        QVERIFY(std::abs(c.angularVelocity.y() - 1.5) < 1e-12);
        QVERIFY(std::abs(std::abs(c.orientation.w()) - std::cos(1.5 * t10 / 2)) < 1e-9);
        // The static ground never moves.
        QCOMPARE(t.frames[10].bodies[0].position, Vec3(0, 0, 0));
    }

    void selection() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "part.JSON";  // case ignored
        const SceneDesc s = scene();
        io::ExportOptions options;
        options.firstFrame = 2;
        options.lastFrame = 9;
        options.frameStep = 3;
        options.bodies = {3, 1};
        auto writer = io::makeTrajectoryWriter(file, options);
        const std::vector<State> frames = run(s, writer.get());
        QCOMPARE(writer->selectedFrameCount(), 3);
        QVERIFY(writer->selected(2) && writer->selected(5) && writer->selected(8));
        QVERIFY(!writer->selected(0) && !writer->selected(3) && !writer->selected(9) &&
                !writer->selected(11));
        writer->finish();

        const Model model = compile(s);
        const io::Trajectory t = io::readTrajectoryJson(file);
        QCOMPARE(t.bodies.size(), size_t(2));
        QCOMPARE(t.bodies[0].name, std::string("carousel"));
        QCOMPARE(int(t.bodies[0].motion), int(Motion::Kinematic));
        QCOMPARE(t.bodies[1].name, s.bodies[1].name);
        QCOMPARE(t.frames.size(), size_t(3));
        const int expected[3] = {2, 5, 8};
        for (int n = 0; n < 3; ++n) {
            const int k = expected[n];
            QCOMPARE(t.frames[n].frame, k);
            QCOMPARE(bits(t.frames[n].time), bits(k / 20.0));
            checkPose(t.frames[n].bodies[0], model, frames[k], 3, "carousel");
            checkPose(t.frames[n].bodies[1], model, frames[k], 1, "ball");
        }
    }

    void csvWriterWritesTheCsvRows() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "run.csv";
        const SceneDesc s = scene();
        auto writer = io::makeTrajectoryWriter(file);
        const std::vector<State> frames = run(s, writer.get());
        writer->finish();
        const Model model = compile(s);
        std::ostringstream expected;
        expected << io::kTrajectoryCsvHeader << "\n";
        for (size_t k = 0; k < frames.size(); ++k) io::writeCsvFrame(expected, model, frames[k], k / 20.0);
        QCOMPARE(readAll(file), expected.str());

        // A subset: the rows of the bodies chosen, in the order chosen.
        io::ExportOptions options;
        options.bodies = {2, 0};
        options.lastFrame = 1;
        const fs::path part = fs::path(dir.path().toStdString()) / "part.csv";
        auto partWriter = io::makeTrajectoryWriter(part, options);
        run(s, partWriter.get());
        partWriter->finish();
        auto row = [&](int k, int i) {
            Model one = model;
            one.bodies = {model.bodies[i]};
            State st;
            st.bodies = {frames[k].bodies[i]};
            std::ostringstream r;
            io::writeCsvFrame(r, one, st, k / 20.0);
            return QString::fromStdString(r.str());
        };
        const QString want =
            QString(io::kTrajectoryCsvHeader) + "\n" + row(0, 2) + row(0, 0) + row(1, 2) + row(1, 0);
        QCOMPARE(QString::fromStdString(readAll(part)), want);
    }

    // A writer destroyed without finish() (a cancelled export) leaves no file and no
    // temporary, and an existing file as it was; so does a finish() with frames missing.
    void cancelLeavesNoFile_data() {
        QTest::addColumn<QString>("name");
        for (const char* n : {"t.json", "t.csv", "t.gltf", "t.glb"}) QTest::newRow(n) << QString(n);
    }

    void cancelLeavesNoFile() {
        QFETCH(QString, name);
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / name.toStdString();
        const SceneDesc s = scene();
        World world(s);
        {
            auto writer = io::makeTrajectoryWriter(file);
            writer->begin(world.model(), s, frameCount(world.model().settings), 20);
            writer->frame(0, world.state());
            QVERIFY(!entries(dir).isEmpty());  // the temporary is there while writing
        }
        QCOMPARE(entries(dir), QStringList());

        { std::ofstream(file) << "old"; }
        {
            auto writer = io::makeTrajectoryWriter(file);
            writer->begin(world.model(), s, frameCount(world.model().settings), 20);
            writer->frame(0, world.state());
            QVERIFY_THROWS_EXCEPTION(std::runtime_error, writer->finish());  // 1 of 11 frames
        }
        QCOMPARE(entries(dir), QStringList({name}));
        QCOMPARE(readAll(file), std::string("old"));
    }

    void badRequests() {
        QTemporaryDir dir;
        const fs::path base(dir.path().toStdString());
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, io::makeTrajectoryWriter(base / "t.txt"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, io::makeTrajectoryWriter(base / "t"));
        io::TrajectoryFormat f;
        QVERIFY(io::trajectoryFormatFor("a/B.GlB", f) && f == io::TrajectoryFormat::Glb);
        QVERIFY(!io::trajectoryFormatFor("a.json.bak", f));

        const SceneDesc s = scene();
        const Model model = compile(s);
        auto begin = [&](io::ExportOptions o) {
            io::makeTrajectoryWriter(base / "t.json", o)->begin(model, s, 11, 20);
        };
        io::ExportOptions o;
        o.bodies = {4};
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, begin(o));
        o = {};
        o.lastFrame = 11;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, begin(o));
        o = {};
        o.firstFrame = 5;
        o.lastFrame = 4;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, begin(o));
        o = {};
        o.frameStep = 0;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, begin(o));
        QCOMPARE(entries(dir), QStringList());

        QVERIFY_THROWS_EXCEPTION(std::runtime_error,
                                 io::makeTrajectoryWriter(base / "no" / "t.json")->begin(model, s, 11, 20));
    }

    // With the joints' reactions: the JSON names each joint and gives every frame's force,
    // couple and broken flag equal to the state's bit for bit; the CSV gets them in
    // run-joints.csv beside it (and a cancelled export leaves neither file); glTF refuses.
    void jointForces() {
        SceneDesc s = scene();
        s.settings.integrator = "splitting";
        JointDesc rod;  // the ball on a rod from a world point, and the box on a rope to the ball
        rod.name = "rod";
        rod.type = JointType::Distance;
        rod.bodyA = s.bodies[1].name;
        rod.anchorB = s.bodies[1].position + Vec3(0.5, 0.5, 0);
        s.joints.push_back(rod);
        JointDesc rope = rod;
        rope.name = "rope";
        rope.type = JointType::Rope;
        rope.bodyA = "offset";
        rope.bodyB = s.bodies[1].name;
        rope.anchorB = Vec3::Zero();
        s.joints.push_back(rope);
        QTemporaryDir dir;
        const fs::path base(dir.path().toStdString());
        io::ExportOptions options;
        options.jointForces = true;
        auto json = io::makeTrajectoryWriter(base / "run.json", options);
        const std::vector<State> frames = run(s, json.get());
        json->finish();
        const io::Trajectory t = io::readTrajectoryJson(base / "run.json");
        QCOMPARE(t.joints.size(), size_t(2));
        QCOMPARE(t.joints[0].name, std::string("rod"));
        QCOMPARE(t.joints[0].type, std::string("distance"));
        QCOMPARE(t.joints[0].bodyA, s.bodies[1].name);
        QVERIFY(t.joints[0].bodyB.empty());  // the world
        QCOMPARE(t.joints[1].bodyB, s.bodies[1].name);
        QCOMPARE(t.frames.size(), frames.size());
        bool pulled = false;
        for (size_t k = 0; k < frames.size(); ++k) {
            QCOMPARE(t.frames[k].joints.size(), size_t(2));
            for (int j = 0; j < 2; ++j) {
                const Vec3 f = k == 0 ? Vec3::Zero() : frames[k].jointForces[size_t(j)];
                for (int c = 0; c < 3; ++c) QCOMPARE(bits(t.frames[k].joints[size_t(j)].force[c]), bits(f[c]));
                QCOMPARE(t.frames[k].joints[size_t(j)].torque, Vec3(Vec3::Zero()));  // no couple: rod and rope
                QVERIFY(!t.frames[k].joints[size_t(j)].broken);
            }
            pulled = pulled || (frames[k].jointForces.size() == 2 && frames[k].jointForces[0].norm() > 1.0);
        }
        QVERIFY(pulled);

        auto csv = io::makeTrajectoryWriter(base / "run.csv", options);
        run(s, csv.get());
        csv->finish();
        QCOMPARE(io::jointCsvPath(base / "run.csv"), base / "run-joints.csv");
        std::istringstream rows(readAll(base / "run-joints.csv"));
        std::string line;
        std::getline(rows, line);
        QCOMPARE(line, std::string(io::kJointCsvHeader));
        int count = 0;
        while (std::getline(rows, line)) {
            const QStringList cells = QString::fromStdString(line).split(',');
            QCOMPARE(cells.size(), 9);
            const int k = count / 2, j = count % 2;
            QCOMPARE(cells[1], QString(j ? "rope" : "rod"));
            const Vec3 f = k == 0 ? Vec3::Zero() : frames[size_t(k)].jointForces[size_t(j)];
            QCOMPARE(bits(cells[3].toDouble()), bits(f.y()));
            QCOMPARE(cells[8], QString("0"));
            ++count;
        }
        QCOMPARE(count, int(frames.size()) * 2);

        QTemporaryDir cancelled;
        {
            World world(s);
            auto writer = io::makeTrajectoryWriter(fs::path(cancelled.path().toStdString()) / "c.csv", options);
            writer->begin(world.model(), s, frameCount(world.model().settings), 20);
            writer->frame(0, world.state());
        }
        QCOMPARE(entries(cancelled), QStringList());
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, io::makeTrajectoryWriter(base / "t.glb", options));
    }

    void readerNamesTheField_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("message");
        const QString body =
            R"({"position": [0, 0, 0], "orientation": [1, 0, 0, 0], "velocity": [0, 0, 0], )";
        QTest::newRow("format") << R"({"format": "tumble-scene", "version": 1})"
                                << "t.json: format: must be \"tumble-trajectory\"";
        QTest::newRow("version") << R"({"format": "tumble-trajectory", "version": 2})"
                                 << "t.json: version: must be 1 (this build reads up to version 1)";
        QTest::newRow("motion") << R"({"format": "tumble-trajectory", "version": 1, "frame_rate": 30,
                                       "bodies": [{"name": "a", "motion": "flying"}], "frames": []})"
                                << "t.json: bodies[0].motion: must be dynamic, static, kinematic or animated";
        QTest::newRow("count") << R"({"format": "tumble-trajectory", "version": 1, "frame_rate": 30,
                                      "bodies": [{"name": "a", "motion": "static"}],
                                      "frames": [{"frame": 0, "time": 0, "bodies": []}]})"
                               << "t.json: frames[0].bodies: must be an array with one entry per body (1)";
        QTest::newRow("missing")
            << R"({"format": "tumble-trajectory", "version": 1, "frame_rate": 30,
                                        "bodies": [{"name": "a", "motion": "static"}],
                                        "frames": [{"frame": 0, "time": 0, "bodies": [)" +
                   body + R"("angular_velocity": [0, 0]}]}]})"
            << "t.json: frames[0].bodies[0].angular_velocity: must be an array of 3 numbers";
    }

    void readerNamesTheField() {
        QFETCH(QString, text);
        QFETCH(QString, message);
        try {
            io::parseTrajectoryJson(text.toStdString(), "t.json");
            QFAIL("no error");
        } catch (const io::InputError& e) {
            QCOMPARE(QString(e.what()), message);
        }
    }
};

QTEST_APPLESS_MAIN(TestTrajectoryJson)
#include "tst_trajectory_json.moc"
