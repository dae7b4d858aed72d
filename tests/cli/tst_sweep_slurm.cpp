// tumble sweep --slurm on a real Slurm (issue 22): a one-node cluster on this machine,
// started by the test (munged, slurmctld and slurmd from Debian's slurm-wlm, a minimal
// slurm.conf: no cgroups, no accounting, root), runs a 20-variant sweep as a job array;
// merged, it equals the same sweep run locally row by row. Where slurm-wlm cannot start
// (not installed, not root), the test says so and skips.
#include <QtTest>

#include "cli_harness.h"

#include <QStandardPaths>
#include <QThread>

#include <unistd.h>

using namespace tumble::clitest;

namespace {

const char* const kDrop = R"({
  "format": "tumble-scene",
  "version": 1,
  "settings": {"gravity": [0, -9.81, 0], "duration": 1.0, "frame_rate": 60},
  "bodies": [
    {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.05}, "mass": 0.2, "position": [0, 1.05, 0],
     "velocity": [0.5, 0, 0], "restitution": 0.5, "friction": 0.3}
  ]
}
)";

}  // namespace

class TestSweepSlurm : public QObject, private Harness {
    Q_OBJECT

    QProcess controller_, node_;
    QString conf_;

    QString tool(const QString& name) {
        for (const char* dir : {"/usr/sbin", "/usr/bin", "/sbin", "/bin"})
            if (QFileInfo(QString(dir) + "/" + name).isExecutable()) return QString(dir) + "/" + name;
        return QStandardPaths::findExecutable(name);
    }

    // A command's exit code and output (stdout and stderr), SLURM_CONF set.
    std::pair<int, QString> command(const QString& program, const QStringList& args) {
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert("SLURM_CONF", conf_);
        p.setProcessEnvironment(env);
        p.setProcessChannelMode(QProcess::MergedChannels);
        p.start(program, args);
        if (!p.waitForFinished(30000)) {
            p.kill();
            p.waitForFinished();
            return {-1, "timed out"};
        }
        return {p.exitCode(), QString::fromUtf8(p.readAll())};
    }

private slots:
    void initTestCase() {
        makeFolder();
        for (const char* name : {"munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo"})
            if (tool(name).isEmpty())
                QSKIP(qPrintable(QString("slurm-wlm cannot start here: no %1 (apt-get install slurm-wlm munge)").arg(name)));
        if (geteuid() != 0) QSKIP("slurm-wlm cannot start here: the one-node cluster runs as root (SlurmUser=root)");

        // munge: the cluster's authentication, one daemon per machine.
        if (command("pgrep", {"-x", "munged"}).first != 0) {
            QDir().mkpath("/run/munge");
            const auto [code, out] = command(tool("munged"), {"--force"});
            if (code != 0) QSKIP(qPrintable("slurm-wlm cannot start here: munged: " + out));
        }
        char name[256] = {};
        gethostname(name, sizeof name - 1);
        const QString host = QString::fromLocal8Bit(name).section('.', 0, 0);
        const QString dir = path("slurm");
        QVERIFY(QDir().mkpath(dir + "/state") && QDir().mkpath(dir + "/spool"));
        // Ports of its own, so that it cannot meet a cluster this machine runs already.
        const int port = 17000 + static_cast<int>(getpid() % 2000) * 2;
        conf_ = dir + "/slurm.conf";
        write("slurm/slurm.conf", QString(R"(ClusterName=tumbletest
SlurmctldHost=%1(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=%2/state
SlurmdSpoolDir=%2/spool
SlurmctldPidFile=%2/slurmctld.pid
SlurmdPidFile=%2/slurmd.pid
SlurmctldLogFile=%2/slurmctld.log
SlurmdLogFile=%2/slurmd.log
SlurmctldPort=%3
SlurmdPort=%4
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=%1 NodeAddr=127.0.0.1 CPUs=%5 State=UNKNOWN
PartitionName=test Nodes=%1 Default=YES MaxTime=INFINITE State=UP
)")
                                        .arg(host, dir)
                                        .arg(port)
                                        .arg(port + 1)
                                        .arg(QThread::idealThreadCount())
                                        .toUtf8());
        controller_.setProcessChannelMode(QProcess::MergedChannels);
        node_.setProcessChannelMode(QProcess::MergedChannels);
        controller_.start(tool("slurmctld"), {"-D", "-f", conf_});
        node_.start(tool("slurmd"), {"-D", "-f", conf_});
        QVERIFY(controller_.waitForStarted() && node_.waitForStarted());
        QString state;
        for (int i = 0; i < 60 && state != "idle"; ++i) {
            QTest::qWait(500);
            state = command(tool("sinfo"), {"-h", "-o", "%t"}).second.trimmed();
        }
        if (state != "idle") {
            const QString log = QString::fromUtf8(read("slurm/slurmctld.log")).right(600);
            QSKIP(qPrintable("slurm-wlm cannot start here: the node is '" + state + "' after 30 s; " + log));
        }
        qInfo("a one-node Slurm cluster (%s, %d CPUs) is up", qPrintable(host), QThread::idealThreadCount());
    }

    void cleanupTestCase() {
        for (QProcess* p : {&node_, &controller_}) {
            if (p->state() == QProcess::NotRunning) continue;
            p->terminate();
            if (!p->waitForFinished(10000)) {
                p->kill();
                p->waitForFinished();
            }
        }
        // (munged, if started here, is left running: a machine's one authentication daemon,
        // which another suite's cluster may be using.)
        dir_.reset();
    }

    // 20 variants (restitution x friction) through sbatch, followed with squeue, merged: the
    // same rows as the sweep run here, measure for measure (all but the wall time).
    void slurmSweepEqualsTheLocalOne() {
        write("drop.json", kDrop);
        const QStringList vary = {"--vary", "ball.restitution=0.2:0.8:5", "--vary", "ball.friction=0,0.2,0.5,1"};
        QProcess p;
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert("SLURM_CONF", conf_);
        p.setProcessEnvironment(env);
        p.setWorkingDirectory(dir_->path());
        QElapsedTimer clock;
        clock.start();
        p.start(TUMBLE_EXECUTABLE, QStringList{"sweep", "drop.json", "--out", "onslurm", "--slurm",
                                               "--sbatch=--time=10"} + vary);
        QVERIFY(p.waitForFinished(300000));
        const QString err = QString::fromUtf8(p.readAllStandardError());
        QVERIFY2(p.exitCode() == 0, qPrintable(err + QString::fromUtf8(p.readAllStandardOutput())));
        qInfo("20 variants on Slurm in %.1f s", clock.elapsed() / 1000.0);
        QVERIFY(read("onslurm/sweep.sbatch").contains("#SBATCH --array=0-19"));
        QVERIFY(read("onslurm/sweep.sbatch").contains("#SBATCH --time=10"));

        RUN(local, QStringList{"sweep", "drop.json", "--out", "here"} + vary);
        QCOMPARE(local.code, 0);
        const QStringList a = lines(QString::fromUtf8(read("onslurm/summary.csv")));
        const QStringList b = lines(QString::fromUtf8(read("here/summary.csv")));
        QCOMPARE(a.size(), 21);
        QCOMPARE(a.first(), b.first());
        const int wall = a.first().split(',').indexOf("wall_s");
        QVERIFY(wall > 0);
        for (int i = 1; i < a.size(); ++i) {
            QStringList x = a[i].split(','), y = b[i].split(',');
            x.removeAt(wall);
            y.removeAt(wall);
            QCOMPARE(x, y);
            QVERIFY(a[i].contains(",ok,"));
        }
        // Resumed, it has nothing to submit; merged again, the same table.
        p.start(TUMBLE_EXECUTABLE, QStringList{"sweep", "drop.json", "--out", "onslurm", "--slurm"} + vary);
        QVERIFY(p.waitForFinished(60000));
        QCOMPARE(p.exitCode(), 0);
        QVERIFY(!QString::fromUtf8(p.readAllStandardOutput()).contains("job:"));
        QCOMPARE(lines(QString::fromUtf8(read("onslurm/summary.csv"))), a);
    }
};

QTEST_GUILESS_MAIN(TestSweepSlurm)
#include "tst_sweep_slurm.moc"
