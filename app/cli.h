// The headless command line (INTERFACES.md): tumble --headless SCENE [options],
// --help, --version, --list-integrators. Plain C++: it runs without Qt.
#pragma once

#include <tumble/scene.h>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace tumble::cli {

/// True when the arguments ask for the command line rather than the editor.
bool wantsCommandLine(const std::vector<std::string>& args);

/// Runs the command line; returns the exit status (0 ok, 2 invalid input, 1 failure).
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

/// Draws the frames of `scene` as PNGs into `folder` (and an MP4 `video` when not empty) at
/// width × height; returns "" or the message. The editor's exporter, installed by main()
/// when the editor is built: `--out DIR/` and `--out FILE.mp4` need it. `stop` is asked now
/// and then: true (SIGINT or SIGTERM came) cancels the export, which leaves nothing.
using ImageRenderer =
    std::function<std::string(const SceneDesc& scene, const std::string& folder, const std::string& video,
                              int width, int height, const std::function<bool()>& stop)>;
void setImageRenderer(ImageRenderer renderer);

}  // namespace tumble::cli
