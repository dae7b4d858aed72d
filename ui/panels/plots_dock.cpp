#include "panels/plots_dock.h"

#include "document/document.h"
#include "panels/plot_chart_view.h"
#include "timeline/timeline.h"

#include <tumble/model.h>

#include <QChart>
#include <QElapsedTimer>
#include <QHeaderView>
#include <QLineSeries>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <QValueAxis>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::ui {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kAngularAxis = PlotsDock::kChartCount;  // the momentum chart's right axis

int idx(PlotsDock::Series s) {
    return static_cast<int>(s);
}
int idx(PlotsDock::Chart c) {
    return static_cast<int>(c);
}

QValueAxis* makeAxis(const QString& title) {
    auto* axis = new QValueAxis;
    axis->setTitleText(title);
    axis->setLabelFormat("%.3g");
    axis->setTickCount(5);
    axis->setRange(0.0, 1.0);
    return axis;
}

QTableWidgetItem* readOnly(const QString& text) {
    auto* item = new QTableWidgetItem(text);
    item->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable);
    return item;
}

// 1, 2, 2.5 or 5 times a power of ten, at least x (x > 0).
double niceStep(double x) {
    if (!(x > 0) || !std::isfinite(x)) return 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(x)));
    const double f = x / p;
    return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 2.5 ? 2.5 : f <= 5 ? 5 : 10) * p;
}

}  // namespace

void PlotsDock::Range::add(double v) {
    if (!std::isfinite(v)) return;
    if (empty) {
        lo = hi = v;
        empty = false;
    } else {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
}

PlotsDock::PlotsDock(Timeline* timeline, QWidget* parent)
    : QDockWidget(tr("Plots"), parent), timeline_(timeline) {
    setObjectName("plotsDock");

    struct ChartSpec {
        Chart chart;
        const char* name;
        QString title;
        QString valueTitle;
    };
    const ChartSpec specs[kChartCount] = {
        {Chart::Energy, "energyChart", tr("Energy"), tr("Energy (J)")},
        {Chart::Momentum, "momentumChart", tr("Momentum"), tr("Linear momentum |P| (kg·m/s)")},
        {Chart::Position, "positionChart", tr("Position"), tr("Centre of mass (m)")},
        {Chart::Velocity, "velocityChart", tr("Velocity"), tr("Velocity (m/s)")},
    };
    struct SeriesSpec {
        Series series;
        Chart chart;
        QString name;
        int axis;
    };
    const SeriesSpec seriesSpecs[kSeriesCount] = {
        {Series::Kinetic, Chart::Energy, tr("Kinetic"), idx(Chart::Energy)},
        {Series::Potential, Chart::Energy, tr("Potential"), idx(Chart::Energy)},
        {Series::Total, Chart::Energy, tr("Total"), idx(Chart::Energy)},
        {Series::Momentum, Chart::Momentum, tr("|P| (kg·m/s)"), idx(Chart::Momentum)},
        {Series::AngularMomentum, Chart::Momentum, tr("|L| about the origin (kg·m²/s)"), kAngularAxis},
        {Series::PositionX, Chart::Position, tr("x"), idx(Chart::Position)},
        {Series::PositionY, Chart::Position, tr("y"), idx(Chart::Position)},
        {Series::PositionZ, Chart::Position, tr("z"), idx(Chart::Position)},
        {Series::VelocityX, Chart::Velocity, tr("vx"), idx(Chart::Velocity)},
        {Series::VelocityY, Chart::Velocity, tr("vy"), idx(Chart::Velocity)},
        {Series::VelocityZ, Chart::Velocity, tr("vz"), idx(Chart::Velocity)},
    };

    tabs_ = new QTabWidget;
    tabs_->setObjectName("plotTabs");
    for (const ChartSpec& spec : specs) {
        auto* chart = new QChart;
        // The tab names the energy and momentum charts; the body charts name the body.
        if (spec.chart == Chart::Position || spec.chart == Chart::Velocity) chart->setTitle(spec.title);
        chart->setMargins(QMargins(4, 4, 4, 4));
        chart->legend()->setAlignment(Qt::AlignBottom);
        const int c = idx(spec.chart);
        timeAxes_[c] = makeAxis(tr("Time (s)"));
        valueAxes_[c] = makeAxis(spec.valueTitle);
        chart->addAxis(timeAxes_[c], Qt::AlignBottom);
        chart->addAxis(valueAxes_[c], Qt::AlignLeft);
        if (spec.chart == Chart::Momentum) {
            valueAxes_[kAngularAxis] = makeAxis(tr("Angular momentum |L| (kg·m²/s)"));
            chart->addAxis(valueAxes_[kAngularAxis], Qt::AlignRight);
        }
        auto* view = new PlotChartView(chart);
        view->setObjectName(spec.name);
        connect(view, &PlotChartView::timeClicked, this, &PlotsDock::seekTo);
        views_[static_cast<std::size_t>(c)] = view;
        tabs_->addTab(view, spec.title);
    }
    for (const SeriesSpec& spec : seriesSpecs) {
        auto* series = new QLineSeries;
        series->setName(spec.name);
        QChart* chart = views_[static_cast<std::size_t>(idx(spec.chart))]->chart();
        chart->addSeries(series);
        series->attachAxis(timeAxes_[idx(spec.chart)]);
        series->attachAxis(valueAxes_[spec.axis]);
        series_[static_cast<std::size_t>(idx(spec.series))] = series;
    }

    profile_ = new QTableWidget(ProfileRowCount, 3);
    profile_->setObjectName("profile");
    profile_->setHorizontalHeaderLabels({tr("Stage"), tr("Per step"), tr("Share")});
    profile_->verticalHeader()->hide();
    profile_->verticalHeader()->setDefaultSectionSize(profile_->fontMetrics().height() + 6);
    profile_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
    profile_->horizontalHeader()->setSectionResizeMode(1, QHeaderView::Stretch);
    profile_->horizontalHeader()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
    profile_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    const QString rowNames[ProfileRowCount] = {
        tr("Forces"),         tr("Integration"),       tr("Broadphase"),
        tr("Narrowphase"),    tr("Time of impact"),    tr("Impact solve"),
        tr("Contact solver"), tr("Islands and sleep"), tr("All stages"),
        tr("Steps (run so far)"),  tr("Broadphase pairs"),       tr("Contact points"),
        tr("Impacts (pairs)"),
    };
    for (int r = 0; r < ProfileRowCount; ++r) {
        profile_->setItem(r, 0, readOnly(rowNames[r]));
        auto* value = readOnly(QString());
        value->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        profile_->setItem(r, 1, value);
        auto* share = readOnly(QString());
        share->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        profile_->setItem(r, 2, share);
    }
    profile_->item(ProfileSteps, 1)->setToolTip(tr("Steps taken so far; the other rows are per step"));
    tabs_->addTab(profile_, tr("Profile"));

    auto* body = new QWidget;
    auto* layout = new QVBoxLayout(body);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(tabs_);
    setWidget(body);

    syncTimer_ = new QTimer(this);
    syncTimer_->setSingleShot(true);
    connect(syncTimer_, &QTimer::timeout, this, &PlotsDock::syncCharts);
    connect(tabs_, &QTabWidget::currentChanged, this, &PlotsDock::syncCharts);
    // Queued: when the dock is shown its children are visible only after the show event.
    connect(this, &QDockWidget::visibilityChanged, this, &PlotsDock::syncCharts, Qt::QueuedConnection);
    connect(timeline_, &Timeline::recordingReset, this, &PlotsDock::reset);
    connect(timeline_, &Timeline::progress, this, &PlotsDock::onProgress);
    connect(timeline_, &Timeline::currentFrameChanged, this, &PlotsDock::onCurrentFrame);
    connect(timeline_->document(), &Document::selectionChanged, this, &PlotsDock::onSelection);

    reset();
    onSelection();
    onProgress();
    onCurrentFrame(timeline_->currentFrame());
}

PlotsDock::~PlotsDock() = default;

int PlotsDock::pointCount(Series which) const {
    return static_cast<int>(data_[static_cast<std::size_t>(idx(which))].size());
}

QList<QPointF> PlotsDock::points(Series which) const {
    return data_[static_cast<std::size_t>(idx(which))];
}

int PlotsDock::drawnPointCount(Series which) const {
    return series_[static_cast<std::size_t>(idx(which))]->count();
}

double PlotsDock::cursorTime() const {
    return views_[0]->cursorTime();
}

QWidget* PlotsDock::chartView(Chart which) const {
    return views_[static_cast<std::size_t>(idx(which))];
}

QPoint PlotsDock::viewportPosition(Chart which, double time) const {
    return views_[static_cast<std::size_t>(idx(which))]->viewportPosition(time);
}

void PlotsDock::showChart(Chart which) {
    tabs_->setCurrentIndex(idx(which));
}

int PlotsDock::frameNearest(double time) const {
    if (times_.empty() || std::isnan(time)) return -1;
    const auto it = std::lower_bound(times_.begin(), times_.end(), time);
    if (it == times_.end()) return static_cast<int>(times_.size()) - 1;
    const int k = static_cast<int>(it - times_.begin());
    if (k > 0 && time - times_[static_cast<std::size_t>(k - 1)] <= *it - time) return k - 1;
    return k;
}

void PlotsDock::seekTo(double time) {
    const int k = frameNearest(time);
    if (k >= 0 && timeline_) timeline_->seek(k);
}

void PlotsDock::extend(Series which, const QList<QPointF>& pts) {
    if (pts.isEmpty()) return;
    data_[static_cast<std::size_t>(idx(which))].append(pts);
    dirty_[static_cast<std::size_t>(idx(chartOf(which)))] = true;
}

void PlotsDock::clearSeries(Series which) {
    data_[static_cast<std::size_t>(idx(which))].clear();
    dirty_[static_cast<std::size_t>(idx(chartOf(which)))] = true;
}

PlotsDock::Chart PlotsDock::chartOf(Series which) {
    switch (which) {
        case Series::Kinetic:
        case Series::Potential:
        case Series::Total: return Chart::Energy;
        case Series::Momentum:
        case Series::AngularMomentum: return Chart::Momentum;
        case Series::PositionX:
        case Series::PositionY:
        case Series::PositionZ: return Chart::Position;
        default: return Chart::Velocity;
    }
}

// Whatever changes, a chart recomputes the geometry of its whole curves (Qt Charts keeps no
// partial paths): a few ms per thousand points. So the points are handed to a chart only
// while it is on screen, and while a run goes on at most every syncInterval_, which grows
// with what a sync costs, keeping the UI thread mostly free for a 10 000-frame run.
void PlotsDock::scheduleSync() {
    const bool running = timeline_->status() == Timeline::Status::Running;
    const qint64 since = lastSync_.isValid() ? lastSync_.elapsed() : std::numeric_limits<qint64>::max();
    if (!running || since >= syncInterval_) {
        syncTimer_->stop();
        syncCharts();
    } else if (!syncTimer_->isActive()) {
        syncTimer_->start(static_cast<int>(syncInterval_ - since));
    }
}

void PlotsDock::syncCharts() {
    QElapsedTimer cost;
    cost.start();
    bool any = false;
    for (int c = 0; c < kChartCount; ++c) {
        const auto ci = static_cast<std::size_t>(c);
        if (!dirty_[ci] || !isVisible() || tabs_->currentIndex() != c) continue;
        // Axes first, while the curves are still the shorter old ones.
        fitAxis(valueAxes_[c], ranges_[c]);
        if (c == idx(Chart::Momentum)) fitAxis(valueAxes_[kAngularAxis], ranges_[kAngularAxis]);
        for (int s = 0; s < kSeriesCount; ++s) {
            if (chartOf(static_cast<Series>(s)) != static_cast<Chart>(c)) continue;
            const auto si = static_cast<std::size_t>(s);
            // QXYSeries::append(QList) adds points one at a time, recomputing the curve after
            // each (quadratic); replace() recomputes once and shares the list (no copy).
            if (data_[si].isEmpty())
                series_[si]->clear();
            else
                series_[si]->replace(data_[si]);
        }
        dirty_[ci] = false;
        any = true;
    }
    if (!any) return;
    lastSync_.start();
    syncInterval_ = std::clamp<qint64>(4 * cost.elapsed(), 100, 2000);
}

void PlotsDock::reset() {
    for (int i = 0; i < kSeriesCount; ++i) clearSeries(static_cast<Series>(i));
    times_.clear();
    bodyFrames_.clear();
    for (Range& r : ranges_) r = Range();
    for (PlotChartView* v : views_) v->setCursorTime(kNaN);
    updateTimeAxis();
    updateProfile();
    syncCharts();  // empty charts at once: cheap, and the old run must not linger
}

void PlotsDock::onProgress() {
    // A run is only ever appended to; fewer frames than plotted means a new run whose
    // reset we have not seen (cannot happen with the timeline's signals, but costs nothing).
    if (timeline_->framesDone() < static_cast<int>(times_.size())) reset();
    updateTimeAxis();
    appendSummaries();
    updateBodySeries(false);
    updateProfile();
    onCurrentFrame(timeline_->currentFrame());
    scheduleSync();
}

void PlotsDock::appendSummaries() {
    const int done = timeline_->framesDone();
    const int from = static_cast<int>(times_.size());
    if (done <= from) return;
    QList<QPointF> pts[5];
    for (auto& p : pts) p.reserve(done - from);
    for (int k = from; k < done; ++k) {
        const FrameSummary f = timeline_->summary(k);
        const double total = f.kinetic + f.potential;
        pts[0].append({f.time, f.kinetic});
        pts[1].append({f.time, f.potential});
        pts[2].append({f.time, total});
        pts[3].append({f.time, f.momentum});
        pts[4].append({f.time, f.angularMomentum});
        times_.push_back(f.time);
        Range& energy = ranges_[idx(Chart::Energy)];
        energy.add(f.kinetic);
        energy.add(f.potential);
        energy.add(total);
        ranges_[idx(Chart::Momentum)].add(f.momentum);
        ranges_[kAngularAxis].add(f.angularMomentum);
    }
    const Series order[5] = {Series::Kinetic, Series::Potential, Series::Total, Series::Momentum,
                             Series::AngularMomentum};
    for (int i = 0; i < 5; ++i) extend(order[i], pts[i]);
}

void PlotsDock::clearBodySeries() {
    for (Series s : {Series::PositionX, Series::PositionY, Series::PositionZ, Series::VelocityX,
                     Series::VelocityY, Series::VelocityZ})
        clearSeries(s);
    bodyFrames_.clear();
    ranges_[idx(Chart::Position)] = Range();
    ranges_[idx(Chart::Velocity)] = Range();
}

void PlotsDock::updateBodySeries(bool rebuild) {
    QChart* position = views_[static_cast<std::size_t>(idx(Chart::Position))]->chart();
    QChart* velocity = views_[static_cast<std::size_t>(idx(Chart::Velocity))]->chart();
    const std::shared_ptr<const Model> model = timeline_->model();
    if (body_ < 0 || !model || body_ >= static_cast<int>(model->bodies.size())) {
        if (!bodyFrames_.empty() || rebuild) clearBodySeries();
        const QString none = body_ < 0 ? tr("(no body selected)") : tr("(not simulated yet)");
        position->setTitle(tr("Position %1").arg(none));
        velocity->setTitle(tr("Velocity %1").arg(none));
        return;
    }
    const BodyModel& bm = model->bodies[static_cast<std::size_t>(body_)];
    const QString name = QString::fromStdString(bm.name);
    position->setTitle(tr("Centre of mass of %1").arg(name));
    velocity->setTitle(tr("Velocity of %1").arg(name));

    std::vector<int> frames;
    std::vector<BodyState> states;
    timeline_->bodyTrack(body_, &frames, &states);
    // Appended to while every frame is kept; when the recording thins itself (its frames
    // become the keyframes) the track is no longer an extension of what is drawn: redraw.
    const std::size_t had = bodyFrames_.size();
    const bool extends = !rebuild && frames.size() >= had &&
                         std::equal(bodyFrames_.begin(), bodyFrames_.end(), frames.begin());
    if (!extends) clearBodySeries();
    const std::size_t from = bodyFrames_.size();
    if (frames.size() <= from) return;

    const double rate = timeline_->frameRate();
    QList<QPointF> pts[6];
    for (auto& p : pts) p.reserve(static_cast<qsizetype>(frames.size() - from));
    Range& pr = ranges_[idx(Chart::Position)];
    Range& vr = ranges_[idx(Chart::Velocity)];
    for (std::size_t i = from; i < frames.size(); ++i) {
        const int f = frames[i];
        const double t = f < static_cast<int>(times_.size()) ? times_[static_cast<std::size_t>(f)]
                                                             : (rate > 0 ? f / rate : 0.0);
        const BodyState& s = states[i];
        const Vec3 v = derive(bm, s).v;
        for (int a = 0; a < 3; ++a) {
            pts[a].append({t, s.x[a]});
            pts[3 + a].append({t, v[a]});
            pr.add(s.x[a]);
            vr.add(v[a]);
        }
    }
    const Series order[6] = {Series::PositionX, Series::PositionY, Series::PositionZ,
                             Series::VelocityX, Series::VelocityY, Series::VelocityZ};
    for (int i = 0; i < 6; ++i) extend(order[i], pts[i]);
    bodyFrames_.insert(bodyFrames_.end(), frames.begin() + static_cast<std::ptrdiff_t>(from), frames.end());
}

void PlotsDock::onSelection() {
    if (!timeline_) return;
    const QList<int>& sel = timeline_->document()->selection();
    const int body = sel.isEmpty() ? -1 : sel.first();
    if (body == body_ && !bodyFrames_.empty()) return;
    body_ = body;
    updateBodySeries(true);
    syncCharts();
}

void PlotsDock::onCurrentFrame(int frame) {
    double t = kNaN;
    if (frame >= 0 && frame < static_cast<int>(times_.size()))
        t = times_[static_cast<std::size_t>(frame)];
    else if (frame >= 0 && frame < timeline_->framesDone())
        t = timeline_->summary(frame).time;
    for (PlotChartView* v : views_) v->setCursorTime(t);
}

void PlotsDock::updateTimeAxis() {
    const double rate = timeline_->frameRate();
    const int frames = timeline_->frameCount();
    const double end = rate > 0 && frames > 1 ? (frames - 1) / rate : 1.0;
    for (QValueAxis* axis : timeAxes_) {
        if (axis->min() == 0.0 && axis->max() == end) continue;
        // The axis spans the run exactly; the ticks fall on round times. The range changes
        // under a fixed tick count: a long run's range under a short run's interval (or the
        // other way round) would make a tick item per interval (100 000 s at 0.5 s hung the
        // UI thread building 200 000 of them).
        axis->setTickType(QValueAxis::TicksFixed);
        axis->setRange(0.0, end);
        axis->setTickAnchor(0.0);
        axis->setTickInterval(niceStep(end / 5));
        axis->setTickType(QValueAxis::TicksDynamic);
    }
}

QString PlotsDock::timeText(double seconds) {
    // Three figures in the unit that needs no leading zeros (a stage of a small scene took
    // "0.00010 ms" a step).
    const double ms = seconds * 1e3;
    if (ms >= 0.1 || ms == 0.0) return QString::number(ms, 'f', ms >= 100 ? 0 : ms >= 10 ? 1 : 2) + " ms";
    const double us = ms * 1e3;
    if (us >= 0.1) return QString::number(us, 'f', us >= 10 ? 1 : 2) + QString::fromUtf8(" µs");
    return QString::number(us * 1e3, 'f', 0) + " ns";
}

QString PlotsDock::axisLabelFormat(double lo, double hi, double step) {
    // Plain numbers with as many decimals as the ticks' step needs ("80000", "0.05"); the
    // exponent form only past what reads plainly ("8e+04" was the energy axis's label).
    const double big = std::max(std::abs(lo), std::abs(hi));
    if (!(step > 0.0) || big >= 1e7 || step < 1e-4) return QStringLiteral("%.3g");
    const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
    return QStringLiteral("%.%1f").arg(decimals);
}

void PlotsDock::fitAxis(QValueAxis* axis, const Range& r) {
    double lo = -1.0, hi = 1.0;
    if (!r.empty) {
        const double span = r.hi - r.lo;
        const double scale = std::max(std::abs(r.lo), std::abs(r.hi));
        // A flat curve (a body at rest, conserved energy) still gets a readable band.
        const double pad = span > 1e-9 * scale ? 0.05 * span : (scale > 0 ? 0.1 * scale : 1.0);
        lo = r.lo - pad;
        hi = r.hi + pad;
    }
    // Quantities that are never negative (kinetic energy, magnitudes) keep 0 as the floor.
    if (!r.empty && r.lo >= 0 && lo < 0) lo = 0;
    // Round ends and ticks (about six).
    const double step = niceStep((hi - lo) / 5);
    lo = std::floor(lo / step) * step;
    hi = std::ceil(hi / step) * step;
    if (axis->min() == lo && axis->max() == hi) return;
    axis->setLabelFormat(axisLabelFormat(lo, hi, step));
    axis->setRange(lo, hi);
    axis->setTickCount(static_cast<int>(std::lround((hi - lo) / step)) + 1);
}

void PlotsDock::updateProfile() {
    const Profile p = timeline_->profile();
    const double steps = static_cast<double>(p.steps);
    auto ms = [&](double seconds) { return p.steps > 0 ? timeText(seconds / steps) : QString(); };
    auto per = [&](long count) { return p.steps > 0 ? QString::number(count / steps, 'f', 2) : QString(); };
    const double stages[] = {p.forces,       p.integrate,   p.broadphase, p.narrowphase,
                             p.timeOfImpact, p.impactSolve, p.solve,      p.sleep};
    double all = 0.0;
    for (double t : stages) all += t;
    for (int r = 0; r < 8; ++r) {
        profile_->item(r, 1)->setText(ms(stages[r]));
        profile_->item(r, 2)->setText(all > 0 ? QString("%1 %").arg(100.0 * stages[r] / all, 0, 'f', 0)
                                              : QString());
    }
    profile_->item(ProfileTotal, 1)->setText(ms(all));
    profile_->item(ProfileSteps, 1)->setText(QString::number(p.steps));
    profile_->item(ProfilePairs, 1)->setText(per(p.pairs));
    profile_->item(ProfileContactPoints, 1)->setText(per(p.contactPoints));
    profile_->item(ProfileImpacts, 1)->setText(per(p.impacts));
}

}  // namespace tumble::ui
