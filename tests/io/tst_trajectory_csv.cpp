// The trajectory CSV: header, one row per body per frame in scene order, frame times
// exactly k / frame_rate, and numbers that read back bit for bit.
#include <tumble/io/trajectory_csv.h>
#include <tumble/world.h>

#include "trajectory_scene.h"

#include <QtTest>

#include <bit>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

using namespace tumble;

namespace {

using Record = std::vector<std::string>;

// RFC 4180: fields separated by commas, records by line breaks; a quoted field may hold
// commas, line breaks and doubled quotes. Returns false on text that is not well formed.
bool parseCsv(const std::string& text, std::vector<Record>& records) {
    records.clear();
    Record record;
    std::string field;
    bool quoted = false, wasQuoted = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field += c;
            }
        } else if (c == '"') {
            if (!field.empty() || wasQuoted) return false;  // a quote inside an unquoted field
            quoted = wasQuoted = true;
        } else if (c == ',') {
            record.push_back(field);
            field.clear();
            wasQuoted = false;
        } else if (c == '\n') {
            record.push_back(field);
            records.push_back(record);
            record.clear();
            field.clear();
            wasQuoted = false;
        } else {
            if (wasQuoted) return false;  // text after the closing quote
            field += c;
        }
    }
    // Every record, the last included, ends with a line break.
    return !quoted && field.empty() && record.empty();
}

// The number a field holds; the whole field must be the number.
bool readNumber(const std::string& field, double& out) {
    if (field.empty()) return false;
    char* end = nullptr;
    out = std::strtod(field.c_str(), &end);
    return *end == '\0';
}

std::uint64_t bits(double d) {
    return std::bit_cast<std::uint64_t>(d);
}

// Every kind of body, a name that needs quoting, and an offset centre of mass; a turned
// static post besides the ground.
SceneDesc csvScene() {
    SceneDesc s = test::trajectoryScene("say \"hi\", ball");
    BodyDesc post;
    post.name = "post";
    post.motion = Motion::Static;
    post.shape.type = ShapeType::Box;
    post.position = Vec3(4, 0.5, -2);
    post.orientation = Quat(Eigen::AngleAxisd(1.0, Vec3(1, 1, 0).normalized()));
    s.bodies.push_back(post);
    return s;
}

}  // namespace

class TestTrajectoryCsv : public QObject {
    Q_OBJECT

private slots:
    void simulatedRun() {
        const SceneDesc scene = csvScene();
        World world(scene);
        const Model& model = world.model();
        std::ostringstream out;
        out << io::kTrajectoryCsvHeader << "\n";
        std::vector<State> frames;
        const RunResult result = simulate(world, [&](int k, const State& s) {
            io::writeCsvFrame(out, model, s, k / model.settings.frameRate);
            frames.push_back(s);
        });
        QCOMPARE(result.frames, 11);  // round(0.5 * 20) + 1
        QCOMPARE(int(frames.size()), result.frames);

        std::vector<Record> records;
        QVERIFY(parseCsv(out.str(), records));
        QCOMPARE(out.str().substr(0, out.str().find('\n')),
                 std::string("time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz"));
        QCOMPARE(std::string(io::kTrajectoryCsvHeader),
                 std::string("time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz"));
        const size_t bodies = scene.bodies.size();
        QCOMPARE(records.size(), 1 + bodies * frames.size());

        for (size_t k = 0; k < frames.size(); ++k) {
            const State& s = frames[k];
            const double frameTime = double(k) / 20.0;
            QCOMPARE(bits(s.time), bits(frameTime));  // the stepper landed on the frame time
            for (size_t i = 0; i < bodies; ++i) {
                const Record& r = records[1 + k * bodies + i];
                const QByteArray where = QByteArray("frame ") + QByteArray::number(qulonglong(k)) +
                                         ", body " + QByteArray::number(qulonglong(i));
                QVERIFY2(r.size() == 15, where);
                QVERIFY2(r[1] == scene.bodies[i].name, where);  // scene order, static bodies included
                double v[15] = {};
                for (int c = 0; c < 15; ++c) {
                    if (c == 1) continue;
                    QVERIFY2(readNumber(r[c], v[c]),
                             where + ": field " + QByteArray::number(c) + " '" + r[c].c_str() + "'");
                }
                const BodyModel& b = model.bodies[i];
                const BodyState& bs = s.bodies[i];
                const Derived d = derive(b, bs);
                const Vec3 p = bodyFramePosition(b, bs);
                const double expected[15] = {frameTime, 0,        p.x(),       p.y(),       p.z(),
                                             bs.q.w(),  bs.q.x(), bs.q.y(),    bs.q.z(),    d.v.x(),
                                             d.v.y(),   d.v.z(),  d.omega.x(), d.omega.y(), d.omega.z()};
                for (int c = 0; c < 15; ++c) {
                    if (c == 1) continue;
                    QVERIFY2(bits(v[c]) == bits(expected[c]), where + ": field " + QByteArray::number(c) +
                                                                  " reads " + r[c].c_str() + ", state " +
                                                                  QByteArray::number(expected[c], 'g', 17));
                }
            }
        }

        // The columns mean what they say, checked without the engine's helpers.
        const int ball = 1, offset = 2, carousel = 3, post = 4;
        auto row = [&](size_t k, int body) { return records[1 + k * bodies + body]; };
        auto num = [](const std::string& f) { return std::strtod(f.c_str(), nullptr); };
        auto vec = [&](const Record& r, int c) { return Vec3(num(r[c]), num(r[c + 1]), num(r[c + 2])); };
        auto quat = [&](const Record& r) { return Quat(num(r[5]), num(r[6]), num(r[7]), num(r[8])); };
        for (size_t k = 0; k < frames.size(); ++k) {
            const double t = double(k) / 20.0;
            // A free ball: v = v0 + g t, whatever the integrator.
            QVERIFY((vec(row(k, ball), 9) - (Vec3(2, 5, -1) + t * Vec3(0, -9.81, 0))).norm() < 1e-12);
            // The offset body shows its body frame: the centre of mass sits at the rotated offset.
            const Record r = row(k, offset);
            const Vec3 com = frames[k].bodies[offset].x;
            QVERIFY((vec(r, 2) + quat(r) * Vec3(0.3, -0.2, 0.1) - com).norm() < 1e-12);
            QVERIFY(std::abs((vec(r, 2) - com).norm() - Vec3(0.3, -0.2, 0.1).norm()) < 1e-12);
            // Kinematic: its given velocities; static: where the scene put it, at rest.
            QCOMPARE(vec(row(k, carousel), 9), Vec3(0.25, 0, 0));
            QCOMPARE(vec(row(k, carousel), 12), Vec3(0, 1.5, 0));
            QVERIFY((vec(row(k, carousel), 2) - Vec3(-1 + 0.25 * t, 0, 0)).norm() < 1e-12);
            QCOMPARE(vec(row(k, post), 2), Vec3(4, 0.5, -2));
            QCOMPARE(vec(row(k, post), 9), Vec3::Zero());
            QCOMPARE(vec(row(k, post), 12), Vec3::Zero());
            QVERIFY((quat(row(k, post)).coeffs() - scene.bodies[post].orientation.coeffs()).norm() < 1e-15);
        }
        // At t = 0 the offset body is where the scene put it, not at its centre of mass.
        QVERIFY((vec(row(0, offset), 2) - Vec3(1, 2, 3)).norm() < 1e-15);
        QVERIFY((vec(row(0, offset), 2) - frames[0].bodies[offset].x).norm() > 0.3);
    }

    // 17 significant digits: every double reads back exactly, times like 0.1 and 1/3 included.
    void numbersReadBackExactly_data() {
        QTest::addColumn<double>("value");
        QTest::newRow("0.1") << 0.1;
        QTest::newRow("1/3") << 1.0 / 3.0;
        QTest::newRow("tiny") << 4.9406564584124654e-324;
        QTest::newRow("huge") << 1.7976931348623157e308;
        QTest::newRow("negative") << -2.718281828459045;
        QTest::newRow("large") << 123456789012345678.0;
        QTest::newRow("pi") << 3.141592653589793;
        QTest::newRow("next after 1") << std::nextafter(1.0, 2.0);
    }

    void numbersReadBackExactly() {
        QFETCH(double, value);
        SceneDesc scene;
        BodyDesc b;
        b.name = "b";
        b.motion = Motion::Static;
        b.position = Vec3(value, -value, 0.5 * value);
        scene.bodies.push_back(b);
        const World world(scene);
        std::ostringstream out;
        io::writeCsvFrame(out, world.model(), world.state(), value);
        std::vector<Record> records;
        QVERIFY(parseCsv(out.str(), records));
        QCOMPARE(records.size(), size_t(1));
        QCOMPARE(records[0].size(), size_t(15));
        double t = 0, x = 0, y = 0, z = 0;
        QVERIFY(readNumber(records[0][0], t));
        QVERIFY(readNumber(records[0][2], x));
        QVERIFY(readNumber(records[0][3], y));
        QVERIFY(readNumber(records[0][4], z));
        QCOMPARE(bits(t), bits(value));
        QCOMPARE(bits(x), bits(value));
        QCOMPARE(bits(y), bits(-value));
        QCOMPARE(bits(z), bits(0.5 * value));
    }

    void csvField_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<QString>("field");
        QTest::newRow("plain") << "ball"
                               << "ball";
        QTest::newRow("spaces") << "big ball 2"
                                << "big ball 2";
        QTest::newRow("comma") << "a,b"
                               << "\"a,b\"";
        QTest::newRow("quote") << "say \"hi\""
                               << "\"say \"\"hi\"\"\"";
        QTest::newRow("comma and quote") << "\"x\", y"
                                         << "\"\"\"x\"\", y\"";
        QTest::newRow("line feed") << "two\nlines"
                                   << "\"two\nlines\"";
        QTest::newRow("carriage return") << "cr\r"
                                         << "\"cr\r\"";
        QTest::newRow("utf-8") << QString::fromUtf8("bål") << QString::fromUtf8("bål");
    }

    void csvField() {
        QFETCH(QString, name);
        QFETCH(QString, field);
        const std::string written = io::csvField(name.toStdString());
        QCOMPARE(QString::fromStdString(written), field);
        // And a reader gets the name back.
        std::vector<Record> records;
        QVERIFY(parseCsv(written + ",1\n", records));
        QCOMPARE(records.size(), size_t(1));
        QCOMPARE(records[0].size(), size_t(2));
        QCOMPARE(QString::fromStdString(records[0][0]), name);
    }
};

QTEST_APPLESS_MAIN(TestTrajectoryCsv)
#include "tst_trajectory_csv.moc"
