// The Khronos glTF validator (npm package gltf-validator) run on a file through node, for
// the tests. ./dev.sh test installs it into the build folder (TUMBLE_GLTF_VALIDATOR, the
// package's folder; the environment variable of that name overrides it). A missing
// validator or node fails the test that asks: CI must validate, never skip.
#pragma once

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

namespace tumble::test {

struct ValidatorReport {
    bool ran = false;
    QString problem;  ///< why it did not run
    int errors = -1, warnings = -1;
    QString messages;  ///< every message, one a line
};

inline ValidatorReport validateGltf(const QString& file) {
    ValidatorReport r;
    QString validator = qEnvironmentVariable("TUMBLE_GLTF_VALIDATOR");
#ifdef TUMBLE_GLTF_VALIDATOR
    if (validator.isEmpty()) validator = TUMBLE_GLTF_VALIDATOR;
#endif
    if (validator.isEmpty() || !QFileInfo::exists(validator + "/package.json")) {
        r.problem = "the glTF validator is not installed at '" + validator +
                    "' (./dev.sh test installs it: npm install --prefix BUILD/gltf-validator "
                    "gltf-validator@2.0.0-dev.3.10)";
        return r;
    }
    QString node = QStandardPaths::findExecutable("node");
    if (node.isEmpty()) node = QStandardPaths::findExecutable("nodejs");
    if (node.isEmpty()) {
        r.problem = "node is not installed (./dev.sh installs nodejs)";
        return r;
    }
    QTemporaryDir dir;
    const QString script = dir.filePath("validate.js");
    {
        QFile f(script);
        if (!f.open(QIODevice::WriteOnly)) {
            r.problem = "cannot write " + script;
            return r;
        }
        f.write(R"(
const fs = require('fs'), path = require('path');
const validator = require(process.argv[2]);
const file = process.argv[3];
validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
  uri: path.basename(file),
  maxIssues: 0,
  externalResourceFunction: (uri) => new Promise((resolve, reject) => {
    try { resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))); }
    catch (e) { reject(e.toString()); }
  })
}).then((report) => { console.log(JSON.stringify(report.issues)); })
  .catch((e) => { console.error('validator failed: ' + e); process.exit(2); });
)");
    }
    QProcess p;
    p.start(node, {script, validator, file});
    if (!p.waitForFinished(120000) || p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0) {
        r.problem = "the validator did not run: " + QString::fromUtf8(p.readAllStandardError());
        return r;
    }
    const QJsonObject issues = QJsonDocument::fromJson(p.readAllStandardOutput()).object();
    if (!issues.contains("numErrors")) {
        r.problem = "the validator gave no report";
        return r;
    }
    r.ran = true;
    r.errors = issues.value("numErrors").toInt();
    r.warnings = issues.value("numWarnings").toInt();
    for (const QJsonValue& m : issues.value("messages").toArray()) {
        const QJsonObject o = m.toObject();
        r.messages += QString::number(o.value("severity").toInt()) + " " + o.value("code").toString() + " " +
                      o.value("pointer").toString() + ": " + o.value("message").toString() + "\n";
    }
    return r;
}

}  // namespace tumble::test

/// Fails the current test unless the validator ran on `file` and found no error.
#define TUMBLE_VERIFY_GLTF_VALID(file)                                                       \
    do {                                                                                     \
        const tumble::test::ValidatorReport report_ = tumble::test::validateGltf(file);      \
        QVERIFY2(report_.ran, qPrintable(report_.problem));                                  \
        QVERIFY2(report_.errors == 0, qPrintable(QString(file) + ":\n" + report_.messages)); \
    } while (false)
