// Editing a compound body part by part (issue 49 item 4): Add Part, Remove Part. Plain
// functions on a body, so that the document applies each as one undo step
// (Document::addPart, removePart) and the tests check them without a window.
#pragma once

#include <tumble/scene.h>

#include <optional>
#include <string>

namespace tumble::ui {

/// The name a part is shown by: its own, or "part N" (N from 1) when it has none.
std::string partLabel(const PartDesc& part, int index);

/// `body` with a part of `type` (a sphere, box, capsule or cylinder of the editor's sizes,
/// half those of Add Body) added last, named after its shape uniquely among the parts, in
/// the body's frame on top of the other parts: its lowest point at their highest, above the
/// frame's origin. A body that is not a compound becomes one first: its shape, as it was,
/// the part "base" at its frame (a mesh keeps its file and collision). The result passes
/// tumble::validate; nothing, with the reason in `why`, when it would not (a plane, a mesh
/// split into convex parts, which a part cannot be), or for another `type`.
std::optional<BodyDesc> withPartAdded(const BodyDesc& body, ShapeType type, std::string* why);

/// `body` without its part `part`; nothing, with the reason in `why`, for its last part (a
/// compound has at least one: delete the body, or Ungroup it) or a part it does not have.
std::optional<BodyDesc> withoutPart(const BodyDesc& body, int part, std::string* why);

}  // namespace tumble::ui
