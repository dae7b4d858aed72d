// The property panel's read-only state at the playhead: the values of the recorded frame,
// checked against the closed-form projectile; hidden for several bodies; marked stale.
#include "document/document.h"
#include "panels/live_state_box.h"
#include "panels/property_dock.h"
#include "timeline/timeline.h"

#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

Vec3 parseVector(const QString& text) {
    const QStringList parts = text.section(' ', 0, 2).split(',', Qt::SkipEmptyParts);
    if (parts.size() != 3) return Vec3::Constant(std::nan(""));
    return Vec3(parts[0].trimmed().toDouble(), parts[1].trimmed().toDouble(), parts[2].trimmed().toDouble());
}

}  // namespace

class TestLiveState : public QObject {
    Q_OBJECT
private slots:
    // The projectile sample: a 0.43 kg ball of radius 0.11 m thrown at (8, 9.81, 0) m/s from
    // (0, 1, 0) spinning at -20 rad/s about z; it is in the air for the whole 2 s.
    void showsTheFrameAtThePlayhead() {
        Document doc;
        QString error;
        QVERIFY(doc.open(":/scenes/projectile.json", &error));
        Timeline t(&doc);
        PropertyDock dock(&doc);
        dock.setTimeline(&t);
        dock.show();
        doc.setSelection({1});
        t.simulate();
        QVERIFY(QTest::qWaitFor([&] { return t.status() == Timeline::Status::Complete; }, 60000));
        auto* box = dock.findChild<LiveStateBox*>();
        QVERIFY(box);
        const int k = 45;  // t = 1.5 s at 30 frames/s
        t.seek(k);
        QVERIFY(box->isVisible());
        const double time = 1.5, g = 9.81, m = 0.43, r = 0.11;
        const Vec3 x(8.0 * time, 1.0 + 9.81 * time - 0.5 * g * time * time, 0.0);
        const Vec3 v(8.0, 9.81 - g * time, 0.0);
        QVERIFY((parseVector(box->valueText("position")) - x).norm() < 1e-4);
        QVERIFY((parseVector(box->valueText("velocity")) - v).norm() < 1e-4);
        QVERIFY((parseVector(box->valueText("angular_velocity")) - Vec3(0, 0, -20)).norm() < 1e-4);
        // Turned by -20 rad/s × 1.5 s = -30 rad about z: -1718.87° wrapped to (-180, 180].
        const double z = std::remainder(-30.0 * 180.0 / M_PI, 360.0);
        QVERIFY2(std::abs(parseVector(box->valueText("orientation")).z() - z) < 0.01,
                 qPrintable(box->valueText("orientation")));
        const double ke = 0.5 * m * v.squaredNorm() + 0.5 * (0.4 * m * r * r) * 400.0;
        QVERIFY2(std::abs(box->valueText("kinetic_energy").section(' ', 0, 0).toDouble() - ke) < 1e-4 * ke,
                 qPrintable(box->valueText("kinetic_energy")));
        QVERIFY(box->valueText("frame").contains("frame 45"));
        QCOMPARE(box->valueText("sleeping"), QString("no"));

        t.seek(0);  // the initial state
        QVERIFY((parseVector(box->valueText("position")) - Vec3(0, 1, 0)).norm() < 1e-9);

        doc.setSelection({0, 1});
        QVERIFY(!box->isVisible());
        doc.setSelection({1});
        QVERIFY(box->isVisible());

        t.setAutoSimulate(false);
        BodyDesc b = doc.body(1);
        b.mass = 1.0;
        doc.setBody(1, b, "Mass");
        t.seek(10);
        QVERIFY2(box->valueText("frame").contains("before the last edit"),
                 qPrintable(box->valueText("frame")));
    }
};

QTEST_MAIN(TestLiveState)
#include "tst_live_state.moc"
