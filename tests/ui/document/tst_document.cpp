// The scene document: every edit is an undo step, drags merge, macros group, files round
// trip, bad files leave the scene untouched, a failed save leaves the file on disk and says
// which, killed saves' temporaries go, the selection follows inserts and removals.
#include "document/document.h"

#include <tumble/io/atomic_file.h>
#include <tumble/io/scene_file.h>
#include <tumble/mass.h>
#include <tumble/world.h>

#include <QDir>
#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace tumble;
using namespace tumble::ui;

namespace {

BodyDesc ball(const std::string& name, double y) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = 0.5;
    b.mass = 1.0;
    b.position = Vec3(0, y, 0);
    return b;
}

// The name of a temporary that a save of `target` killed long ago left beside it: made by
// a process that has ended, and two minutes old.
QString staleTemporary(const QString& target) {
    const pid_t pid = fork();
    if (pid == 0) _exit(0);
    waitpid(pid, nullptr, 0);
    const QString path = QStringLiteral("%1.tumble-tmp-%2-0badcafe").arg(target).arg(pid);
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly)) return {};
    f.write("{\"format\": \"tum");
    f.close();
    timespec times[2];
    clock_gettime(CLOCK_REALTIME, &times[0]);
    times[0].tv_sec -= 120;
    times[1] = times[0];
    utimensat(AT_FDCWD, QFile::encodeName(path).constData(), times, 0);
    return path;
}

}  // namespace

class TestDocument : public QObject {
    Q_OBJECT
private slots:
    void newSceneHasAGroundAndNothingToUndo() {
        Document doc;
        QCOMPARE(doc.bodyCount(), 1);
        QCOMPARE(doc.body(0).motion, Motion::Static);
        QVERIFY(!doc.undoStack()->canUndo());
        QVERIFY(!doc.isModified());
        QCOMPARE(doc.displayName(), QString("untitled"));
    }

    void anEditIsOneUndoStepWithItsText() {
        Document doc;
        doc.addBody(ball("ball", 1.0));
        BodyDesc b = doc.body(1);
        b.restitution = 0.9;
        QSignalSpy changed(&doc, &Document::bodyChanged);
        doc.setBody(1, b, "Set restitution");
        QCOMPARE(changed.count(), 1);
        QCOMPARE(doc.body(1).restitution, 0.9);
        QCOMPARE(doc.undoStack()->undoText(), QString("Set restitution of ball"));  // the body named
        QVERIFY(doc.isModified());
        doc.undoStack()->undo();
        QCOMPARE(doc.body(1).restitution, 0.5);
        doc.undoStack()->redo();
        QCOMPARE(doc.body(1).restitution, 0.9);
    }

    void anEditThatChangesNothingIsNotAStep() {
        Document doc;
        const int before = doc.undoStack()->count();
        doc.setBody(0, doc.body(0), "Nothing");
        QCOMPARE(doc.undoStack()->count(), before);
    }

    void aDragMergesIntoOneStep() {
        Document doc;
        doc.addBody(ball("ball", 1.0));
        const int steps = doc.undoStack()->count();
        for (int k = 1; k <= 10; ++k) {
            BodyDesc b = doc.body(1);
            b.position.x() = 0.1 * k;
            doc.setBody(1, b, "Move ball", 7);
        }
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        QCOMPARE(doc.body(1).position.x(), 1.0);
        doc.undoStack()->undo();
        QCOMPARE(doc.body(1).position.x(), 0.0);
        // A different merge id starts a new step.
        BodyDesc b = doc.body(1);
        b.position.x() = 2.0;
        doc.setBody(1, b, "Move ball", 7);
        b.position.x() = 3.0;
        doc.setBody(1, b, "Move ball", 8);
        QCOMPARE(doc.undoStack()->count(), steps + 2);
    }

    void addDuplicateDeleteAndUndo() {
        Document doc;
        doc.addBody(ball("ball", 1.0));
        doc.addBody(ball("ball", 2.0));  // the name is made unique
        QCOMPARE(doc.bodyCount(), 3);
        QCOMPARE(QString::fromStdString(doc.body(2).name), QString("ball-2"));
        doc.duplicateBodies({1, 2});
        QCOMPARE(doc.bodyCount(), 5);
        QCOMPARE(doc.selection(), QList<int>({3, 4}));
        QCOMPARE(doc.body(3).position, doc.body(1).position);
        QCOMPARE(doc.undoStack()->undoText(), QString("Duplicate"));
        doc.undoStack()->undo();
        QCOMPARE(doc.bodyCount(), 3);

        doc.setSelection({0, 2});
        doc.removeBodies({2, 0});
        QCOMPARE(doc.bodyCount(), 1);
        QCOMPARE(QString::fromStdString(doc.body(0).name), QString("ball"));
        QVERIFY(doc.selection().isEmpty());
        doc.undoStack()->undo();  // one step brings both back, in place
        QCOMPARE(doc.bodyCount(), 3);
        QCOMPARE(QString::fromStdString(doc.body(0).name), QString("ground"));
        QCOMPARE(QString::fromStdString(doc.body(2).name), QString("ball-2"));
    }

    void selectionFollowsInsertsAndRemovals() {
        Document doc;
        doc.addBody(ball("a", 1.0));
        doc.addBody(ball("b", 2.0));
        doc.setSelection({2});
        doc.addBody(ball("c", 3.0), 1);  // before b
        QCOMPARE(doc.selection(), QList<int>({3}));
        doc.removeBodies({0});
        QCOMPARE(doc.selection(), QList<int>({2}));
        QCOMPARE(QString::fromStdString(doc.body(2).name), QString("b"));
    }

    void macroIsOneStep() {
        Document doc;
        doc.beginMacro("Add two");
        doc.addBody(ball("a", 1.0));
        doc.addBody(ball("b", 2.0));
        doc.endMacro();
        QCOMPARE(doc.undoStack()->undoText(), QString("Add two"));
        doc.undoStack()->undo();
        QCOMPARE(doc.bodyCount(), 1);
    }

    void settingsEditsUndo() {
        Document doc;
        Settings s = doc.scene().settings;
        s.sleeping = false;
        s.dt = 0.001;
        doc.setSettings(s, "Scene settings");
        QCOMPARE(doc.scene().settings.dt, 0.001);
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().settings.dt, 1.0 / 240.0);
        QCOMPARE(doc.scene().settings.sleeping, true);
    }

    void saveAndReopenGiveTheSameScene() {
        QTemporaryDir dir;
        Document doc;
        doc.addBody(ball("ball", 1.0));
        QVERIFY(doc.isModified());
        QString error;
        const QString path = dir.filePath("scene.json");
        QVERIFY2(doc.saveAs(path, &error), qPrintable(error));
        QVERIFY(!doc.isModified());
        QCOMPARE(doc.displayName(), QString("scene.json"));
        Document other;
        QVERIFY2(other.open(path, &error), qPrintable(error));
        QCOMPARE(other.scene(), doc.scene());
        QCOMPARE(other.filePath(), path);
        // Undo after a save makes it modified again; redo back to the saved state is clean.
        doc.undoStack()->undo();
        QVERIFY(doc.isModified());
        doc.undoStack()->redo();
        QVERIFY(!doc.isModified());
    }

    // Joints name their bodies: a rename is carried into them and a deleted body takes its
    // joints along, each in the same undo step as the edit, so the scene stays one that
    // runs (a joint naming a missing body is refused by the engine). The sample on strings
    // opens with its ten joints and saves them back.
    void jointsFollowTheirBodies() {
        Document doc;
        QString error;
        QVERIFY2(doc.open(":/scenes/newtons-cradle-strings.json", &error), qPrintable(error));
        QCOMPARE(doc.scene().joints.size(), size_t(10));
        QSignalSpy jointsChanged(&doc, &Document::jointsChanged);

        BodyDesc renamed = doc.body(1);
        QCOMPARE(renamed.name, std::string("ball-1"));
        renamed.name = "striker";
        doc.setBody(1, renamed, "Rename");
        QCOMPARE(doc.scene().joints[0].bodyA, std::string("striker"));
        QCOMPARE(doc.scene().joints[1].bodyA, std::string("striker"));
        QCOMPARE(doc.scene().joints[2].bodyA, std::string("ball-2"));
        QCOMPARE(jointsChanged.count(), 1);
        doc.undoStack()->undo();  // one step: the body and its joints
        QCOMPARE(doc.body(1).name, std::string("ball-1"));
        QCOMPARE(doc.scene().joints[0].bodyA, std::string("ball-1"));

        const SceneDesc before = doc.scene();
        doc.removeBodies({2, 4});  // ball-2 and ball-4
        QCOMPARE(doc.scene().joints.size(), size_t(6));
        for (const JointDesc& j : doc.scene().joints)
            QVERIFY(j.bodyA != "ball-2" && j.bodyA != "ball-4");
        (void)World(doc.scene());  // still a scene the engine takes
        doc.undoStack()->undo();
        QCOMPARE(doc.scene(), before);

        QTemporaryDir dir;
        QVERIFY2(doc.saveAs(dir.filePath("cradle.json"), &error), qPrintable(error));
        Document again;
        QVERIFY2(again.open(dir.filePath("cradle.json"), &error), qPrintable(error));
        QCOMPARE(again.scene().joints, doc.scene().joints);
    }

    void aBadFileLeavesTheSceneUntouched() {
        QTemporaryDir dir;
        const QString path = dir.filePath("bad.json");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(
            R"({"format": "tumble-scene", "version": 1, "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": -1}, "mass": 1}]})");
        f.close();
        Document doc;
        doc.addBody(ball("keep", 1.0));
        const SceneDesc before = doc.scene();
        QString error;
        QVERIFY(!doc.open(path, &error));
        QVERIFY2(error.contains("bad.json") && error.contains("bodies[0].shape.radius"), qPrintable(error));
        QCOMPARE(doc.scene(), before);
        QVERIFY(!doc.open(dir.filePath("missing.json"), &error));
        QVERIFY2(error.contains("missing.json"), qPrintable(error));
        QCOMPARE(doc.scene(), before);
    }

    void samplesOpenWithoutAFile() {
        Document doc;
        QString error;
        QVERIFY2(doc.open(":/scenes/tower-20.json", &error), qPrintable(error));
        QCOMPARE(doc.bodyCount(), 21);
        QVERIFY(doc.filePath().isEmpty());  // Save must ask where
        QVERIFY(!doc.undoStack()->canUndo());
        // The compound samples are there too: the pile of 200 chairs, each of six parts.
        QVERIFY2(doc.open(":/scenes/chair-pile.json", &error), qPrintable(error));
        QCOMPARE(doc.bodyCount(), 201);
        QCOMPARE(int(doc.body(200).shape.parts.size()), 6);
    }

    // A save that cannot be written says which file and why, leaves what was on disk, and
    // leaves the document as it was (its file, unsaved changes).
    void aFailedSaveNamesTheFileAndKeepsTheOldOne() {
        QTemporaryDir dir;
        Document doc;
        doc.addBody(ball("ball", 1.0));
        QString error;
        const QString saved = dir.filePath("scene.json");
        QVERIFY2(doc.saveAs(saved, &error), qPrintable(error));
        doc.addBody(ball("another", 2.0));
        const QString missing = dir.filePath("nodir/scene.json");
        QVERIFY(!doc.saveAs(missing, &error));
        QCOMPARE(error, missing + ": cannot be written: no such folder");
        QFile file(dir.filePath("file"));
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.close();
        const QString underAFile = dir.filePath("file/scene.json");
        QVERIFY(!doc.saveAs(underAFile, &error));
        QCOMPARE(error,
                 underAFile + ": cannot be written: a file stands where a folder of its path should be");
        QVERIFY(!doc.saveWithMeshes(missing, &error));
        QCOMPARE(error, missing + ": cannot be written: no such folder");
        // A folder where the file should be: it cannot be replaced, and stays as it was.
        QVERIFY(QDir(dir.path()).mkpath("taken.json/inside"));
        QVERIFY(!doc.saveAs(dir.filePath("taken.json"), &error));
        QVERIFY2(error.startsWith(dir.filePath("taken.json") + ": cannot be replaced: "), qPrintable(error));
        QVERIFY(QFileInfo(dir.filePath("taken.json/inside")).isDir());
        QCOMPARE(doc.filePath(), saved);
        QVERIFY(doc.isModified());
        Document reread;
        QVERIFY2(reread.open(saved, &error), qPrintable(error));
        QCOMPARE(reread.bodyCount(), 2);
        QCOMPARE(QDir(dir.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot, QDir::Name),
                 QStringList({"file", "scene.json", "taken.json"}));
    }

    // What killed saves left beside a scene goes when it is opened, and beside the scene
    // and its mesh copies when it is saved; a file that merely looks alike stays.
    void killedSavesTemporariesAreRemoved() {
        QTemporaryDir root;
        QVERIFY(QFile::copy(kMeshes + "/box.stl", root.filePath("box.stl")));
        const QString scene = root.filePath("scene.json");
        writeMeshScene(scene, {"box.stl"});
        QFile backup(scene + ".backup");
        QVERIFY(backup.open(QIODevice::WriteOnly));
        backup.close();
        const QString beforeOpen = staleTemporary(scene);
        QVERIFY(QFileInfo::exists(beforeOpen));
        Document doc;
        QString error;
        QVERIFY2(doc.open(scene, &error), qPrintable(error));
        QVERIFY(!QFileInfo::exists(beforeOpen));
        QVERIFY(QDir(root.path()).mkpath("out/moved-meshes"));
        const QString target = root.filePath("out/moved.json");
        const QStringList stale = {staleTemporary(target),
                                   staleTemporary(root.filePath("out/moved-meshes/box.stl"))};
        for (const QString& s : stale) QVERIFY(QFileInfo::exists(s));
        QVERIFY2(doc.saveWithMeshes(target, &error), qPrintable(error));
        for (const QString& s : stale) QVERIFY2(!QFileInfo::exists(s), qPrintable(s));
        QVERIFY(QFileInfo::exists(scene + ".backup"));
        QCOMPARE(QDir(root.filePath("out/moved-meshes")).entryList(QDir::Files), QStringList({"box.stl"}));
    }

    // A scene whose mesh sits beside it, saved into another folder: the saved file points
    // back at the mesh (relative to the new folder) and reopens with it.
    void saveAsElsewhereKeepsMeshesReachable() {
        QTemporaryDir root;
        QVERIFY(QDir(root.path()).mkpath("a") && QDir(root.path()).mkpath("b/deeper"));
        const QString mesh = root.filePath("a/box.stl");
        QVERIFY(QFile::copy(kMeshes + "/box.stl", mesh));
        const QString first = root.filePath("a/scene.json");
        writeMeshScene(first, {"box.stl"});
        Document doc;
        QString error;
        QVERIFY2(doc.open(first, &error), qPrintable(error));
        QCOMPARE(QString::fromStdString(doc.body(1).shape.file), QFileInfo(mesh).absoluteFilePath());
        const QString second = root.filePath("b/deeper/scene.json");
        QVERIFY2(doc.saveAs(second, &error), qPrintable(error));
        QVERIFY(readAll(second).contains("\"../../a/box.stl\""));
        Document again;
        QVERIFY2(again.open(second, &error), qPrintable(error));
        QVERIFY(again.body(1).shape.meshData);
        QCOMPARE(int(again.body(1).shape.meshData->triangles.size()), 12);
    }

    // Save with meshes copies each mesh file beside the scene (one copy per file, names made
    // unique) and the scene then opens without the originals.
    void saveWithMeshesCopiesThemBeside() {
        QTemporaryDir root;
        QVERIFY(QDir(root.path()).mkpath("src/one") && QDir(root.path()).mkpath("src/two") &&
                QDir(root.path()).mkpath("out"));
        QVERIFY(QFile::copy(kMeshes + "/box.stl", root.filePath("src/one/shape.stl")));
        QVERIFY(QFile::copy(kMeshes + "/tetrahedron.off", root.filePath("src/two/shape.off")));
        QVERIFY(
            QFile::copy(kMeshes + "/box.stl", root.filePath("src/two/shape.stl")));  // same name, other file
        const QString first = root.filePath("src/scene.json");
        writeMeshScene(first, {"one/shape.stl", "two/shape.off", "two/shape.stl", "one/shape.stl"});
        Document doc;
        QString error;
        QVERIFY2(doc.open(first, &error), qPrintable(error));
        const QString target = root.filePath("out/moved.json");
        QVERIFY2(doc.saveWithMeshes(target, &error), qPrintable(error));
        QCOMPARE(doc.filePath(), target);
        QVERIFY(!doc.isModified());
        const QDir copies(root.filePath("out/moved-meshes"));
        QCOMPARE(copies.entryList(QDir::Files, QDir::Name),
                 QStringList({"shape-2.stl", "shape.off", "shape.stl"}));
        QCOMPARE(readAll(copies.filePath("shape.stl")), readAll(kMeshes + "/box.stl"));
        const QByteArray text = readAll(target);
        QVERIFY(text.contains("\"moved-meshes/shape.stl\"") && text.contains("\"moved-meshes/shape-2.stl\""));
        QVERIFY(QDir(root.filePath("src")).removeRecursively());  // the originals are gone
        Document again;
        QVERIFY2(again.open(target, &error), qPrintable(error));
        for (int i = 1; i <= 4; ++i) QVERIFY(again.body(i).shape.meshData);
        QCOMPARE(int(again.body(2).shape.meshData->triangles.size()), 4);
    }

    // A compound's mesh part is a mesh like a body's: opened from its folder, copied by Save
    // With Meshes, and found again without the original.
    void compoundMeshPartsTravelWithTheScene() {
        QTemporaryDir root;
        QVERIFY(QDir(root.path()).mkpath("src/parts") && QDir(root.path()).mkpath("out"));
        QVERIFY(QFile::copy(kMeshes + "/tetrahedron.off", root.filePath("src/parts/lump.off")));
        const QString first = root.filePath("src/cart.json");
        QFile f(first);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"format": "tumble-scene", "version": 1, "bodies": [
  {"name": "cart", "mass": 2, "shape": {"type": "compound", "parts": [
    {"shape": {"type": "box", "half_extents": [0.5, 0.1, 0.3]}},
    {"name": "lump", "shape": {"type": "mesh", "file": "parts/lump.off"}, "position": [0, 0.2, 0]}]}}]})");
        f.close();
        Document doc;
        QString error;
        QVERIFY2(doc.open(first, &error), qPrintable(error));
        QVERIFY(doc.body(0).shape.parts[1].shape.meshData);
        const QString target = root.filePath("out/cart.json");
        QVERIFY2(doc.saveWithMeshes(target, &error), qPrintable(error));
        QVERIFY(QFile::exists(root.filePath("out/cart-meshes/lump.off")));
        QVERIFY(readAll(target).contains("\"cart-meshes/lump.off\""));
        QVERIFY(QDir(root.filePath("src")).removeRecursively());
        Document again;
        QVERIFY2(again.open(target, &error), qPrintable(error));
        QCOMPARE(int(again.body(0).shape.parts[1].shape.meshData->triangles.size()), 4);
    }

    // A mesh that cannot be read: a message naming it, and nothing written.
    void saveWithMeshesRefusesAMissingMesh() {
        QTemporaryDir root;
        QVERIFY(QFile::copy(kMeshes + "/box.stl", root.filePath("box.stl")));
        writeMeshScene(root.filePath("scene.json"), {"box.stl"});
        Document doc;
        QString error;
        QVERIFY2(doc.open(root.filePath("scene.json"), &error), qPrintable(error));
        QVERIFY(QFile::remove(root.filePath("box.stl")));
        QVERIFY(QDir(root.path()).mkpath("out"));
        QVERIFY(!doc.saveWithMeshes(root.filePath("out/scene.json"), &error));
        QVERIFY2(error.contains("box.stl"), qPrintable(error));
        QVERIFY(QDir(root.filePath("out")).entryList(QDir::NoDotAndDotDot | QDir::AllEntries).isEmpty());
        QCOMPARE(doc.filePath(), root.filePath("scene.json"));
    }

    // A missing mesh does not keep the scene from opening: that body comes without its
    // mesh, the others with theirs, and the reason names the file, the field and the mesh.
    void aMissingMeshStillOpens() {
        QTemporaryDir root;
        QVERIFY(QFile::copy(kMeshes + "/box.stl", root.filePath("box.stl")));
        writeMeshScene(root.filePath("scene.json"), {"box.stl", "gone.obj"});
        Document doc;
        QString error;
        QVERIFY2(doc.open(root.filePath("scene.json"), &error), qPrintable(error));
        QCOMPARE(doc.bodyCount(), 3);
        QVERIFY(doc.body(1).shape.meshData);
        QVERIFY(!doc.body(2).shape.meshData);
        QCOMPARE(doc.openWarnings().size(), 1);
        const QString w = doc.openWarnings().first();
        QVERIFY2(w.contains("scene.json") && w.contains("bodies[2].shape.file") && w.contains("gone.obj"),
                 qPrintable(w));
        // Saving keeps the reference (nothing is lost), and a good file clears the warnings.
        QVERIFY(doc.saveAs(root.filePath("again.json"), &error));
        QVERIFY(readAll(root.filePath("again.json")).contains("gone.obj"));
        writeMeshScene(root.filePath("good.json"), {"box.stl"});
        QVERIFY(doc.open(root.filePath("good.json"), &error));
        QVERIFY(doc.openWarnings().isEmpty());
    }

    // Issue 46 item 3: a mesh file removed or changed while its scene is open. The scene keeps
    // the mesh as it read it; Save says so (meshFilesChangedOnDisk, which the window shows
    // after a save) and keeps the reference; Save with Meshes refuses rather than copy a
    // mesh that is not the one shown, and leaves nothing behind.
    void aMeshFileRemovedOrChangedWhileOpen() {
        QTemporaryDir root;
        QVERIFY(QFile::copy(kMeshes + "/box.stl", root.filePath("box.stl")));
        QVERIFY(QFile::copy(kMeshes + "/l-prism.obj", root.filePath("prism.obj")));
        writeMeshScene(root.filePath("scene.json"), {"box.stl", "prism.obj"});
        Document doc;
        QString error;
        QVERIFY2(doc.open(root.filePath("scene.json"), &error), qPrintable(error));
        QVERIFY(doc.meshFilesChangedOnDisk().isEmpty());
        const auto loaded = doc.body(1).shape.meshData;
        QVERIFY(loaded);

        QVERIFY(QFile::remove(root.filePath("box.stl")));
        {
            QFile changed(root.filePath("prism.obj"));
            QVERIFY(changed.open(QIODevice::Append));
            changed.write("# changed\n");
        }
        const QStringList changes = doc.meshFilesChangedOnDisk();
        QCOMPARE(changes.size(), 2);
        QVERIFY2(changes[0].endsWith("box.stl (removed)") && changes[1].endsWith("prism.obj (changed)"),
                 qPrintable(changes.join(", ")));
        QCOMPARE(doc.body(1).shape.meshData, loaded);  // the scene keeps what it read

        QVERIFY2(doc.saveAs(root.filePath("scene.json"), &error), qPrintable(error));
        QVERIFY(readAll(root.filePath("scene.json")).contains("box.stl"));
        QCOMPARE(doc.meshFilesChangedOnDisk(), changes);  // still so after the save

        const QString copy = root.filePath("copy.json");
        QVERIFY(!doc.saveWithMeshes(copy, &error));
        QVERIFY2(error.contains("box.stl") && error.contains("removed since it was loaded"),
                 qPrintable(error));
        QVERIFY(QFile::copy(kMeshes + "/box.stl", root.filePath("box.stl")));  // back, but newer
        QVERIFY(!doc.saveWithMeshes(copy, &error));
        QVERIFY2(error.contains("changed on disk since it was loaded"), qPrintable(error));
        QVERIFY(!QFileInfo::exists(copy));
        QVERIFY(!QFileInfo::exists(root.filePath("copy-meshes")));

        // Opened again, the scene reads the files as they are now: nothing changed since.
        QVERIFY2(doc.open(root.filePath("scene.json"), &error), qPrintable(error));
        QVERIFY(doc.meshFilesChangedOnDisk().isEmpty());
        QVERIFY2(doc.saveWithMeshes(copy, &error), qPrintable(error));
    }

private:
    const QString kMeshes = QStringLiteral(TUMBLE_SCENES_DIR "/../meshes");

    static QByteArray readAll(const QString& path) {
        QFile f(path);
        return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
    }

    // A scene with a ground and one convex-hull mesh body per file (paths as given).
    static void writeMeshScene(const QString& path, const QStringList& files) {
        QString bodies =
            R"({"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}})";
        int n = 0;
        for (const QString& f : files) {
            ++n;
            bodies +=
                QStringLiteral(
                    R"(, {"name": "m%1", "shape": {"type": "mesh", "file": "%2"}, "density": 1000, "position": [0, %3, 0]})")
                    .arg(n)
                    .arg(f)
                    .arg(2 * n);
        }
        QFile out(path);
        QVERIFY(out.open(QIODevice::WriteOnly));
        out.write(QStringLiteral(R"({"format": "tumble-scene", "version": 1, "bodies": [%1]})")
                      .arg(bodies)
                      .toUtf8());
    }
};

QTEST_MAIN(TestDocument)
#include "tst_document.moc"
