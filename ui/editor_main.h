// Entry point of the editor, kept apart so that app/ sees no Qt header.
#pragma once

#include <tumble/scene.h>

#include <functional>
#include <string>

namespace tumble::ui {

/// Runs the editor's event loop; argv[1], when given, is a scene file to open.
int runEditor(int argc, char** argv);

/// Keeps the memory a frame frees for the next frame: the software renderer allocates and
/// frees buffers of megabytes every frame, which glibc maps and unmaps (and the kernel
/// zeroes again) until it has seen one freed; a viewport that was the first thing drawn in
/// its process spent 110-160 ms an orbit frame at 1 000 bodies against 32 ms otherwise,
/// two fifths of it in page faults and unmapping. Called before the QApplication by the
/// editor, the image export and the editor's benchmark.
void keepFrameMemory();

/// For the headless command line's `--out DIR/` and `--out FILE.mp4`: simulates `scene`
/// (settings overrides applied, meshes loaded) and writes a PNG per frame into `folder` at
/// width × height (and, when `video` is not empty, an MP4 of them) with the editor's own
/// viewport and exporter, the camera framing every body. Needs a display (xvfb-run).
/// Returns an empty string on success, else the message. `stop` is asked every 50 ms: true
/// cancels the run or the export (nothing is left) and the message says it was stopped.
std::string renderImages(const SceneDesc& scene, const std::string& folder, const std::string& video,
                         int width, int height, const std::function<bool()>& stop);

}  // namespace tumble::ui
