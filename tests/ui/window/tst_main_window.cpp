// The editor window, as a user sees it: it opens the samples, refuses a bad scene without
// losing the open one, imports meshes as undoable bodies (recovery: tst_recovery.cpp), asks
// before closing over unsaved changes, opens a dropped scene and imports a dropped mesh, and
// its viewport shows one entity per body.
#include "document/body_presets.h"
#include "document/document.h"
#include "import/import_options_dialog.h"
#include "import/mesh_import_job.h"
#include "../helpers/choose_file.h"
#include "message_box_answer.h"
#include "timeline/timeline.h"
#include "viewport/viewport.h"
#include "window/main_window.h"
#include "window/shortcuts_dialog.h"

#include <tumble/mass.h>

#include <QAbstractButton>
#include <QAbstractItemView>
#include <QAbstractSpinBox>
#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressDialog>
#include <QScopeGuard>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QUndoStack>
#include <QUrl>
#include <QtTest>

#include <functional>
#include <memory>

using namespace tumble;
using namespace tumble::ui;
using tumble::ui::test::answerNextMessageBox;
using tumble::test::chooseFile;

namespace {

// A drop on the window, as a file manager makes it; whether the drag's enter was accepted.
bool drop(QWidget* target, const QMimeData& mime) {
    const QPoint at(target->width() / 2, target->height() / 2);
    QDragEnterEvent enter(at, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(target, &enter);
    if (!enter.isAccepted()) return false;
    QDropEvent dropped(QPointF(at), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(target, &dropped);
    return true;
}

bool dropUrls(QWidget* target, const QList<QUrl>& urls) {
    QMimeData mime;
    mime.setUrls(urls);
    return drop(target, mime);
}

}  // namespace

class TestMainWindow : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QApplication::setQuitOnLastWindowClosed(false);  // the close tests close windows
    }

    // Issue 21 item 4: Ctrl+Z and Ctrl+Shift+Z in a focused number field undo and redo the
    // document's edits, as Edit > Undo does; a name being typed keeps its own undo until it
    // is given (Enter), then the keys undo the document's rename.
    void undoKeysWorkInAFocusedField() {
        MainWindow w;
        QString error;
        QVERIFY2(w.openScene(MainWindow::defaultScenePath(), &error), qPrintable(error));
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        QApplication::setActiveWindow(&w);
        Document& doc = *w.document();
        int box = -1;
        for (int i = 0; i < doc.bodyCount(); ++i)
            if (doc.body(i).motion == Motion::Dynamic) box = i;
        QVERIFY(box >= 0);
        doc.setSelection({box});
        auto* friction = w.findChild<QDockWidget*>("PropertyDock")->findChild<QAbstractSpinBox*>("friction");
        QVERIFY(friction);
        const double before = doc.body(box).friction;
        friction->setFocus();
        QTRY_VERIFY(friction->hasFocus());
        friction->selectAll();
        QTest::keyClicks(friction, "0.75");
        QTest::keyClick(friction, Qt::Key_Return);
        QCOMPARE(doc.body(box).friction, 0.75);
        QVERIFY(friction->hasFocus());
        QTest::keyClick(friction, Qt::Key_Z, Qt::ControlModifier);
        QCOMPARE(doc.body(box).friction, before);
        QTest::keyClick(friction, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
        QCOMPARE(doc.body(box).friction, 0.75);

        auto* name = w.findChild<QDockWidget*>("PropertyDock")->findChild<QLineEdit*>("name");
        QVERIFY(name);
        const std::string oldName = doc.body(box).name;
        name->setFocus();
        QTRY_VERIFY(name->hasFocus());
        name->selectAll();
        QTest::keyClicks(name, "crate");
        QTest::keyClick(name, Qt::Key_Z, Qt::ControlModifier);  // the typing, not the document
        QCOMPARE(doc.body(box).name, oldName);
        QCOMPARE(doc.body(box).friction, 0.75);
        QCOMPARE(name->text(), QString::fromStdString(oldName));
        name->selectAll();
        QTest::keyClicks(name, "crate");
        QTest::keyClick(name, Qt::Key_Return);
        QCOMPARE(doc.body(box).name, std::string("crate"));
        QTest::keyClick(name, Qt::Key_Z, Qt::ControlModifier);  // the rename
        QCOMPARE(doc.body(box).name, oldName);
    }

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

    // File > Samples: the compiled-in samples, then the sample files with meshes beside them
    // (from the installed folder; here, built, the source tree's), which open from their
    // folder with their meshes; a convex parts file is not offered as a scene.
    void theSamplesMenuOpensTheSampleFilesWithMeshes() {
        MainWindow w;
        auto* menu = w.findChild<QMenu*>("samplesMenu");
        QVERIFY(menu);
        QStringList names;
        QAction* meshShapes = nullptr;
        for (QAction* a : menu->actions()) {
            if (a->isSeparator()) continue;
            names << a->text();
            if (a->text() == "mesh-shapes") meshShapes = a;
        }
        for (const char* name : {"tumbling-box", "newtons-cradle", "tilt-platform", "mesh-shapes", "mug-on-board"})
            QVERIFY2(names.contains(name), qPrintable(names.join(' ')));
        QCOMPARE(names.count("tumbling-box"), 1);
        QVERIFY2(!names.contains("mug-on-board.convex-parts"), qPrintable(names.join(' ')));
        QVERIFY2(names.indexOf("mesh-shapes") > names.indexOf("tilt-platform"), qPrintable(names.join(' ')));
        QVERIFY(meshShapes);
        QCOMPARE(meshShapes->data().toString(), QDir(TUMBLE_SCENES_DIR).canonicalPath() + "/mesh-shapes.json");
        meshShapes->trigger();
        QVERIFY2(w.windowTitle().startsWith("mesh-shapes.json"), qPrintable(w.windowTitle()));
        QVERIFY(w.document()->openWarnings().isEmpty());  // its meshes were found
        QCOMPARE(w.viewport()->entityCount(), int(w.scene().bodies.size()));
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
        // Several problems: each named, one a line (issue 21 item 8: only the first was).
        const QString worse = dir.filePath("worse.json");
        QFile g(worse);
        QVERIFY(g.open(QIODevice::WriteOnly));
        g.write(R"({"format": "tumble-scene", "version": 1, "bodies": [
            {"name": "a", "shape": {"type": "sphere", "radius": -1}, "mass": 1},
            {"name": "b", "shape": {"type": "sphere", "radius": 1}, "mass": -3},
            {"name": "c", "shape": {"type": "sphere", "radius": 1}, "mass": 1, "restitution": 2}]})");
        g.close();
        QVERIFY(!w.openScene(worse, &error));
        const QStringList lines = error.split('\n');
        QCOMPARE(lines.size(), 3);
        QCOMPARE(lines[0], worse + ": bodies[0].shape.radius: must be greater than 0");
        QVERIFY2(lines[1].startsWith(worse + ": bodies[1].mass: "), qPrintable(lines[1]));
        QVERIFY2(lines[2].startsWith(worse + ": bodies[2].restitution: "), qPrintable(lines[2]));
        QCOMPARE(w.scene(), before);
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

    // Issue 21 item 3: Import Mesh reads the file, then asks its units (or a size to fit)
    // showing the body's size in metres and its mass; issue 52: the body is set down, as Add
    // does, on the surface under the view's centre (here the ground beside the tower).
    void importAsksUnitsShowsSizeAndMassAndSetsItDownUnderTheView() {
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(":/scenes/tower-20.json", &error));
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        w.viewport()->setCamera(QVector3D(5, 0, 5), 12.0f, 30.0f, 35.0f);
        const int before = w.document()->bodyCount();
        QAction* import = nullptr;
        for (QAction* a : w.findChildren<QAction*>())
            if (a->text() == "&Import Mesh...") import = a;
        QVERIFY(import);
        const QString file = TUMBLE_SCENES_DIR "/../meshes/box.stl";  // a unit cube
        QString inMetres, inCentimetres, fitted;
        double massFitted = 0.0;
        bool asked = false;
        QTimer poll;
        poll.setInterval(20);
        connect(&poll, &QTimer::timeout, &w, [&] {
            QWidget* modal = QApplication::activeModalWidget();
            if (auto* files = qobject_cast<QFileDialog*>(modal)) {
                chooseFile(files, file);
            } else if (auto* options = qobject_cast<ImportOptionsDialog*>(modal); options && !asked) {
                asked = true;
                inMetres = options->sizeText();
                options->setFit(2.0);
                fitted = options->sizeText();
                massFitted = options->mass();
                options->setFit(0.0);
                options->setUnits(ImportOptionsDialog::Units::Centimetres);
                inCentimetres = options->sizeText();
                options->accept();
            }
        });
        poll.start();
        import->trigger();
        QTRY_VERIFY_WITH_TIMEOUT(w.document()->bodyCount() == before + 1, 30000);
        poll.stop();
        QVERIFY(asked);
        QCOMPARE(inMetres, QString("1 × 1 × 1 m"));
        QCOMPARE(fitted, QString("2 × 2 × 2 m"));
        QVERIFY2(std::abs(massFitted - 8000.0) < 1e-6, qPrintable(QString::number(massFitted)));  // water, 8 m³
        QCOMPARE(inCentimetres, QString("0.01 × 0.01 × 0.01 m"));
        const BodyDesc& b = w.document()->body(before);
        QCOMPARE(b.shape.scale, Vec3::Constant(0.01));
        Vec3 lo = b.shape.meshData->vertices.front(), hi = lo;
        for (const Vec3& v : b.shape.meshData->vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        QVERIFY((hi - lo).isApprox(Vec3::Constant(0.01), 1e-12));
        // Resting on the ground at the view's centre (within the touch tolerance).
        const double lowest = b.position.y() + lo.y();
        QVERIFY2(std::abs(lowest) < 1e-4, qPrintable(QString::number(lowest, 'g', 12)));
        QVERIFY2(std::abs(b.position.x() - 5.0) < 1e-6 && std::abs(b.position.z() - 5.0) < 1e-6,
                 qPrintable(QString("%1, %2").arg(b.position.x()).arg(b.position.z())));
    }

    // Issue 21 item 6: at the default window size the Properties panel shows every field
    // whole (the third column of half extents, scale and velocity was cut off behind a
    // horizontal scroll bar).
    void thePropertiesFitTheirPanel() {
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(TUMBLE_SCENES_DIR "/mesh-shapes.json", &error));
        w.resize(1600, 1000);
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        auto* area = w.findChild<QDockWidget*>("PropertyDock")->findChild<QScrollArea*>();
        QVERIFY(area);
        for (int i = 1; i < w.document()->bodyCount(); ++i) {  // a static mesh, a dynamic one
            w.document()->setSelection({i});
            QApplication::processEvents();
            QCOMPARE(area->horizontalScrollBar()->maximum(), 0);
        }
        BodyDesc box;
        box.name = "box";
        box.shape.type = ShapeType::Box;
        box.mass = 1.0;
        box.position = Vec3(0, 3, 0);
        box.velocity = Vec3(1.25, -3.5, 0.75);
        w.document()->setSelection({w.document()->addBody(box)});
        QApplication::processEvents();
        QCOMPARE(area->horizontalScrollBar()->maximum(), 0);
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

    // A slow read (a PLY assimp loops on, let through on purpose) runs beside the window:
    // its timers fire and it paints while the progress dialog is up, the dialog's Cancel
    // stops the read at once, and nothing is added.
    void importRunsInTheBackgroundAndCancels() {
        QTemporaryDir dir;
        const QString file = dir.filePath("noend.ply");
        QFile f(file);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\n0 0 0\n1 0 0\n0 1 0\n");
        f.close();
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        io::MeshImportOptions options;
        options.timeLimit = 60;
        options.refuseKnownHangs = false;
        w.setMeshImportOptions(options);
        const SceneDesc before = w.scene();
        QSignalSpy finished(&w, &MainWindow::importFinished);
        int ticks = 0;
        QTimer ticker;
        ticker.setInterval(50);
        connect(&ticker, &QTimer::timeout, [&] { ++ticks; });
        ticker.start();
        QElapsedTimer clock;
        clock.start();
        QVERIFY(w.startImport({file}, true, 1.0, false));
        QVERIFY(!w.startImport({file}, true, 1.0, false));  // one import at a time
        QTRY_VERIFY_WITH_TIMEOUT(w.importJob()->progressDialog() && w.importJob()->progressDialog()->isVisible(),
                                 10000);
        QVERIFY(w.isImporting());
        QVERIFY2(w.importJob()->progressDialog()->labelText().contains("noend.ply"),
                 qPrintable(w.importJob()->progressDialog()->labelText()));
        QTest::qWait(600);
        QVERIFY2(ticks >= 10, qPrintable(QString("%1 ticks in %2 ms").arg(ticks).arg(clock.elapsed())));
        QVERIFY(finished.isEmpty());
        // The user presses Cancel.
        QAbstractButton* cancel = nullptr;
        for (QAbstractButton* b : w.importJob()->progressDialog()->findChildren<QAbstractButton*>())
            if (b->text().remove('&') == "Cancel") cancel = b;
        QVERIFY(cancel);
        clock.restart();
        QTest::mouseClick(cancel, Qt::LeftButton);
        QVERIFY(finished.wait(5000));
        QVERIFY2(clock.elapsed() < 3000, qPrintable(QString::number(clock.elapsed())));
        QCOMPARE(finished[0][0].toInt(), 0);
        QCOMPARE(finished[0][2].toBool(), true);
        QVERIFY(!w.isImporting());
        QCOMPARE(w.scene(), before);
        QVERIFY(!w.document()->undoStack()->canUndo());
        QTRY_VERIFY(w.findChildren<QProgressDialog*>().isEmpty());
    }

    // Several files at once (a drop of three): the good ones added as one undo step, the
    // bad one named in the message, and the dialog counts the files.
    void severalMeshesAreOneStepAndTheBadOneNamed() {
        QTemporaryDir dir;
        const QString junk = dir.filePath("junk.obj");
        QFile f(junk);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("this is not a mesh\n");
        f.close();
        MainWindow w;
        const int bodies = w.document()->bodyCount();
        const int steps = w.document()->undoStack()->count();
        QSignalSpy finished(&w, &MainWindow::importFinished);
        QVERIFY(w.startImport({TUMBLE_SCENES_DIR "/../meshes/box.stl", junk, TUMBLE_SCENES_DIR "/../meshes/l-prism.obj"},
                              false, 0.5, false));
        QVERIFY(finished.wait(30000));
        QCOMPARE(finished[0][0].toInt(), 2);
        QVERIFY2(finished[0][1].toString().contains("junk.obj"), qPrintable(finished[0][1].toString()));
        QCOMPARE(finished[0][2].toBool(), false);
        QCOMPARE(w.document()->bodyCount(), bodies + 2);
        QCOMPARE(w.document()->body(bodies).name, std::string("box"));
        QCOMPARE(w.document()->body(bodies + 1).name, std::string("l-prism"));
        QCOMPARE(w.document()->body(bodies + 1).shape.collision, MeshCollision::Triangles);
        QCOMPARE(w.document()->body(bodies + 1).shape.scale, Vec3(0.5, 0.5, 0.5));
        QCOMPARE(w.document()->selection(), QList<int>({bodies, bodies + 1}));
        QCOMPARE(w.document()->undoStack()->count(), steps + 1);
        w.document()->undoStack()->undo();
        QCOMPARE(w.document()->bodyCount(), bodies);
    }

    void closingWithUnsavedChangesAsks() {
        QTemporaryDir dir;
        const QString path = dir.filePath("ball.json");
        MainWindow w;
        QString error;
        QVERIFY2(w.openScene(":/scenes/bouncing-ball.json", &error), qPrintable(error));
        QVERIFY2(w.document()->saveAs(path, &error), qPrintable(error));
        QFile file(path);
        QVERIFY(file.open(QIODevice::ReadOnly));
        const QByteArray onDisk = file.readAll();
        file.close();
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        // Nothing unsaved: it closes without asking.
        QVERIFY(w.close());
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));

        BodyDesc ball;
        ball.name = "extra";
        ball.mass = 1.0;
        ball.position = Vec3(0, 4, 0);
        w.document()->addBody(ball);
        QVERIFY(w.isWindowModified());
        const SceneDesc edited = w.scene();

        // Cancel: the window stays, with the scene as it was.
        QString asked;
        answerNextMessageBox(QMessageBox::Cancel, &asked);
        QVERIFY(!w.close());
        QVERIFY2(asked.contains("ball.json"), qPrintable(asked));
        QVERIFY(w.isVisible());
        QCOMPARE(w.scene(), edited);
        QVERIFY(w.isWindowModified());
        QCOMPARE(w.document()->undoStack()->count(), 1);

        // Discard: it closes, and the file on disk is as it was saved.
        asked.clear();
        answerNextMessageBox(QMessageBox::Discard, &asked);
        QVERIFY(w.close());
        QVERIFY2(asked.contains("ball.json"), qPrintable(asked));
        QVERIFY(!w.isVisible());
        QVERIFY(file.open(QIODevice::ReadOnly));
        QCOMPARE(file.readAll(), onDisk);
    }

    void droppingASceneFileOpensIt() {
        QTemporaryDir dir;
        const QString path = dir.filePath("dropped.json");
        SceneDesc saved;
        {
            MainWindow source;
            QString error;
            QVERIFY(source.openScene(":/scenes/newtons-cradle.json", &error));
            QVERIFY2(source.document()->saveAs(path, &error), qPrintable(error));
            saved = source.scene();
        }
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        QVERIFY(dropUrls(&w, {QUrl::fromLocalFile(path)}));
        QCOMPARE(w.scenePath(), path);
        QCOMPARE(w.scene(), saved);
        QVERIFY(!w.isWindowModified());
        QVERIFY2(w.windowTitle().startsWith("dropped.json"), qPrintable(w.windowTitle()));
        QCOMPARE(w.viewport()->entityCount(), int(saved.bodies.size()));

        // With unsaved changes it asks first; Cancel keeps the open scene and its changes.
        w.document()->removeBodies({1});
        const SceneDesc edited = w.scene();
        answerNextMessageBox(QMessageBox::Cancel, nullptr);
        QVERIFY(dropUrls(&w, {QUrl::fromLocalFile(TUMBLE_SCENES_DIR "/projectile.json")}));
        QCOMPARE(w.scenePath(), path);
        QCOMPARE(w.scene(), edited);
    }

    void droppingAMeshFileImportsItAsOneStep() {
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        const SceneDesc before = w.scene();
        const int bodies = w.document()->bodyCount();
        const int steps = w.document()->undoStack()->count();
        QSignalSpy imported(&w, &MainWindow::importFinished);
        QVERIFY(dropUrls(&w, {QUrl::fromLocalFile(TUMBLE_SCENES_DIR "/../meshes/box.stl")}));
        QVERIFY(imported.wait(20000));  // read in the background
        QCOMPARE(w.document()->bodyCount(), bodies + 1);
        const BodyDesc& b = w.document()->body(bodies);
        QCOMPARE(b.name, std::string("box"));
        QCOMPARE(b.shape.type, ShapeType::Mesh);
        QCOMPARE(b.shape.collision, MeshCollision::ConvexHull);  // the drop's defaults
        QCOMPARE(b.shape.scale, Vec3(1, 1, 1));
        QVERIFY(b.shape.meshData);
        QCOMPARE(int(b.shape.meshData->triangles.size()), 12);
        QCOMPARE(w.document()->selection(), QList<int>({bodies}));
        QCOMPARE(w.viewport()->entityCount(), bodies + 1);
        QCOMPARE(w.document()->undoStack()->count(), steps + 1);
        w.document()->undoStack()->undo();
        QCOMPARE(w.scene(), before);
        // Something that is no file is refused at the door.
        QMimeData text;
        text.setText("box.stl");
        QVERIFY(!drop(&w, text));
        // Nor is a file of no known kind, or a remote one.
        QVERIFY(!dropUrls(&w, {QUrl::fromLocalFile(TUMBLE_SCENES_DIR "/README.md")}));
        QVERIFY(!dropUrls(&w, {QUrl("https://example.org/box.stl")}));
        QCOMPARE(w.scene(), before);

        // Two meshes dropped together: one undo step.
        QVERIFY(dropUrls(&w, {QUrl::fromLocalFile(TUMBLE_SCENES_DIR "/../meshes/box.stl"),
                              QUrl::fromLocalFile(TUMBLE_SCENES_DIR "/../meshes/tetrahedron.off")}));
        QVERIFY(imported.wait(20000));
        QCOMPARE(w.document()->bodyCount(), bodies + 2);
        QCOMPARE(w.document()->undoStack()->count(), steps + 1);
        QCOMPARE(w.document()->undoStack()->undoText(), QString("Import 2 Meshes"));
        w.document()->undoStack()->undo();
        QCOMPARE(w.scene(), before);
    }

    // The question on closing names the sample the scene came from, as the title does.
    void closingAnEditedSampleNamesIt() {
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(":/scenes/bouncing-ball.json", &error));
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        BodyDesc b = w.document()->body(1);
        b.restitution = 0.3;
        w.document()->setBody(1, b, "Restitution");
        QString asked;
        answerNextMessageBox(QMessageBox::Cancel, &asked);
        QVERIFY(!w.close());
        QVERIFY2(asked.contains("bouncing-ball.json"), qPrintable(asked));
        QVERIFY(w.windowTitle().startsWith("bouncing-ball.json"));
    }

    // The View menu's overlays switch the viewport's, and the next window remembers them.
    void overlaysFromTheViewMenu() {
        {
            MainWindow w;
            QCOMPARE(w.viewport()->timeline(), w.timeline());
            auto* contacts =
                w.findChild<QAction*>(QStringLiteral("overlay%1").arg(int(Viewport::Overlay::Contacts)));
            QVERIFY(contacts);
            QCOMPARE(contacts->text(), Viewport::overlayText(Viewport::Overlay::Contacts));
            QVERIFY(!w.viewport()->overlay(Viewport::Overlay::Contacts));
            contacts->trigger();
            QVERIFY(w.viewport()->overlay(Viewport::Overlay::Contacts));
            w.viewport()->setOverlay(Viewport::Overlay::Contacts,
                                     false);  // from elsewhere: the check follows
            QVERIFY(!contacts->isChecked());
            contacts->trigger();
        }
        MainWindow again;
        QVERIFY(again.viewport()->overlay(Viewport::Overlay::Contacts));
        QVERIFY(!again.viewport()->overlay(Viewport::Overlay::Trails));
        again.findChild<QAction*>(QStringLiteral("overlay%1").arg(int(Viewport::Overlay::Contacts)))
            ->trigger();
    }

    // Issue 21 item 10: the overlays' menu stays open while its boxes are ticked (it
    // closed at each: three overlays, nine clicks), and Alt+N switches overlay N.
    void overlaysAreTickedWithTheMenuOpen() {
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        auto* contacts = w.findChild<QAction*>(QStringLiteral("overlay%1").arg(int(Viewport::Overlay::Contacts)));
        auto* forces = w.findChild<QAction*>(QStringLiteral("overlay%1").arg(int(Viewport::Overlay::Forces)));
        QVERIFY(contacts && forces);
        auto* menu = qobject_cast<QMenu*>(contacts->parent());
        QVERIFY(menu);
        const bool before = w.viewport()->overlay(Viewport::Overlay::Contacts);
        const bool forcesBefore = w.viewport()->overlay(Viewport::Overlay::Forces);
        // Whatever happens below, the overlays are left as they were (the choice is kept
        // between sessions, and overlaysFromTheViewMenu starts from the defaults).
        const auto restore = qScopeGuard([&] {
            if (contacts->isChecked() != before) contacts->trigger();
            if (forces->isChecked() != forcesBefore) forces->trigger();
        });
        menu->popup(w.mapToGlobal(QPoint(100, 100)));
        QVERIFY(QTest::qWaitForWindowExposed(menu));
        QTest::mouseClick(menu, Qt::LeftButton, Qt::NoModifier, menu->actionGeometry(contacts).center());
        QCOMPARE(w.viewport()->overlay(Viewport::Overlay::Contacts), !before);
        QVERIFY(menu->isVisible());
        QTest::mouseClick(menu, Qt::LeftButton, Qt::NoModifier, menu->actionGeometry(forces).center());
        QCOMPARE(w.viewport()->overlay(Viewport::Overlay::Forces), !forcesBefore);
        QVERIFY(menu->isVisible());
        menu->close();
        QCOMPARE(contacts->shortcut(), QKeySequence(Qt::ALT | Qt::Key_2));
    }

    // Help > Keyboard Shortcuts (F1) lists every key, from the actions themselves: each
    // menu item with a key, the View menu's viewport keys, the overlays', the viewport's
    // camera keys.
    void helpListsEveryShortcut() {
        MainWindow w;
        const QList<ShortcutRow> rows = w.shortcuts();
        auto has = [&](const QString& menu, const QString& command, const QString& keys) {
            for (const ShortcutRow& r : rows)
                if (r.menu == menu && r.command == command && r.keys == keys) return true;
            return false;
        };
        QVERIFY(has("View", "Frame Selection", "F"));
        QVERIFY(has("View", "Frame All", "A"));
        QVERIFY(has("View", "Move Handles", "W"));
        QVERIFY(has("View > Overlays", Viewport::overlayText(Viewport::Overlay::Contacts),
                    QKeySequence(Qt::ALT | Qt::Key_2).toString(QKeySequence::NativeText)));
        QVERIFY(has("Edit", "Undo", QKeySequence(QKeySequence::Undo).toString(QKeySequence::NativeText)));
        QVERIFY(has("Viewport", "Zoom in / out", "+ / -"));
        // Every action of the menus that has a key is listed.
        int keyed = 0;
        for (QAction* a : w.findChildren<QAction*>())
            if (!a->shortcut().isEmpty() && !a->associatedObjects().isEmpty()) ++keyed;
        QVERIFY(keyed > 10);
        auto* help = w.findChild<QAction*>("helpShortcuts");
        QVERIFY(help);
        QCOMPARE(help->shortcut(), QKeySequence(QKeySequence::HelpContents));
        int shown = -1;
        QTimer::singleShot(0, &w, [&] {
            auto* dialog = qobject_cast<QDialog*>(QApplication::activeModalWidget());
            if (!dialog) return;
            if (auto* table = dialog->findChild<QTableWidget*>("shortcuts")) shown = table->rowCount();
            dialog->reject();
        });
        help->trigger();
        QCOMPARE(shown, int(rows.size()));
    }

    // A scene with a missing mesh opens: the body is marked in the tree and the run fails
    // with a message naming it, the scene untouched.
    void aMissingMeshIsMarkedAndNamed() {
        QTemporaryDir dir;
        QVERIFY(QFile::copy(TUMBLE_SCENES_DIR "/../meshes/box.stl", dir.filePath("box.stl")));
        QFile f(dir.filePath("s.json"));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"format": "tumble-scene", "version": 1, "bodies": [
            {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}},
            {"name": "rock", "shape": {"type": "mesh", "file": "rock.obj"}, "density": 1000, "position": [0, 2, 0]},
            {"name": "box", "shape": {"type": "mesh", "file": "box.stl"}, "density": 1000, "position": [3, 2, 0]}]})");
        f.close();
        MainWindow w;
        QString error;
        QVERIFY2(w.openScene(dir.filePath("s.json"), &error), qPrintable(error));
        QCOMPARE(w.document()->openWarnings().size(), 1);
        auto* tree = w.findChild<QAbstractItemView*>();
        QVERIFY(tree);
        const QModelIndex shape = tree->model()->index(1, 2);
        QVERIFY2(shape.data().toString().contains("missing"), qPrintable(shape.data().toString()));
        QVERIFY(shape.data(Qt::ToolTipRole).toString().contains("rock.obj"));
        QVERIFY(!tree->model()->index(2, 2).data().toString().contains("missing"));
        const SceneDesc scene = w.scene();
        QVERIFY(QTest::qWaitFor([&] { return w.timeline()->status() == Timeline::Status::Failed; }, 60000));
        QVERIFY2(w.timeline()->errorMessage().contains("bodies[1]"),
                 qPrintable(w.timeline()->errorMessage()));
        QCOMPARE(w.scene(), scene);
    }

    // Issue 21 item 10: Save As with a name typed without an extension writes NAME.json,
    // which the Open dialog's filter shows.
    void saveAsAddsTheExtension() {
        QTemporaryDir dir;
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(":/scenes/bouncing-ball.json", &error));
        QAction* saveAs = nullptr;
        for (QAction* a : w.findChildren<QAction*>())
            if (a->text() == "Save &As...") saveAs = a;
        QVERIFY(saveAs);
        bool answered = false;
        QTimer::singleShot(0, &w, [&] {
            auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
            if (!dialog) return;
            chooseFile(dialog, QDir(dir.path()).filePath("my-scene"));  // as its Save button does
            answered = true;
        });
        saveAs->trigger();
        QVERIFY(answered);
        QVERIFY2(QFileInfo::exists(QDir(dir.path()).filePath("my-scene.json")),
                 qPrintable(QDir(dir.path()).entryList(QDir::Files).join(", ")));
        QVERIFY(!QFileInfo::exists(QDir(dir.path()).filePath("my-scene")));
        QCOMPARE(w.scenePath(), QDir(dir.path()).filePath("my-scene.json"));
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
