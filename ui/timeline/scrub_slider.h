// The timeline's scrub slider, with marks on it: a short red line above the groove at each
// marked frame (a joint that broke), an amber one below it at a key of the selected animated
// body, its text shown when the pointer rests near it. A click
// on the track jumps to the frame there. A key's mark can be dragged to another frame, or
// deleted with a right click.
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
        int key = -1;  ///< an animated body's key (its index; amber, below the groove), or -1
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

signals:
    /// A key's mark dragged to `frame` (released there).
    void keyMoved(int key, int frame);
    /// A right click on a key's mark.
    void keyDeleteRequested(int key);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    bool event(QEvent* event) override;

private:
    // Where the style draws the groove and the handle, and how far the handle travels.
    struct Track {
        QRect groove, handle;
        int span = 0;
        bool upsideDown = false;
    };
    Track track() const;

    /// The key mark at x in the lower third (where key marks are drawn), or -1: its index
    /// in marks_.
    int keyMarkAt(const QPoint& at) const;

    std::vector<Mark> marks_;
    int dragged_ = -1;     // the key mark being dragged (index in marks_), or -1
    int draggedFrom_ = 0;  // its frame when pressed
};

}  // namespace tumble::ui
