#include "timeline/scrub_slider.h"

#include <QHelpEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QToolTip>

namespace tumble::ui {

namespace {
constexpr int kNear = 4;  // pixels either side of a mark that show its text
}

ScrubSlider::ScrubSlider(QWidget* parent) : QSlider(Qt::Horizontal, parent) {}

void ScrubSlider::setMarks(std::vector<Mark> marks) {
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

void ScrubSlider::mousePressEvent(QMouseEvent* event) {
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
    p.setPen(QPen(QColor(0xd3, 0x2f, 0x2f), 2));
    for (const Mark& m : marks_) {
        if (m.frame < minimum() || m.frame > maximum()) continue;
        const int x = xOf(m.frame);
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
