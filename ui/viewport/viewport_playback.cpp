// The viewport's playback (recorded frames drawn at the playhead) and overlays. See
// viewport_impl.h.
#include "viewport/viewport_impl.h"

#include <tumble/model.h>

namespace tumble::ui {

using namespace viewport_detail;

// ---- Playback and overlays.

Timeline* Viewport::timeline() const {
    return d_->timeline;
}

void Viewport::setTimeline(Timeline* timeline) {
    if (timeline == d_->timeline) return;
    for (const auto& c : d_->timelineConnections) disconnect(c);
    d_->timelineConnections.clear();
    d_->timeline = timeline;
    d_->trackFrames.clear();
    d_->trackPoints.clear();
    if (timeline) {
        auto& c = d_->timelineConnections;
        c.push_back(connect(timeline, &Timeline::currentFrameChanged, this, [this] { refreshPlayback(); }));
        c.push_back(connect(timeline, &Timeline::recordingReset, this, [this] {
            d_->trackFrames.clear();
            d_->trackPoints.clear();
            refreshPlayback();
        }));
        c.push_back(connect(timeline, &Timeline::staleChanged, this, [this] { refreshPlayback(); }));
        c.push_back(connect(timeline, &QObject::destroyed, this, [this] {
            d_->timelineConnections.clear();
            refreshPlayback();
        }));
    }
    refreshPlayback();
}

int Viewport::shownFrame() const {
    return d_->shownFrame;
}

QMatrix4x4 Viewport::drawnTransform(int index) const {
    return d_->scene->drawnTransform(index);
}

void Viewport::refreshPlayback() {
    if (!d_->doc) return;  // the window is closing: nothing is drawn again
    const State* state = d_->frameState();
    const int frame = state ? d_->timeline->currentFrame() : 0;
    if (frame > 0) {
        const Model& model = *d_->timeline->model();
        for (size_t i = 0; i < state->bodies.size(); ++i) {
            const BodyState& s = state->bodies[i];
            d_->scene->setShownPose(int(i), toQt(bodyFramePosition(model.bodies[i], s)), toQt(s.q));
        }
    } else {
        d_->scene->clearShownPoses();
    }
    if (frame != d_->shownFrame) {
        d_->shownFrame = frame;
        if (d_->dragAxis >= 0) cancelHandleDrag();  // the frame changed mid-drag (playback)
    }
    // (At a later frame an animated body's handles follow it, and show once its run has
    // come that far again.)
    if (d_->dragAxis < 0) updateHandles();
    refreshOverlays();
}

void Viewport::refreshOverlays() {
    ViewportOverlays& o = *d_->overlays;
    // The frame at the playhead, unless it is frame 0 of a stale recording (the document
    // was edited since: the recording's start is no longer what is drawn).
    const State* state = d_->frameState();
    if (state && d_->shownFrame == 0 && d_->timeline->isStale()) state = nullptr;
    const std::shared_ptr<const Model> model = state ? d_->timeline->model() : nullptr;
    auto on = [this, state](Overlay which) { return state && d_->overlayOn[size_t(which)]; };
    using K = ViewportOverlays::Kind;
    auto draw = [&](Overlay which, K kind, overlays::Lines (*compute)(const Model&, const State&)) {
        if (on(which)) {
            o.set(kind, compute(*model, *state));
        } else {
            o.clear(kind);
        }
    };
    draw(Overlay::Contacts, K::Contacts, &overlays::contacts);
    draw(Overlay::Velocities, K::Velocities, &overlays::velocities);
    draw(Overlay::AngularVelocities, K::AngularVelocities, &overlays::angularVelocities);
    draw(Overlay::Forces, K::Forces, &overlays::forces);
    draw(Overlay::CentresOfMass, K::CentresOfMass, &overlays::centresOfMass);

    // Trails: each dynamic body's centre of mass from frame 0 to the playhead. The tracks
    // are asked of the timeline as far as it has recorded, and again only when the
    // playhead passes their end.
    d_->trails.clear();
    if (on(Overlay::Trails)) {
        const int frame = d_->timeline->currentFrame();
        const size_t n = model->bodies.size();
        d_->trackFrames.resize(n);
        d_->trackPoints.resize(n);
        d_->trails.resize(n);
        const int cap = overlays::trailCap(int(model->dynamicBodies.size()));
        for (int i : model->dynamicBodies) {
            std::vector<int>& frames = d_->trackFrames[size_t(i)];
            std::vector<Vec3>& points = d_->trackPoints[size_t(i)];
            if (frames.empty() || frames.back() < frame) {
                std::vector<BodyState> states;
                d_->timeline->bodyTrack(i, &frames, &states, -1);
                points.clear();
                points.reserve(states.size());
                for (const BodyState& s : states) points.push_back(s.x);
            }
            const size_t end = size_t(std::upper_bound(frames.begin(), frames.end(), frame) - frames.begin());
            std::vector<Vec3> upTo(points.begin(),
                                   points.begin() + std::ptrdiff_t(std::min(end, points.size())));
            // The keyframes may stop short of the playhead: the trail ends where the body is.
            if (upTo.empty() || end == 0 || frames[end - 1] != frame)
                upTo.push_back(state->bodies[size_t(i)].x);
            d_->trails[size_t(i)] = overlays::thinned(upTo, cap);
        }
        o.set(K::Trails, overlays::trails(d_->trails));
    } else {
        o.clear(K::Trails);
    }

    // Sleeping bodies tinted.
    const bool tint = on(Overlay::Sleeping);
    for (int i = 0; i < d_->scene->count(); ++i) d_->scene->setAsleep(i, tint && state->isAsleep(i));
    refreshJoints();
}

void Viewport::refreshJoints() {
    ViewportOverlays& o = *d_->overlays;
    using K = ViewportOverlays::Kind;
    // The animated bodies' paths, as the document's keys give them (the selected one amber).
    if (d_->doc) {
        const QList<int>& selection = d_->doc->selection();
        o.set(K::Paths,
              overlays::paths(d_->doc->scene(), std::vector<int>(selection.begin(), selection.end())));
    } else {
        o.clear(K::Paths);
    }
    if (!d_->overlayOn[size_t(Overlay::Joints)] || !d_->doc || d_->doc->scene().joints.empty()) {
        o.clear(K::Joints);
        return;
    }
    // A recorded frame where one is drawn; the document's bodies while editing (frame 0).
    const State* state = d_->frameState();
    if (state && d_->shownFrame > 0)
        o.set(K::Joints, overlays::joints(*d_->timeline->model(), *state, d_->doc->selectedJoint()));
    else
        o.set(K::Joints, overlays::joints(d_->doc->scene(), d_->doc->selectedJoint()));
}

bool Viewport::overlay(Overlay which) const {
    return d_->overlayOn[size_t(which)];
}

void Viewport::setOverlay(Overlay which, bool on) {
    if (d_->overlayOn[size_t(which)] == on) return;
    d_->overlayOn[size_t(which)] = on;
    if (!on && which == Overlay::Trails) {  // nothing kept that is not drawn
        d_->trackFrames.clear();
        d_->trackPoints.clear();
    }
    refreshOverlays();
    emit overlayChanged(which, on);
}

int Viewport::overlayItemCount(Overlay which) const {
    using K = ViewportOverlays::Kind;
    switch (which) {
        case Overlay::Trails: return d_->overlays->count(K::Trails);
        case Overlay::Contacts: return d_->overlays->count(K::Contacts);
        case Overlay::Velocities: return d_->overlays->count(K::Velocities);
        case Overlay::AngularVelocities: return d_->overlays->count(K::AngularVelocities);
        case Overlay::Forces: return d_->overlays->count(K::Forces);
        case Overlay::CentresOfMass: return d_->overlays->count(K::CentresOfMass);
        case Overlay::Sleeping: return d_->scene->asleepCount();
        case Overlay::Joints: return d_->overlays->count(K::Joints);
    }
    return 0;
}

QList<QVector3D> Viewport::trailPoints(int index) const {
    QList<QVector3D> out;
    if (index < 0 || size_t(index) >= d_->trails.size()) return out;
    for (const Vec3& p : d_->trails[size_t(index)]) out.append(toQt(p));
    return out;
}

QString Viewport::overlayText(Overlay which) {
    switch (which) {
        case Overlay::Trails: return tr("Trails");
        case Overlay::Contacts: return tr("Contact Points");
        case Overlay::Velocities: return tr("Velocities");
        case Overlay::AngularVelocities: return tr("Angular Velocities");
        case Overlay::Forces: return tr("Applied Forces");
        case Overlay::CentresOfMass: return tr("Centres of Mass");
        case Overlay::Sleeping: return tr("Sleeping Bodies");
        case Overlay::Joints: return tr("Joints");
    }
    return {};
}

}  // namespace tumble::ui
