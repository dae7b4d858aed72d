// The sample scenes File > Samples offers (main_window.cpp).
#pragma once

#include <QString>

#include <vector>

namespace tumble::ui {

struct SampleScene {
    QString name;  ///< as the menu shows it: the file's name without ".json"
    QString path;  ///< ":/scenes/NAME.json" when compiled in, else the file in samplesFolder()
};

/// The samples compiled into the editor (":/scenes/NAME.json"), in the menu's order, then the
/// scenes of samplesFolder() that are not compiled in (the ones with mesh files beside them:
/// mesh-shapes, mug-on-board), read from that folder so that their meshes are found, by name.
/// A file counts as a scene when its first 4 KiB say "format": "tumble-scene" (what the
/// installed MIME type matches); a scene's convex parts file does not.
std::vector<SampleScene> sampleScenes();

/// The folder of sample scene files: share/tumble/scenes under the running program's prefix
/// (installed: bin/tumble and share/tumble/scenes), else the source tree's resources/scenes
/// the editor was built from; "" when neither is there.
QString samplesFolder();

}  // namespace tumble::ui
