#include "panels/plot_chart_view.h"

#include <QChart>
#include <QMouseEvent>
#include <QPainter>
#include <QValueAxis>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::ui {

PlotChartView::PlotChartView(QChart* chart, QWidget* parent)
    : QChartView(chart, parent), cursor_(std::numeric_limits<double>::quiet_NaN()) {
    setRenderHint(QPainter::Antialiasing);
    setRubberBand(QChartView::NoRubberBand);
    setMinimumSize(240, 160);
}

QValueAxis* PlotChartView::timeAxis() const {
    const auto axes = chart()->axes(Qt::Horizontal);
    return axes.isEmpty() ? nullptr : qobject_cast<QValueAxis*>(axes.first());
}

QRectF PlotChartView::plotRect() const {
    return chart()->mapRectToScene(chart()->plotArea());
}

void PlotChartView::setCursorTime(double time) {
    if (time == cursor_ || (std::isnan(time) && std::isnan(cursor_))) return;
    // Repaint only the strips under the old and the new line: the curves beneath are then
    // rasterised in those strips only (a whole chart of 10 000-point curves takes ~10 ms).
    const int before = std::isnan(cursor_) ? -1 : viewportPosition(cursor_).x();
    cursor_ = time;
    const int after = std::isnan(cursor_) ? -1 : viewportPosition(cursor_).x();
    const int h = viewport()->height();
    if (before >= 0) viewport()->update(QRect(before - 3, 0, 7, h));
    if (after >= 0) viewport()->update(QRect(after - 3, 0, 7, h));
}

QPoint PlotChartView::viewportPosition(double time) const {
    const QValueAxis* axis = timeAxis();
    const QRectF area = plotRect();
    if (!axis || !(axis->max() > axis->min()) || area.isEmpty()) return {-1, -1};
    const double x = area.left() + (time - axis->min()) / (axis->max() - axis->min()) * area.width();
    return mapFromScene(QPointF(x, area.center().y()));
}

bool PlotChartView::timeAt(const QPoint& pos, double* time) const {
    const QValueAxis* axis = timeAxis();
    const QRectF area = plotRect();
    if (!axis || !(axis->max() > axis->min()) || area.isEmpty()) return false;
    const QPointF p = mapToScene(pos);
    // A pixel of slack on each side: the edges of the plot area are frames too.
    if (!area.adjusted(-1, -1, 1, 1).contains(p)) return false;
    const double u = std::clamp((p.x() - area.left()) / area.width(), 0.0, 1.0);
    *time = axis->min() + u * (axis->max() - axis->min());
    return true;
}

void PlotChartView::mousePressEvent(QMouseEvent* event) {
    double t = 0.0;
    if (event->button() == Qt::LeftButton && timeAt(event->position().toPoint(), &t)) {
        emit timeClicked(t);
        event->accept();
        return;
    }
    QChartView::mousePressEvent(event);
}

void PlotChartView::mouseMoveEvent(QMouseEvent* event) {
    double t = 0.0;
    if ((event->buttons() & Qt::LeftButton) && timeAt(event->position().toPoint(), &t)) {
        emit timeClicked(t);
        event->accept();
        return;
    }
    QChartView::mouseMoveEvent(event);
}

void PlotChartView::drawForeground(QPainter* painter, const QRectF& rect) {
    QChartView::drawForeground(painter, rect);
    const QValueAxis* axis = timeAxis();
    if (std::isnan(cursor_) || !axis || !(axis->max() > axis->min())) return;
    const QRectF area = plotRect();
    if (cursor_ < axis->min() || cursor_ > axis->max()) return;
    // The same pixel column viewportPosition() names, so a click on the line seeks to it.
    const QPoint top = viewportPosition(cursor_);
    const QPointF x = mapToScene(QPoint(top.x(), 0));
    painter->save();
    painter->setRenderHint(QPainter::Antialiasing, false);
    QPen pen(cursorColor(), 2);
    pen.setCosmetic(true);
    painter->setPen(pen);
    painter->drawLine(QPointF(x.x(), area.top()), QPointF(x.x(), area.bottom()));
    painter->restore();
}

}  // namespace tumble::ui
