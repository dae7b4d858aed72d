// The scene document: every edit is an undo step, drags merge, macros group, files round
// trip, bad files leave the scene untouched, the selection follows inserts and removals.
#include "document.h"

#include <tumble/io/scene_file.h>

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest>

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
        QCOMPARE(doc.undoStack()->undoText(), QString("Set restitution"));
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
    }
};

QTEST_MAIN(TestDocument)
#include "tst_document.moc"
