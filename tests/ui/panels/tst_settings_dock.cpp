// The scene settings dock: each field's edit reaches the document as one undo step and
// undo brings the field back; a scrub is one step; a value the engine refuses never
// reaches the document, and the field says why and keeps its last good value.
#include "document/document.h"
#include "panels/settings_dock.h"

#include <tumble/integrators.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QSignalSpy>
#include <QSpinBox>
#include <QUndoStack>
#include <QtTest>

#include <functional>

using namespace tumble;
using namespace tumble::ui;

class TestSettingsDock : public QObject {
    Q_OBJECT

    template <typename W>
    static W* field(SettingsDock& dock, const char* name) {
        auto* w = dock.findChild<W*>(name);
        if (!w) qFatal("no field %s", name);
        return w;
    }

private slots:
    void eachLabelHasItsOwnAltKey() {
        // Alt+letter moves to a field: two labels with one letter (Gravity and Energy guard
        // both had G, Integrator and Solver iterations I) made the second unreachable.
        Document doc;
        SettingsDock dock(&doc, nullptr);
        QMap<QChar, QString> taken;
        int labels = 0;
        for (const QLabel* label : dock.findChildren<QLabel*>()) {
            const QString text = QString(label->text()).replace("&&", "");
            const qsizetype at = text.indexOf('&');
            if (at < 0 || at + 1 >= text.size()) continue;
            const QChar key = text[at + 1].toLower();
            QVERIFY2(!taken.contains(key), qPrintable(QString("'%1' and '%2' share Alt+%3")
                                                          .arg(taken.value(key), label->text(), key)));
            taken.insert(key, label->text());
            QVERIFY2(label->buddy() != nullptr, qPrintable(label->text() + " moves to no field"));
            ++labels;
        }
        QVERIFY(labels >= 9);  // every row of the form
    }

    void showsTheDocumentsSettingsWithUnits() {
        Document doc;
        SettingsDock dock(&doc, nullptr);
        const Settings& s = doc.scene().settings;
        QCOMPARE(field<QDoubleSpinBox>(dock, "gravityY")->value(), s.gravity.y());
        QCOMPARE(field<QDoubleSpinBox>(dock, "step")->value(), std::round(s.dt * 1e6) / 1e6);
        QCOMPARE(field<QDoubleSpinBox>(dock, "duration")->value(), s.duration);
        QCOMPARE(field<QDoubleSpinBox>(dock, "frameRate")->value(), s.frameRate);
        QCOMPARE(field<QCheckBox>(dock, "sleeping")->isChecked(), s.sleeping);
        QCOMPARE(field<QSpinBox>(dock, "iterations")->value(), s.solverIterations);
        QVERIFY(s.energyGuard);
        QVERIFY(field<QCheckBox>(dock, "energyGuard")->isChecked());
        for (const char* name : {"gravityX", "gravityY", "gravityZ", "step", "duration", "frameRate"})
            QVERIFY2(!field<QDoubleSpinBox>(dock, name)->suffix().trimmed().isEmpty(), name);
        QCOMPARE(field<QDoubleSpinBox>(dock, "gravityX")->suffix(), QString(" m/s²"));
        QCOMPARE(field<QDoubleSpinBox>(dock, "step")->suffix(), QString(" s"));
        QVERIFY(!field<QSpinBox>(dock, "iterations")->suffix().isEmpty());
    }

    // Issue 47 item 1: a dt longer than a frame steps once a frame; the dock says so under
    // the step, with the step used, and says nothing when dt divides a frame.
    void theStepUsedIsShownWhenItIsNotDt() {
        Document doc;
        SettingsDock dock(&doc, nullptr);
        auto* note = field<QLabel>(dock, "step.note");
        QVERIFY(note->isHidden());  // 1/240 s: four steps a frame at 60 frames a second
        Settings s = doc.scene().settings;
        s.dt = 1.0 / 30.0;
        doc.setSettings(s, "step");
        QVERIFY(!note->isHidden());
        QVERIFY2(
            note->text().contains("longer than a frame") && note->text().contains("one step of 0.0166667 s"),
            qPrintable(note->text()));
        s.frameRate = 30.0;
        doc.setSettings(s, "frame rate");
        QVERIFY(note->isHidden());
    }

    void theIntegratorListIsTheEngines() {
        Document doc;
        SettingsDock dock(&doc, nullptr);
        auto* combo = field<QComboBox>(dock, "integrator");
        QCOMPARE(combo->count(), int(integrators().size()) + 1);  // and "Default"
        QCOMPARE(combo->currentIndex(), 0);
        QCOMPARE(combo->itemData(0).toString(), QString());
        for (const IntegratorInfo& info : integrators())
            QVERIFY2(combo->findData(QString::fromLatin1(info.name)) > 0, info.name);
    }

    void eachFieldReachesTheDocumentAndUndoRestoresIt_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<double>("value");
        QTest::newRow("gravity x") << "gravityX" << 1.5;
        QTest::newRow("gravity y") << "gravityY" << -1.62;
        QTest::newRow("gravity z") << "gravityZ" << 0.25;
        QTest::newRow("step") << "step" << 0.002;
        QTest::newRow("duration") << "duration" << 12.5;
        QTest::newRow("frame rate") << "frameRate" << 30.0;
        QTest::newRow("iterations") << "iterations" << 7.0;
        QTest::newRow("sleeping") << "sleeping" << 0.0;
        QTest::newRow("energy guard") << "energyGuard" << 0.0;
        QTest::newRow("integrator rk4") << "integrator" << 0.0;
        QTest::newRow("impacts at the end of the step") << "impacts" << 0.0;
    }

    void eachFieldReachesTheDocumentAndUndoRestoresIt() {
        QFETCH(QString, name);
        QFETCH(double, value);
        Document doc;
        SettingsDock dock(&doc, nullptr);
        const Settings before = doc.scene().settings;
        const int steps = doc.undoStack()->count();

        // What each field is in the settings, and how the user sets it.
        std::function<bool(const Settings&)> holds;
        std::function<void()> set;
        std::function<bool()> showsBefore;
        const std::string n = name.toStdString();
        if (n == "sleeping") {
            auto* box = field<QCheckBox>(dock, "sleeping");
            set = [box] { box->click(); };
            holds = [&](const Settings& s) { return s.sleeping == !before.sleeping; };
            showsBefore = [box, &before] { return box->isChecked() == before.sleeping; };
        } else if (n == "energyGuard") {
            auto* box = field<QCheckBox>(dock, "energyGuard");
            set = [box] { box->click(); };
            holds = [&](const Settings& s) { return s.energyGuard == !before.energyGuard; };
            showsBefore = [box, &before] { return box->isChecked() == before.energyGuard; };
        } else if (n == "integrator") {
            auto* combo = field<QComboBox>(dock, "integrator");
            set = [combo] { combo->setCurrentIndex(combo->findData(QString("rk4"))); };
            holds = [](const Settings& s) { return s.integrator == "rk4"; };
            showsBefore = [combo] { return combo->currentIndex() == 0; };
        } else if (n == "impacts") {
            auto* combo = field<QComboBox>(dock, "impacts");
            set = [combo] { combo->setCurrentIndex(combo->findData(int(ImpactTiming::EndOfStep))); };
            holds = [](const Settings& s) { return s.impacts == ImpactTiming::EndOfStep; };
            showsBefore = [combo] { return combo->currentData().toInt() == int(ImpactTiming::Exact); };
        } else if (n == "iterations") {
            auto* spin = field<QSpinBox>(dock, "iterations");
            set = [spin, value] { spin->setValue(int(value)); };
            holds = [value](const Settings& s) { return s.solverIterations == int(value); };
            showsBefore = [spin, &before] { return spin->value() == before.solverIterations; };
        } else {
            auto* spin = field<QDoubleSpinBox>(dock, name.toLatin1().constData());
            const double shown = spin->value();
            set = [spin, value] { spin->setValue(value); };
            holds = [n, value](const Settings& s) {
                if (n == "gravityX") return s.gravity.x() == value;
                if (n == "gravityY") return s.gravity.y() == value;
                if (n == "gravityZ") return s.gravity.z() == value;
                if (n == "step") return s.dt == value;
                if (n == "duration") return s.duration == value;
                return s.frameRate == value;
            };
            showsBefore = [spin, shown] { return spin->value() == shown; };
        }

        set();
        QVERIFY(holds(doc.scene().settings));
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        QVERIFY(!doc.undoStack()->undoText().isEmpty());
        // Only that field changed.
        Settings expected = doc.scene().settings;
        QVERIFY(!(expected == before));
        doc.undoStack()->undo();
        QVERIFY(doc.scene().settings == before);
        QVERIFY(showsBefore());                         // the field followed the undo
        QCOMPARE(doc.undoStack()->count(), steps + 1);  // and the dock pushed nothing back
        doc.undoStack()->redo();
        QVERIFY(holds(doc.scene().settings));
        QVERIFY(!showsBefore());
    }

    void aScrubIsOneUndoStep() {
        Document doc;
        SettingsDock dock(&doc, nullptr);
        auto* gravityY = field<QDoubleSpinBox>(dock, "gravityY");
        const double before = doc.scene().settings.gravity.y();
        const int steps = doc.undoStack()->count();
        for (int k = 0; k < 10; ++k) gravityY->stepBy(1);  // as the arrows or the wheel do
        QCOMPARE(doc.scene().settings.gravity.y(), gravityY->value());
        QVERIFY(std::abs(gravityY->value() - (before + 1.0)) < 1e-9);
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        // The entry says what changed and to what (issue 52).
        QCOMPARE(doc.undoStack()->undoText(), QString("Set gravity y to %1").arg(gravityY->text()));
        QVERIFY(gravityY->text().endsWith("m/s²"));
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().settings.gravity.y(), before);
        QCOMPARE(gravityY->value(), before);

        // Another field after the scrub is a step of its own; so is the same field once
        // its edit was finished.
        doc.undoStack()->redo();
        field<QDoubleSpinBox>(dock, "duration")->stepBy(1);
        QCOMPARE(doc.undoStack()->count(), steps + 2);
        auto* duration = field<QDoubleSpinBox>(dock, "duration");
        emit duration->editingFinished();
        duration->stepBy(1);
        QCOMPARE(doc.undoStack()->count(), steps + 3);
    }

    void anInvalidValueIsRefusedWithAMessage_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<double>("value");
        QTest::addColumn<QString>("why");
        QTest::newRow("step 0") << "step" << 0.0 << "greater than 0";
        QTest::newRow("frame rate 0") << "frameRate" << 0.0 << "greater than 0";
        QTest::newRow("too many frames") << "duration" << 5e6 << "10^8 frames";
        QTest::newRow("no solver iterations") << "iterations" << 0.0 << "from 1 to 10000";
    }

    void anInvalidValueIsRefusedWithAMessage() {
        QFETCH(QString, name);
        QFETCH(double, value);
        QFETCH(QString, why);
        Document doc;
        SettingsDock dock(&doc, nullptr);
        const Settings before = doc.scene().settings;
        const int steps = doc.undoStack()->count();
        QSignalSpy changed(&doc, &Document::settingsChanged);
        auto* message = field<QLabel>(dock, (name + "Message").toLatin1().constData());
        QVERIFY(message->isHidden());

        double shownBefore = 0.0;
        double shownAfter = 0.0;
        if (name == "iterations") {
            auto* spin = field<QSpinBox>(dock, "iterations");
            shownBefore = spin->value();
            spin->setValue(int(value));
            shownAfter = spin->value();
        } else {
            auto* spin = field<QDoubleSpinBox>(dock, name.toLatin1().constData());
            QVERIFY(spin->minimum() <= value &&
                    value <= spin->maximum());  // the spin box lets it through ...
            shownBefore = spin->value();
            spin->setValue(value);
            shownAfter = spin->value();
        }
        // ... the document does not, and the field is back at its last good value.
        QVERIFY(doc.scene().settings == before);
        QCOMPARE(doc.undoStack()->count(), steps);
        QCOMPARE(changed.count(), 0);
        QCOMPARE(shownAfter, shownBefore);
        QVERIFY(!message->isHidden());
        QVERIFY2(message->text().contains(why), qPrintable(message->text()));

        // A good value afterwards goes through and clears the message.
        if (name == "iterations")
            field<QSpinBox>(dock, "iterations")->setValue(5);
        else
            field<QDoubleSpinBox>(dock, name.toLatin1().constData())
                ->setValue(name == "duration" ? 20.0 : 0.5);
        QCOMPARE(doc.undoStack()->count(), steps + 1);
        QVERIFY(message->isHidden());
    }

    void anInvalidValueThroughTheApiIsRefused() {
        Document doc;
        SettingsDock dock(&doc, nullptr);
        const Settings before = doc.scene().settings;
        Settings bad = before;
        bad.frameRate = -30.0;
        QVERIFY(!dock.trySetSettings(SettingsDock::FrameRate, bad));
        QVERIFY(dock.message(SettingsDock::FrameRate).contains("greater than 0"));
        bad = before;
        bad.gravity.x() = std::numeric_limits<double>::quiet_NaN();
        QVERIFY(!dock.trySetSettings(SettingsDock::GravityX, bad));
        QVERIFY(dock.message(SettingsDock::GravityX).contains("finite"));
        bad = before;
        bad.integrator = "leapfrog";
        QVERIFY(!dock.trySetSettings(SettingsDock::Integrator, bad));
        QVERIFY(dock.message(SettingsDock::Integrator).contains("unknown integrator"));
        QVERIFY(doc.scene().settings == before);
        QVERIFY(!doc.undoStack()->canUndo());
    }

    void followsTheDocumentWithoutEchoes() {
        Document doc;
        SettingsDock dock(&doc, nullptr);
        Settings s = doc.scene().settings;
        s.dt = 0.01;
        s.sleeping = !s.sleeping;
        s.energyGuard = false;
        s.integrator = "euler";
        s.impacts = ImpactTiming::EndOfStep;
        doc.setSettings(s, "From elsewhere");
        QCOMPARE(doc.undoStack()->count(), 1);  // the dock's refresh pushed nothing
        QCOMPARE(field<QDoubleSpinBox>(dock, "step")->value(), 0.01);
        QCOMPARE(field<QCheckBox>(dock, "sleeping")->isChecked(), s.sleeping);
        QVERIFY(!field<QCheckBox>(dock, "energyGuard")->isChecked());
        QCOMPARE(field<QComboBox>(dock, "integrator")->currentData().toString(), QString("euler"));
        QCOMPARE(field<QComboBox>(dock, "impacts")->currentData().toInt(), int(ImpactTiming::EndOfStep));

        // Opening a scene shows its settings and clears old messages.
        field<QDoubleSpinBox>(dock, "step")->setValue(0.0);
        QVERIFY(!dock.message(SettingsDock::Step).isEmpty());
        QString error;
        QVERIFY2(doc.open(":/scenes/newtons-cradle.json", &error), qPrintable(error));
        QVERIFY(dock.message(SettingsDock::Step).isEmpty());
        QCOMPARE(field<QDoubleSpinBox>(dock, "frameRate")->value(), doc.scene().settings.frameRate);
        QCOMPARE(field<QDoubleSpinBox>(dock, "duration")->value(), doc.scene().settings.duration);
        QVERIFY(!doc.undoStack()->canUndo());
    }
};

QTEST_MAIN(TestSettingsDock)
#include "tst_settings_dock.moc"
