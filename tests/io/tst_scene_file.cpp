// Scene files: a round trip through every field, the sample scenes, and one refusal with
// the file and the field for every class of bad input.
#include <tumble/io/scene_file.h>
#include <tumble/world.h>

#include "every_field.h"
#include "joint_rows.h"

#include <QtTest>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

using namespace tumble;
using tumble::io::InputError;
using tumble::test::everyField;

namespace fs = std::filesystem;

namespace {

// A valid scene to break one thing at a time. Every text replaced below occurs once.
const char* const kBase = R"({
  "format": "tumble-scene",
  "version": 1,
  "settings": {"gravity": [0, -9.81, 0], "dt": 0.01, "duration": 1, "integrator": "rk4", "frame_rate": 30},
  "bodies": [
    {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "mass": 1,
     "position": [0, 2, 0], "orientation": [1, 0, 0, 0], "restitution": 0.5, "friction": 0.4,
     "linear_damping": 0.1, "angular_damping": 0.2,
     "forces": [{"type": "spring", "anchor": [0, 3, 0], "stiffness": 10, "start": 0, "end": 1}]},
    {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.25, 0.5]}, "density": 1000}
  ],
  "joints": [
    {"name": "string", "type": "rope", "body_a": "ball", "anchor_a": [0, 0.5, 0], "anchor_b": [0, 3.5, 0], "length": 1.5},
    {"name": "hitch", "type": "ball", "body_a": "crate", "anchor_a": [0.5, 0, 0], "body_b": "ball", "anchor_b": [0, -0.5, 0]}
  ]
}
)";

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

QStringList filesIn(const QString& dir) {
    return QDir(dir).entryList(QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

}  // namespace

class TestSceneFile : public QObject {
    Q_OBJECT

private slots:
    void roundTripInMemory() {
        const SceneDesc scene = everyField();
        const std::string text = io::sceneToJson(scene);
        const SceneDesc back = io::parseScene(text, "every.json");
        QVERIFY(back == scene);
        // The comparison is not vacuous: one changed field makes it fail.
        SceneDesc other = back;
        other.bodies[2].inertia->coeffRef(0, 1) = 0.2;
        other.bodies[2].inertia->coeffRef(1, 0) = 0.2;
        QVERIFY(!(other == scene));
        QCOMPARE(io::sceneToJson(back), text);
    }

    // Optional fields stay absent rather than becoming explicit defaults.
    void absentOptionalsStayAbsent() {
        SceneDesc scene = everyField();
        scene.settings.integrator.clear();
        const SceneDesc back = io::parseScene(io::sceneToJson(scene), "every.json");
        QVERIFY(back.settings.integrator.empty());
        QVERIFY(!back.bodies[1].forces[1].point);
        QVERIFY(!back.bodies[1].forces[1].start);
        QVERIFY(!back.bodies[1].forces[1].end);
        QVERIFY(!back.bodies[1].inertia);
        QVERIFY(!back.bodies[1].centerOfMass);
        QVERIFY(!back.bodies[1].density);
        QVERIFY(!back.bodies[6].mass);
        QVERIFY(back == scene);
    }

    void roundTripThroughFiles() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const fs::path first = fs::path(dir.path().toStdString()) / "first.json";
        const fs::path second = fs::path(dir.path().toStdString()) / "second.json";
        const SceneDesc scene = everyField();
        // Reading a scene file reads its meshes too: give the bunny a (tetrahedral) mesh.
        fs::create_directories(first.parent_path() / "meshes");
        std::ofstream(first.parent_path() / "meshes" / "bunny.obj")
            << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        io::writeSceneFile(scene, first);
        QCOMPARE(readBytes(first), io::sceneToJson(scene));
        const SceneDesc loaded = io::readSceneFile(first);
        QVERIFY(loaded.bodies[5].shape.meshData);
        QVERIFY(loaded.bodies[7].shape.parts[1].shape.meshData);  // a compound's mesh part is read too
        QVERIFY(loaded == scene);
        io::writeSceneFile(loaded, second);
        QCOMPARE(readBytes(second), readBytes(first));
        // Overwriting an existing file works too, and leaves no temporary behind.
        io::writeSceneFile(loaded, first);
        QCOMPARE(readBytes(first), readBytes(second));
        QCOMPARE(filesIn(dir.path()), QStringList({"first.json", "second.json"}));
    }

    void writingIntoAMissingFolderFails() {
        QTemporaryDir dir;
        const fs::path path = fs::path(dir.path().toStdString()) / "no-such-folder" / "x.json";
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, io::writeSceneFile(everyField(), path));
        QVERIFY(!fs::exists(path));
    }

    void sampleScenes_data() {
        QTest::addColumn<QString>("file");
        const QStringList files = QDir(TUMBLE_SCENES_DIR).entryList({"*.json"}, QDir::Files, QDir::Name);
        QVERIFY(!files.isEmpty());
        for (const QString& f : files)
            if (!f.endsWith(".convex-parts.json"))  // a scene's sidecar, not a scene
                QTest::newRow(qPrintable(f)) << QString(TUMBLE_SCENES_DIR "/" + f);
    }

    void sampleScenes() {
        QFETCH(QString, file);
        SceneDesc scene;
        try {
            scene = io::readSceneFile(file.toStdString());
        } catch (const InputError& e) {
            QFAIL(e.what());
        }
        QVERIFY(!scene.bodies.empty());
        const World world(scene);  // compiles: every value is in range for the engine too
        QCOMPARE(world.model().bodies.size(), scene.bodies.size());
        QVERIFY(io::parseScene(io::sceneToJson(scene), "again.json") == scene);
    }

    void badInput_data() {
        QTest::addColumn<QString>("from");  // empty: `to` is the whole text
        QTest::addColumn<QString>("to");
        QTest::addColumn<QString>("field");
        QTest::addColumn<QString>("message");  // the whole what()
        const QString base = kBase;
        auto row = [](const char* name, const QString& from, const QString& to, const char* field,
                      const char* message) {
            QTest::newRow(name) << from << to << QString(field) << QString(message);
        };

        // Syntax.
        row("truncated", "", base.left(base.indexOf("\"bodies\"")), "",
            "drop.json: malformed JSON: parse error at line 5, column 3: "
            "syntax error while parsing object key - unexpected end of input; expected string literal");
        row("trailing comma", R"("frame_rate": 30})", R"("frame_rate": 30,})", "",
            "drop.json: malformed JSON: parse error at line 4, column 107: "
            "syntax error while parsing object key - unexpected '}'; expected string literal");
        row("empty file", "", "", "",
            "drop.json: malformed JSON: parse error at line 1, column 1: syntax error while parsing value - "
            "unexpected end of input; expected '[', '{', or a literal");
        row("NaN literal", R"("mass": 1,)", R"("mass": NaN,)", "",
            "drop.json: malformed JSON: parse error at line 7, column 74: syntax error while parsing value - "
            "invalid literal; last read: '\"mass\": N'");
        row("duplicate key at top", R"("version": 1,)", R"("version": 1, "version": 1,)", "",
            "drop.json: malformed JSON: the key 'version' appears twice in one object");
        row("duplicate key in body", R"("mass": 1,)", R"("mass": 1, "mass": 2,)", "",
            "drop.json: malformed JSON: the key 'mass' appears twice in one object");
        row("top level array", "", "[" + base + "]", "(top level)",
            "drop.json: (top level): must be an object");
        row("top level number", "", "42", "(top level)", "drop.json: (top level): must be an object");

        // Missing keys.
        row("missing format", "\"format\": \"tumble-scene\",", "", "format", "drop.json: format: is missing");
        row("missing version", "\"version\": 1,", "", "version", "drop.json: version: is missing");
        row("missing bodies", "", base.left(base.indexOf(",\n  \"bodies\"")) + "\n}\n", "bodies",
            "drop.json: bodies: is missing");
        row("missing name", R"("name": "ball", )", "", "bodies[1].name",
            "drop.json: bodies[1].name: is missing");
        row("missing shape", R"("shape": {"type": "sphere", "radius": 0.5}, )", "", "bodies[1].shape",
            "drop.json: bodies[1].shape: is missing");
        row("missing shape.type", R"({"type": "sphere", "radius": 0.5})", R"({"radius": 0.5})",
            "bodies[1].shape.type", "drop.json: bodies[1].shape.type: is missing");
        row("missing radius", R"({"type": "sphere", "radius": 0.5})", R"({"type": "sphere"})",
            "bodies[1].shape.radius", "drop.json: bodies[1].shape.radius: is missing");
        row("missing half_extents", R"(, "half_extents": [0.5, 0.25, 0.5])", "",
            "bodies[2].shape.half_extents", "drop.json: bodies[2].shape.half_extents: is missing");
        row("missing plane normal", R"("normal": [0, 1, 0], )", "", "bodies[0].shape.normal",
            "drop.json: bodies[0].shape.normal: is missing");
        row("missing spring stiffness", R"(, "stiffness": 10)", "", "bodies[1].forces[0].stiffness",
            "drop.json: bodies[1].forces[0].stiffness: is missing");

        // Unknown keys.
        row("unknown key at top", R"("version": 1,)", R"("version": 1, "author": "me",)", "author",
            "drop.json: author: unknown key");
        row("unknown key in settings", R"("dt": 0.01,)", R"("dt": 0.01, "timestep": 0.01,)",
            "settings.timestep", "drop.json: settings.timestep: unknown key");
        row("unknown key in body", R"("mass": 1,)", R"("mass": 1, "colour": "red",)", "bodies[1].colour",
            "drop.json: bodies[1].colour: unknown key");
        row("radius in a box", R"("half_extents": [0.5, 0.25, 0.5])",
            R"("half_extents": [0.5, 0.25, 0.5], "radius": 0.5)", "bodies[2].shape.radius",
            "drop.json: bodies[2].shape.radius: unknown key");
        row("vector in a spring", R"("stiffness": 10,)", R"("stiffness": 10, "vector": [1, 0, 0],)",
            "bodies[1].forces[0].vector", "drop.json: bodies[1].forces[0].vector: unknown key");

        // Types.
        row("string for a number", R"("mass": 1,)", R"("mass": "1",)", "bodies[1].mass",
            "drop.json: bodies[1].mass: must be a number");
        row("bool for a number", R"("radius": 0.5)", R"("radius": true)", "bodies[1].shape.radius",
            "drop.json: bodies[1].shape.radius: must be a number");
        row("null for a number", R"("dt": 0.01)", R"("dt": null)", "settings.dt",
            "drop.json: settings.dt: must be a number");
        row("2-element vector", R"("anchor": [0, 3, 0])", R"("anchor": [0, 3])", "bodies[1].forces[0].anchor",
            "drop.json: bodies[1].forces[0].anchor: must be an array of 3 numbers");
        row("string in a vector", R"("position": [0, 2, 0])", R"("position": [0, "2", 0])",
            "bodies[1].position[1]", "drop.json: bodies[1].position[1]: must be a number");
        row("3-element quaternion", R"("orientation": [1, 0, 0, 0])", R"("orientation": [1, 0, 0])",
            "bodies[1].orientation", "drop.json: bodies[1].orientation: must be an array of 4 numbers");
        row("inertia 2x2", R"("mass": 1,)", R"("mass": 1, "inertia": [[1, 0], [0, 1]],)", "bodies[1].inertia",
            "drop.json: bodies[1].inertia: must be 3 rows of 3 numbers");
        row("inertia short row", R"("mass": 1,)", R"("mass": 1, "inertia": [[1, 0, 0], [0, 1, 0], [0, 1]],)",
            "bodies[1].inertia[2]", "drop.json: bodies[1].inertia[2]: must be an array of 3 numbers");
        row("inertia flat", R"("mass": 1,)", R"("mass": 1, "inertia": [1, 1, 1],)", "bodies[1].inertia[0]",
            "drop.json: bodies[1].inertia[0]: must be an array of 3 numbers");
        row("name a number", R"("name": "crate")", R"("name": 7)", "bodies[2].name",
            "drop.json: bodies[2].name: must be a string");
        row("bodies an object", "",
            QString(base).replace(R"("bodies": [)", R"("bodies": {"b": [)").replace("\n  ]\n}", "\n  ]}\n}"),
            "bodies", "drop.json: bodies: must be an array");
        row("body a string", R"("bodies": [)", R"("bodies": ["ball",)", "bodies[0]",
            "drop.json: bodies[0]: must be an object");
        row("forces an object",
            R"("forces": [{"type": "spring", "anchor": [0, 3, 0], "stiffness": 10, "start": 0, "end": 1}])",
            R"("forces": {})", "bodies[1].forces", "drop.json: bodies[1].forces: must be an array");
        row("unknown motion", R"("motion": "static")", R"("motion": "frozen")", "bodies[0].motion",
            "drop.json: bodies[0].motion: 'frozen' is not one of dynamic, static, kinematic, animated");
        row("unknown impact timing", R"("frame_rate": 30})", R"("frame_rate": 30, "impacts": "later"})",
            "settings.impacts", "drop.json: settings.impacts: 'later' is not one of exact, end-of-step");
        row("impact timing not a string", R"("frame_rate": 30})", R"("frame_rate": 30, "impacts": true})",
            "settings.impacts", "drop.json: settings.impacts: must be a string");

        // Compounds (docs/scene-format.md "Compound bodies").
        const char* crate = R"({"type": "box", "half_extents": [0.5, 0.25, 0.5]})";
        auto compound = [](const char* parts) {
            return QString(R"({"type": "compound", "parts": %1})").arg(parts);
        };
        row("compound parts not an array", crate, compound("{}"), "bodies[2].shape.parts",
            "drop.json: bodies[2].shape.parts: must be an array of parts");
        row("compound without parts", crate, R"({"type": "compound"})", "bodies[2].shape.parts",
            "drop.json: bodies[2].shape.parts: is missing");
        row("compound with no parts", crate, compound("[]"), "bodies[2].shape.parts",
            "drop.json: bodies[2].shape.parts: a compound needs at least one part");
        row("compound part without shape", crate, compound(R"([{"position": [0, 0, 0]}])"),
            "bodies[2].shape.parts[0].shape", "drop.json: bodies[2].shape.parts[0].shape: is missing");
        row("compound part unknown key", crate,
            compound(R"([{"shape": {"type": "sphere", "radius": 0.1}, "colour": 1}])"),
            "bodies[2].shape.parts[0].colour", "drop.json: bodies[2].shape.parts[0].colour: unknown key");
        row("compound in a compound", crate, compound(R"([{"shape": {"type": "compound", "parts": []}}])"),
            "bodies[2].shape.parts[0].shape.type",
            "drop.json: bodies[2].shape.parts[0].shape.type: a part cannot be a compound (nested compounds "
            "are not supported: list its parts in this one)");
        row("compound plane part", crate, compound(R"([{"shape": {"type": "plane", "normal": [0, 1, 0]}}])"),
            "bodies[2].shape.parts[0].shape.type",
            "drop.json: bodies[2].shape.parts[0].shape.type: a plane cannot be a part; make it a static body "
            "of its own");
        row("compound part negative density", crate,
            compound(R"([{"shape": {"type": "sphere", "radius": 0.1}, "density": -1}])"),
            "bodies[2].shape.parts[0].density",
            "drop.json: bodies[2].shape.parts[0].density: must be greater than 0");
        row("compound part zero orientation", crate,
            compound(R"([{"shape": {"type": "sphere", "radius": 0.1}, "orientation": [0, 0, 0, 0]}])"),
            "bodies[2].shape.parts[0].orientation",
            "drop.json: bodies[2].shape.parts[0].orientation: must not be the zero quaternion");

        // A mesh's split into convex parts: its options only with it, in range.
        const char* mesh = R"({"type": "box", "half_extents": [0.5, 0.25, 0.5]})";
        row("max_parts without convex-parts", mesh, R"({"type": "mesh", "file": "m.obj", "max_parts": 4})",
            "bodies[2].shape.max_parts",
            "drop.json: bodies[2].shape.max_parts: is for \"collision\": \"convex-parts\" only");
        row("tolerance with triangles", mesh,
            R"({"type": "mesh", "file": "m.obj", "collision": "triangles", "tolerance": 0.01})",
            "bodies[2].shape.tolerance",
            "drop.json: bodies[2].shape.tolerance: is for \"collision\": \"convex-parts\" only");
        row("max_parts 0", mesh,
            R"({"type": "mesh", "file": "m.obj", "collision": "convex-parts", "max_parts": 0})",
            "bodies[2].shape.max_parts", "drop.json: bodies[2].shape.max_parts: must be from 1 to 256");
        row("max_parts not an integer", mesh,
            R"({"type": "mesh", "file": "m.obj", "collision": "convex-parts", "max_parts": 2.5})",
            "bodies[2].shape.max_parts", "drop.json: bodies[2].shape.max_parts: must be an integer");
        row("negative tolerance", mesh,
            R"({"type": "mesh", "file": "m.obj", "collision": "convex-parts", "tolerance": -1})",
            "bodies[2].shape.tolerance", "drop.json: bodies[2].shape.tolerance: must be greater than 0");

        // Numbers a double cannot hold: the JSON library refuses them; so must the reader.
        row("1e999", R"("mass": 1,)", R"("mass": 1e999,)", "bodies[1].mass",
            "drop.json: bodies[1].mass: must be a finite number");
        row("-1e999 in a vector", R"("position": [0, 2, 0])", R"("position": [0, -1e999, 0])",
            "bodies[1].position[1]", "drop.json: bodies[1].position[1]: must be a finite number");
        row("1e999 in settings", R"("duration": 1,)", R"("duration": 1e999,)", "settings.duration",
            "drop.json: settings.duration: must be a finite number");
        row("1e999 in inertia", R"("mass": 1,)",
            R"("mass": 1, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1e999]],)", "bodies[1].inertia[2][2]",
            "drop.json: bodies[1].inertia[2][2]: must be a finite number");

        // Sizes beyond what the engine's arithmetic holds (the scene fuzzer's box of
        // 4.4e93 m took seconds a step and overflowed its energies).
        row("a box of 1e7 m", R"("half_extents": [0.5, 0.25, 0.5])", R"("half_extents": [0.5, 1e7, 0.5])",
            "bodies[2].shape.half_extents[1]", "drop.json: bodies[2].shape.half_extents[1]: must be at most 1e6 m");
        row("a ball of 2e6 m", R"("radius": 0.5})", R"("radius": 2e6})", "bodies[1].shape.radius",
            "drop.json: bodies[1].shape.radius: must be at most 1e6 m");

        // Mass.
        row("zero mass", R"("mass": 1,)", R"("mass": 0,)", "bodies[1].mass",
            "drop.json: bodies[1].mass: must be greater than 0");
        row("negative mass", R"("mass": 1,)", R"("mass": -2,)", "bodies[1].mass",
            "drop.json: bodies[1].mass: must be greater than 0");
        row("negative density", R"("density": 1000)", R"("density": -1000)", "bodies[2].density",
            "drop.json: bodies[2].density: must be greater than 0");
        row("mass and density", R"("mass": 1,)", R"("mass": 1, "density": 1000,)", "bodies[1]",
            "drop.json: bodies[1]: give mass or density, not both");
        row("neither mass nor density", R"(, "density": 1000)", "", "bodies[2]",
            "drop.json: bodies[2]: a dynamic body needs mass or density");
        row("mass on a static body", R"("motion": "static",)", R"("motion": "static", "mass": 1,)",
            "bodies[0].mass", "drop.json: bodies[0].mass: a static body has no mass properties; remove it");
        row("inertia not symmetric", R"("mass": 1,)",
            R"("mass": 1, "inertia": [[1, 0.1, 0], [0, 1, 0], [0, 0, 1]],)", "bodies[1].inertia",
            "drop.json: bodies[1].inertia: must be symmetric");
        row("inertia not positive definite", R"("mass": 1,)",
            R"("mass": 1, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, -1]],)", "bodies[1].inertia",
            "drop.json: bodies[1].inertia: must be positive definite");
        row("inertia singular", R"("mass": 1,)",
            R"("mass": 1, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 0]],)", "bodies[1].inertia",
            "drop.json: bodies[1].inertia: must be positive definite");
        row("inertia triangle inequality", R"("mass": 1,)",
            R"("mass": 1, "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 3]],)", "bodies[1].inertia",
            "drop.json: bodies[1].inertia: principal moments break the triangle inequality "
            "(no mass distribution has them)");

        // Body values.
        row("zero radius", R"("radius": 0.5)", R"("radius": 0)", "bodies[1].shape.radius",
            "drop.json: bodies[1].shape.radius: must be greater than 0");
        row("negative half extent", R"([0.5, 0.25, 0.5])", R"([0.5, -0.25, 0.5])",
            "bodies[2].shape.half_extents[1]",
            "drop.json: bodies[2].shape.half_extents[1]: must be greater than 0");
        row("zero quaternion", R"("orientation": [1, 0, 0, 0])", R"("orientation": [0, 0, 0, 0])",
            "bodies[1].orientation", "drop.json: bodies[1].orientation: must not be the zero quaternion");
        row("zero plane normal", R"("normal": [0, 1, 0])", R"("normal": [0, 0, 0])", "bodies[0].shape.normal",
            "drop.json: bodies[0].shape.normal: must not be zero");
        row("duplicate names", R"("name": "crate")", R"("name": "ball")", "bodies[2].name",
            "drop.json: bodies[2].name: 'ball' is already the name of another body");
        row("empty name", R"("name": "crate")", R"("name": "")", "bodies[2].name",
            "drop.json: bodies[2].name: must not be empty");
        row("restitution 1.5", R"("restitution": 0.5)", R"("restitution": 1.5)", "bodies[1].restitution",
            "drop.json: bodies[1].restitution: must be between 0 and 1");
        row("restitution -0.1", R"("restitution": 0.5)", R"("restitution": -0.1)", "bodies[1].restitution",
            "drop.json: bodies[1].restitution: must be 0 or greater");
        row("negative friction", R"("friction": 0.4)", R"("friction": -0.4)", "bodies[1].friction",
            "drop.json: bodies[1].friction: must be 0 or greater");
        row("negative linear damping", R"("linear_damping": 0.1)", R"("linear_damping": -0.1)",
            "bodies[1].linear_damping", "drop.json: bodies[1].linear_damping: must be 0 or greater");
        row("negative angular damping", R"("angular_damping": 0.2)", R"("angular_damping": -0.2)",
            "bodies[1].angular_damping", "drop.json: bodies[1].angular_damping: must be 0 or greater");
        row("static body moving", R"("motion": "static",)", R"("motion": "static", "velocity": [1, 0, 0],)",
            "bodies[0].velocity",
            "drop.json: bodies[0].velocity: a static body cannot move; make it kinematic");

        // Settings.
        row("dt 0", R"("dt": 0.01)", R"("dt": 0)", "settings.dt",
            "drop.json: settings.dt: must be greater than 0");
        row("negative duration", R"("duration": 1,)", R"("duration": -1,)", "settings.duration",
            "drop.json: settings.duration: must be 0 or greater");
        row("frame_rate 0", R"("frame_rate": 30)", R"("frame_rate": 0)", "settings.frame_rate",
            "drop.json: settings.frame_rate: must be greater than 0");
        row("unknown integrator", R"("integrator": "rk4")", R"("integrator": "leapfrog")",
            "settings.integrator",
            "drop.json: settings.integrator: unknown integrator 'leapfrog' (see --list-integrators)");
        row("sleeping a string", R"("frame_rate": 30})", R"("frame_rate": 30, "sleeping": "yes"})",
            "settings.sleeping", "drop.json: settings.sleeping: must be true or false");
        row("sleeping a number", R"("frame_rate": 30})", R"("frame_rate": 30, "sleeping": 0})",
            "settings.sleeping", "drop.json: settings.sleeping: must be true or false");
        row("sleeping null", R"("frame_rate": 30})", R"("frame_rate": 30, "sleeping": null})",
            "settings.sleeping", "drop.json: settings.sleeping: must be true or false");
        row("solver_iterations 2.5", R"("frame_rate": 30})", R"("frame_rate": 30, "solver_iterations": 2.5})",
            "settings.solver_iterations", "drop.json: settings.solver_iterations: must be an integer");
        row("solver_iterations 5.0", R"("frame_rate": 30})", R"("frame_rate": 30, "solver_iterations": 5.0})",
            "settings.solver_iterations", "drop.json: settings.solver_iterations: must be an integer");
        row("solver_iterations a string", R"("frame_rate": 30})",
            R"("frame_rate": 30, "solver_iterations": "20"})", "settings.solver_iterations",
            "drop.json: settings.solver_iterations: must be an integer");
        row("solver_iterations true", R"("frame_rate": 30})",
            R"("frame_rate": 30, "solver_iterations": true})", "settings.solver_iterations",
            "drop.json: settings.solver_iterations: must be an integer");
        row("solver_iterations 0", R"("frame_rate": 30})", R"("frame_rate": 30, "solver_iterations": 0})",
            "settings.solver_iterations", "drop.json: settings.solver_iterations: must be from 1 to 10000");
        row("solver_iterations -3", R"("frame_rate": 30})", R"("frame_rate": 30, "solver_iterations": -3})",
            "settings.solver_iterations", "drop.json: settings.solver_iterations: must be from 1 to 10000");
        row("solver_iterations 10001", R"("frame_rate": 30})",
            R"("frame_rate": 30, "solver_iterations": 10001})", "settings.solver_iterations",
            "drop.json: settings.solver_iterations: must be from 1 to 10000");
        row("settings an array",
            R"("settings": {"gravity": [0, -9.81, 0], "dt": 0.01, "duration": 1, "integrator": "rk4", "frame_rate": 30})",
            R"("settings": [])", "settings", "drop.json: settings: must be an object");

        // Format and version.
        row("version 2", R"("version": 1,)", R"("version": 2,)", "version",
            "drop.json: version: version 2 is not one this build reads (it reads 1)");
        row("version 1.0", R"("version": 1,)", R"("version": 1.0,)", "version",
            "drop.json: version: must be an integer");
        row("version a string", R"("version": 1,)", R"("version": "1",)", "version",
            "drop.json: version: must be an integer");
        row("wrong format", R"("tumble-scene")", R"("tumble-project")", "format",
            "drop.json: format: must be \"tumble-scene\"");

        // Shapes and forces.
        row("unknown shape type", R"("type": "sphere")", R"("type": "cone")", "bodies[1].shape.type",
            "drop.json: bodies[1].shape.type: 'cone' is not one of sphere, box, capsule, cylinder, plane, "
            "mesh, compound");
        row("plane on a dynamic body", R"("motion": "static", )", "", "bodies[0].shape.type",
            "drop.json: bodies[0].shape.type: a plane must belong to a static body");
        row("plane on a kinematic body", R"("motion": "static")", R"("motion": "kinematic")",
            "bodies[0].shape.type", "drop.json: bodies[0].shape.type: a plane must belong to a static body");
        row("force on a static body", R"("motion": "static",)",
            R"("motion": "static", "forces": [{"type": "torque", "vector": [0, 1, 0]}],)", "bodies[0].forces",
            "drop.json: bodies[0].forces: forces act on dynamic bodies only");
        row("negative stiffness", R"("stiffness": 10)", R"("stiffness": -10)",
            "bodies[1].forces[0].stiffness",
            "drop.json: bodies[1].forces[0].stiffness: must be 0 or greater");
        row("end before start", R"("start": 0, "end": 1)", R"("start": 0.5, "end": 0.25)",
            "bodies[1].forces[0].end", "drop.json: bodies[1].forces[0].end: must be later than start");
        row("end equal to start", R"("start": 0, "end": 1)", R"("start": 0.5, "end": 0.5)",
            "bodies[1].forces[0].end", "drop.json: bodies[1].forces[0].end: must be later than start");
        row("unknown force type", R"("type": "spring")", R"("type": "magnet")", "bodies[1].forces[0].type",
            "drop.json: bodies[1].forces[0].type: 'magnet' is not one of force, torque, spring");
        // Each number is in range but the mass or inertia computed from them is not.
        row("mass overflows", R"("radius": 0.5}, "mass": 1,)", R"("radius": 1e6}, "mass": 1e305,)", "bodies[1].mass",
            "drop.json: bodies[1].mass: with this shape gives an inertia tensor that is not finite and "
            "positive definite (largest entry inf kg m^2)");
        row("volume overflows", R"("half_extents": [0.5, 0.25, 0.5]}, "density": 1000)",
            R"("half_extents": [1e6, 1e6, 1e6]}, "density": 1e300)", "bodies[2].density",
            "drop.json: bodies[2].density: with this shape gives a mass of inf kg, which is not a usable "
            "finite positive number");
        row("volume underflows", R"("half_extents": [0.5, 0.25, 0.5])",
            R"("half_extents": [1e-120, 1e-120, 1e-120])", "bodies[2].density",
            "drop.json: bodies[2].density: with this shape gives a mass of 0 kg, which is not a usable "
            "finite positive number");
        // Joints (docs/scene-format.md "Joints").
        row("joints not an array", "", R"({"format": "tumble-scene", "version": 1, "bodies": [], "joints": {}})",
            "joints", "drop.json: joints: must be an array");
        row("joint without a type", R"("type": "rope", )", "", "joints[0].type",
            "drop.json: joints[0].type: is missing");
        row("unknown joint type", R"("type": "rope")", R"("type": "glue")", "joints[0].type",
            "drop.json: joints[0].type: 'glue' is not one of ball, distance, rope, hinge, slider, fixed, six_axis");
        row("unknown joint key", R"("name": "hitch", )", R"("name": "hitch", "axis": [0, 1, 0], )",
            "joints[1].axis", "drop.json: joints[1].axis: unknown key");
        row("joint's body missing", R"("body_a": "crate")", R"("body_a": "cart")", "joints[1].body_a",
            "drop.json: joints[1].body_a: no body is named 'cart'");
        row("joint's other body missing", R"("body_b": "ball")", R"("body_b": "bal")", "joints[1].body_b",
            "drop.json: joints[1].body_b: no body is named 'bal'");
        row("joint's body_b empty", R"("body_b": "ball")", R"("body_b": "")", "joints[1].body_b",
            "drop.json: joints[1].body_b: must name a body (leave it out to join body_a to the world)");
        row("joint to itself", R"("body_b": "ball")", R"("body_b": "crate")", "joints[1].body_b",
            "drop.json: joints[1].body_b: a joint needs two different bodies");
        row("joint to the ground only", R"("body_a": "ball")", R"("body_a": "ground")", "joints[0]",
            "drop.json: joints[0]: joins nothing that moves: one of its bodies must be dynamic");
        row("joint names twice", R"("name": "hitch")", R"("name": "string")", "joints[1].name",
            "drop.json: joints[1].name: 'string' is already the name of another joint");
        row("negative length", R"("length": 1.5)", R"("length": -1)", "joints[0].length",
            "drop.json: joints[0].length: must be at least 0 (leave it out for the anchors' distance at the "
            "start)");
        row("ball joint with a length", R"("anchor_b": [0, -0.5, 0])", R"("anchor_b": [0, -0.5, 0], "length": 1)",
            "joints[1].length", "drop.json: joints[1].length: a ball joint has no length (only distance and rope joints have one)");
        row("hinge without its axis", R"("type": "ball", "body_a": "crate")", R"("type": "hinge", "body_a": "crate")",
            "joints[1].axis_a", "drop.json: joints[1].axis_a: is missing (a hinge joint needs its axis)");
        row("zero axis", R"("type": "ball", "body_a": "crate")",
            R"("type": "slider", "axis_a": [0, 0, 0], "body_a": "crate")", "joints[1].axis_a",
            "drop.json: joints[1].axis_a: must not be the zero vector");
        row("ball joint's axis_b alone", R"("anchor_b": [0, -0.5, 0])", R"("anchor_b": [0, -0.5, 0], "axis_b": [0, 1, 0])",
            "joints[1].axis_a", "drop.json: joints[1].axis_a: is missing (a ball joint's axis_b goes with its axis_a)");
        row("anchor not a vector", R"("anchor_a": [0.5, 0, 0])", R"("anchor_a": [0.5, 0])", "joints[1].anchor_a",
            "drop.json: joints[1].anchor_a: must be an array of 3 numbers");
        row("inverted limits", R"("type": "ball", "body_a": "crate")",
            R"("type": "hinge", "axis_a": [0, 1, 0], "limits": [1, -1], "body_a": "crate")", "joints[1].limits",
            "drop.json: joints[1].limits: the lower limit is above the upper one");
        row("hinge limits not finite", R"("type": "ball", "body_a": "crate")",
            R"("type": "hinge", "axis_a": [0, 1, 0], "limits": [-4, 1e999], "body_a": "crate")", "joints[1].limits[1]",
            "drop.json: joints[1].limits[1]: must be a finite number");
        row("limits on a ball joint", R"("anchor_b": [0, -0.5, 0])", R"("anchor_b": [0, -0.5, 0], "limits": [0, 1])",
            "joints[1].limits", "drop.json: joints[1].limits: a ball joint has none (only hinge and slider joints do)");
        row("negative motor torque", R"("type": "ball", "body_a": "crate")",
            R"("type": "hinge", "axis_a": [0, 1, 0], "motor": {"speed": 1, "max_torque": -2}, "body_a": "crate")",
            "joints[1].motor.max_torque", "drop.json: joints[1].motor.max_torque: must be a finite number, at least 0");
        row("slider motor with a torque", R"("type": "ball", "body_a": "crate")",
            R"("type": "slider", "axis_a": [0, 1, 0], "motor": {"speed": 1, "max_torque": 2}, "body_a": "crate")",
            "joints[1].motor.max_torque", "drop.json: joints[1].motor.max_torque: a slider's motor gives a force: max_force");
        row("motor without its speed", R"("type": "ball", "body_a": "crate")",
            R"("type": "hinge", "axis_a": [0, 1, 0], "motor": {"max_torque": 2}, "body_a": "crate")",
            "joints[1].motor.speed", "drop.json: joints[1].motor.speed: is missing");
        test::jointFeatureRows(row);
        row("zero break force", R"("anchor_b": [0, -0.5, 0])", R"("anchor_b": [0, -0.5, 0], "break_force": 0)",
            "joints[1].break_force", "drop.json: joints[1].break_force: must be a finite number greater than 0");
        row("unknown frame",
            R"("type": "spring", "anchor": [0, 3, 0], "stiffness": 10, "start": 0, "end": 1)",
            R"("type": "torque", "vector": [0, 1, 0], "frame": "local")", "bodies[1].forces[0].frame",
            "drop.json: bodies[1].forces[0].frame: 'local' is not one of world, body");

        // Collision groups (issue 50 item 3).
        row("groups not names", R"("frame_rate": 30})", R"("frame_rate": 30, "collision_groups": ["a", 3]})",
            "settings.collision_groups[1]", "drop.json: settings.collision_groups[1]: must be a string");
        row("groups apart not pairs", R"("frame_rate": 30})", R"("frame_rate": 30, "groups_apart": [["a"]]})",
            "settings.groups_apart[0]",
            "drop.json: settings.groups_apart[0]: must be a pair of names, [\"a\", \"b\"]");
        row("unknown group", R"("density": 1000})", R"("density": 1000, "collision_group": "fence"})",
            "bodies[2].collision_group",
            "drop.json: bodies[2].collision_group: 'fence' is not a collision group ('default'; name it in "
            "settings.collision_groups)");
        row("groups apart unknown", R"("frame_rate": 30})",
            R"("frame_rate": 30, "collision_groups": ["fence"], "groups_apart": [["fence", "debris"]]})",
            "settings.groups_apart[0][1]",
            "drop.json: settings.groups_apart[0][1]: 'debris' is not a collision group ('default', 'fence')");
        row("no_collide not a body", R"("frame_rate": 30},)",
            R"("frame_rate": 30}, "no_collide": [["ball", "box"]],)", "no_collide[0][1]",
            "drop.json: no_collide[0][1]: 'box' is not a body");
        row("no_collide not pairs", R"("frame_rate": 30},)", R"("frame_rate": 30}, "no_collide": "ball",)",
            "no_collide", "drop.json: no_collide: must be an array of pairs of names, [[\"a\", \"b\"], ...]");
        // Animated bodies (issue 50 item 1).
        row("key times out of order", R"("density": 1000})",
            R"("motion": "animated", "keys": [{"time": 1, "position": [0, 0, 0]}, {"time": 0.5, "position": [1, 0, 0]}]})",
            "bodies[2].keys[1].time",
            "drop.json: bodies[2].keys[1].time: must be later than the key before (1 s); this one is at 0.5 "
            "s");
        row("zero key quaternion", R"("density": 1000})",
            R"("motion": "animated", "keys": [{"time": 0, "position": [0, 0, 0], "orientation": [0, 0, 0, 0]}]})",
            "bodies[2].keys[0].orientation",
            "drop.json: bodies[2].keys[0].orientation: must not be the zero quaternion");
        row("key without a position", R"("density": 1000})",
            R"("motion": "animated", "keys": [{"time": 0}]})", "bodies[2].keys[0].position",
            "drop.json: bodies[2].keys[0].position: is missing");
        row("unknown key field", R"("density": 1000})",
            R"("motion": "animated", "keys": [{"time": 0, "position": [0, 0, 0], "speed": 2}]})",
            "bodies[2].keys[0].speed", "drop.json: bodies[2].keys[0].speed: unknown key");
        row("animated with a density", R"("density": 1000})",
            R"("density": 1000, "motion": "animated", "keys": [{"time": 0, "position": [0, 0, 0]}]})",
            "bodies[2].density",
            "drop.json: bodies[2].density: an animated body has no mass properties; remove it");
        row("animated without keys", R"("density": 1000})", R"("motion": "animated"})", "bodies[2].keys",
            "drop.json: bodies[2].keys: an animated body needs at least one key (time, position, "
            "orientation)");
        row("keys on a dynamic body", R"("density": 1000})",
            R"("density": 1000, "keys": [{"time": 0, "position": [0, 0, 0]}]})", "bodies[2].keys",
            "drop.json: bodies[2].keys: only an animated body has keys (this one is dynamic); set motion to "
            "animated "
            "or remove them");
        row("unknown interpolation", R"("density": 1000})",
            R"("motion": "animated", "interpolation": "cubic", "keys": [{"time": 0, "position": [0, 0, 0]}]})",
            "bodies[2].interpolation",
            "drop.json: bodies[2].interpolation: 'cubic' is not one of linear, smooth");
        row("collide_connected not a boolean", R"("anchor_b": [0, -0.5, 0])",
            R"("anchor_b": [0, -0.5, 0], "collide_connected": 1)", "joints[1].collide_connected",
            "drop.json: joints[1].collide_connected: must be true or false");
    }

    void badInput() {
        QFETCH(QString, from);
        QFETCH(QString, to);
        QFETCH(QString, field);
        QFETCH(QString, message);
        QString text = to;
        if (!from.isEmpty()) {
            text = kBase;
            QCOMPARE(text.count(from), 1);  // the row breaks exactly what it means to
            text.replace(from, to);
        }
        try {
            io::parseScene(text.toStdString(), "drop.json");
            QFAIL("no error for this input");
        } catch (const InputError& e) {
            QCOMPARE(QString::fromStdString(e.what()), message);
            QCOMPARE(QString::fromStdString(e.file()), QString("drop.json"));
            QCOMPARE(QString::fromStdString(e.field()), field);
        }
    }

    // Issue 21 item 8: a file with several bad values names all of them (the first in
    // what(), for the command line's one line; the rest in more(), for the editor), in the
    // order validation meets them.
    void everyProblemOfAFileIsNamed() {
        QString text = kBase;
        text.replace(R"("dt": 0.01)", R"("dt": -1)");
        text.replace(R"("radius": 0.5)", R"("radius": 0)");
        text.replace(R"("density": 1000)", R"("density": -5)");
        try {
            io::parseScene(text.toStdString(), "drop.json");
            QFAIL("no error for this input");
        } catch (const InputError& e) {
            QCOMPARE(QString::fromStdString(e.field()), QString("settings.dt"));
            QCOMPARE(e.more().size(), size_t(2));
            QVERIFY2(QString::fromStdString(e.more()[0]).startsWith("bodies[1].shape.radius: "),
                     e.more()[0].c_str());
            QVERIFY2(QString::fromStdString(e.more()[1]).startsWith("bodies[2].density: "), e.more()[1].c_str());
        }
        // One bad value: nothing more.
        text = kBase;
        text.replace(R"("radius": 0.5)", R"("radius": 0)");
        try {
            io::parseScene(text.toStdString(), "drop.json");
            QFAIL("no error for this input");
        } catch (const InputError& e) {
            QVERIFY(e.more().empty());
        }
    }

    // The text each row of badInput starts from is itself valid.
    void baseIsValid() {
        const SceneDesc scene = io::parseScene(kBase, "drop.json");
        QCOMPARE(scene.bodies.size(), size_t(3));
        QCOMPARE(scene.joints.size(), size_t(2));
        QCOMPARE(scene.joints[0].bodyB, std::string());  // absent: the world
        QCOMPARE(scene.joints[0].length, 1.5);
        QCOMPARE(scene.joints[1].length, -1.0);  // absent: from the scene
        QCOMPARE(scene.settings.integrator, std::string("rk4"));
        QCOMPARE(scene.bodies[1].forces.size(), size_t(1));
        // Absent sleeping and solver_iterations take their documented defaults.
        QCOMPARE(scene.settings.sleeping, true);
        QCOMPARE(scene.settings.solverIterations, 20);
        QVERIFY(scene.settings.impacts == ImpactTiming::Exact);
    }

    // "impacts" is read, and written back only when it is not the default (so a saved scene
    // that keeps exact impacts is byte for byte what it was before the key existed).
    void impactTiming() {
        QString text = kBase;
        text.replace(R"("frame_rate": 30})", R"("frame_rate": 30, "impacts": "end-of-step"})");
        const SceneDesc scene = io::parseScene(text.toStdString(), "drop.json");
        QVERIFY(scene.settings.impacts == ImpactTiming::EndOfStep);
        const std::string saved = io::sceneToJson(scene);
        QVERIFY(saved.find(R"("impacts": "end-of-step")") != std::string::npos);
        QVERIFY(io::parseScene(saved, "again.json") == scene);
        SceneDesc exact = scene;
        exact.settings.impacts = ImpactTiming::Exact;
        QVERIFY(!(exact == scene));
        QVERIFY(io::sceneToJson(exact).find("impacts") == std::string::npos);
        QVERIFY(io::parseScene(io::sceneToJson(exact), "again.json") == exact);
    }

    void solverSettings_data() {
        QTest::addColumn<QString>("keys");  // inserted after "frame_rate": 30
        QTest::addColumn<bool>("sleeping");
        QTest::addColumn<int>("iterations");
        QTest::newRow("sleeping off") << R"(, "sleeping": false)" << false << 20;
        QTest::newRow("sleeping on") << R"(, "sleeping": true)" << true << 20;
        QTest::newRow("5 iterations") << R"(, "solver_iterations": 5)" << true << 5;
        QTest::newRow("both") << R"(, "solver_iterations": 5, "sleeping": false)" << false << 5;
        QTest::newRow("1 iteration") << R"(, "solver_iterations": 1)" << true << 1;
        QTest::newRow("10000 iterations") << R"(, "solver_iterations": 10000)" << true << 10000;
    }

    void solverSettings() {
        QFETCH(QString, keys);
        QFETCH(bool, sleeping);
        QFETCH(int, iterations);
        QString text = kBase;
        QCOMPARE(text.count(R"("frame_rate": 30})"), 1);
        text.replace(R"("frame_rate": 30})", R"("frame_rate": 30)" + keys + "}");
        const SceneDesc scene = io::parseScene(text.toStdString(), "drop.json");
        QCOMPARE(scene.settings.sleeping, sleeping);
        QCOMPARE(scene.settings.solverIterations, iterations);
        // The engine takes them (in range), and saving keeps them.
        const World world(scene);
        QCOMPARE(world.model().bodies.size(), scene.bodies.size());
        const SceneDesc back = io::parseScene(io::sceneToJson(scene), "again.json");
        QCOMPARE(back.settings.sleeping, sleeping);
        QCOMPARE(back.settings.solverIterations, iterations);
        QVERIFY(back == scene);
    }

    // The round trip of every field is not vacuous for the two solver settings either.
    void roundTripKeepsSolverSettings() {
        const SceneDesc scene = everyField();
        const SceneDesc back = io::parseScene(io::sceneToJson(scene), "every.json");
        QCOMPARE(back.settings.sleeping, false);
        QCOMPARE(back.settings.solverIterations, 7);
        SceneDesc other = back;
        other.settings.sleeping = true;
        QVERIFY(!(other == scene));
        other = back;
        other.settings.solverIterations = 20;
        QVERIFY(!(other == scene));
    }

    // A file read from disk is named as given, in every message.
    void badFileNamesTheFile() {
        QTemporaryDir dir;
        const fs::path path = fs::path(dir.path().toStdString()) / "drop.json";
        std::ofstream(path) << QString(kBase).replace(R"("radius": 0.5)", R"("radius": -1)").toStdString();
        try {
            io::readSceneFile(path);
            QFAIL("no error");
        } catch (const InputError& e) {
            QCOMPARE(e.what(), path.string() + ": bodies[1].shape.radius: must be greater than 0");
            QCOMPARE(e.file(), path.string());
        }
    }

    void unreadableFiles_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<QString>("message");
        QTest::newRow("missing") << "nope.json"
                                 << "cannot be read (missing, or no permission)";
        QTest::newRow("directory") << "folder.json"
                                   << "is a directory, not a scene file";
    }

    void unreadableFiles() {
        QFETCH(QString, name);
        QFETCH(QString, message);
        QTemporaryDir dir;
        QVERIFY(QDir(dir.path()).mkdir("folder.json"));
        const fs::path path = fs::path(dir.path().toStdString()) / name.toStdString();
        try {
            io::readSceneFile(path);
            QFAIL("no error");
        } catch (const InputError& e) {
            QCOMPARE(QString::fromStdString(e.what()),
                     QString::fromStdString(path.string()) + ": " + message);
            QCOMPARE(e.file(), path.string());
            QVERIFY(e.field().empty());
        }
    }

    void normalisesOnLoad() {
        QString text = kBase;
        text.replace(R"("orientation": [1, 0, 0, 0])", R"("orientation": [2, 2, 2, 2])");
        text.replace(R"("normal": [0, 1, 0])", R"("normal": [0, 3, 4])");
        SceneDesc scene = io::parseScene(text.toStdString(), "drop.json");
        QCOMPARE(scene.bodies[1].orientation.coeffs(), Quat(0.5, 0.5, 0.5, 0.5).coeffs());
        QVERIFY(std::abs(scene.bodies[0].shape.normal.norm() - 1.0) < 1e-15);
        QVERIFY((scene.bodies[0].shape.normal - Vec3(0, 0.6, 0.8)).norm() < 1e-15);

        // Components whose squares overflow keep their direction.
        text = kBase;
        text.replace(R"("orientation": [1, 0, 0, 0])", R"("orientation": [1e200, 1e200, 0, 0])");
        text.replace(R"("normal": [0, 1, 0])", R"("normal": [0, 3e300, 4e300])");
        scene = io::parseScene(text.toStdString(), "drop.json");
        QVERIFY((scene.bodies[1].orientation.coeffs() - Eigen::Vector4d(std::sqrt(0.5), 0, 0, std::sqrt(0.5)))
                    .norm() < 1e-15);
        QVERIFY((scene.bodies[0].shape.normal - Vec3(0, 0.6, 0.8)).norm() < 1e-15);
        QVERIFY(World(scene).state().bodies[1].q.coeffs().allFinite());

        // A general one: unit length, same direction.
        text = kBase;
        text.replace(R"("orientation": [1, 0, 0, 0])", R"("orientation": [0.3, -1.7, 2.9, 0.05])");
        scene = io::parseScene(text.toStdString(), "drop.json");
        const Quat& q = scene.bodies[1].orientation;
        QVERIFY(std::abs(q.norm() - 1.0) < 1e-15);
        const Eigen::Vector4d raw(-1.7, 2.9, 0.05, 0.3);  // x, y, z, w: Eigen's coefficient order
        const Eigen::Vector4d cs = q.coeffs();
        QVERIFY((cs - raw / raw.norm()).norm() < 1e-15);
        // Written out as loaded: unit.
        const SceneDesc again = io::parseScene(io::sceneToJson(scene), "again.json");
        QVERIFY(again == scene);
    }

    // Load -> save -> load changes nothing, bit for bit, whatever the orientation and plane
    // normal: otherwise a scene saved by --save-scene or the editor would not reproduce the
    // run it came from.
    void normalisationIsStable() {
        std::mt19937_64 random(12345);
        std::normal_distribution<double> gauss;
        for (int trial = 0; trial < 3000; ++trial) {
            const double scale = std::pow(10.0, trial % 7 - 3);
            char text[1024];
            std::snprintf(text, sizeof text,
                          R"({"format": "tumble-scene", "version": 1, "bodies": [
                             {"name": "p", "motion": "static", "shape": {"type": "plane", "normal": [%.17g, %.17g, %.17g]}},
                             {"name": "b", "mass": 1, "shape": {"type": "sphere", "radius": 1},
                              "orientation": [%.17g, %.17g, %.17g, %.17g]}]})",
                          scale * gauss(random), scale * gauss(random), scale * gauss(random),
                          scale * gauss(random), scale * gauss(random), scale * gauss(random),
                          scale * gauss(random));
            const SceneDesc first = io::parseScene(text, "random.json");
            const std::string saved = io::sceneToJson(first);
            const SceneDesc second = io::parseScene(saved, "random.json");
            if (!(second == first)) QFAIL(qPrintable(QString("load-save-load changed the scene:\n") + text));
            QCOMPARE(io::sceneToJson(second), saved);
            QVERIFY(std::abs(first.bodies[1].orientation.norm() - 1.0) < 1e-15);
            QVERIFY(std::abs(first.bodies[0].shape.normal.norm() - 1.0) < 1e-15);
            // The engine starts from the same state either way.
            QCOMPARE(hashState(World(second).state()), hashState(World(first).state()));
        }
    }
};

QTEST_APPLESS_MAIN(TestSceneFile)
#include "tst_scene_file.moc"
