#include "timeline/scrub_slider.h"

#include <QHelpEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QToolTip>

#include <algorithm>

namespace tumble::ui {

namespace {
constexpr int kNear = 4;  // pixels either side of a mark that show its text
}

ScrubSlider::ScrubSlider(QWidget* parent) : QSlider(Qt::Horizontal, parent) {}

void ScrubSlider::setMarks(std::vector<Mark> marks) {
    // A key's mark being dragged stays under the pointer while the run goes on (the range
    // grows); a drag of a mark that is no more ends.
    const size_t d = size_t(dragged_);
    if (dragged_ >= 0 && d < marks.size() && d < marks_.size() && marks[d].key == marks_[d].key)
        marks[d].frame = marks_[d].frame;
    else
        dragged_ = -1;
    marks_ = std::move(marks);
    update();
}

ScrubSlider::Track ScrubSlider::track() const {
    QStyleOptionSlider opt;
    initStyleOption(&opt);
    Track t;
    t.groove = style()->subControlRect(QStyle::CC_Slider, &opt, QStyle::SC_SliderGroove, this);
    t.handle = style()->subControlRect(QStyle::CC_Slider, &opt, QStyle::SC_SliderHandle, this);
    t.span = std::max(0, t.groove.width() - t.handle.width());
    t.upsideDown = opt.upsideDown;
    return t;
}

int ScrubSlider::xOf(int value) const {
    const Track t = track();
    return t.groove.x() + t.handle.width() / 2 +
           QStyle::sliderPositionFromValue(minimum(), maximum(), value, t.span, t.upsideDown);
}

int ScrubSlider::valueAt(int x) const {
    const Track t = track();
    return QStyle::sliderValueFromPosition(minimum(), maximum(), x - t.groove.x() - t.handle.width() / 2, t.span,
                                           t.upsideDown);
}

int ScrubSlider::keyMarkAt(const QPoint& at) const {
    if (at.y() < height() - height() / 3 - kNear) return -1;
    for (size_t k = 0; k < marks_.size(); ++k) {
        const Mark& m = marks_[k];
        if (m.key >= 0 && m.frame >= minimum() && m.frame <= maximum() &&
            std::abs(xOf(m.frame) - at.x()) <= kNear)
            return int(k);
    }
    return -1;
}

void ScrubSlider::mouseMoveEvent(QMouseEvent* event) {
    if (dragged_ < 0) {
        QSlider::mouseMoveEvent(event);
        return;
    }
    marks_[size_t(dragged_)].frame =
        std::clamp(valueAt(event->position().toPoint().x()), minimum(), maximum());
    update();
}

void ScrubSlider::mouseReleaseEvent(QMouseEvent* event) {
    if (dragged_ < 0) {
        QSlider::mouseReleaseEvent(event);
        return;
    }
    const Mark m = marks_[size_t(dragged_)];
    dragged_ = -1;
    if (m.frame != draggedFrom_) emit keyMoved(m.key, m.frame);  // (a click leaves a key off the frames be)
}

void ScrubSlider::mousePressEvent(QMouseEvent* event) {
    // A key's mark: dragged (left) or deleted (right), the playhead left where it is.
    if (const int k = keyMarkAt(event->position().toPoint()); k >= 0) {
        if (event->button() == Qt::LeftButton) {
            dragged_ = k;
            draggedFrom_ = marks_[size_t(k)].frame;
        }
        if (event->button() == Qt::RightButton) emit keyDeleteRequested(marks_[size_t(k)].key);
        event->accept();
        return;
    }
    // A click on the track jumps to the frame under the pointer (QSlider steps a page
    // towards it, ten frames), and the handle, now under the pointer, drags from there.
    if (event->button() == Qt::LeftButton) {
        const QPoint at = event->position().toPoint();
        if (!track().handle.contains(at)) setValue(valueAt(at.x()));
    }
    QSlider::mousePressEvent(event);
}

QString ScrubSlider::textNear(int x) const {
    QStringList lines;
    for (const Mark& m : marks_)
        if (m.frame >= minimum() && m.frame <= maximum() && std::abs(xOf(m.frame) - x) <= kNear) lines << m.text;
    return lines.join('\n');
}

void ScrubSlider::paintEvent(QPaintEvent* event) {
    QSlider::paintEvent(event);
    if (marks_.empty()) return;
    QPainter p(this);
    const QPen broke(QColor(0xd3, 0x2f, 0x2f), 2), key(QColor(0xff, 0xa0, 0x00), 2);
    for (const Mark& m : marks_) {
        if (m.frame < minimum() || m.frame > maximum()) continue;
        const int x = xOf(m.frame);
        p.setPen(m.key >= 0 ? key : broke);
        if (m.key >= 0)
            p.drawLine(x, height() - height() / 3, x, height());
        else
            p.drawLine(x, 0, x, height() / 3);
    }
}

bool ScrubSlider::event(QEvent* e) {
    if (e->type() == QEvent::ToolTip) {
        auto* help = static_cast<QHelpEvent*>(e);
        const QString text = textNear(help->pos().x());
        if (!text.isEmpty()) {
            QToolTip::showText(help->globalPos(), text, this);
            return true;
        }
    }
    return QSlider::event(e);
}

}  // namespace tumble::ui
