// What the viewport draws over a recorded frame (View > Overlays): trails of the centres of
// mass, contact points and normals, velocity, angular velocity and applied force arrows and
// centre-of-mass markers, as coloured lines in the overlay layer (never hidden by a body).
// Each is computed only while it is on, from the frame's state and the recording's model.
// The computing part (overlays::) is Qt-free; ViewportOverlays holds the Qt3D entities.
//
// Scales (stated in docs/editor.md, "Overlays"):
// - velocity arrow: the distance travelled in kVelocitySeconds at v;
// - angular velocity arrow: along ω (right hand), kAngularMetres metres per rad/s;
// - force arrow: the non-gravity force F over the body's mass, times kForceSeconds2
//   (F/m · 0.05 s²: a force equal to the body's weight under 9.81 m/s² is 0.49 m long);
// - contact normal: 0.6 of the smaller bounded body's radius, the point a cross a sixth
//   of that.
#pragma once

#include <tumble/model.h>
#include <tumble/state.h>

#include <memory>
#include <vector>

namespace Qt3DCore {
class QEntity;
}

namespace tumble::ui {

namespace overlays {

inline constexpr double kVelocitySeconds = 0.1;
inline constexpr double kAngularMetres = 0.1;
inline constexpr double kForceSeconds2 = 0.05;
/// Arrows shorter than this (in their own units: m/s, rad/s, N) are not drawn.
inline constexpr double kSmallest = 1e-9;
/// Points kept per trail: longer tracks are thinned evenly (the newest point always kept).
inline constexpr int kMaxTrailPoints = 4096;
/// Points of all trails together: with many bodies each trail gets its share (but never
/// fewer than kMinTrailPoints), so that a frame's trails stay a few megabytes at most.
inline constexpr int kMaxTrailPointsTotal = 200000;
inline constexpr int kMinTrailPoints = 64;
/// The points a trail may have when `trails` are drawn.
int trailCap(int trails);

/// Lines to draw: six floats a vertex (position, colour 0..1), two vertices a segment.
struct Lines {
    std::vector<float> xyzrgb;
    int items = 0;  ///< what the overlay counts: polylines, contact points, arrows, markers
};

/// Contact points and normals of `state`, found by the engine's broadphase and narrowphase
/// (tumble/contact_query.h) at the engine's touch tolerance; sleeping bodies count as awake
/// so that their resting contacts show. items: contact points.
Lines contacts(const Model& model, const State& state);
/// Arrows of v at the centre of mass of each dynamic body that moves. items: arrows.
Lines velocities(const Model& model, const State& state);
/// Arrows of ω at the centre of mass of each dynamic body that turns. items: arrows.
Lines angularVelocities(const Model& model, const State& state);
/// Arrows of the force on each dynamic body at the state's time, all but gravity (applied
/// forces, springs, damping), at its centre of mass. items: arrows.
Lines forces(const Model& model, const State& state);
/// A cross at the centre of mass of each dynamic body. items: markers.
Lines centresOfMass(const Model& model, const State& state);
/// Each joint (amber): a line from its anchor on body_a to its anchor on body_b (or its
/// world point), and a cross at each anchor of 0.25 × body_a's bounding radius. From a
/// recorded frame, or (`scene`) from the bodies as placed in the document. items: joints.
/// A hinge's or slider's axis is a line through anchor A; joint `selected` (an index in the
/// scene's joints, -1: none) is drawn light and larger.
Lines joints(const Model& model, const State& state, int selected = -1);
Lines joints(const SceneDesc& scene, int selected = -1);
/// Each animated body's path as its keys give it (the body frame's origin, 24 points a
/// segment from the first key to the last) and a cross at each key: amber for the bodies in
/// `selected` (indices in the scene), grey for the others. items: paths.
Lines paths(const SceneDesc& scene, const std::vector<int>& selected);
/// The poke being dragged (viewport.cpp): an arrow from the pressed point along the drag.
/// items: 1.
Lines pokeArrow(const Vec3& from, const Vec3& drag);
/// One polyline per track of two points or more. items: polylines.
Lines trails(const std::vector<std::vector<Vec3>>& tracks);

/// `points` thinned to at most `cap`, evenly, the last one kept.
std::vector<Vec3> thinned(const std::vector<Vec3>& points, int cap);

}  // namespace overlays

class ViewportOverlays {
public:
    enum Kind {
        Trails,
        Contacts,
        Velocities,
        AngularVelocities,
        Forces,
        CentresOfMass,
        Joints,
        Paths,
        Poke,
        KindCount
    };

    /// Under `root`; the caller puts entity() in its overlay layer.
    explicit ViewportOverlays(Qt3DCore::QEntity* root);
    ~ViewportOverlays();
    ViewportOverlays(const ViewportOverlays&) = delete;
    ViewportOverlays& operator=(const ViewportOverlays&) = delete;

    Qt3DCore::QEntity* entity() const;
    /// Draws `lines` for a kind (replacing what it drew).
    void set(Kind kind, const overlays::Lines& lines);
    /// Draws nothing for a kind.
    void clear(Kind kind);
    /// items of what is drawn for a kind (0 when cleared).
    int count(Kind kind) const;

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
