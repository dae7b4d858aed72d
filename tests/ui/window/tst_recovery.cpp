// Crash recovery in the editor (issue 46): each editor's own autosave, the leftovers of an
// editor that did not end cleanly, and the recovery prompt's Recover, Discard and Later.
#include "document/document.h"
#include "message_box_answer.h"
#include "window/autosave.h"
#include "window/main_window.h"

#include <QFile>
#include <QStandardPaths>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;
using tumble::ui::test::answerNextMessageBox;

class TestRecovery : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

    void autosaveAndRecovery() {
        for (const AutosaveLeftover& l : Autosave::leftovers()) Autosave::discard(l);
        SceneDesc edited;
        QString file;
        {
            MainWindow w;
            file = w.autosavePath();
            w.autosave();  // nothing unsaved: no file
            QVERIFY(!QFile::exists(file));
            BodyDesc ball;
            ball.name = "ball";
            ball.mass = 2.0;
            ball.position = Vec3(0, 3, 0);
            w.document()->addBody(ball);
            w.autosave();
            QVERIFY(QFile::exists(file));
            QVERIFY(Autosave::leftovers().isEmpty());  // its editor runs: not a leftover
            edited = w.scene();
            // The window is destroyed without closing: as after a crash, the file stays.
        }
        const QList<AutosaveLeftover> left = Autosave::leftovers();
        QCOMPARE(left.size(), 1);
        QCOMPARE(left.first().file, file);
        QVERIFY(left.first().scenePath.isEmpty());  // untitled
        MainWindow next;
        QString error;
        QVERIFY2(next.recoverAutosave(&error), qPrintable(error));
        QCOMPARE(next.scene(), edited);
        QVERIFY(next.isWindowModified());  // recovered work is unsaved work
        QVERIFY(next.document()->filePath().isEmpty());
        QVERIFY(!QFile::exists(file));  // taken over: the next editor's own autosave holds it
        QVERIFY(QFile::exists(next.autosavePath()));
        next.document()->undoStack()->undo();
        QCOMPARE(next.document()->bodyCount(), 1);  // back to the new scene
        next.autosave();
        QVERIFY(!QFile::exists(next.autosavePath()));
    }

    // Issue 46: Later keeps a leftover for the next start, which offers it again with its
    // time; Recover there brings it back; Discard deletes it.
    void laterThenRecoverThenDiscard() {
        for (const AutosaveLeftover& l : Autosave::leftovers()) Autosave::discard(l);
        auto leaveOne = [](double y) {
            MainWindow w;  // destroyed without closing, as after a crash
            BodyDesc ball;
            ball.name = "ball";
            ball.mass = 1.0;
            ball.position = Vec3(0, y, 0);
            w.document()->addBody(ball);
            w.autosave();
        };
        leaveOne(3.0);
        QString asked;
        {
            MainWindow w;
            answerNextMessageBox(QStringLiteral("Later"), &asked);
            w.offerRecovery();
            QVERIFY2(asked.contains("untitled scene") && asked.contains("autosaved"), qPrintable(asked));
            QCOMPARE(w.document()->bodyCount(), 1);     // nothing recovered
            QCOMPARE(Autosave::leftovers().size(), 1);  // kept
        }
        {
            MainWindow w;
            answerNextMessageBox(QStringLiteral("Recover"), &asked);
            w.offerRecovery();
            QCOMPARE(w.document()->bodyCount(), 2);
            QCOMPARE(w.document()->body(1).position.y(), 3.0);
            QVERIFY(w.isWindowModified());
            QVERIFY(Autosave::leftovers().isEmpty());  // this editor holds it now
            w.document()->undoStack()->undo();
            w.autosave();
        }
        leaveOne(4.0);
        {
            MainWindow w;
            answerNextMessageBox(QStringLiteral("Discard"), &asked);
            w.offerRecovery();
            QCOMPARE(w.document()->bodyCount(), 1);
            QVERIFY(Autosave::leftovers().isEmpty());
        }
    }

    void twoEditorsKeepTheirOwnAutosaves() {
        for (const AutosaveLeftover& l : Autosave::leftovers()) Autosave::discard(l);
        MainWindow a, b;
        QVERIFY(a.autosavePath() != b.autosavePath());
        BodyDesc ball;
        ball.name = "ball";
        a.document()->addBody(ball);
        b.document()->addBody(ball);
        b.document()->addBody(ball);
        a.autosave();
        b.autosave();
        QVERIFY(QFile::exists(a.autosavePath()) && QFile::exists(b.autosavePath()));
        QVERIFY(Autosave::leftovers().isEmpty());  // both editors run
        a.document()->undoStack()->undo();
        a.autosave();  // a has nothing unsaved: its file goes, b's stays
        QVERIFY(!QFile::exists(a.autosavePath()));
        QVERIFY(QFile::exists(b.autosavePath()));
        b.document()->undoStack()->undo();
        b.document()->undoStack()->undo();
        b.autosave();
    }
};

QTEST_MAIN(TestRecovery)
#include "tst_recovery.moc"
