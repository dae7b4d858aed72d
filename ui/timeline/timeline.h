// The timeline: the simulation of the document's scene, run in a worker thread into a
// Recording, and the playhead over it (principle 8 of DESIGN.md: the simulation runs off
// the UI thread and the UI shows snapshots).
//
// Every edit to the document makes the recording stale (the edit is to the initial state):
// the run in progress is cancelled and, after a short pause so that a drag restarts it
// once, a new run starts from the edited scene. A cancelled run keeps the frames it made;
// the document is never touched by the timeline, except by "use this frame as the start",
// which is one undo step.
//
// The worker owns its World; the UI thread reads the recording under a mutex. A frame
// thinned out by the memory cap is re-simulated on the UI thread from its keyframe with a
// World of its own (bit for bit the recorded run).
#pragma once

#include <tumble/recording.h>
#include <tumble/world.h>

#include <QElapsedTimer>
#include <QObject>
#include <QString>

#include <functional>
#include <memory>
#include <vector>

class QTimer;

namespace tumble::ui {

class Document;

class Timeline : public QObject {
    Q_OBJECT
public:
    enum class Status {
        Empty,      ///< nothing simulated yet (or the scene does not compile)
        Running,    ///< the worker is filling the recording
        Complete,   ///< every frame of the scene's duration is recorded
        Cancelled,  ///< stopped by the user; the frames made so far stay playable
        Failed,     ///< the engine stopped (non-finite state, bad scene): see errorMessage()
    };
    Q_ENUM(Status)

    explicit Timeline(Document* document, QObject* parent = nullptr);
    ~Timeline() override;

    Document* document() const { return doc_; }

    // ---- The run.
    Status status() const { return status_; }
    /// The scene was edited since the recording was made (a new run is due or running).
    bool isStale() const { return stale_; }
    /// The engine's message when the run failed or the scene did not compile.
    const QString& errorMessage() const { return error_; }
    /// Frames of the whole run (duration × frame rate + 1) and frames recorded so far.
    int frameCount() const;
    int framesDone() const;
    double frameRate() const;
    /// Simulated seconds per wall-clock second of the current or last run.
    double speed() const;
    /// The compiled model of the recording (null before the first run).
    std::shared_ptr<const Model> model() const;
    /// The engine's stage times and counts, summed over the run so far.
    Profile profile() const;
    /// A copy of frame k's state (re-simulated when thinned); false when not recorded.
    bool frameState(int frame, State* out) const;
    /// Frame k's energy and momentum; frames done only.
    FrameSummary summary(int frame) const;
    /// Summaries of frames [0, framesDone()).
    std::vector<FrameSummary> summaries() const;
    /// Body `body`'s state at every kept frame up to `lastFrame` (-1: all done), with the
    /// frame numbers: every frame while keyframeInterval() is 1, else the keyframes (no
    /// re-simulation). For plots and trails.
    void bodyTrack(int body, std::vector<int>* frames, std::vector<BodyState>* states,
                   int lastFrame = -1) const;

    /// A joint that broke in the run: the first recorded frame at or after the moment (its
    /// state is the first without the joint), the joint (Model::joints' index) and the time.
    struct JointBreak {
        int frame = 0;
        int joint = -1;
        double time = 0.0;
    };
    /// The breaks of the run so far, in frame order.
    std::vector<JointBreak> jointBreaks() const;

    /// What an exporter needs of the current recording, valid and thread-safe after the
    /// timeline has moved on to another run (it keeps that run's recording alive).
    struct Frames {
        std::shared_ptr<const Model> model;
        SceneDesc scene;  ///< the scene as it was simulated (meshes loaded)
        int frameCount = 0;
        double frameRate = 0.0;
        /// Frame k's state (re-simulated when thinned); false when not recorded.
        std::function<bool(int frame, State* out)> read;
    };
    /// Null model when nothing is recorded.
    Frames frames() const;

    /// The memory cap of the recording (bytes). Lowering it thins a recording at once.
    std::size_t memoryCap() const { return cap_; }
    void setMemoryCap(std::size_t bytes);
    /// 1 while every frame is kept in memory; else K, frames kept at multiples of K.
    int keyframeInterval() const;
    std::size_t recordingBytes() const;

    /// Re-simulate by itself after every edit (on by default).
    bool autoSimulate() const { return auto_; }
    void setAutoSimulate(bool on);

    // ---- The playhead and playback.
    int currentFrame() const { return frame_; }
    /// The state shown at the playhead (a copy; invalid time when nothing is recorded).
    const State& currentState() const { return current_; }
    bool hasCurrentState() const { return hasCurrent_; }
    bool isPlaying() const;
    bool loops() const { return loop_; }
    /// Playback rate: 1 is real time; 0.1 to 4.
    double playbackSpeed() const { return rate_; }

public slots:
    /// Starts a new run of the document's scene from its initial state (cancels any run).
    void simulate();
    /// Stops the run in progress; the frames made so far stay.
    void cancel();
    /// Moves the playhead (clamped to the frames done) and shows that frame.
    void seek(int frame);
    void stepForward() { seek(frame_ + 1); }
    void stepBack() { seek(frame_ - 1); }
    void toStart() { seek(0); }
    void toEnd();
    void play();
    void pause();
    void togglePlay();
    void setLoop(bool on);
    void setPlaybackSpeed(double rate);
    /// Makes the state at the playhead the scene's initial state: every body's position,
    /// orientation, velocity and angular velocity (one undo step). False when there is no
    /// frame there or it is frame 0.
    bool useCurrentFrameAsStart();

signals:
    void statusChanged(tumble::ui::Timeline::Status status);
    void staleChanged(bool stale);
    /// A new run started: the recording was cleared.
    void recordingReset();
    /// Frames were added (throttled to a few times a second, and once at the end).
    void progress(int framesDone, int frameCount);
    /// The playhead moved, or the frame under it changed (a new run).
    void currentFrameChanged(int frame);
    void playingChanged(bool playing);

private:
    struct Run;
    static bool readFrame(Run& run, int frame, State* out);
    void markStale();
    void startRun();
    void retire();
    void onWorkerProgress(int runId);
    void onWorkerFinished(int runId);
    void advancePlayback();
    void loadCurrent();

    Document* doc_;
    std::shared_ptr<Run> run_;
    std::vector<std::shared_ptr<Run>> retired_;  // cancelled runs whose threads are still ending
    Status status_ = Status::Empty;
    bool stale_ = false;
    bool auto_ = true;
    QString error_;
    std::size_t cap_ = std::size_t(512) << 20;
    QTimer* restart_ = nullptr;  // the pause after an edit before a new run
    QTimer* playTimer_ = nullptr;
    QElapsedTimer playClock_;
    double playOrigin_ = 0.0;  // simulated time at playClock_ start
    int frame_ = 0;
    State current_;
    bool hasCurrent_ = false;
    bool loop_ = false;
    double rate_ = 1.0;
};

}  // namespace tumble::ui
