// How the panels' fields share the mouse and keys with the window around them:
// - The wheel scrolls the panel: a spin box, combo box or slider that has not been clicked
//   into (no keyboard focus) passes the wheel to the scroll area around it instead of
//   changing its value (a user scrolling a long property panel changed the friction under
//   the pointer, an undo step and a re-run). Ctrl+wheel still changes the field under the
//   pointer, and a field being edited (focused) takes the wheel as usual.
// - Ctrl+Z and Ctrl+Shift+Z (the platform's Undo and Redo keys) in a number field undo and
//   redo the document's edits, as Edit > Undo does: a number field's edits reach the
//   document as they are typed, so its own undo of keystrokes had nothing left to undo and
//   the keys did nothing. A text field (a name) keeps its own undo while it holds typing
//   not yet given to the document, and passes the keys on after that.
#pragma once

namespace tumble::ui {

/// Installs the guard on the application, once (later calls do nothing). Every dock with
/// fields calls it; the wheel part acts on fields inside a scroll area only.
void installFieldGuard();

}  // namespace tumble::ui
