// The timeline's scrub slider, with marks on it: a short red line above the groove at each
// marked frame (a joint that broke), its text shown when the pointer rests near it. A click
// on the track jumps to the frame there.
#pragma once

#include <QRect>
#include <QSlider>
#include <QString>

#include <vector>

namespace tumble::ui {

class ScrubSlider : public QSlider {
    Q_OBJECT
public:
    struct Mark {
        int frame = 0;
        QString text;
    };
    explicit ScrubSlider(QWidget* parent = nullptr);

    void setMarks(std::vector<Mark> marks);
    const std::vector<Mark>& marks() const { return marks_; }
    /// The x (widget pixels) at which frame `value` is drawn: where the handle's centre is
    /// when the slider is at it.
    int xOf(int value) const;
    /// The frame drawn at x (the inverse of xOf, to the nearest frame).
    int valueAt(int x) const;
    /// The marks' texts within a few pixels of x, one per line (empty: none there).
    QString textNear(int x) const;

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    bool event(QEvent* event) override;

private:
    // Where the style draws the groove and the handle, and how far the handle travels.
    struct Track {
        QRect groove, handle;
        int span = 0;
        bool upsideDown = false;
    };
    Track track() const;

    std::vector<Mark> marks_;
};

}  // namespace tumble::ui
