// One chart of the plots dock: a QChartView that draws the playhead as a vertical line over
// the plot area and turns a click (or a drag) in the plot area into a time. Kept out of
// plots_dock.h so that only the editor library sees Qt Charts.
//
// The cursor is drawn in the foreground from the time axis' range rather than as a series:
// it then never changes the value axes' ranges and costs no series update when it moves.
#pragma once

#include <QChartView>
#include <QColor>

class QValueAxis;

namespace tumble::ui {

class PlotChartView : public QChartView {
    Q_OBJECT
public:
    /// Takes ownership of `chart`; its horizontal axis (a QValueAxis) is time in seconds.
    explicit PlotChartView(QChart* chart, QWidget* parent = nullptr);

    /// The colour of the playhead line (distinct from the series' colours).
    static QColor cursorColor() { return QColor(220, 0, 110); }

    /// Draws the playhead at `time` (s); NaN hides it.
    void setCursorTime(double time);
    double cursorTime() const { return cursor_; }

    /// Viewport coordinates of `time` on the time axis, halfway up the plot area; the
    /// x is where the cursor line is drawn. (-1, -1) when the axis has no range.
    QPoint viewportPosition(double time) const;
    /// The time under viewport position `pos`; false outside the plot area.
    bool timeAt(const QPoint& pos, double* time) const;

signals:
    /// The user clicked or dragged in the plot area at `time` (s).
    void timeClicked(double time);

protected:
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void drawForeground(QPainter* painter, const QRectF& rect) override;

private:
    QValueAxis* timeAxis() const;
    /// The plot area in scene coordinates.
    QRectF plotRect() const;

    double cursor_;
};

}  // namespace tumble::ui
