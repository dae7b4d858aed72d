// The plots dock: energy, momentum and the selected body's position and velocity against
// time, one point per recorded frame, and the engine's profile (time per step of each
// stage). It follows the timeline: points are appended as frames arrive (progress), the
// series are cleared when a new run starts (recordingReset), a vertical line marks the
// playhead in every chart, and a click in a chart seeks the timeline to the nearest frame.
//
// Qt Charts stays out of this header (the editor library links it privately).
#pragma once

#include <QDockWidget>
#include <QElapsedTimer>
#include <QList>
#include <QPointF>
#include <QPointer>

#include <array>
#include <vector>

class QLabel;
class QTabWidget;
class QTableWidget;
class QTimer;

QT_BEGIN_NAMESPACE
class QLineSeries;
class QValueAxis;
QT_END_NAMESPACE

namespace tumble::ui {

class PlotChartView;
class Timeline;

class PlotsDock : public QDockWidget {
    Q_OBJECT
public:
    /// Every curve the dock draws. Energy in J, momentum in kg·m/s, angular momentum (about
    /// the origin) in kg·m²/s, the selected body's centre of mass in m and its velocity in m/s.
    enum class Series {
        Kinetic,
        Potential,
        Total,
        Momentum,
        AngularMomentum,
        PositionX,
        PositionY,
        PositionZ,
        VelocityX,
        VelocityY,
        VelocityZ,
    };
    Q_ENUM(Series)
    static constexpr int kSeriesCount = 11;

    /// The charts, one tab each (the profile readout is the last tab).
    enum class Chart { Energy, Momentum, Position, Velocity };
    Q_ENUM(Chart)
    static constexpr int kChartCount = 4;

    /// Rows of the profile readout (column 1 holds the value).
    enum ProfileRow {
        ProfileForces,
        ProfileIntegrate,
        ProfileBroadphase,
        ProfileNarrowphase,
        ProfileTimeOfImpact,
        ProfileImpactSolve,
        ProfileSolve,
        ProfileSleep,
        ProfileTotal,
        ProfileSteps,
        ProfilePairs,
        ProfileContactPoints,
        ProfileImpacts,
        ProfileRowCount
    };

    explicit PlotsDock(Timeline* timeline, QWidget* parent = nullptr);
    ~PlotsDock() override;

    Timeline* timeline() const { return timeline_; }

    // ---- What is plotted (for tests and tools). A chart receives its points while it is on
    // screen (its tab current, the dock shown), at most a few times a second during a run.
    int pointCount(Series which) const;
    QList<QPointF> points(Series which) const;
    /// Points the chart's series holds now (pointCount once the chart has been shown).
    int drawnPointCount(Series which) const;
    static Chart chartOf(Series which);
    /// A time per step as the Profile tab shows it: three figures in ms, µs or ns.
    static QString timeText(double seconds);
    /// The printf format of a value axis from lo to hi with ticks `step` apart.
    static QString axisLabelFormat(double lo, double hi, double step);
    /// The body the position and velocity charts show (-1: none selected).
    int plottedBody() const { return body_; }
    /// The playhead's time (s) drawn in every chart; NaN when nothing is recorded.
    double cursorTime() const;
    /// The chart's view (a QChartView); clicks go to its viewport().
    QWidget* chartView(Chart which) const;
    /// Viewport coordinates of `time` in chart `which` (where its cursor line is drawn).
    QPoint viewportPosition(Chart which, double time) const;
    /// Brings chart `which` to the front.
    void showChart(Chart which);
    /// The profile readout (rows: ProfileRow; columns: what, value).
    QTableWidget* profileTable() const { return profile_; }

    /// The frame nearest `time` among the frames plotted (-1 when none).
    int frameNearest(double time) const;

private:
    struct Range {
        double lo = 0.0, hi = 0.0;
        bool empty = true;
        void add(double v);
    };

    void reset();
    void onProgress();
    void onCurrentFrame(int frame);
    void onSelection();
    void appendSummaries();
    void updateBodySeries(bool rebuild);
    void clearBodySeries();
    void extend(Series which, const QList<QPointF>& pts);
    void clearSeries(Series which);
    void updateTimeAxis();
    void updateProfile();
    void fitAxis(QValueAxis* axis, const Range& range);
    void seekTo(double time);
    void scheduleSync();
    void syncCharts();

    QPointer<Timeline> timeline_;  // the main window may destroy it first
    QTabWidget* tabs_ = nullptr;
    std::array<PlotChartView*, kChartCount> views_{};
    std::array<QLineSeries*, kSeriesCount> series_{};
    std::array<QList<QPointF>, kSeriesCount> data_;  // the series' points (shared with them)
    std::array<bool, kChartCount> dirty_{};          // data_ has points the chart does not
    QTimer* syncTimer_ = nullptr;
    QElapsedTimer lastSync_;
    qint64 syncInterval_ = 100;  // ms between chart updates during a run
    QValueAxis* timeAxes_[kChartCount] = {};
    QValueAxis* valueAxes_[kChartCount + 1] = {};  // energy, momentum, position, velocity, angular momentum
    Range ranges_[kChartCount + 1];
    QTableWidget* profile_ = nullptr;
    std::vector<double> times_;  // time of each plotted frame (energy series x values)
    int body_ = -1;
    std::vector<int> bodyFrames_;  // frames of the position/velocity points
    int lastFrame_ = 0;
};

}  // namespace tumble::ui
