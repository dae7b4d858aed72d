// The plots dock: one point per recorded frame, each the engine's energy and momentum of
// that frame (and, for a free fall, the closed form); the selected body's position and
// velocity are its recorded states; the playhead line follows the timeline and a click in
// a chart seeks to the nearest frame; an edit clears the plots and the new run refills them;
// the profile readout counts the run's steps.
#include "document/document.h"
#include "panels/plots_dock.h"
#include "timeline/timeline.h"

#include <tumble/model.h>

#include <QAbstractScrollArea>
#include <QImage>
#include <QSignalSpy>
#include <QTableWidget>
#include <QtTest>

#include <cmath>
#include <functional>

using namespace tumble;
using namespace tumble::ui;
using Series = PlotsDock::Series;
using Chart = PlotsDock::Chart;

namespace {

constexpr double kG = 9.81;

BodyDesc fallingBall(double mass) {
    BodyDesc b;
    b.name = "ball";
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = 0.1;
    b.mass = mass;
    b.position = Vec3(0.5, 10.0, -0.25);
    return b;
}

// A ball falling freely from rest for one second at 30 frames per second (31 frames).
SceneDesc freeFall(double mass) {
    SceneDesc s;
    s.settings.gravity = Vec3(0, -kG, 0);
    s.settings.duration = 1.0;
    s.settings.frameRate = 30.0;
    s.bodies.push_back(fallingBall(mass));
    return s;
}

bool runToCompletion(Timeline& timeline) {
    timeline.simulate();
    return QTest::qWaitFor(
        [&] {
            return timeline.status() == Timeline::Status::Complete &&
                   timeline.framesDone() == timeline.frameCount();
        },
        30000);
}

bool close(double a, double b, double tol) {
    return std::abs(a - b) <= tol * std::max(1.0, std::abs(b));
}

// The x of the longest vertical run of the cursor's colour in the image (-1: none).
int cursorColumn(const QImage& image, int* length) {
    const QRgb c = QColor(220, 0, 110).rgb();
    int best = -1;
    *length = 0;
    for (int x = 0; x < image.width(); ++x) {
        int n = 0;
        for (int y = 0; y < image.height(); ++y)
            if (image.pixel(x, y) == c) ++n;
        if (n > *length) {
            *length = n;
            best = x;
        }
    }
    return best;
}

}  // namespace

class TestPlotsDock : public QObject {
    Q_OBJECT
private slots:
    void energyAndMomentumHaveOnePointPerFrameAndAreTheEngines() {
        const double m = 2.0;
        Document doc;
        doc.replaceScene(freeFall(m), "free fall", false);
        Timeline timeline(&doc);
        PlotsDock dock(&timeline);
        QVERIFY(runToCompletion(timeline));
        const int n = timeline.frameCount();
        QCOMPARE(n, 31);
        for (Series s :
             {Series::Kinetic, Series::Potential, Series::Total, Series::Momentum, Series::AngularMomentum})
            QCOMPARE(dock.pointCount(s), n);

        const auto model = timeline.model();
        QVERIFY(model);
        const QList<QPointF> kinetic = dock.points(Series::Kinetic);
        const QList<QPointF> potential = dock.points(Series::Potential);
        const QList<QPointF> total = dock.points(Series::Total);
        const QList<QPointF> momentum = dock.points(Series::Momentum);
        const QList<QPointF> angular = dock.points(Series::AngularMomentum);
        for (int k = 0; k < n; ++k) {
            State state;
            QVERIFY(timeline.frameState(k, &state));
            const Energy e = energy(*model, state);
            QCOMPARE(kinetic[k].x(), state.time);
            QCOMPARE(total[k].x(), state.time);
            QVERIFY2(kinetic[k].y() == e.kinetic, qPrintable(QString("frame %1").arg(k)));
            QVERIFY2(potential[k].y() == e.potential, qPrintable(QString("frame %1").arg(k)));
            QVERIFY2(total[k].y() == e.total(), qPrintable(QString("frame %1").arg(k)));
            // Free fall from rest: v = g t, so T = ½ m g² t² and |P| = m g t.
            const double t = k / 30.0;
            QVERIFY(close(state.time, t, 1e-12));
            QVERIFY2(close(kinetic[k].y(), 0.5 * m * kG * kG * t * t, 1e-9),
                     qPrintable(QString("frame %1: %2").arg(k).arg(kinetic[k].y())));
            QVERIFY2(close(momentum[k].y(), m * kG * t, 1e-9), qPrintable(QString("frame %1").arg(k)));
            // |L| = |x × P| about the origin: x and z stay (0.5, -0.25), P = (0, -m g t, 0).
            QVERIFY2(close(angular[k].y(), m * kG * t * std::sqrt(0.5 * 0.5 + 0.25 * 0.25), 1e-9),
                     qPrintable(QString("frame %1").arg(k)));
            // Potential m g y from the recorded height.
            QVERIFY(close(potential[k].y(), m * kG * state.bodies[0].x.y(), 1e-12));
        }
    }

    void pointsArriveWithTheFramesAndStayPut() {
        // A long free fall (many progress reports while it runs).
        SceneDesc scene = freeFall(1.0);
        scene.settings.duration = 60.0;
        scene.settings.frameRate = 60.0;
        Document doc;
        doc.replaceScene(scene, "free fall", false);
        doc.setSelection({0});
        Timeline timeline(&doc);
        PlotsDock dock(&timeline);
        QList<int> counts;
        QList<QPointF> first;  // the points drawn at the first report
        connect(&timeline, &Timeline::progress, &dock, [&](int framesDone, int frameCount) {
            const int n = dock.pointCount(Series::Kinetic);
            QVERIFY(n >= framesDone && n <= frameCount);
            QCOMPARE(dock.pointCount(Series::Total), n);
            QVERIFY(dock.pointCount(Series::PositionY) >= framesDone);
            if (counts.isEmpty()) first = dock.points(Series::Kinetic);
            counts << n;
        });
        QVERIFY(runToCompletion(timeline));
        QCOMPARE(timeline.frameCount(), 3601);
        QVERIFY(!counts.isEmpty());
        QCOMPARE(counts.last(), timeline.frameCount());
        for (int i = 1; i < counts.size(); ++i) QVERIFY(counts[i] >= counts[i - 1]);
        // What was drawn early is still drawn, unchanged.
        const QList<QPointF> all = dock.points(Series::Kinetic);
        QVERIFY(!first.isEmpty());
        QCOMPARE(all.mid(0, first.size()), first);
        QCOMPARE(dock.pointCount(Series::PositionY), timeline.frameCount());
        // Frame k is at t = k / 60 s, the last at the scene's duration.
        QVERIFY(close(all.last().x(), 60.0, 1e-9));
    }

    void selectedBodyPositionAndVelocityAreItsRecordedStates() {
        const double m = 1.5;
        Document doc;
        doc.replaceScene(freeFall(m), "free fall", false);
        Timeline timeline(&doc);
        PlotsDock dock(&timeline);
        QVERIFY(runToCompletion(timeline));
        QCOMPARE(dock.plottedBody(), -1);
        QCOMPARE(dock.pointCount(Series::PositionY), 0);

        doc.setSelection({0});
        QCOMPARE(dock.plottedBody(), 0);
        const int n = timeline.frameCount();
        const Series pos[3] = {Series::PositionX, Series::PositionY, Series::PositionZ};
        const Series vel[3] = {Series::VelocityX, Series::VelocityY, Series::VelocityZ};
        for (int a = 0; a < 3; ++a) {
            QCOMPARE(dock.pointCount(pos[a]), n);
            QCOMPARE(dock.pointCount(vel[a]), n);
        }
        for (int k = 0; k < n; ++k) {
            State state;
            QVERIFY(timeline.frameState(k, &state));
            const BodyState& b = state.bodies[0];
            for (int a = 0; a < 3; ++a) {
                const QPointF p = dock.points(pos[a])[k];
                QCOMPARE(p.x(), state.time);
                QVERIFY2(p.y() == b.x[a], qPrintable(QString("frame %1 axis %2").arg(k).arg(a)));
                QVERIFY(close(dock.points(vel[a])[k].y(), b.P[a] / m, 1e-14));
            }
            // Free fall: the velocity is (0, -g t, 0).
            QVERIFY(close(dock.points(Series::VelocityY)[k].y(), -kG * k / 30.0, 1e-9));
            QCOMPARE(dock.points(Series::VelocityX)[k].y(), 0.0);
        }
        // Deselecting empties the body's charts.
        doc.setSelection({});
        QCOMPARE(dock.plottedBody(), -1);
        QCOMPARE(dock.pointCount(Series::PositionY), 0);
    }

    void pastTheMemoryCapThePositionIsPlottedAtTheKeyframes() {
        Document doc;
        doc.replaceScene(freeFall(1.0), "free fall", false);
        doc.setSelection({0});
        Timeline timeline(&doc);
        timeline.setMemoryCap(3000);  // a few single-body snapshots
        PlotsDock dock(&timeline);
        QVERIFY(runToCompletion(timeline));
        const int interval = timeline.keyframeInterval();
        QVERIFY2(interval > 1, qPrintable(QString::number(interval)));
        // Energy is kept for every frame, the body's states only at the keyframes.
        QCOMPARE(dock.pointCount(Series::Kinetic), timeline.frameCount());
        std::vector<int> frames;
        std::vector<BodyState> states;
        timeline.bodyTrack(0, &frames, &states);
        QCOMPARE(dock.pointCount(Series::PositionY), int(frames.size()));
        const QList<QPointF> y = dock.points(Series::PositionY);
        for (std::size_t i = 0; i < frames.size(); ++i) {
            QCOMPARE(frames[i] % interval, 0);
            QVERIFY(close(y[int(i)].x(), frames[i] / 30.0, 1e-12));
            QVERIFY(y[int(i)].y() == states[i].x.y());
        }
    }

    void clickingAChartSeeksAndTheCursorFollowsThePlayhead() {
        Document doc;
        doc.replaceScene(freeFall(1.0), "free fall", false);
        doc.setSelection({0});
        Timeline timeline(&doc);
        PlotsDock dock(&timeline);
        dock.resize(900, 600);
        dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&dock));
        QVERIFY(runToCompletion(timeline));
        const QList<QPointF> kinetic = dock.points(Series::Kinetic);
        const int n = kinetic.size();
        QCOMPARE(n, timeline.frameCount());

        for (Chart chart : {Chart::Energy, Chart::Momentum, Chart::Position, Chart::Velocity}) {
            dock.showChart(chart);
            QWidget* view = dock.chartView(chart);
            QVERIFY(view->isVisible());
            // The chart on screen draws every frame's point.
            for (int i = 0; i < PlotsDock::kSeriesCount; ++i)
                if (PlotsDock::chartOf(Series(i)) == chart) QCOMPARE(dock.drawnPointCount(Series(i)), n);
            QWidget* viewport = qobject_cast<QAbstractScrollArea*>(view)->viewport();
            QVERIFY(viewport);
            for (int k : {7, 0, n - 1, 19}) {
                const QPoint at = dock.viewportPosition(chart, kinetic[k].x());
                QVERIFY(at.x() >= 0);
                QTest::mouseClick(viewport, Qt::LeftButton, {}, at);
                QCOMPARE(timeline.currentFrame(), k);
                QCOMPARE(dock.cursorTime(), kinetic[k].x());
            }
            // A click a third of the way from frame 10 to frame 11 is nearest frame 10.
            const double t = kinetic[10].x() + (kinetic[11].x() - kinetic[10].x()) / 3;
            const QPoint a10 = dock.viewportPosition(chart, t);
            QTest::mouseClick(viewport, Qt::LeftButton, {}, a10);
            QCOMPARE(timeline.currentFrame(), 10);
        }

        // Outside the plot area (the chart's margin, its axis labels) a click does nothing.
        {
            QWidget* viewport =
                qobject_cast<QAbstractScrollArea*>(dock.chartView(Chart::Velocity))->viewport();
            timeline.seek(3);
            QTest::mouseClick(viewport, Qt::LeftButton, {}, QPoint(2, 2));
            QCOMPARE(timeline.currentFrame(), 3);
            // Dragging along the chart scrubs: press at frame 5, release at frame 22.
            QTest::mousePress(viewport, Qt::LeftButton, {},
                              dock.viewportPosition(Chart::Velocity, kinetic[5].x()));
            QCOMPARE(timeline.currentFrame(), 5);
            QTest::mouseMove(viewport, dock.viewportPosition(Chart::Velocity, kinetic[22].x()));
            QCOMPARE(timeline.currentFrame(), 22);
            QTest::mouseRelease(viewport, Qt::LeftButton, {},
                                dock.viewportPosition(Chart::Velocity, kinetic[22].x()));
            QCOMPARE(timeline.currentFrame(), 22);
        }

        // The playhead moved by the timeline: the line is drawn in the chart where frame k is.
        dock.showChart(Chart::Energy);
        QWidget* viewport = qobject_cast<QAbstractScrollArea*>(dock.chartView(Chart::Energy))->viewport();
        for (int k : {4, 25}) {
            timeline.seek(k);
            QCOMPARE(dock.cursorTime(), kinetic[k].x());
            const QImage image = viewport->grab().toImage().convertToFormat(QImage::Format_RGB32);
            int length = 0;
            const int x = cursorColumn(image, &length);
            const QPoint expected = dock.viewportPosition(Chart::Energy, kinetic[k].x());
            QVERIFY2(length > image.height() / 3, qPrintable(QString::number(length)));
            QVERIFY2(std::abs(x - expected.x()) <= 1,
                     qPrintable(QString("%1 vs %2").arg(x).arg(expected.x())));
        }
    }

    void anEditClearsThePlotsAndTheNewRunRefillsThem() {
        Document doc;
        doc.replaceScene(freeFall(1.0), "free fall", false);
        doc.setSelection({0});
        Timeline timeline(&doc);
        PlotsDock dock(&timeline);
        QVERIFY(runToCompletion(timeline));
        const int n = timeline.frameCount();
        QCOMPARE(dock.pointCount(Series::Kinetic), n);

        // The dock connected first, so by the time this runs it has reacted to the reset.
        QList<int> countsAtReset;
        connect(&timeline, &Timeline::recordingReset, &dock, [&] {
            countsAtReset << dock.pointCount(Series::Kinetic) << dock.pointCount(Series::Total)
                          << dock.pointCount(Series::PositionY);
        });
        const double m = 4.0;
        BodyDesc heavier = doc.body(0);
        heavier.mass = m;
        heavier.velocity = Vec3(1.0, 0, 0);
        doc.setBody(0, heavier, "mass");
        QTRY_VERIFY_WITH_TIMEOUT(!countsAtReset.isEmpty(), 10000);
        QCOMPARE(countsAtReset, QList<int>({0, 0, 0}));
        QTRY_VERIFY_WITH_TIMEOUT(timeline.status() == Timeline::Status::Complete && !timeline.isStale() &&
                                     timeline.framesDone() == n,
                                 30000);
        QCOMPARE(dock.pointCount(Series::Kinetic), n);
        QCOMPARE(dock.pointCount(Series::VelocityX), n);
        const QList<QPointF> kinetic = dock.points(Series::Kinetic);
        const QList<QPointF> vx = dock.points(Series::VelocityX);
        for (int k = 0; k < n; ++k) {
            const double t = k / 30.0;
            // ½ m (1² + (g t)²) with the new mass and velocity.
            QVERIFY2(close(kinetic[k].y(), 0.5 * m * (1.0 + kG * kG * t * t), 1e-9),
                     qPrintable(QString::number(k)));
            QVERIFY(close(vx[k].y(), 1.0, 1e-12));
        }
    }

    // A very long run then a short one (and back): the time axis follows each run's length
    // without building a tick per old interval (this hung the UI thread once).
    void theTimeAxisFollowsLongAndShortRuns() {
        Document doc;
        SceneDesc longRun = freeFall(1.0);
        longRun.settings.duration = 100000.0;
        doc.replaceScene(longRun, "long", false);
        Timeline timeline(&doc);
        timeline.setAutoSimulate(false);
        PlotsDock dock(&timeline);
        dock.show();
        timeline.simulate();
        QVERIFY(QTest::qWaitFor([&] { return timeline.framesDone() > 10; }, 30000));
        timeline.cancel();
        QVERIFY(QTest::qWaitFor([&] { return timeline.status() == Timeline::Status::Cancelled; }, 30000));
        doc.replaceScene(freeFall(1.0), "short", false);
        QVERIFY(runToCompletion(timeline));
        QCoreApplication::processEvents();
        QCOMPARE(dock.pointCount(Series::Kinetic), 31);
        doc.replaceScene(longRun, "long again", false);
        timeline.simulate();
        QVERIFY(QTest::qWaitFor([&] { return timeline.framesDone() > 10; }, 30000));
        timeline.cancel();
        QVERIFY(QTest::qWaitFor([&] { return timeline.status() == Timeline::Status::Cancelled; }, 30000));
        QCoreApplication::processEvents();
        QVERIFY(dock.pointCount(Series::Kinetic) > 10);
    }

    void outlivingItsTimelineIsSafe() {
        Document doc;
        doc.replaceScene(freeFall(1.0), "free fall", false);
        auto* timeline = new Timeline(&doc);
        PlotsDock dock(timeline);
        dock.resize(600, 400);
        dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&dock));
        QVERIFY(runToCompletion(*timeline));
        const QPoint at = dock.viewportPosition(Chart::Energy, 0.5);
        delete timeline;  // a window closing may take the timeline first
        QCOMPARE(dock.timeline(), nullptr);
        doc.setSelection({0});
        QTest::mouseClick(qobject_cast<QAbstractScrollArea*>(dock.chartView(Chart::Energy))->viewport(),
                          Qt::LeftButton, {}, at);
        QCOMPARE(dock.pointCount(Series::Kinetic), 31);  // what was plotted stays
    }

    // The value axes read as plain numbers at the scale of their ticks: an energy axis of
    // 0 to 80 000 J reads "80000", not "8e+04" (issue 21).
    void axesReadAsPlainNumbers() {
        auto label = [](double lo, double hi, double step, double v) {
            return QString::asprintf(qPrintable(PlotsDock::axisLabelFormat(lo, hi, step)), v);
        };
        QCOMPARE(label(0, 80000, 20000, 80000), QString("80000"));
        QCOMPARE(label(0, 1, 0.2, 0.4), QString("0.4"));
        QCOMPARE(label(-0.1, 0.15, 0.05, 0.05), QString("0.05"));
        QCOMPARE(label(0, 2.5, 0.5, 1.5), QString("1.5"));
        QCOMPARE(label(0, 4e8, 1e8, 3e8), QString("3e+08"));  // past plain reading
    }

    void theProfileReadoutCountsTheRunsSteps() {
        Document doc;
        QString error;
        QVERIFY2(doc.open(":/scenes/bouncing-ball.json", &error), qPrintable(error));
        Timeline timeline(&doc);
        PlotsDock dock(&timeline);
        QVERIFY(runToCompletion(timeline));
        QTableWidget* table = dock.profileTable();
        QCOMPARE(table->rowCount(), int(PlotsDock::ProfileRowCount));

        long steps = 0;
        for (const FrameSummary& f : timeline.summaries()) steps += f.steps;
        const Profile p = timeline.profile();
        QCOMPARE(p.steps, steps);
        QCOMPARE(table->item(PlotsDock::ProfileSteps, 1)->text(), QString::number(steps));
        // 5 s at the default step of 1/240 s: at least 1200 steps.
        QVERIFY(steps >= 1200);
        // The ball rests on the ground for part of the run: contact points in some steps.
        bool ok = false;
        const double points = table->item(PlotsDock::ProfileContactPoints, 1)->text().toDouble(&ok);
        QVERIFY(ok);
        QVERIFY(std::abs(points - double(p.contactPoints) / steps) < 0.01);
        QVERIFY(points > 0.0);
        // Times in ms, µs or ns, three figures each (issue 21: "0.00010 ms" before).
        auto inMs = [&](const QString& text) {
            const QStringList parts = text.split(' ');
            const double v = parts.value(0).toDouble(&ok);
            const QString unit = parts.value(1);
            return unit == "ms" ? v : unit == QString::fromUtf8("µs") ? v * 1e-3 : unit == "ns" ? v * 1e-6 : -1.0;
        };
        double sum = 0.0;
        for (int r = PlotsDock::ProfileForces; r < PlotsDock::ProfileTotal; ++r) {
            const double ms = inMs(table->item(r, 1)->text());
            QVERIFY2(ok && ms >= 0.0, qPrintable(table->item(r, 0)->text() + ": " + table->item(r, 1)->text()));
            sum += ms;
        }
        const double all = inMs(table->item(PlotsDock::ProfileTotal, 1)->text());
        QVERIFY(ok);
        QVERIFY2(std::abs(all - sum) <= 0.02 * all + 1e-4, qPrintable(QString("%1 vs %2").arg(all).arg(sum)));
        QCOMPARE(PlotsDock::timeText(2.5e-7), QString::fromUtf8("0.25 µs"));
        QCOMPARE(PlotsDock::timeText(3.2e-8), QString("32 ns"));
        QCOMPARE(PlotsDock::timeText(2.43e-2), QString("24.3 ms"));
        QCOMPARE(PlotsDock::timeText(3.5e-4), QString("0.35 ms"));
        QCOMPARE(PlotsDock::timeText(4e-11), QString("0 ns"));
        // Each stage's share of the time, in whole percent, adds up to 100 (up to rounding).
        int shares = 0;
        for (int r = PlotsDock::ProfileForces; r < PlotsDock::ProfileTotal; ++r) {
            QString text = table->item(r, 2)->text();
            QVERIFY2(text.endsWith(" %"), qPrintable(text));
            shares += text.chopped(2).toInt(&ok);
            QVERIFY(ok);
        }
        QVERIFY2(std::abs(shares - 100) <= 4, qPrintable(QString::number(shares)));

        // And the energies there, with contacts, are still the engine's, frame by frame.
        const auto model = timeline.model();
        const QList<QPointF> total = dock.points(Series::Total);
        QCOMPARE(total.size(), timeline.frameCount());
        for (int k = 0; k < total.size(); k += 17) {
            State state;
            QVERIFY(timeline.frameState(k, &state));
            QVERIFY(total[k].y() == energy(*model, state).total());
        }
    }
};

QTEST_MAIN(TestPlotsDock)
#include "tst_plots_dock.moc"
