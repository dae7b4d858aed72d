// The editor window, as a user sees it: it opens the samples, refuses a bad scene without
// losing the open one, imports meshes as undoable bodies, autosaves and recovers, and its
// viewport shows one entity per body.
#include "document.h"
#include "main_window.h"
#include "viewport.h"

#include <tumble/mass.h>

#include <QDockWidget>
#include <QFile>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

class TestMainWindow : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

    void opensTheDefaultSample() {
        MainWindow w;
        QString error;
        QVERIFY2(w.openScene(MainWindow::defaultScenePath(), &error), qPrintable(error));
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        QVERIFY2(w.windowTitle().startsWith("tumbling-box.json"), qPrintable(w.windowTitle()));
        QVERIFY(!w.isWindowModified());
        QCOMPARE(w.viewport()->entityCount(), int(w.scene().bodies.size()));
        // The docks a user expects are there.
        QStringList docks;
        for (QDockWidget* d : w.findChildren<QDockWidget*>()) docks << d->objectName();
        for (const char* name : {"SceneTreeDock", "PropertyDock", "SettingsDock", "UndoHistoryDock"})
            QVERIFY2(docks.contains(name), name);
    }

    void everySampleOpens() {
        MainWindow w;
        for (const char* name :
             {"tumbling-box", "spring-pendulum", "projectile", "bouncing-ball", "head-on",
              "tilted-box-impact", "newtons-cradle", "sliding-block", "incline", "rolling-sphere", "tower-20",
              "pyramid-15", "mass-ratio-stack", "sleeping-wake"}) {
            QString error;
            QVERIFY2(w.openScene(QString(":/scenes/%1.json").arg(name), &error), qPrintable(error));
            QCOMPARE(w.viewport()->entityCount(), int(w.scene().bodies.size()));
        }
    }

    void badSceneKeepsTheOpenOne() {
        QTemporaryDir dir;
        const QString bad = dir.filePath("bad.json");
        QFile f(bad);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(
            R"({"format": "tumble-scene", "version": 1, "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": -1}, "mass": 1}]})");
        f.close();
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(MainWindow::defaultScenePath(), &error));
        const SceneDesc before = w.scene();
        QVERIFY(!w.openScene(bad, &error));
        QCOMPARE(error, bad + ": bodies[0].shape.radius: must be greater than 0");
        QCOMPARE(w.scenePath(), MainWindow::defaultScenePath());
        QCOMPARE(w.scene(), before);
        QVERIFY(!w.openScene(dir.filePath("missing.json"), &error));
        QVERIFY(error.contains("missing.json"));
    }

    void importMesh_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<int>("triangles");
        QTest::newRow("obj") << QString(TUMBLE_SCENES_DIR "/../meshes/l-prism.obj") << 28;
        QTest::newRow("stl") << QString(TUMBLE_SCENES_DIR "/../meshes/box.stl") << 12;
        QTest::newRow("gltf") << QString("/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf")
                              << 12;
    }
    void importMesh() {
        QFETCH(QString, file);
        QFETCH(int, triangles);
        MainWindow w;
        const int before = w.document()->bodyCount();
        QString error;
        QVERIFY2(w.importMesh(file, true, 2.0, &error), qPrintable(error));
        QCOMPARE(w.document()->bodyCount(), before + 1);
        const BodyDesc& b = w.document()->body(before);
        QCOMPARE(b.shape.type, ShapeType::Mesh);
        QCOMPARE(b.shape.scale, Vec3(2, 2, 2));
        QVERIFY(b.shape.meshData);
        QCOMPARE(int(b.shape.meshData->triangles.size()), triangles);
        QCOMPARE(w.document()->selection(), QList<int>({before}));
        QCOMPARE(w.viewport()->entityCount(), before + 1);
        QVERIFY(w.isWindowModified());
        w.document()->undoStack()->undo();  // one step takes it away
        QCOMPARE(w.document()->bodyCount(), before);
    }

    void aBadMeshLeavesTheSceneUntouched() {
        QTemporaryDir dir;
        const QString junk = dir.filePath("junk.obj");
        QFile f(junk);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("this is not a mesh\n");
        f.close();
        MainWindow w;
        const SceneDesc before = w.scene();
        QString error;
        QVERIFY(!w.importMesh(junk, true, 1.0, &error));
        QVERIFY2(error.contains("junk.obj"), qPrintable(error));
        QVERIFY(!w.importMesh(dir.filePath("missing.stl"), true, 1.0, &error));
        QVERIFY2(error.contains("missing.stl"), qPrintable(error));
        QCOMPARE(w.scene(), before);
        QVERIFY(!w.document()->undoStack()->canUndo());
    }

    void autosaveAndRecovery() {
        QFile::remove(MainWindow::autosavePath());
        SceneDesc edited;
        {
            MainWindow w;
            w.autosave();  // nothing unsaved: no file
            QVERIFY(!QFile::exists(MainWindow::autosavePath()));
            BodyDesc ball;
            ball.name = "ball";
            ball.mass = 2.0;
            ball.position = Vec3(0, 3, 0);
            w.document()->addBody(ball);
            w.autosave();
            QVERIFY(QFile::exists(MainWindow::autosavePath()));
            edited = w.scene();
            // The window is destroyed without closing: as after a crash, the file stays.
        }
        MainWindow next;
        QString error;
        QVERIFY2(next.recoverAutosave(&error), qPrintable(error));
        QCOMPARE(next.scene(), edited);
        QVERIFY(next.isWindowModified());  // recovered work is unsaved work
        next.document()->undoStack()->undo();
        QCOMPARE(next.document()->bodyCount(), 1);  // back to the new scene
        QFile::remove(MainWindow::autosavePath());
    }

    void saveAndReopen() {
        QTemporaryDir dir;
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(":/scenes/bouncing-ball.json", &error));
        QVERIFY(w.document()->saveAs(dir.filePath("copy.json"), &error));
        MainWindow other;
        QVERIFY2(other.openScene(dir.filePath("copy.json"), &error), qPrintable(error));
        QCOMPARE(other.scene(), w.scene());
        QVERIFY2(other.windowTitle().startsWith("copy.json"), qPrintable(other.windowTitle()));
    }
};

QTEST_MAIN(TestMainWindow)
#include "tst_main_window.moc"
