// Entry point of the editor, kept apart so that app/ sees no Qt header.
#pragma once

namespace tumble::ui {

/// Runs the editor's event loop; argv[1], when given, is a scene file to open.
int runEditor(int argc, char** argv);

}  // namespace tumble::ui
