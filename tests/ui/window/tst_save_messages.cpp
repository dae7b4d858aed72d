// What the editor says when a write goes wrong behind the user's back (issue 46 item 3):
// an autosave that cannot be written is in the status bar until one succeeds again (the
// work is not protected meanwhile), and a Save of a scene whose mesh files were removed or
// changed on disk since they were read names them. tests/ui/window/tst_write_faults.cpp runs
// every write under a full disk, a read-only one and kills.
#include "document/document.h"
#include "message_box_answer.h"
#include "window/autosave.h"
#include "window/main_window.h"

#include <QAction>
#include <QDir>
#include <QFile>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;
using tumble::ui::test::answerNextMessageBox;

class TestSaveMessages : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

    void aFailedAutosaveIsShownUntilOneSucceeds() {
        MainWindow w;
        BodyDesc ball;
        ball.name = "ball";
        ball.mass = 1.0;
        w.document()->addBody(ball);
        // The autosave folder made impossible: a file where the folder should be.
        const QString folder = Autosave::folder();
        const QString aside = folder + ".aside";
        QDir().rename(folder, aside);
        {
            QFile blocker(folder);
            QVERIFY(blocker.open(QIODevice::WriteOnly));
        }
        w.autosave();
        const QString said = w.statusBar()->currentMessage();
        QVERIFY2(said.startsWith("Autosave failed: ") &&
                     said.contains(QFileInfo(w.autosavePath()).fileName()) && said.contains("Save your work"),
                 qPrintable(said));
        QVERIFY(QFile::remove(folder));
        if (QFileInfo::exists(aside)) QVERIFY(QDir().rename(aside, folder));
        w.autosave();
        QVERIFY(QFile::exists(w.autosavePath()));
        QVERIFY2(w.statusBar()->currentMessage().isEmpty(), qPrintable(w.statusBar()->currentMessage()));
    }

    void saveNamesTheMeshFilesChangedOnDisk() {
        QTemporaryDir root;
        QVERIFY(QFile::copy(QStringLiteral(TUMBLE_SCENES_DIR "/../meshes/l-prism.obj"),
                            root.filePath("prism.obj")));
        {
            QFile scene(root.filePath("scene.json"));
            QVERIFY(scene.open(QIODevice::WriteOnly));
            scene.write(R"({"format": "tumble-scene", "version": 1, "bodies": [
                {"name": "prism", "shape": {"type": "mesh", "file": "prism.obj"}, "density": 1000}]})");
        }
        MainWindow w;
        QString error;
        QVERIFY2(w.openScene(root.filePath("scene.json"), &error), qPrintable(error));
        QAction* save = w.findChild<QAction*>("fileSave");
        QVERIFY(save);
        save->trigger();  // nothing changed: no message box
        QVERIFY(!QApplication::activeModalWidget());
        {
            QFile mesh(root.filePath("prism.obj"));
            QVERIFY(mesh.open(QIODevice::Append));
            mesh.write("# changed\n");
        }
        QString text;
        answerNextMessageBox(QMessageBox::Ok, &text);
        save->trigger();
        QVERIFY2(text.contains("scene.json was saved") && text.contains("prism.obj (changed)"),
                 qPrintable(text));
    }
};

QTEST_MAIN(TestSaveMessages)
#include "tst_save_messages.moc"
