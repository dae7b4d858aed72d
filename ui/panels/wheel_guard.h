// The mouse wheel over a panel scrolls the panel: a spin box, combo box or slider that has
// not been clicked into (no keyboard focus) passes the wheel to the scroll area around it
// instead of changing its value (a user scrolling a long property panel changed the
// friction under the pointer, an undo step and a re-run). Ctrl+wheel still changes the
// field under the pointer, and a field being edited (focused) takes the wheel as usual.
#pragma once

namespace tumble::ui {

/// Installs the guard on the application, once (later calls do nothing). Every dock with
/// fields calls it; it acts on fields inside a scroll area only.
void installWheelGuard();

}  // namespace tumble::ui
