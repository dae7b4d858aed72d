// "-" for a file (issue 47 item 9): a scene read from standard input, and the trajectory,
// the measures or the saved scene written to standard output, all or nothing: the bytes a
// file would hold, only once the run has succeeded, the report then on standard error, and
// nothing left in TMPDIR.
#include <tumble/io/scene_file.h>

#include <QJsonDocument>
#include <QJsonObject>
#include <QtTest>

#include "../io/gltf_validator.h"
#include "cli_harness.h"

using namespace tumble::clitest;

class TestStdio : public QObject, private Harness {
    Q_OBJECT

    QStringList leftInTmp() const {
        return QDir(tmp_->path()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot);
    }

private slots:
    void init() { makeFolder(); }
    void cleanup() { dir_.reset(); }

    // The scene from standard input runs as the file does: the same report, hash included.
    void sceneFromStandardInput() {
        RUN(file, {"--headless", "box.json"});
        RUN(piped, {"--headless", "-"}, QByteArray(kBox));
        QCOMPARE(piped.code, 0);
        QCOMPARE(piped.err, QString());
        QCOMPARE(report(piped.out).value("state_hash"), report(file.out).value("state_hash"));
        QVERIFY(!report(file.out).value("state_hash").isEmpty());
    }

    // Its messages name <stdin>, with the field, as they name a file.
    void badSceneFromStandardInput() {
        QByteArray broken = kBox;
        broken.replace("\"mass\": 2", "\"mass\": -2");
        RUN(r, {"--headless", "-", "--out", "-"}, broken);
        QCOMPARE(r.code, 2);
        QCOMPARE(r.outBytes, QByteArray());
        QVERIFY2(r.err.startsWith("<stdin>: ") && r.err.contains("mass"), qPrintable(r.err));
        RUN(empty, {"--headless", "-"}, QByteArray());
        QCOMPARE(empty.code, 2);
        QVERIFY2(empty.err.startsWith("<stdin>: "), qPrintable(empty.err));
    }

    void trajectoryToStandardOutput_data() {
        QTest::addColumn<QString>("format");
        QTest::addColumn<QString>("file");
        QTest::newRow("csv (default)") << QString() << "t.csv";
        QTest::newRow("csv") << "csv"
                             << "t.csv";
        QTest::newRow("json") << "json"
                              << "t.json";
        QTest::newRow("glb") << "glb"
                             << "box.glb";  // the root node is named after the file: the scene's
    }

    // The bytes on standard output are the file's, and the report moves to standard error.
    void trajectoryToStandardOutput() {
        QFETCH(QString, format);
        QFETCH(QString, file);
        RUN(toFile, {"--headless", "box.json", "--out", file, "--quiet"});
        QCOMPARE(toFile.code, 0);
        QStringList args = {"--headless", "box.json", "--out", "-"};
        if (!format.isEmpty()) args << "--format" << format;
        RUN(r, args);
        QCOMPARE(r.code, 0);
        QVERIFY(!r.outBytes.isEmpty());
        QCOMPARE(r.outBytes, read(file));
        QVERIFY2(report(r.err).contains("state_hash"), qPrintable(r.err));
        QCOMPARE(leftInTmp(), QStringList());
        if (format == "glb") {
            write("piped.glb", r.outBytes);
            TUMBLE_VERIFY_GLTF_VALID(path("piped.glb"));
        }
    }

    // --metrics - and --save-scene -: the JSON on standard output; the saved scene reads back.
    void measuresAndSceneToStandardOutput() {
        RUN(m, {"--headless", "box.json", "--metrics", "-", "--quiet"});
        QCOMPARE(m.code, 0);
        const QJsonObject metrics = QJsonDocument::fromJson(m.outBytes).object();
        QVERIFY2(metrics.contains("run") && metrics.contains("bodies"), m.outBytes.constData());
        RUN(s, {"--headless", "-", "--save-scene", "-", "--duration", "0.25"}, QByteArray(kBox));
        QCOMPARE(s.code, 0);
        const tumble::SceneDesc saved = tumble::io::parseScene(s.outBytes.toStdString(), "saved");
        QCOMPARE(saved.settings.duration, 0.25);
        QCOMPARE(saved.bodies.size(), size_t(2));
        QVERIFY(report(s.err).contains("state_hash"));
    }

    // A run that fails writes nothing on standard output, and leaves nothing in TMPDIR.
    void aFailedRunWritesNothing() {
        RUN(r, {"--headless", "blow.json", "--out", "-"});
        QCOMPARE(r.code, 1);
        QCOMPARE(r.outBytes, QByteArray());
        QVERIFY2(r.err.contains("blow.json"), qPrintable(r.err));
        QCOMPARE(leftInTmp(), QStringList());
    }

    void refused_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<QString>("message");
        QTest::newRow("two to stdout") << QStringList({"--out", "-", "--metrics", "-"})
                                       << "tumble: only one of --out, --save-scene and --metrics can be - "
                                          "(standard output carries one file)\n";
        QTest::newRow("format with a file") << QStringList({"--out", "t.csv", "--format", "json"})
                                            << "tumble: --format: only for --out - (a file's format follows "
                                               "its extension)\n";
        QTest::newRow("gltf")
            << QStringList({"--out", "-", "--format", "gltf"})
            << "tumble: --format: 'gltf' is not one of csv, json, glb (the formats standard "
               "output can carry)\n";
    }

    void refused() {
        QFETCH(QStringList, args);
        QFETCH(QString, message);
        RUN(r, QStringList({"--headless", "box.json"}) + args);
        QCOMPARE(r.code, 2);
        QCOMPARE(r.err, message);
        QCOMPARE(r.outBytes, QByteArray());
        QCOMPARE(entries(), QStringList({"blow.json", "box.json"}));
    }

    // A sweep needs its scene as a file: it reads it again to resume.
    void aSweepOfStandardInputIsRefused() {
        RUN(r, {"sweep", "-", "--vary", "box.mass=1,2", "--out", "sw"}, QByteArray(kBox));
        QCOMPARE(r.code, 2);
        QVERIFY2(r.err.contains("the scene must be a file, not -"), qPrintable(r.err));
        QVERIFY(!QFile::exists(path("sw")));
    }
};

QTEST_GUILESS_MAIN(TestStdio)
#include "tst_stdio.moc"
