// The timeline dock: transport buttons, the scrub slider with time and frame number, loop
// and playback speed; the run's progress (frames done, simulated time, speed) with Cancel;
// "Use Frame as Start"; the recording's memory cap. Its actions carry the keyboard
// shortcuts (Space, Left, Right, Home, End) and the main window puts them in a menu so
// they work anywhere in the window.
#pragma once

#include <vector>

#include "timeline/scrub_slider.h"

#include <QDockWidget>

class QAction;
class QCheckBox;
class QComboBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSlider;
class QSpinBox;
class QToolButton;

namespace tumble::ui {

class Timeline;

class TimelineDock : public QDockWidget {
    Q_OBJECT
public:
    explicit TimelineDock(Timeline* timeline, QWidget* parent = nullptr);

    Timeline* timeline() const { return timeline_; }

    QAction* playAction() const { return play_; }
    QAction* stepBackAction() const { return back_; }
    QAction* stepForwardAction() const { return forward_; }
    QAction* toStartAction() const { return start_; }
    QAction* toEndAction() const { return end_; }
    QAction* loopAction() const { return loop_; }
    QAction* simulateAction() const { return simulate_; }
    QAction* cancelAction() const { return cancel_; }
    QAction* useFrameAction() const { return useFrame_; }

    /// The scrub slider (its value is the playhead's frame; a joint's break is marked on it).
    ScrubSlider* slider() const { return slider_; }
    /// "t = 1.250 s   frame 75 / 121".
    QString positionText() const;
    /// The progress line: frames done, simulated time, speed, stale or failed.
    QString statusText() const;

    /// The keys of the selected animated body (`body`: its name), drawn as amber ticks on the
    /// slider at their frames; none when `times` is empty.
    void setKeyTimes(const std::vector<double>& times, const QString& body);

signals:
    /// Key `key` (of setKeyTimes' list) dragged on the slider to `time`, or asked deleted.
    void keyMoved(int key, double time);
    void keyDeleteRequested(int key);

private:
    void updateRange();
    void updatePosition();
    void updateStatus();

    Timeline* timeline_;
    std::vector<double> keyTimes_;
    QString keyBody_;
    QAction* play_;
    QAction* back_;
    QAction* forward_;
    QAction* start_;
    QAction* end_;
    QAction* loop_;
    QAction* simulate_;
    QAction* cancel_;
    QAction* useFrame_;
    ScrubSlider* slider_;
    QLabel* position_;
    QComboBox* speed_;
    QProgressBar* progress_;
    QLabel* status_;
    QSpinBox* cap_;
    QCheckBox* auto_;
};

}  // namespace tumble::ui
