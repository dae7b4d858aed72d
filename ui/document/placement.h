// Setting bodies down where the user builds: on the surface under a point the view looks at,
// dropped along gravity onto what is below, and laid out as stacks, pyramids, walls and
// arrays. Qt-free: the positions are a function of the scene only (travelToTouch, the
// engine's own collision shapes), so tests know where a body will land.
#pragma once

#include <tumble/scene.h>

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace tumble::ui {

/// Down in `scene`: along its gravity, or -y when it has none.
Vec3 downOf(const SceneDesc& scene);

/// How far each of `indices` drops along downOf(scene) before it touches a body it may
/// collide with (at most 10 km), in that order, each after those before it have dropped (give
/// them lowest first: a body resting on another follows it down). Nothing for a body with
/// nothing below it or a plane, or for all when the scene cannot be compiled (a mesh not
/// loaded). The scene is compiled once.
std::vector<std::optional<double>> dropDistances(const SceneDesc& scene, const std::vector<int>& indices);

/// `body` (not yet in `scene`) set down on what lies under `point`: raised above the point
/// by its size, then lowered along down until it rests on the first body it meets. Where it
/// would start inside another body it is raised until it does not. With nothing under it
/// (empty space, or the scene cannot be compiled) it is centred on `point`.
BodyDesc setDownAt(const SceneDesc& scene, BodyDesc body, const Vec3& point);

/// Body `index` of `scene` at `moved`'s place and turn, resting on what is under it there
/// (setDownAt without the joints that hold the body, the pairs kept apart honoured): a body
/// dragged across a table snaps onto it, off its edge down to the floor.
BodyDesc settledAt(const SceneDesc& scene, int index, const BodyDesc& moved);

/// settledAt for a drag: the scene is compiled once, when made, and each settle only moves
/// the body in the compiled state (a scene of thousands of bodies or large meshes stays
/// smooth under the pointer). A move that changes more than the body's position (its turn,
/// its shape) is settled by settledAt.
class Settler {
public:
    Settler(const SceneDesc& scene, int index);
    ~Settler();
    BodyDesc settle(const BodyDesc& moved) const;

private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

/// The bodies' order from the lowest to the highest along down (by their positions).
std::vector<int> lowestFirst(const SceneDesc& scene, std::vector<int> indices);

/// The turn that stands a body upright where down is `down`: it takes -y to down (the least
/// turn; the identity for gravity along -y).
Quat uprightFor(const Vec3& down);

/// A layout of copies of one box, resting on each other: a stack (a column), a pyramid (rows
/// of count, count - 1, ... 1 boxes, or square layers of count², (count - 1)², ... 1), or a
/// wall (rows of `count`, every other shifted by half a box when staggered, a brick bond).
enum class Layout { Stack, Pyramid, Wall };
struct LayoutSpec {
    Layout kind = Layout::Stack;
    int count = 10;          ///< Stack: boxes; Pyramid: the bottom row's boxes; Wall: boxes a row
    int rows = 5;            ///< Wall: rows
    bool square = false;     ///< Pyramid: square layers instead of a single row a layer
    bool staggered = true;   ///< Wall
    Vec3 halfExtents = Vec3(0.25, 0.25, 0.25);
    double gap = 0.0;        ///< m between neighbours in a row (sideways only)
};
/// How many boxes the layout has.
long layoutCount(const LayoutSpec& spec);
/// The boxes' centres with up = +y and the layout's base point (the middle of its bottom
/// row's lowest faces) at the origin, bottom row first. Empty past kMostLaidOut boxes.
inline constexpr long kMostLaidOut = 10000;
std::vector<Vec3> layoutCentres(const LayoutSpec& spec);

/// The places of an array of n x m x k (`counts`) from `start`, `steps[d]` apart along each of
/// its three directions, `start` first; empty past kMostLaidOut places or with a count below 1.
std::vector<Vec3> arrayPlaces(const Vec3& start, const std::array<int, 3>& counts, const std::array<Vec3, 3>& steps);

}  // namespace tumble::ui
