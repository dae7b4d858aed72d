// AtomicFile: a save appears whole or not at all, and what a killed save leaves beside its
// target (a "<target>.tumble-tmp-<pid>-<hex>" temporary) is removed by the next save of that
// target once its process is gone and the file is older than a minute, and never anything
// else: not a live process's temporary, not a young one, not a file that merely looks alike.
#include <tumble/io/atomic_file.h>

#include <QtTest>

#include <fcntl.h>
#include <linux/capability.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace tumble;

namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
}

// Sets the file's modification time `seconds` into the past.
bool age(const fs::path& path, int seconds) {
    timespec times[2];
    clock_gettime(CLOCK_REALTIME, &times[0]);
    times[0].tv_sec -= seconds;
    times[1] = times[0];
    return utimensat(AT_FDCWD, path.c_str(), times, 0) == 0;
}

std::set<std::string> namesIn(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

// The pid of a process that has ended (and been reaped): no process runs under it.
pid_t deadPid() {
    const pid_t pid = fork();
    if (pid == 0) _exit(0);
    int status = 0;
    waitpid(pid, &status, 0);
    return pid;
}

std::string temporaryName(const std::string& target, long pid, const std::string& hex = "0badcafe") {
    return target + ".tumble-tmp-" + std::to_string(pid) + "-" + hex;
}

}  // namespace

class TestAtomicFile : public QObject {
    Q_OBJECT
private slots:
    void aSaveReplacesTheFileAndLeavesNothingElse() {
        QTemporaryDir dir;
        const fs::path target = dir.filePath("scene.json").toStdString();
        io::writeFileAtomically(target, "first");
        io::writeFileAtomically(target, "second");
        QCOMPARE(readBytes(target), std::string("second"));
        QCOMPARE(namesIn(dir.path().toStdString()), std::set<std::string>{"scene.json"});
    }

    // A child that dies (SIGKILL) in the middle of a save leaves its temporary; the next save
    // of the target, once that temporary is older than the threshold, removes it.
    void aKilledSavesTemporaryGoesWithTheNextSave() {
        QTemporaryDir dir;
        const fs::path target = dir.filePath("scene.json").toStdString();
        writeBytes(target, "before");
        const pid_t child = fork();
        if (child == 0) {
            io::AtomicFile file(target);
            file.stream() << "half written" << std::flush;
            kill(getpid(), SIGKILL);
            _exit(3);
        }
        int status = 0;
        QCOMPARE(waitpid(child, &status, 0), child);
        QVERIFY(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
        std::vector<fs::path> temporaries;
        for (const auto& e : fs::directory_iterator(dir.path().toStdString())) {
            long pid = 0;
            if (io::isTemporaryOf(e.path().filename().string(), "scene.json", &pid) && pid == child)
                temporaries.push_back(e.path());
        }
        QCOMPARE(int(temporaries.size()), 1);
        QCOMPARE(readBytes(target), std::string("before"));
        QCOMPARE(readBytes(temporaries[0]), std::string("half written"));

        QVERIFY(age(temporaries[0], 2 * 60));
        io::writeFileAtomically(target, "after");
        QCOMPARE(readBytes(target), std::string("after"));
        QCOMPARE(namesIn(dir.path().toStdString()), std::set<std::string>{"scene.json"});
    }

    void aLiveProcesssTemporaryIsKept() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        // This process's, and a sleeping child's: both run, both are kept however old.
        const fs::path mine = folder / temporaryName("scene.json", getpid());
        struct Sleeper {  // a child that runs until killed, killed at the latest on return
            pid_t pid = fork();
            ~Sleeper() {
                if (pid > 0 && kill(pid, SIGKILL) == 0) waitpid(pid, nullptr, 0);
            }
        } sleeperChild;
        const pid_t sleeper = sleeperChild.pid;
        if (sleeper == 0) {
            prctl(PR_SET_PDEATHSIG, SIGKILL);
            for (;;) pause();
        }
        QVERIFY(sleeper > 0);
        const fs::path theirs = folder / temporaryName("scene.json", sleeper);
        for (const fs::path& p : {mine, theirs}) {
            writeBytes(p, "being written");
            QVERIFY(age(p, 3600));
        }
        io::writeFileAtomically(folder / "scene.json", "saved");
        QVERIFY(fs::exists(mine));
        QVERIFY(fs::exists(theirs));
        // Once the child is gone, its temporary goes with the next save; ours stays.
        kill(sleeper, SIGKILL);
        waitpid(sleeper, nullptr, 0);
        io::writeFileAtomically(folder / "scene.json", "saved again");
        QVERIFY(fs::exists(mine));
        QVERIFY(!fs::exists(theirs));
    }

    // A dead pid may be another machine's live save in a shared folder: kept while young.
    void aYoungTemporaryOfADeadPidIsKept() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        const fs::path young = folder / temporaryName("scene.json", deadPid());
        writeBytes(young, "being written elsewhere");
        QVERIFY(age(young, 30));
        io::writeFileAtomically(folder / "scene.json", "saved");
        QVERIFY(fs::exists(young));
        QVERIFY(age(young, io::kStaleTemporaryAge.count() + 5));
        io::writeFileAtomically(folder / "scene.json", "saved again");
        QVERIFY(!fs::exists(young));
    }

    // Only the exact pattern of this target's temporaries is ever removed.
    void filesThatMerelyLookAlikeAreKept() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        const pid_t dead = deadPid();
        const std::set<std::string> lookalikes = {
            "scene.json.backup",
            "scene.json.tmp-123456",
            "scene.json.tumble-tmp-",
            "scene.json.tumble-tmp-" + std::to_string(dead),
            temporaryName("scene.json", dead, "0badcaf"),                    // 7 hex digits
            temporaryName("scene.json", dead, "0badcafe0"),                  // 9
            temporaryName("scene.json", dead, "0BADCAFE"),                   // upper case
            temporaryName("scene.json", dead, "0badcafg"),                   // not hex
            temporaryName("scene.json", dead) + ".bak",                      // more after it
            "scene.json.tumble-tmp-0" + std::to_string(dead) + "-0badcafe",  // leading zero
            "scene.json.tumble-tmp--1-0badcafe",
            "xscene.json.tumble-tmp-" + std::to_string(dead) + "-0badcafe",  // another target
            temporaryName("other.json", dead),                               // another target
            temporaryName("scene", dead),                                    // another target
        };
        for (const std::string& name : lookalikes) {
            writeBytes(folder / name, "a user's file");
            QVERIFY(age(folder / name, 3600));
        }
        // A folder with the exact name is not ours either; a real stale temporary is.
        const std::string folderNamedLikeOne = temporaryName("scene.json", dead, "00000001");
        fs::create_directory(folder / folderNamedLikeOne);
        QVERIFY(age(folder / folderNamedLikeOne, 3600));
        const std::string stale = temporaryName("scene.json", dead);
        writeBytes(folder / stale, "left by a killed save");
        QVERIFY(age(folder / stale, 3600));

        QCOMPARE(io::removeStaleTemporaries(folder / "scene.json"), 1);
        std::set<std::string> expected = lookalikes;
        expected.insert(folderNamedLikeOne);
        QCOMPARE(namesIn(folder), expected);
        for (const std::string& name : lookalikes)
            QCOMPARE(readBytes(folder / name), std::string("a user's file"));
    }

    void theNameSaysWhoMadeIt() {
        QTemporaryDir dir;
        const fs::path target = dir.filePath("scene.json").toStdString();
        io::AtomicFile file(target);
        long pid = 0;
        QCOMPARE(file.temporaryPath().parent_path(), target.parent_path());
        QVERIFY(io::isTemporaryOf(file.temporaryPath().filename().string(), "scene.json", &pid));
        QCOMPARE(pid, long(getpid()));
    }

    // For a pair of files switched in steps (a .gltf and its .bin): the target is replaced
    // while the temporary stays whole under its own name, which another file may name
    // meanwhile; Stale::Keep leaves old temporaries for the caller; keepTemporary() keeps
    // the temporary (made ready) of a file that is never committed.
    void aTemporaryCanOutliveItsCommit() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        writeBytes(folder / "run.bin", "old");
        const std::string stale = temporaryName("run.bin", deadPid());
        writeBytes(folder / stale, "named by an old .gltf");
        QVERIFY(age(folder / stale, 2 * 60));
        fs::path temporary;
        {
            io::AtomicFile file(folder / "run.bin", io::AtomicFile::Stale::Keep);
            temporary = file.temporaryPath();
            file.stream() << "new";
            file.commitKeepingTemporary();
        }
        QCOMPARE(readBytes(folder / "run.bin"), std::string("new"));
        QCOMPARE(readBytes(temporary), std::string("new"));
        QCOMPARE(namesIn(folder), (std::set<std::string>{"run.bin", stale, temporary.filename().string()}));
        fs::remove(temporary);
        {
            io::AtomicFile file(folder / "run.bin", io::AtomicFile::Stale::Keep);
            temporary = file.temporaryPath();
            file.stream() << "never committed";
            file.ready();
            file.keepTemporary();
        }
        QCOMPARE(readBytes(temporary), std::string("never committed"));
        QCOMPARE(readBytes(folder / "run.bin"), std::string("new"));
        QCOMPARE(io::removeStaleTemporaries(folder / "run.bin"), 1);  // the dead one only
        QVERIFY(fs::exists(temporary));
    }

    void destroyedWithoutCommitLeavesTheTargetAsItWas() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        writeBytes(folder / "scene.json", "before");
        {
            io::AtomicFile file(folder / "scene.json");
            file.stream() << "never committed";
            QVERIFY(fs::exists(file.temporaryPath()));
        }
        {
            io::AtomicFile file(folder / "new.json");
            file.stream() << "never committed";
        }
        QCOMPARE(readBytes(folder / "scene.json"), std::string("before"));
        QCOMPARE(namesIn(folder), std::set<std::string>{"scene.json"});
    }

    // A write that fails (here: past the file size limit, as on a full disk) throws naming
    // the file, and leaves the old file and no temporary.
    void aFailedWriteLeavesTheTargetAsItWas() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        const fs::path target = folder / "scene.json";
        writeBytes(target, "before");
        const pid_t child = fork();
        if (child == 0) {
            signal(SIGXFSZ, SIG_IGN);
            const rlimit limit{4096, 4096};
            setrlimit(RLIMIT_FSIZE, &limit);
            try {
                io::writeFileAtomically(target, std::string(1 << 20, 'x'));
            } catch (const std::exception& e) {
                const std::string said = e.what();
                _exit(said == target.string() +
                                  ": writing failed: the file is larger than this system lets it be"
                          ? 0
                          : 4);
            }
            _exit(5);
        }
        int status = 0;
        QCOMPARE(waitpid(child, &status, 0), child);
        QVERIFY(WIFEXITED(status));
        QCOMPARE(WEXITSTATUS(status), 0);
        QCOMPARE(readBytes(target), std::string("before"));
        QCOMPARE(namesIn(folder), std::set<std::string>{"scene.json"});
    }

    // A commit that cannot rename (the target is a folder) throws naming it, leaves it.
    void aFailedRenameLeavesTheTargetAsItWas() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        fs::create_directory(folder / "scene.json");
        writeBytes(folder / "scene.json" / "inside", "kept");
        try {
            io::writeFileAtomically(folder / "scene.json", "new");
            QFAIL("no error");
        } catch (const std::runtime_error& e) {
            QVERIFY2(
                std::string(e.what()).find((folder / "scene.json").string() + ": cannot be replaced") == 0,
                e.what());
        }
        QCOMPARE(readBytes(folder / "scene.json" / "inside"), std::string("kept"));
        QCOMPARE(namesIn(folder), std::set<std::string>{"scene.json"});
    }

    void aMissingFolderIsRefusedNamingTheFile() {
        QTemporaryDir dir;
        const fs::path target = fs::path(dir.path().toStdString()) / "nodir" / "scene.json";
        try {
            io::AtomicFile file(target);
            QFAIL("no error");
        } catch (const std::runtime_error& e) {
            QCOMPARE(std::string(e.what()), target.string() + ": cannot be written: no such folder");
        }
        QVERIFY(!fs::exists(target.parent_path()));
    }

    // A folder the user may not write into: the save is refused naming the file, the old
    // file stays as it was and nothing is left beside it. The tests run as root, whom
    // permission bits do not stop: the save runs in a child that first gives up the
    // capabilities that pass them by (an ordinary user has none to give up).
    void aReadOnlyFolderIsRefusedAndTheOldFileKept() {
        QTemporaryDir dir;
        const fs::path folder = fs::path(dir.path().toStdString()) / "locked";
        fs::create_directory(folder);
        const fs::path target = folder / "scene.json";
        writeBytes(target, "before");
        fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                    fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
        const pid_t child = ::fork();
        QVERIFY(child >= 0);
        if (child == 0) {
            __user_cap_header_struct header{_LINUX_CAPABILITY_VERSION_3, 0};
            __user_cap_data_struct caps[2]{};
            if (::syscall(SYS_capget, &header, caps) != 0) ::_exit(10);
            for (int cap : {CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH, CAP_FOWNER}) {
                caps[cap / 32].effective &= ~(1u << (cap % 32));
                caps[cap / 32].permitted &= ~(1u << (cap % 32));
            }
            if (::syscall(SYS_capset, &header, caps) != 0) ::_exit(11);
            try {
                io::writeFileAtomically(target, "after");
            } catch (const std::runtime_error& e) {
                const std::string expected =
                    target.string() + ": cannot be written: no permission to write there";
                ::_exit(std::string(e.what()) == expected ? 0 : 12);
            }
            ::_exit(13);  // written: the folder did not stop it
        }
        int status = 0;
        QCOMPARE(::waitpid(child, &status, 0), child);
        fs::permissions(folder, fs::perms::owner_all);  // for QTemporaryDir to remove it
        QVERIFY2(WIFEXITED(status), "the child did not exit");
        QCOMPARE(WEXITSTATUS(status), 0);  // 12: another message; 13: the save went through
        QCOMPARE(readBytes(target), std::string("before"));
        QCOMPARE(namesIn(folder), std::set<std::string>{"scene.json"});
    }

    // As QSaveFile did: a link is saved through (the file it points to is replaced, the link
    // stays), and a replaced file keeps its permissions.
    void linksAndPermissionsSurviveASave() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        fs::create_directory(folder / "real");
        writeBytes(folder / "real" / "scene.json", "before");
        fs::permissions(folder / "real" / "scene.json", fs::perms::owner_read | fs::perms::owner_write);
        fs::create_symlink("real/scene.json", folder / "link.json");
        io::writeFileAtomically(folder / "link.json", "after");
        QVERIFY(fs::is_symlink(folder / "link.json"));
        QCOMPARE(readBytes(folder / "real" / "scene.json"), std::string("after"));
        QCOMPARE(fs::status(folder / "real" / "scene.json").permissions(),
                 fs::perms::owner_read | fs::perms::owner_write);
        QCOMPARE(namesIn(folder / "real"), std::set<std::string>{"scene.json"});
    }
};

QTEST_MAIN(TestAtomicFile)
#include "tst_atomic_file.moc"
