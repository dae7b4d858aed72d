// What the command-line suites share: the executable run in a fresh folder (RUN), its
// key: value report, and the sample scenes the runs use.
#pragma once

#include <QDir>
#include <QFile>
#include <QMap>
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QtTest>

#include <memory>
#include <optional>

namespace tumble::clitest {

struct Run {
    int code = -1;
    QString out, err;
    QByteArray outBytes;  ///< standard output as written (a .glb on it is binary)
};

// A tumbling box on a spring, with an offset centre of mass and a static ground: 0.5 s at
// 20 frames/s in steps of 0.005 s. Its orientation is not unit length; normalised once more
// on saving and again on loading with Eigen's normalized(), it would drift by an ulp and
// --save-scene would not reproduce the run.
inline const char* const kBox = R"({
  "format": "tumble-scene",
  "version": 1,
  "settings": {"gravity": [0, -9.81, 0], "dt": 0.005, "duration": 0.5, "frame_rate": 20},
  "bodies": [
    {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": -5}},
    {"name": "box", "shape": {"type": "box", "half_extents": [0.5, 0.25, 0.1]}, "mass": 2,
     "center_of_mass": [0.1, 0, 0], "position": [0, 1, 0], "orientation": [0.1, -0.8, -0.6, 0.5],
     "velocity": [1, 0, 0], "angular_velocity": [0.3, 4, 0.1],
     "forces": [{"type": "spring", "anchor": [0, 2, 0], "point": [0.4, 0.2, 0], "stiffness": 30,
                 "rest_length": 0.5, "damping": 0.2}]}
  ]
}
)";

// A stiff spring that explicit Euler with this step cannot hold: the energy guard stops it
// (with "energy_guard": false, the state overflows).
inline const char* const kBlowUp = R"({
  "format": "tumble-scene",
  "version": 1,
  "settings": {"gravity": [0, 0, 0], "dt": 0.01, "duration": 2, "integrator": "euler", "frame_rate": 10},
  "bodies": [
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [1, 0, 0],
     "forces": [{"type": "spring", "anchor": [0, 0, 0], "stiffness": 1e12}]}
  ]
}
)";

inline QStringList lines(const QString& text) {
    QStringList l = text.split('\n');
    if (!l.isEmpty() && l.last().isEmpty()) l.removeLast();
    return l;
}

// The key: value lines of a successful run; an empty map when a line is not of that form.
inline QMap<QString, QString> report(const QString& out) {
    static const QRegularExpression line("^([a-z_]+): (\\S.*)$");
    QMap<QString, QString> map;
    for (const QString& l : lines(out)) {
        const QRegularExpressionMatch m = line.match(l);
        if (!m.hasMatch()) return {};
        map.insert(m.captured(1), m.captured(2));
    }
    return map;
}

// The folder a test runs in and the executable run there; a test class derives from it.
class Harness {
protected:
    std::unique_ptr<QTemporaryDir> dir_;
    /// The runs' TMPDIR: a folder of the test's own, so that a test sees what is left there.
    std::unique_ptr<QTemporaryDir> tmp_;

    /// `input`: written to the process's standard input, which is then closed (without it,
    /// standard input is closed at once).
    Run run(const QStringList& args, const std::optional<QByteArray>& input = std::nullopt) {
        QProcess p;
        p.setWorkingDirectory(dir_->path());
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert("TMPDIR", tmp_->path());
        p.setProcessEnvironment(env);
        p.start(TUMBLE_EXECUTABLE, args);
        if (!p.waitForStarted(10000)) {
            QTest::qFail("the executable did not start", __FILE__, __LINE__);
            return {};
        }
        if (input) p.write(*input);
        p.closeWriteChannel();
        if (!p.waitForFinished(120000)) {
            p.kill();
            p.waitForFinished();
            QTest::qFail("the executable did not finish in 120 s", __FILE__, __LINE__);
            return {};
        }
        Run r;
        r.outBytes = p.readAllStandardOutput();
        r.out = QString::fromUtf8(r.outBytes);
        r.err = QString::fromUtf8(p.readAllStandardError());
        if (p.exitStatus() != QProcess::NormalExit) {
            QTest::qFail(qPrintable("the executable crashed: " + args.join(' ') + "\n" + r.err), __FILE__,
                         __LINE__);
            return {};
        }
        r.code = p.exitCode();
        return r;
    }

    QString path(const QString& name) const { return dir_->filePath(name); }

    void write(const QString& name, const QByteArray& text) {
        QFile f(path(name));
        QVERIFY(f.open(QIODevice::WriteOnly));
        QCOMPARE(f.write(text), text.size());
    }

    QByteArray read(const QString& name) const {
        QFile f(path(name));
        return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
    }

    // A PNG's size from its IHDR chunk (bytes 16 to 23, big-endian width and height).
    static QSize pngSize(const QString& file) {
        QFile f(file);
        if (!f.open(QIODevice::ReadOnly)) return {};
        const QByteArray h = f.read(24);
        if (h.size() < 24 || !h.startsWith("\x89PNG")) return {};
        auto be = [&](int at) {
            return (uchar(h[at]) << 24) | (uchar(h[at + 1]) << 16) | (uchar(h[at + 2]) << 8) |
                   uchar(h[at + 3]);
        };
        return QSize(int(be(16)), int(be(20)));
    }

    // Every entry of the folder, hidden ones and temporaries included.
    QStringList entries() const {
        return QDir(dir_->path())
            .entryList(QDir::AllEntries | QDir::Hidden | QDir::System | QDir::NoDotAndDotDot, QDir::Name);
    }


    void makeFolder() {
        dir_ = std::make_unique<QTemporaryDir>();
        tmp_ = std::make_unique<QTemporaryDir>();
        QVERIFY(dir_->isValid() && tmp_->isValid());
        write("box.json", kBox);
        write("blow.json", kBlowUp);
    }
};

}  // namespace tumble::clitest

// Runs the executable in the test's folder; fails the test when it crashes or hangs.
#define RUN(result, ...)                 \
    const Run result = run(__VA_ARGS__); \
    if (QTest::currentTestFailed()) return

