#include "timeline/timeline.h"

#include "document/document.h"

#include <tumble/errors.h>
#include <tumble/model.h>

#include <QTimer>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

namespace tumble::ui {

namespace {
// A drag sends an edit per mouse move: the new run starts once the edits pause this long.
constexpr int kRestartDelayMs = 250;
// The worker tells the UI about new frames at most this often.
constexpr double kProgressInterval = 0.05;
constexpr int kPlaybackTickMs = 15;

// Threads a World steps with in the editor: the machine's cores but one, which the window
// keeps, up to 8 (the stages spread over them give the same frames bit for bit, so recorded
// and re-simulated frames agree). A helper thread that the window's drawing pushes off its
// core in the middle of a chunk holds the whole step up: on 2 cores with the other one busy
// a small scene stepped 14 times slower on two threads than on one.
int stepThreads() {
    const unsigned cores = std::thread::hardware_concurrency();
    return static_cast<int>(std::clamp(cores > 1 ? cores - 1 : 1U, 1U, 8U));
}
}  // namespace

// One run of the simulation: the worker thread, what it records, and the UI thread's own
// World for re-simulating thinned frames. Everything the two threads share is under `mutex`
// or atomic.
struct Timeline::Run {
    int id = 0;  // the queued reports name their run by this, never by address
    SceneDesc scene;
    int frames = 0;
    double frameRate = 60.0;
    mutable std::mutex mutex;
    Recording recording;                   // guarded
    std::vector<JointBreak> breaks;        // guarded
    std::shared_ptr<const Model> model;    // guarded; set once compiled
    Profile profile;                       // guarded
    std::string error;                     // guarded
    bool failed = false;                   // guarded
    mutable std::unique_ptr<World> scrub;  // guarded: re-simulates thinned frames
    double wallSeconds = 0.0;              // guarded
    std::atomic<bool> cancel{false};
    std::atomic<bool> finished{false};
    std::atomic<bool> notifyPending{false};
    std::thread thread;

    explicit Run(std::size_t cap) : recording(cap) {}
    ~Run() {
        cancel = true;
        if (thread.joinable()) thread.join();
    }
};

Timeline::Timeline(Document* document, QObject* parent) : QObject(parent), doc_(document) {
    restart_ = new QTimer(this);
    restart_->setSingleShot(true);
    restart_->setInterval(kRestartDelayMs);
    connect(restart_, &QTimer::timeout, this, &Timeline::simulate);
    playTimer_ = new QTimer(this);
    playTimer_->setInterval(kPlaybackTickMs);
    playTimer_->setTimerType(Qt::PreciseTimer);
    connect(playTimer_, &QTimer::timeout, this, &Timeline::advancePlayback);

    connect(doc_, &Document::bodyChanged, this, &Timeline::markStale);
    connect(doc_, &Document::bodyInserted, this, &Timeline::markStale);
    connect(doc_, &Document::bodyRemoved, this, &Timeline::markStale);
    connect(doc_, &Document::settingsChanged, this, &Timeline::markStale);
    connect(doc_, &Document::jointsChanged, this, &Timeline::markStale);
    connect(doc_, &Document::sceneReset, this, [this] {
        // A different scene: the old frames say nothing about it.
        seek(0);
        markStale();
    });
}

Timeline::~Timeline() {
    if (run_) run_->cancel = true;
    for (auto& r : retired_) r->cancel = true;
    run_.reset();
    retired_.clear();  // joins
}

int Timeline::frameCount() const {
    if (!run_) return 0;
    return run_->frames;
}

int Timeline::framesDone() const {
    if (!run_) return 0;
    std::lock_guard lock(run_->mutex);
    return run_->recording.framesDone();
}

double Timeline::frameRate() const {
    return run_ ? run_->frameRate : doc_->scene().settings.frameRate;
}

double Timeline::speed() const {
    if (!run_) return 0.0;
    std::lock_guard lock(run_->mutex);
    const int done = run_->recording.framesDone();
    if (done < 2 || run_->wallSeconds <= 0.0) return 0.0;
    return run_->recording.summary(done - 1).time / run_->wallSeconds;
}

std::shared_ptr<const Model> Timeline::model() const {
    if (!run_) return nullptr;
    std::lock_guard lock(run_->mutex);
    return run_->model;
}

Profile Timeline::profile() const {
    if (!run_) return {};
    std::lock_guard lock(run_->mutex);
    return run_->profile;
}

bool Timeline::frameState(int frame, State* out) const {
    return run_ && readFrame(*run_, frame, out);
}

Timeline::Frames Timeline::frames() const {
    Frames f;
    if (!run_) return f;
    std::shared_ptr<Run> run = run_;
    f.model = model();
    f.scene = run->scene;
    f.frameCount = run->frames;
    f.frameRate = run->frameRate;
    f.read = [run](int k, State* out) { return readFrame(*run, k, out); };
    return f;
}

bool Timeline::readFrame(Run& r, int frame, State* out) {
    std::lock_guard lock(r.mutex);
    if (frame < 0 || frame >= r.recording.framesDone() || !r.model) return false;
    if (const State* s = r.recording.stored(frame)) {
        *out = *s;
        return true;
    }
    if (!r.scrub) {
        r.scrub = std::make_unique<World>(Model(*r.model), State{});
        r.scrub->setThreads(stepThreads());
    }
    const State* s = r.recording.state(frame, *r.scrub);
    if (!s) return false;
    *out = *s;
    return true;
}

FrameSummary Timeline::summary(int frame) const {
    if (!run_) return {};
    std::lock_guard lock(run_->mutex);
    if (frame < 0 || frame >= run_->recording.framesDone()) return {};
    return run_->recording.summary(frame);
}

std::vector<Timeline::JointBreak> Timeline::jointBreaks() const {
    if (!run_) return {};
    std::lock_guard lock(run_->mutex);
    return run_->breaks;
}

std::vector<FrameSummary> Timeline::summaries() const {
    std::vector<FrameSummary> out;
    if (!run_) return out;
    std::lock_guard lock(run_->mutex);
    const int n = run_->recording.framesDone();
    out.reserve(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) out.push_back(run_->recording.summary(k));
    return out;
}

void Timeline::bodyTrack(int body, std::vector<int>* frames, std::vector<BodyState>* states,
                         int lastFrame) const {
    frames->clear();
    states->clear();
    if (!run_) return;
    std::lock_guard lock(run_->mutex);
    const Recording& rec = run_->recording;
    const int end = lastFrame < 0 ? rec.framesDone() : std::min(lastFrame + 1, rec.framesDone());
    for (int k = 0; k < end; ++k) {
        const State* s = rec.stored(k);
        if (!s || body < 0 || body >= static_cast<int>(s->bodies.size())) continue;
        frames->push_back(k);
        states->push_back(s->bodies[static_cast<std::size_t>(body)]);
    }
}

void Timeline::setMemoryCap(std::size_t bytes) {
    cap_ = bytes;
    if (!run_) return;
    std::lock_guard lock(run_->mutex);
    run_->recording.setCapBytes(bytes);
}

int Timeline::keyframeInterval() const {
    if (!run_) return 1;
    std::lock_guard lock(run_->mutex);
    return run_->recording.keyframeInterval();
}

std::size_t Timeline::recordingBytes() const {
    if (!run_) return 0;
    std::lock_guard lock(run_->mutex);
    return run_->recording.bytes();
}

void Timeline::setAutoSimulate(bool on) {
    auto_ = on;
    if (!on)
        restart_->stop();
    else if (stale_)
        restart_->start();
}

bool Timeline::isPlaying() const {
    return playTimer_->isActive();
}

void Timeline::markStale() {
    if (!stale_) {
        stale_ = true;
        emit staleChanged(true);
    }
    if (run_ && !run_->finished) cancel();
    if (auto_) restart_->start();  // (re)starts the pause
}

void Timeline::simulate() {
    restart_->stop();
    startRun();
}

// Cancelled runs may still be inside a frame: they end in the background and are joined
// once they have.
void Timeline::retire() {
    if (run_) {
        run_->cancel = true;
        retired_.push_back(std::move(run_));
    }
    std::erase_if(retired_, [](const std::shared_ptr<Run>& r) { return r->finished.load(); });
}

void Timeline::startRun() {
    retire();
    auto run = std::make_shared<Run>(cap_);
    static int lastId = 0;
    run->id = ++lastId;
    run->scene = doc_->scene();
    run->frameRate = run->scene.settings.frameRate;
    run->frames = tumble::frameCount(run->scene.settings);
    run->recording.reset(run->frames);
    run_ = run;
    error_.clear();
    hasCurrent_ = false;
    const bool wasStale = stale_;
    stale_ = false;
    status_ = Status::Running;
    emit recordingReset();
    if (wasStale) emit staleChanged(false);
    emit statusChanged(status_);

    Run* r = run.get();
    const int id = r->id;
    r->thread = std::thread([this, r, id] {
        const auto wallStart = std::chrono::steady_clock::now();
        auto lastNotify = wallStart;
        auto notify = [&](bool force) {
            const auto now = std::chrono::steady_clock::now();
            {
                std::lock_guard lock(r->mutex);
                r->wallSeconds = std::chrono::duration<double>(now - wallStart).count();
            }
            if (!force && std::chrono::duration<double>(now - lastNotify).count() < kProgressInterval) return;
            lastNotify = now;
            if (!force && r->notifyPending.exchange(true)) return;
            QMetaObject::invokeMethod(
                this, [this, id] { onWorkerProgress(id); }, Qt::QueuedConnection);
        };
        try {
            auto model = std::make_shared<const Model>(compile(r->scene));
            World world(*model, initialState(*model, r->scene));
            world.setThreads(stepThreads());
            {
                std::lock_guard lock(r->mutex);
                r->model = model;
                r->recording.append(world.state(), summarize(*model, world.state(), 0));
            }
            notify(false);
            std::vector<char> broken(model->joints.size(), 0);
            for (int k = 1; k < r->frames && !r->cancel; ++k) {
                const long steps = advanceFrame(world, k);
                const FrameSummary summary = summarize(*model, world.state(), steps);
                {
                    std::lock_guard lock(r->mutex);
                    r->recording.append(world.state(), summary);
                    r->profile = world.profile();
                    for (std::size_t j = 0; j < broken.size(); ++j) {
                        if (broken[j] || !world.state().jointBroken(static_cast<int>(j))) continue;
                        broken[j] = 1;
                        r->breaks.push_back({k, static_cast<int>(j), world.state().jointBrokenAt[j]});
                    }
                }
                notify(false);
            }
        } catch (const std::exception& e) {
            std::lock_guard lock(r->mutex);
            r->error = e.what();
            r->failed = true;
        }
        notify(true);
        r->finished = true;
        QMetaObject::invokeMethod(
            this, [this, id] { onWorkerFinished(id); }, Qt::QueuedConnection);
    });
}

void Timeline::onWorkerProgress(int id) {
    if (!run_ || run_->id != id) return;  // a retired run
    run_->notifyPending = false;
    const int done = framesDone();
    // The frame under the playhead has arrived (a new run after an edit): show it.
    if (!hasCurrent_ && frame_ < done) loadCurrent();
    emit progress(done, frameCount());
}

void Timeline::onWorkerFinished(int id) {
    std::erase_if(retired_, [](const std::shared_ptr<Run>& r) { return r->finished.load(); });
    if (!run_ || run_->id != id) return;
    {
        std::lock_guard lock(run_->mutex);
        if (run_->failed) error_ = QString::fromStdString(run_->error);
        status_ = run_->failed                 ? Status::Failed
                  : run_->recording.complete() ? Status::Complete
                                               : Status::Cancelled;
    }
    if (!hasCurrent_) seek(frame_);
    emit progress(framesDone(), frameCount());
    emit statusChanged(status_);
}

void Timeline::cancel() {
    restart_->stop();
    if (!run_ || run_->finished) return;
    run_->cancel = true;
    // The worker ends within a frame and reports; the status follows there.
}

void Timeline::seek(int frame) {
    const int done = framesDone();
    frame_ = std::clamp(frame, 0, std::max(0, done - 1));
    if (isPlaying()) {
        playOrigin_ = frame_ / frameRate();
        playClock_.restart();
    }
    loadCurrent();
}

void Timeline::toEnd() {
    seek(framesDone() - 1);
}

void Timeline::loadCurrent() {
    hasCurrent_ = frameState(frame_, &current_);
    emit currentFrameChanged(frame_);
}

void Timeline::play() {
    if (isPlaying() || framesDone() == 0) return;
    // Playing from the last frame of a finished run starts again from the beginning.
    if (frame_ >= frameCount() - 1) seek(0);
    playOrigin_ = frame_ / frameRate();
    playClock_.start();
    playTimer_->start();
    emit playingChanged(true);
}

void Timeline::pause() {
    if (!isPlaying()) return;
    playTimer_->stop();
    emit playingChanged(false);
}

void Timeline::togglePlay() {
    isPlaying() ? pause() : play();
}

void Timeline::setLoop(bool on) {
    loop_ = on;
}

void Timeline::setPlaybackSpeed(double rate) {
    rate_ = std::clamp(rate, 0.1, 4.0);
}

// Real time (times the playback rate) decides the frame; frames not yet simulated are
// waited for, and a finished run ends playback or loops.
void Timeline::advancePlayback() {
    const double t = playOrigin_ + playClock_.elapsed() * 1e-3 * rate_;
    int target = static_cast<int>(std::floor(t * frameRate() + 1e-9));
    const int done = framesDone();
    const int last = frameCount() - 1;
    if (target > last) {
        if (loop_ && done == frameCount()) {
            frame_ = 0;
            playOrigin_ = 0.0;
            playClock_.restart();
            loadCurrent();
        } else if (done == frameCount() || status_ != Status::Running) {
            seek(done - 1);
            pause();
        }
        return;
    }
    if (target >= done) {
        if (status_ != Status::Running) {  // cancelled or failed: nothing more will come
            seek(done - 1);
            pause();
            return;
        }
        target = done - 1;  // wait for the worker
    }
    if (target != frame_) {
        frame_ = target;
        loadCurrent();
    }
}

bool Timeline::useCurrentFrameAsStart() {
    std::shared_ptr<const Model> m = model();
    if (!m || frame_ <= 0 || !hasCurrent_ || stale_) return false;
    const State& s = current_;
    if (static_cast<int>(s.bodies.size()) != doc_->bodyCount()) return false;
    const double t = s.time;
    doc_->beginMacro(tr("Use Frame %1 as Start").arg(frame_));
    for (int i = 0; i < doc_->bodyCount(); ++i) {
        const BodyModel& bm = m->bodies[static_cast<std::size_t>(i)];
        const BodyState& st = s.bodies[static_cast<std::size_t>(i)];
        BodyDesc b = doc_->body(i);
        if (b.motion == Motion::Animated) {
            // Its path keeps its times relative to the motion (the pose follows: body_keys.h).
            for (BodyKey& k : b.keys) k.time -= t;
        } else if (bm.motion != Motion::Static) {
            b.position = bodyFramePosition(bm, st);
            b.orientation = st.q;
        }
        if (bm.motion == Motion::Dynamic) {
            const Derived d = derive(bm, st);
            b.velocity = d.v;
            b.angularVelocity = d.omega;
        }
        // The forces keep their times relative to the motion: a window that has ended is gone.
        std::vector<ForceDesc> forces;
        for (ForceDesc f : b.forces) {
            if (f.end && *f.end <= t) continue;
            if (f.start) f.start = *f.start > t ? std::optional<double>(*f.start - t) : std::nullopt;
            if (f.end) f.end = *f.end - t;
            forces.push_back(f);
        }
        b.forces = std::move(forces);
        if (!(b == doc_->body(i))) doc_->setBody(i, b, tr("Use Frame as Start"));
    }
    doc_->endMacro();
    seek(0);
    return true;
}

}  // namespace tumble::ui
