#include "timeline/timeline_dock.h"

#include "timeline/timeline.h"

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QSettings>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>

namespace tumble::ui {

namespace {

QToolButton* buttonFor(QAction* action) {
    auto* b = new QToolButton;
    b->setDefaultAction(action);
    b->setAutoRaise(true);
    return b;
}

QAction* newAction(QObject* parent, const QString& text, const QString& name, QStyle::StandardPixmap icon,
                   const QKeySequence& key) {
    auto* a = new QAction(text, parent);
    a->setObjectName(name);
    if (icon != QStyle::SP_CustomBase) a->setIcon(qApp->style()->standardIcon(icon));
    if (!key.isEmpty()) {
        a->setShortcut(key);
        a->setToolTip(QStringLiteral("%1 (%2)").arg(text, key.toString(QKeySequence::NativeText)));
    }
    return a;
}

constexpr double kSpeeds[] = {0.1, 0.25, 0.5, 1.0, 2.0, 4.0};

}  // namespace

TimelineDock::TimelineDock(Timeline* timeline, QWidget* parent)
    : QDockWidget(tr("Timeline"), parent), timeline_(timeline) {
    setObjectName(QStringLiteral("TimelineDock"));

    start_ = newAction(this, tr("Jump to Start"), "toStart", QStyle::SP_MediaSkipBackward, Qt::Key_Home);
    back_ = newAction(this, tr("Step Back"), "stepBack", QStyle::SP_MediaSeekBackward, Qt::Key_Left);
    play_ = newAction(this, tr("Play"), "play", QStyle::SP_MediaPlay, Qt::Key_Space);
    forward_ = newAction(this, tr("Step Forward"), "stepForward", QStyle::SP_MediaSeekForward, Qt::Key_Right);
    // End alone is Scene > Drop to Surface (as in other editors); Home keeps the start.
    start_->setShortcuts({QKeySequence(Qt::Key_Home), QKeySequence(Qt::CTRL | Qt::Key_Home)});
    end_ = newAction(this, tr("Jump to End"), "toEnd", QStyle::SP_MediaSkipForward,
                     QKeySequence(Qt::CTRL | Qt::Key_End));
    loop_ = newAction(this, tr("Loop"), "loop", QStyle::SP_BrowserReload, QKeySequence(tr("L")));
    loop_->setCheckable(true);
    simulate_ =
        newAction(this, tr("Simulate"), "simulate", QStyle::SP_CustomBase, QKeySequence(tr("Ctrl+R")));
    cancel_ =
        newAction(this, tr("Cancel"), "cancel", QStyle::SP_DialogCancelButton, QKeySequence(tr("Ctrl+.")));
    useFrame_ = newAction(this, tr("Use Frame as Start"), "useFrame", QStyle::SP_CustomBase, QKeySequence());
    useFrame_->setToolTip(tr("Make the state at the playhead the scene's initial state (one undo step)"));

    connect(start_, &QAction::triggered, timeline_, &Timeline::toStart);
    connect(back_, &QAction::triggered, timeline_, [this] {
        timeline_->pause();
        timeline_->stepBack();
    });
    connect(play_, &QAction::triggered, timeline_, &Timeline::togglePlay);
    connect(forward_, &QAction::triggered, timeline_, [this] {
        timeline_->pause();
        timeline_->stepForward();
    });
    connect(end_, &QAction::triggered, timeline_, &Timeline::toEnd);
    connect(loop_, &QAction::toggled, timeline_, &Timeline::setLoop);
    connect(simulate_, &QAction::triggered, timeline_, &Timeline::simulate);
    connect(cancel_, &QAction::triggered, timeline_, &Timeline::cancel);
    connect(useFrame_, &QAction::triggered, timeline_, &Timeline::useCurrentFrameAsStart);

    slider_ = new ScrubSlider;
    slider_->setObjectName(QStringLiteral("scrub"));
    slider_->setMinimumWidth(200);
    slider_->setTracking(true);  // scrubbing shows each frame as the handle passes it
    connect(slider_, &QSlider::valueChanged, timeline_, [this](int v) {
        if (v != timeline_->currentFrame()) timeline_->seek(v);
    });
    connect(slider_, &ScrubSlider::keyMoved, this, [this](int key, int frame) {
        const double rate = timeline_->frameRate();
        if (rate > 0.0) emit keyMoved(key, frame / rate);
    });
    connect(slider_, &ScrubSlider::keyDeleteRequested, this, &TimelineDock::keyDeleteRequested);
    position_ = new QLabel;
    position_->setObjectName(QStringLiteral("position"));
    position_->setMinimumWidth(
        position_->fontMetrics().horizontalAdvance(QStringLiteral("t = 0000.000 s   frame 00000 / 00000")));

    speed_ = new QComboBox;
    speed_->setObjectName(QStringLiteral("speed"));
    for (double s : kSpeeds) speed_->addItem(QStringLiteral("%1×").arg(s), s);
    speed_->setCurrentIndex(3);  // real time
    speed_->setToolTip(tr("Playback speed (1× is real time)"));
    connect(speed_, &QComboBox::currentIndexChanged, timeline_,
            [this](int i) { timeline_->setPlaybackSpeed(speed_->itemData(i).toDouble()); });

    progress_ = new QProgressBar;
    progress_->setObjectName(QStringLiteral("progress"));
    progress_->setTextVisible(true);
    status_ = new QLabel;
    status_->setObjectName(QStringLiteral("status"));
    status_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    cap_ = new QSpinBox;
    cap_->setObjectName(QStringLiteral("memoryCap"));
    cap_->setRange(16, 65536);
    cap_->setSingleStep(64);
    cap_->setSuffix(tr(" MB"));
    // The cap is the user's choice for their machine: it persists.
    const int savedCap = QSettings().value(QStringLiteral("timeline/memoryCapMB"), 0).toInt();
    if (savedCap >= 16) timeline_->setMemoryCap(std::size_t(savedCap) << 20);
    cap_->setValue(static_cast<int>(timeline_->memoryCap() >> 20));
    cap_->setKeyboardTracking(false);
    cap_->setToolTip(
        tr("Most memory the recording keeps. Past it only keyframes are kept and the frames "
           "between are re-simulated when shown."));
    connect(cap_, &QSpinBox::valueChanged, timeline_, [this](int mb) {
        timeline_->setMemoryCap(std::size_t(mb) << 20);
        QSettings().setValue(QStringLiteral("timeline/memoryCapMB"), mb);
        updateStatus();
    });
    auto_ = new QCheckBox(tr("Re-simulate on edit"));
    auto_->setObjectName(QStringLiteral("autoSimulate"));
    auto_->setChecked(timeline_->autoSimulate());
    connect(auto_, &QCheckBox::toggled, timeline_, &Timeline::setAutoSimulate);

    auto* transport = new QHBoxLayout;
    transport->setContentsMargins(0, 0, 0, 0);
    for (QAction* a : {start_, back_, play_, forward_, end_, loop_}) transport->addWidget(buttonFor(a));
    transport->addWidget(speed_);
    transport->addWidget(slider_, 1);
    transport->addWidget(position_);

    auto* run = new QHBoxLayout;
    run->setContentsMargins(0, 0, 0, 0);
    auto* simButton = new QToolButton;
    simButton->setDefaultAction(simulate_);
    simButton->setToolButtonStyle(Qt::ToolButtonTextOnly);
    auto* cancelButton = buttonFor(cancel_);
    cancelButton->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    auto* useButton = new QToolButton;
    useButton->setDefaultAction(useFrame_);
    run->addWidget(simButton);
    run->addWidget(progress_, 1);
    run->addWidget(cancelButton);
    run->addWidget(status_, 1);
    run->addWidget(useButton);
    run->addWidget(auto_);
    run->addWidget(new QLabel(tr("Memory cap:")));
    run->addWidget(cap_);

    auto* body = new QWidget;
    auto* layout = new QVBoxLayout(body);
    layout->setContentsMargins(4, 2, 4, 2);
    layout->setSpacing(2);
    layout->addLayout(transport);
    layout->addLayout(run);
    setWidget(body);

    connect(timeline_, &Timeline::currentFrameChanged, this, &TimelineDock::updatePosition);
    connect(timeline_, &Timeline::progress, this, [this] {
        updateRange();
        updateStatus();
    });
    connect(timeline_, &Timeline::recordingReset, this, [this] {
        updateRange();
        updateStatus();
    });
    connect(timeline_, &Timeline::statusChanged, this, &TimelineDock::updateStatus);
    connect(timeline_, &Timeline::staleChanged, this, &TimelineDock::updateStatus);
    connect(timeline_, &Timeline::playingChanged, this, [this](bool playing) {
        play_->setText(playing ? tr("Pause") : tr("Play"));
        play_->setIcon(style()->standardIcon(playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
    });
    updateRange();
    updatePosition();
    updateStatus();
}

QString TimelineDock::positionText() const {
    return position_->text();
}

QString TimelineDock::statusText() const {
    return status_->text();
}

void TimelineDock::updateRange() {
    const QSignalBlocker block(slider_);
    slider_->setRange(0, std::max(0, timeline_->framesDone() - 1));
    slider_->setValue(timeline_->currentFrame());
    progress_->setRange(0, std::max(1, timeline_->frameCount()));
    progress_->setValue(timeline_->framesDone());
    progress_->setFormat(tr("%v / %m frames"));
    // A joint that broke: a mark on the slider at the first frame without it.
    std::vector<ScrubSlider::Mark> marks;
    const auto model = timeline_->model();
    for (const Timeline::JointBreak& b : timeline_->jointBreaks()) {
        const QString name = model && b.joint < int(model->joints.size())
                                 ? QString::fromStdString(model->joints[size_t(b.joint)].name)
                                 : QString::number(b.joint);
        marks.push_back({b.frame, tr("joint %1 broke at t = %2 s (frame %3)").arg(name).arg(b.time, 0, 'f', 3).arg(b.frame)});
    }
    // The selected animated body's keys: ticks at their frames.
    const double rate = timeline_->frameRate();
    for (size_t k = 0; k < keyTimes_.size() && rate > 0.0; ++k) {
        const double t = keyTimes_[k];
        marks.push_back(
            {int(std::lround(t * rate)),
             tr("%1: key at t = %2 s (drag to move, right-click to delete)").arg(keyBody_).arg(t, 0, 'g', 6),
             int(k)});
    }
    slider_->setMarks(std::move(marks));
}

void TimelineDock::setKeyTimes(const std::vector<double>& times, const QString& body) {
    keyTimes_ = times;  // (the same again redraws them: a refused drag's tick goes back)
    keyBody_ = body;
    updateRange();
}

void TimelineDock::updatePosition() {
    const int k = timeline_->currentFrame();
    {
        const QSignalBlocker block(slider_);
        slider_->setValue(k);
    }
    const double t = timeline_->frameRate() > 0 ? k / timeline_->frameRate() : 0.0;
    position_->setText(tr("t = %1 s   frame %2 / %3")
                           .arg(t, 0, 'f', 3)
                           .arg(k)
                           .arg(std::max(0, timeline_->frameCount() - 1)));
    useFrame_->setEnabled(k > 0 && timeline_->hasCurrentState() && !timeline_->isStale());
}

void TimelineDock::updateStatus() {
    const Timeline::Status s = timeline_->status();
    const int done = timeline_->framesDone();
    const double simulated = done > 0 ? timeline_->summary(done - 1).time : 0.0;
    QString text;
    switch (s) {
        case Timeline::Status::Empty: text = tr("Not simulated"); break;
        case Timeline::Status::Running: text = tr("Simulating"); break;
        case Timeline::Status::Complete: text = tr("Done"); break;
        case Timeline::Status::Cancelled: text = tr("Cancelled"); break;
        case Timeline::Status::Failed: text = tr("Failed: %1").arg(timeline_->errorMessage()); break;
    }
    if (done > 0) {
        text += tr(" · %1 s simulated").arg(simulated, 0, 'f', 2);
        if (const double v = timeline_->speed(); v > 0)
            text += tr(" · %1× real time").arg(v, 0, 'f', v >= 100 ? 0 : v >= 10 ? 1 : 2);
    }
    if (timeline_->keyframeInterval() > 1)
        text += tr(" · keyframes every %1 frames").arg(timeline_->keyframeInterval());
    if (timeline_->isStale()) text += tr(" · stale: the scene was edited");
    // What the engine noted of the scene it ran (a mesh that is not closed, a joint that does
    // not hold as placed): counted here, each in the tooltip.
    QStringList notes;
    if (const auto model = timeline_->model())
        for (const std::string& n : model->notes) notes << QString::fromStdString(n);
    if (const int broken = int(timeline_->jointBreaks().size()); broken > 0)
        text += tr(" · %n joint(s) broke (red on the slider)", nullptr, broken);
    if (!notes.isEmpty()) text += tr(" · %n note(s): hover to read", nullptr, int(notes.size()));
    status_->setToolTip(notes.join('\n'));
    status_->setText(text);
    status_->setStyleSheet(s == Timeline::Status::Failed ? QStringLiteral("color: #b00020") : QString());
    cancel_->setEnabled(s == Timeline::Status::Running);
    updatePosition();
}

}  // namespace tumble::ui
