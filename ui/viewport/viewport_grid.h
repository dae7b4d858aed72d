// The ground grid's material: its lines, in their own colours, fade out with distance from
// the eye (sooner the lower the eye: where lines a metre apart would crowd into a few
// pixels and shimmer) and towards the grid's edge (no hard end). They are blended over what
// is drawn before them and write no depth, so the grid is drawn in a pass after the scene
// (Viewport's frame graph: the grid layer). The ground under them is drawn a little behind
// where it is (viewport_instances.cpp), so that they are whole at any distance, not dashed.
#pragma once

namespace Qt3DCore {
class QNode;
}
namespace Qt3DRender {
class QMaterial;
}

namespace tumble::ui {

/// The material of the grid's lines (vertex colours), whose grid ends `halfExtent` m from
/// the origin in x and z.
Qt3DRender::QMaterial* makeGridMaterial(Qt3DCore::QNode* parent, float halfExtent);

/// How opaque the grid is at `distance` m from an eye `eyeHeight` m above it, `edge` m from
/// the origin (the larger of |x| and |z|) on a grid of `halfExtent`: what the shader computes,
/// for the tests.
float gridOpacity(float distance, float eyeHeight, float edge, float halfExtent);

}  // namespace tumble::ui
