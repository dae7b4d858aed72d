// libFuzzer target: scene text as a user might hand it to the editor or the command line.
// Whatever the bytes, reading a scene either gives a scene or an InputError naming the file,
// and a scene either compiles or gives a SceneError naming the field; anything else (a crash,
// a sanitizer report, another exception) is a bug. A scene that reads also writes back to
// text that reads as the same scene, and a scene that compiles survives a few steps (or
// stops with a SimulationError).
#include <tumble/errors.h>
#include <tumble/io/scene_file.h>
#include <tumble/world.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace {

// Large scenes are legal but slow; the fuzzer is after wrong input, not big input.
constexpr std::size_t kMaxBodiesToStep = 64;
constexpr int kSteps = 3;

[[noreturn]] void bug(const char* what, const std::string& detail) {
    std::fprintf(stderr, "fuzz_scene: %s: %s\n", what, detail.c_str());
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    tumble::SceneDesc scene;
    try {
        scene = tumble::io::parseScene(text, "fuzz.json");
    } catch (const tumble::io::InputError& e) {
        if (e.file() != "fuzz.json") bug("an InputError that does not name the file", e.what());
        return 0;
    }

    // What Tumble writes, Tumble reads back unchanged.
    const std::string written = tumble::io::sceneToJson(scene);
    tumble::SceneDesc again;
    try {
        again = tumble::io::parseScene(written, "written.json");
    } catch (const tumble::io::InputError& e) {
        bug("a written scene does not read back", std::string(e.what()) + "\n" + written);
    }
    if (!(again == scene)) bug("a written scene reads back different", written);

    if (scene.bodies.size() > kMaxBodiesToStep) return 0;
    try {
        tumble::World world(scene);
        const double h = std::min(world.model().settings.dt, 0.01);
        for (int i = 0; i < kSteps; ++i) world.step(h);
    } catch (const tumble::SceneError&) {
    } catch (const tumble::SimulationError&) {
    }
    return 0;
}
