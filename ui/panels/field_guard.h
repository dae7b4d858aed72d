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

#include <functional>

class QWidget;

namespace tumble::ui {

/// Installs the guard on the application, once (later calls do nothing). Every dock with
/// fields calls it; the wheel part acts on fields inside a scroll area only.
void installFieldGuard();

/// Calls `left` whenever the keyboard focus leaves `editor` or a field inside it for
/// another widget (not for a popup of its own or the window losing the focus). The panels
/// hide a refused value's message then: the field shows its last good value again, and a
/// red message under a valid value read as if that value were wrong.
void whenFieldLeft(QWidget* editor, std::function<void()> left);

}  // namespace tumble::ui
