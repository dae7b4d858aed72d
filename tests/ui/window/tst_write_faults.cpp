// Issue 46 item 3: every write Tumble makes, under the faults of a real machine. Each write
// (the editor's Save, Save with Meshes and autosave; the trajectory exports CSV, JSON, glTF
// and glb, the PNG frames and the MP4 video; a sweep's output folder) runs as a child
// process over an older output of its own, and
//   full     the disk fills part way (a tmpfs this test mounts, with room for the old output
//            and about half the new one);
//   readonly the folder's disk is read-only (the tmpfs remounted so);
//   removed  the folder is removed at a random moment of the write;
//   killed   the process is killed (SIGKILL) at random moments of the write.
// After each: no file is partial. Every file there is the old one, byte for byte, or the
// new one whole (byte for byte the same write's uninterrupted output; whole by its format
// where the bytes hold times); a failed write (full, readonly) says why, naming the file,
// and leaves the old output as it was and no temporary; a killed one leaves at most its
// temporaries, which never pass for outputs.
// The mounts are made in a mount namespace of the test's own (entered before anything
// else runs; unprivileged users get a user namespace too), so nothing leaks to the machine.
// TUMBLE_FAULT_KILLS sets the kills per write (default 5; the soak label runs 20).
#include <QCoreApplication>
#include <QDir>
#include <QDirIterator>
#include <QElapsedTimer>
#include <QFile>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QRandomGenerator>
#include <QTemporaryDir>
#include <QThread>
#include <QtTest>

#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <unistd.h>

#include <functional>
#include <map>
#include <optional>

namespace {

QString g_namespaceError;  // why the test could not mount its own disks (empty: it can)

bool writeProcFile(const char* path, const QByteArray& text) {
    QFile f(QString::fromLatin1(path));
    return f.open(QIODevice::WriteOnly) && f.write(text) == text.size();
}

// A mount namespace of this process's own; must run before any thread starts.
void enterPrivateMounts() {
    if (geteuid() != 0) {
        const uid_t uid = getuid();
        const gid_t gid = getgid();
        if (unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) {
            g_namespaceError = QStringLiteral("unshare(user, mount): %1").arg(strerror(errno));
            return;
        }
        writeProcFile("/proc/self/setgroups", "deny");
        if (!writeProcFile("/proc/self/uid_map", QByteArray("0 ") + QByteArray::number(uid) + " 1") ||
            !writeProcFile("/proc/self/gid_map", QByteArray("0 ") + QByteArray::number(gid) + " 1")) {
            g_namespaceError = QStringLiteral("the user namespace's id maps could not be written");
            return;
        }
    } else if (unshare(CLONE_NEWNS) != 0) {
        g_namespaceError = QStringLiteral("unshare(mount): %1").arg(strerror(errno));
        return;
    }
    if (mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0)
        g_namespaceError = QStringLiteral("making / private: %1").arg(strerror(errno));
}

// A small disk of its own (tmpfs) mounted on `dir`; unmounted when it goes.
class SmallDisk {
public:
    SmallDisk(const QString& dir, qint64 bytes) : dir_(dir) {
        QDir().mkpath(dir);
        const QByteArray options = "size=" + QByteArray::number(bytes) + ",mode=0755";
        mounted_ = mount("tumble-fault", QFile::encodeName(dir).constData(), "tmpfs", MS_NOSUID | MS_NODEV,
                         options.constData()) == 0;
        if (!mounted_) error_ = QString::fromLocal8Bit(strerror(errno));
    }
    ~SmallDisk() {
        if (mounted_) umount2(QFile::encodeName(dir_).constData(), MNT_DETACH);
    }
    bool readOnly() {
        return mount("tumble-fault", QFile::encodeName(dir_).constData(), nullptr, MS_REMOUNT | MS_RDONLY,
                     nullptr) == 0;
    }
    bool ok() const { return mounted_; }
    QString error() const { return error_; }

private:
    QString dir_;
    bool mounted_ = false;
    QString error_;
};

QString scenes() {
    return QStringLiteral(TUMBLE_SCENES_DIR);
}

// One write Tumble makes: a program and its arguments for an output under `dir`, the old
// (small) one or the new (larger) one.
struct Write {
    QString program;
    std::function<QStringList(const QString& dir, bool large)> args;
    bool exact = true;      // the output's bytes follow from the input alone
    bool autosave = false;  // its data folder comes from XDG_DATA_HOME=<dir>/data
    QStringList mustName;   // a failure's message names one of these
};

QStringList cli(const QString& scene, double duration, const QString& out, const QStringList& more = {}) {
    return QStringList{
               "--headless", scenes() + "/" + scene, "--duration", QString::number(duration), "--out", out,
               "--quiet"} +
           more;
}

// A scene file of `count` boxes (big enough that a save takes a while) and, with `mesh`, a
// body of that mesh file; written once.
QString boxesScene(const QString& folder, int count, const QString& mesh = {}) {
    const QString path =
        QStringLiteral("%1/boxes-%2%3.json").arg(folder).arg(count).arg(mesh.isEmpty() ? "" : "-mesh");
    if (QFile::exists(path)) return path;
    QByteArray bodies =
        R"({"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}})";
    if (!mesh.isEmpty())
        bodies += R"(, {"name": "part", "shape": {"type": "mesh", "file": ")" + mesh.toUtf8() +
                  R"("}, "mass": 1, "position": [0, 2, 0]})";
    for (int i = 0; i < count; ++i)
        bodies +=
            QStringLiteral(R"(, {"name": "box%1", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},)"
                           R"( "mass": 1, "position": [%2, 0.1, %3]})")
                .arg(i)
                .arg(i % 50)
                .arg(i / 50)
                .toUtf8();
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly)) qFatal("cannot write %s", qPrintable(path));
    f.write(R"({"format": "tumble-scene", "version": 1, "bodies": [)" + bodies + "]}");
    return path;
}

std::map<QString, Write> writes(const QString& inputs) {
    const QString child = QStringLiteral(TUMBLE_CRASH_CHILD), tumble = QStringLiteral(TUMBLE_EXECUTABLE);
    std::map<QString, Write> w;
    const QString small = boxesScene(inputs, 20), large = boxesScene(inputs, 3000);
    w["save"] = {child,
                 [=](const QString& d, bool big) {
                     return QStringList{"save-once", big ? large : small, d + "/scene.json"};
                 },
                 true,
                 false,
                 {"scene.json"}};
    // Save with Meshes: the scene and a copy of each mesh beside it.
    const QString meshes = boxesScene(inputs, 3000, "meshes/l-prism.obj");
    w["save-meshes"] = {child,
                        [=](const QString& d, bool big) {
                            return QStringList{"save-meshes-once", big ? meshes : small, d + "/scene.json"};
                        },
                        true,
                        false,
                        {"scene.json", "scene-meshes"}};
    w["autosave"] = {child,
                     [=](const QString&, bool big) {
                         return QStringList{"autosave-once", big ? large : small};
                     },
                     false,
                     true,
                     {".autosave.json"}};
    for (const char* ext : {"csv", "json", "gltf", "glb"}) {
        const QString name = QStringLiteral("run.") + ext;
        w[ext] = {tumble,
                  [=](const QString& d, bool big) {
                      return cli("pyramid-15.json", big ? 1.5 : 0.1, d + "/" + name);
                  },
                  true,
                  false,
                  {name}};
    }
    const QStringList small_images{"--image-size", "96x72"};
    w["png"] = {tumble,
                [=](const QString& d, bool big) {
                    return cli("tumbling-box.json", big ? 1.0 : 0.1, d + "/frames/", small_images);
                },
                true,
                false,
                {"frames"}};
    w["mp4"] = {tumble,
                [=](const QString& d, bool big) {
                    return cli("tumbling-box.json", big ? 1.0 : 0.1, d + "/run.mp4", small_images);
                },
                true,
                false,
                {"run.mp4", "run-frames"}};
    // A sweep's files hold wall times: whole by their format. Its old output is another
    // sweep's folder beside it (a folder of another sweep is refused, not replaced).
    w["sweep"] = {
        tumble,
        [=](const QString& d, bool big) {
            return QStringList{
                "sweep",         scenes() + "/pyramid-15.json",
                "--vary",        big ? "settings.duration=0.4,0.5,0.6,0.7" : "settings.duration=0.1",
                "--out",         d + (big ? "/sweep" : "/sweep-old"),
                "--trajectories"};
        },
        false,
        false,
        {"sweep"}};
    return w;
}

struct Run {
    int code = -1;
    bool crashed = false;
    bool killed = false;
    QString out;
    qint64 ms = 0;
};

// Runs `write` into `dir`; kills it after `killAfterMs` (if >= 0) or, with `during`, calls
// it once after `duringMs` while the write goes on.
Run run(const Write& write, const QString& dir, bool large, int killAfterMs = -1,
        const std::function<void()>& during = {}, int duringMs = 0) {
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    if (write.autosave) env.insert("XDG_DATA_HOME", dir + "/data");
    p.setProcessEnvironment(env);
    p.setProcessChannelMode(QProcess::MergedChannels);
    QElapsedTimer clock;
    clock.start();
    p.start(write.program, write.args(dir, large));
    Run r;
    if (!p.waitForStarted(20000)) {
        r.out = "did not start: " + p.errorString();
        return r;
    }
    const int deadline = 180000;
    bool fired = false;
    while (!p.waitForFinished(5)) {
        if (killAfterMs >= 0 && clock.elapsed() >= killAfterMs) {
            ::kill(static_cast<pid_t>(p.processId()), SIGKILL);
            r.killed = true;
            p.waitForFinished(20000);
            break;
        }
        if (during && !fired && clock.elapsed() >= duringMs) {
            during();
            fired = true;
        }
        if (clock.elapsed() > deadline) {
            p.kill();
            p.waitForFinished(20000);
            r.out = "hung";
            return r;
        }
    }
    r.ms = clock.elapsed();
    r.crashed = p.exitStatus() == QProcess::CrashExit && !r.killed;
    r.code = p.exitCode();
    r.out += QString::fromLocal8Bit(p.readAll());
    return r;
}

// The files under `dir` by their path relative to it.
std::map<QString, QByteArray> filesUnder(const QString& dir) {
    std::map<QString, QByteArray> files;
    QDirIterator it(dir, QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot, QDirIterator::Subdirectories);
    while (it.hasNext()) {
        const QString path = it.next();
        QFile f(path);
        files[QDir(dir).relativeFilePath(path)] = f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray("?");
    }
    return files;
}

// A temporary of a write in progress: an AtomicFile's, the image export's hidden folder, an
// autosave's lock.
bool isTemporary(const QString& relative) {
    if (relative.contains(".tumble-tmp-") || relative.endsWith(".lock")) return true;
    for (const QString& part : relative.split('/'))
        if (part.startsWith('.')) return true;
    return false;
}

// Whole by its format (for outputs whose bytes hold times).
bool wholeByFormat(const QString& relative, const QByteArray& bytes) {
    if (relative.endsWith(".json")) return !QJsonDocument::fromJson(bytes).isNull();
    if (relative.endsWith(".csv")) return bytes.endsWith('\n') && bytes.count('\n') >= 1;
    if (relative.endsWith(".png")) return !QImage::fromData(bytes, "PNG").isNull();
    return true;  // a sweep's run log
}

}  // namespace

class TestWriteFaults : public QObject {
    Q_OBJECT

    QTemporaryDir root_{QDir::tempPath() + "/tumble-faults-XXXXXX"};
    std::map<QString, Write> writes_;
    // Each write's uninterrupted outputs, old (small) and new (large), and the new one's time.
    std::map<QString, std::map<QString, QByteArray>> old_, new_;
    std::map<QString, qint64> newMs_;
    int kills_ = 5;

    using Files = std::map<QString, QByteArray>;

    // What is wrong with the files under `dir` after a fault ("" if nothing): each is the
    // old output byte for byte, or the new one whole, or (when `temporariesAllowed`) a
    // temporary; with `kept` (the files before the write), every old file is still there
    // unchanged.
    QString problems(const QString& name, const QString& dir, bool temporariesAllowed, const Files* kept) {
        const Write& w = writes_.at(name);
        const auto& olds = old_.at(name);
        const auto& news = new_.at(name);
        QStringList wrong;
        const auto files = filesUnder(dir);
        for (const auto& [rel, bytes] : files) {
            if (isTemporary(rel)) {
                if (!temporariesAllowed) wrong << rel + " (a temporary left)";
                continue;
            }
            // A killed glTF export may leave the bridge: the new .gltf naming the .bin's
            // temporary. It is judged as a pair below, not byte for byte.
            if (name == "gltf" && rel == "run.gltf") continue;
            const auto o = olds.find(rel), n = news.find(rel);
            const bool keptAsItWas = kept && kept->count(rel) && kept->at(rel) == bytes;
            const bool whole = keptAsItWas || (w.exact ? (o != olds.end() && o->second == bytes) ||
                                                             (n != news.end() && n->second == bytes)
                                                       : wholeByFormat(rel, bytes));
            if (!whole) wrong << rel + QStringLiteral(" (partial: %1 bytes)").arg(bytes.size());
        }
        if (kept)
            for (const auto& [rel, bytes] : *kept) {
                if (isTemporary(rel)) continue;
                const auto f = files.find(rel);
                if (f == files.end() || f->second != bytes) wrong << rel + " (the old file was lost)";
            }
        // A glTF is two files: the .gltf must fit the buffer it names (run.bin, or for a
        // moment while the pair is switched the .bin's temporary), both of one write.
        if (name == "gltf" && files.count("run.gltf")) {
            QJsonObject gltf = QJsonDocument::fromJson(files.at("run.gltf")).object();
            QJsonArray buffers = gltf["buffers"].toArray();
            QJsonObject buffer = buffers[0].toObject();
            const QString uri = buffer["uri"].toString();
            buffer["uri"] = "run.bin";
            buffers[0] = buffer;
            gltf["buffers"] = buffers;
            auto pairOf = [&](const Files& write) {
                return QJsonDocument::fromJson(write.at("run.gltf")).object() == gltf && files.count(uri) &&
                       write.at("run.bin") == files.at(uri);
            };
            if (!files.count(uri))
                wrong << "run.gltf names a buffer that is not there: " + uri;
            else if (!pairOf(olds) && !pairOf(news))
                wrong << "run.gltf and the buffer it names, " + uri + ", are of different writes";
        }
        return wrong.join(", ");
    }

    // Writes the old output into `dir` (uninterrupted); the files there after, or nothing
    // if it failed.
    std::optional<Files> writeOld(const QString& name, const QString& dir) {
        QDir().mkpath(dir);
        const Run r = run(writes_.at(name), dir, false);
        if (r.code != 0) {
            qWarning("%s: the old write failed: %s", qPrintable(name), qPrintable(r.out));
            return std::nullopt;
        }
        return filesUnder(dir);
    }

    // The room `files` take on a tmpfs: whole pages.
    static qint64 pagesOf(const std::map<QString, QByteArray>& files) {
        qint64 n = 0;
        for (const auto& [rel, bytes] : files) n += (bytes.size() + 4095) / 4096 * 4096;
        return n;
    }

    bool namesTheFile(const QString& name, const QString& message) const {
        for (const QString& n : writes_.at(name).mustName)
            if (message.contains(n)) return true;
        return false;
    }

private slots:
    void initTestCase() {
        QVERIFY2(g_namespaceError.isEmpty(),
                 qPrintable("no mount namespace of its own: " + g_namespaceError));
        QVERIFY(root_.isValid());
        if (const int n = qEnvironmentVariableIntValue("TUMBLE_FAULT_KILLS"); n > 0) kills_ = n;
        // The inputs: box scenes, one with a sample mesh beside it.
        const QString inputs = root_.filePath("inputs");
        QVERIFY(QDir().mkpath(inputs + "/meshes"));
        QVERIFY(QFile::copy(scenes() + "/../meshes/l-prism.obj", inputs + "/meshes/l-prism.obj"));
        writes_ = writes(inputs);
        for (const auto& [name, w] : writes_) {
            for (const bool large : {false, true}) {
                const QString dir = root_.filePath("reference/" + name + (large ? "/new" : "/old"));
                QVERIFY(QDir().mkpath(dir));
                const Run r = run(w, dir, large);
                QVERIFY2(r.code == 0, qPrintable(name + ": " + r.out));
                auto files = filesUnder(dir);
                std::erase_if(files, [](const auto& f) { return isTemporary(f.first); });
                QVERIFY2(!files.empty(), qPrintable(name + " wrote nothing"));
                (large ? new_ : old_)[name] = files;
                if (large) newMs_[name] = r.ms;
            }
        }
    }

    void faults_data() {
        QTest::addColumn<QString>("name");
        for (const char* n :
             {"save", "save-meshes", "autosave", "csv", "json", "gltf", "glb", "png", "mp4", "sweep"})
            QTest::newRow(n) << QString::fromLatin1(n);
    }

    // The disk fills part way: the write fails, says so naming the file, and leaves the old
    // output as it was and nothing else.
    void faults() {
        QFETCH(QString, name);
        const Write& w = writes_.at(name);
        const QString base = root_.filePath("faults/" + name);

        {  // full
            const QString dir = base + "/full";
            const qint64 room = pagesOf(old_.at(name)) + pagesOf(new_.at(name)) / 2 / 4096 * 4096;
            SmallDisk disk(dir, room);
            QVERIFY2(disk.ok(), qPrintable(disk.error()));
            const auto before = writeOld(name, dir);
            QVERIFY(before);
            const Run r = run(w, dir, true);
            QVERIFY2(!r.crashed, qPrintable(r.out));
            QVERIFY2(r.code != 0, qPrintable(name + ": a write larger than the disk succeeded"));
            QVERIFY2(r.out.contains("disk is full") && namesTheFile(name, r.out), qPrintable(r.out));
            qInfo("full: exit %d: %s", r.code, qPrintable(r.out.trimmed().split('\n').last()));
            const QString wrong = problems(name, dir, false, &*before);
            QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        }
        {  // read-only
            const QString dir = base + "/readonly";
            SmallDisk disk(dir, 64 << 20);
            QVERIFY2(disk.ok(), qPrintable(disk.error()));
            const auto before = writeOld(name, dir);
            QVERIFY(before);
            QVERIFY(disk.readOnly());
            const Run r = run(w, dir, true);
            QVERIFY2(!r.crashed, qPrintable(r.out));
            QVERIFY2(r.code != 0, qPrintable(name + ": a write to a read-only disk succeeded"));
            QVERIFY2(r.out.contains("read-only") && namesTheFile(name, r.out), qPrintable(r.out));
            qInfo("read-only: exit %d: %s", r.code, qPrintable(r.out.trimmed().split('\n').last()));
            const QString wrong = problems(name, dir, false, &*before);
            QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
        }
        // Removed at a random moment: the write ends (no crash, no hang); a failure names the
        // file; what is there after is whole.
        auto* random = QRandomGenerator::global();
        for (int k = 0; k < 3; ++k) {
            const QString dir = base + QStringLiteral("/removed-%1").arg(k);
            QVERIFY(writeOld(name, dir));
            const int at = random->bounded(static_cast<int>(newMs_.at(name)) + 1);
            const Run r = run(
                w, dir, true, -1, [dir] { QDir(dir).removeRecursively(); }, at);
            QVERIFY2(!r.crashed && r.out != "hung", qPrintable(QStringLiteral("at %1 ms: ").arg(at) + r.out));
            if (r.code != 0) QVERIFY2(namesTheFile(name, r.out) || r.out.contains(dir), qPrintable(r.out));
            qInfo("removed at %d ms: exit %d: %s", at, r.code,
                  qPrintable(r.code ? r.out.trimmed().split('\n').last() : QStringLiteral("written")));
            const QString wrong = problems(name, dir, false, nullptr);
            QVERIFY2(wrong.isEmpty(), qPrintable(QStringLiteral("removed at %1 ms: ").arg(at) + wrong));
        }
        // Killed at random moments: the old output or the new one, whole; temporaries at most.
        const QString dir = base + "/killed";
        const auto before = writeOld(name, dir);
        QVERIFY(before);
        for (int k = 0; k < kills_; ++k) {
            const int at = random->bounded(static_cast<int>(newMs_.at(name) * 11 / 10) + 1);
            const Run r = run(w, dir, true, at);
            const QString wrong = problems(name, dir, true, nullptr);
            QVERIFY2(wrong.isEmpty(), qPrintable(QStringLiteral("killed at %1 ms: ").arg(at) + wrong));
            QVERIFY2(r.killed || r.code == 0, qPrintable(r.out));
        }
        // And an uninterrupted write after the kills gives the new output.
        const Run r = run(w, dir, true);
        QVERIFY2(r.code == 0, qPrintable(r.out));
        const QString wrong = problems(name, dir, true, nullptr);
        QVERIFY2(wrong.isEmpty(), qPrintable(wrong));
    }
};

int main(int argc, char** argv) {
    enterPrivateMounts();  // before any thread: a multithreaded process cannot unshare
    QCoreApplication app(argc, argv);
    TestWriteFaults test;
    return QTest::qExec(&test, argc, argv);
}

#include "tst_write_faults.moc"
