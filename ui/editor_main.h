// Entry point of the editor, kept apart so that app/ sees no Qt header.
#pragma once

#include <tumble/scene.h>

#include <string>

namespace tumble::ui {

/// Runs the editor's event loop; argv[1], when given, is a scene file to open.
int runEditor(int argc, char** argv);

/// For the headless command line's `--out DIR/` and `--out FILE.mp4`: simulates `scene`
/// (settings overrides applied, meshes loaded) and writes a PNG per frame into `folder` at
/// width × height (and, when `video` is not empty, an MP4 of them) with the editor's own
/// viewport and exporter, the camera framing every body. Needs a display (xvfb-run).
/// Returns an empty string on success, else the message.
std::string renderImages(const SceneDesc& scene, const std::string& folder, const std::string& video,
                         int width, int height);

}  // namespace tumble::ui
