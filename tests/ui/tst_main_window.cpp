// The editor window, as a user sees it: it opens the default sample scene, lists the
// bodies, and refuses a bad scene without losing the open one.
#include "main_window.h"

#include <QTemporaryDir>
#include <QTreeWidget>
#include <QtTest>

using namespace tumble::ui;

class TestMainWindow : public QObject {
    Q_OBJECT
private slots:
    void opensTheDefaultSample() {
        MainWindow w;
        QString error;
        QVERIFY2(w.openScene(MainWindow::defaultScenePath(), &error), qPrintable(error));
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        QCOMPARE(w.windowTitle(), QString("tumbling-box.json - Tumble"));
        auto* tree = w.findChild<QTreeWidget*>();
        QVERIFY(tree);
        QCOMPARE(tree->topLevelItemCount(), int(w.scene().bodies.size()));
        QCOMPARE(tree->topLevelItem(0)->text(0), QString("box"));
        QCOMPARE(tree->topLevelItem(0)->text(3), QString("1"));
    }

    void everySampleOpens() {
        for (const char* name : {"tumbling-box.json", "spring-pendulum.json", "projectile.json"}) {
            MainWindow w;
            QString error;
            QVERIFY2(w.openScene(QString(":/scenes/") + name, &error), qPrintable(error));
        }
    }

    void badSceneKeepsTheOpenOne() {
        QTemporaryDir dir;
        const QString bad = dir.filePath("bad.json");
        QFile f(bad);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"format": "tumble-scene", "version": 1, "bodies": [{"name": "b", "shape": {"type": "sphere", "radius": -1}, "mass": 1}]})");
        f.close();
        MainWindow w;
        QString error;
        QVERIFY(w.openScene(MainWindow::defaultScenePath(), &error));
        QVERIFY(!w.openScene(bad, &error));
        QCOMPARE(error, bad + ": bodies[0].shape.radius: must be greater than 0");
        QCOMPARE(w.scenePath(), MainWindow::defaultScenePath());
        QVERIFY(!w.openScene(dir.filePath("missing.json"), &error));
        QVERIFY(error.contains("missing.json"));
    }
};

QTEST_MAIN(TestMainWindow)
#include "tst_main_window.moc"
