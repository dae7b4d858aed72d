// Mesh import (assimp) and mesh bodies in scene files: every format the samples use,
// against solids whose volume, centre and inertia are known in closed form; scale; the
// messages for bad meshes; and a mesh scene that compiles and runs.
// The assimp models are Debian's package assimp-testmodels (/usr/share/assimp/models).
#include <tumble/convex_parts.h>
#include <tumble/errors.h>
#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>
#include <tumble/mass.h>
#include <tumble/model.h>
#include <tumble/world.h>

#include <QTemporaryDir>
#include <QtTest>

#include <sys/stat.h>

// TUMBLE_TEST_ASAN: the build has AddressSanitizer (./dev.sh sanitize; set by
// tests/CMakeLists.txt, so that moc sees the slot too): the reader child's sanitizer reports.
#ifdef TUMBLE_TEST_ASAN
#include "mesh_child.h"  // engine/io/src

#include <assimp/scene.h>
#endif

#include <atomic>
#include <thread>
#include <cstring>
#include <fstream>
#include <optional>

using namespace tumble;
namespace fs = std::filesystem;

namespace {

const fs::path kAssimpModels = "/usr/share/assimp/models";
const fs::path kMeshes = fs::path(TUMBLE_SCENES_DIR) / ".." / "meshes";
// Inputs the fuzzer found (tests/fuzz): the first byte chose the extension, the rest is the file.
const fs::path kFuzzFinds =
    fs::path(TUMBLE_SCENES_DIR) / ".." / ".." / "tests" / "fuzz" / "regressions" / "mesh";

struct Solid {
    double volume = 0.0;
    MassProperties mp;  // density 1
};

Solid solidOf(const TriangleMesh& m) {
    Solid s;
    s.mp = meshMassProperties(m, 1.0, &s.volume);
    return s;
}

// The unit cube [-0.5, 0.5]³ as binary STL: 80-byte header, count, 50 bytes per triangle.
void writeBinaryStlCube(const fs::path& file, const Vec3& offset) {
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    std::ofstream out(file, std::ios::binary);
    const char header[80] = "binary cube written by tst_mesh_import";
    out.write(header, 80);
    const std::uint32_t count = 12;
    out.write(reinterpret_cast<const char*>(&count), 4);
    auto corner = [&](int k) -> Vec3 {
        return Vec3(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.5 : -0.5) + offset;
    };
    for (const auto& q : quads) {
        for (const auto& t : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
            float data[12] = {0, 0, 0};  // the normal is left zero: readers recompute it
            for (int v = 0; v < 3; ++v) {
                for (int a = 0; a < 3; ++a) data[3 + 3 * v + a] = static_cast<float>(corner(t[v])[a]);
            }
            out.write(reinterpret_cast<const char*>(data), sizeof data);
            const std::uint16_t attributes = 0;
            out.write(reinterpret_cast<const char*>(&attributes), 2);
        }
    }
}

void writeText(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

std::string sceneWithMesh(const std::string& file, const std::string& extra = R"("density": 1000)",
                          const std::string& shapeExtra = "") {
    return R"({"format": "tumble-scene", "version": 1, "bodies": [
        {"name": "ground", "motion": "static", "shape": {"type": "plane", "normal": [0, 1, 0]}},
        {"name": "rock", "shape": {"type": "mesh", "file": ")" +
           file + "\"" + shapeExtra + "}, " + extra + "}]}";
}

// The InputError's what() for a scene text read from `dir`, or "no error".
QString inputError(const std::string& text, const fs::path& dir) {
    try {
        io::parseScene(text, "drop.json", dir);
    } catch (const io::InputError& e) {
        return QString::fromStdString(e.what());
    }
    return "no error";
}

bool near(const Mat3& a, const Mat3& b, double tol) {
    return (a - b).cwiseAbs().maxCoeff() <= tol;
}

}  // namespace

class TestMeshImport : public QObject {
    Q_OBJECT
private slots:
    void formats_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<int>("triangles");
        QTest::addColumn<int>("vertices");
        QTest::addColumn<bool>("closed");
        QTest::addColumn<double>("volume");
        QTest::addColumn<Vec3>("center");
        const QString models = QString::fromStdString(kAssimpModels.string());
        const QString ours = QString::fromStdString(kMeshes.string());
        const Vec3 zero = Vec3::Zero();
        QTest::newRow("OBJ box") << models + "/OBJ/box.obj" << 12 << 8 << true << 1.0 << zero;
        QTest::newRow("OBJ faces, lines and points")
            << models + "/OBJ/testmixed.obj" << 12 << 8 << true << 1.0 << zero;
        QTest::newRow("PLY ascii cube")
            << models + "/PLY/cube.ply" << 12 << 8 << true << 1.0 << Vec3(0.5, 0.5, 0.5);
        QTest::newRow("PLY binary cube")
            << models + "/PLY/cube_binary.ply" << 12 << 8 << true << 1.0 << Vec3(0.5, 0.5, 0.5);
        QTest::newRow("OFF cube") << models + "/OFF/Cube.off" << 12 << 8 << true << 1.0 << zero;
        QTest::newRow("glTF2 separate")
            << models + "/glTF2/BoxTextured-glTF/BoxTextured.gltf" << 12 << 8 << true << 1.0 << zero;
        QTest::newRow("glTF2 embedded")
            << models + "/glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf" << 12 << 8 << true << 1.0 << zero;
        QTest::newRow("glTF2 binary")
            << models + "/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb" << 12 << 8 << true << 1.0 << zero;
        // Ours: an ascii STL (each facet its own vertices, joined on import), a concave prism.
        QTest::newRow("STL ascii box") << ours + "/box.stl" << 12 << 8 << true << 1.0 << zero;
        QTest::newRow("OBJ L prism") << ours + "/l-prism.obj" << 28 << 16 << true << 3.0
                                     << Vec3(5.0 / 6.0, 5.0 / 6.0, 0.5);
        QTest::newRow("OFF tetrahedron")
            << ours + "/tetrahedron.off" << 4 << 4 << true << 1.0 / 6.0 << Vec3(0.25, 0.25, 0.25);
        QTest::newRow("PLY open box") << ours + "/open-box.ply" << 10 << 8 << false << -1.0 << zero;
    }

    void formats() {
        QFETCH(QString, file);
        QFETCH(int, triangles);
        QFETCH(int, vertices);
        QFETCH(bool, closed);
        QFETCH(double, volume);
        QFETCH(Vec3, center);
        const TriangleMesh m = io::importMesh(file.toStdString());
        QCOMPARE(static_cast<int>(m.triangles.size()), triangles);
        QCOMPARE(static_cast<int>(m.vertices.size()), vertices);
        QCOMPARE(isClosed(m), closed);
        if (volume > 0) {
            const Solid s = solidOf(m);
            QVERIFY(std::abs(s.volume - volume) < 1e-12);
            QVERIFY((s.mp.centerOfMass - center).norm() < 1e-12);
        }
    }

    // The same spider in both STL encodings: same triangles, same solid (float rounding).
    void stlAsciiAndBinaryAgree() {
        const TriangleMesh a = io::importMesh(kAssimpModels / "STL/Spider_ascii.stl");
        const TriangleMesh b = io::importMesh(kAssimpModels / "STL/Spider_binary.stl");
        QCOMPARE(a.triangles.size(), size_t(1368));
        QCOMPARE(b.triangles.size(), a.triangles.size());
        QCOMPARE(b.vertices.size(), a.vertices.size());
        const Solid sa = solidOf(a), sb = solidOf(b);
        QVERIFY(std::abs(sa.volume - sb.volume) < 1e-6 * std::abs(sa.volume));
        QVERIFY((sa.mp.centerOfMass - sb.mp.centerOfMass).norm() < 1e-5);
    }

    void binaryStlCube() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "cube.stl";
        writeBinaryStlCube(file, Vec3(1, 2, 3));
        const TriangleMesh m = io::importMesh(file);
        QCOMPARE(m.triangles.size(), size_t(12));
        QVERIFY(isClosed(m));
        const Solid s = solidOf(m);
        QVERIFY(std::abs(s.volume - 1.0) < 1e-12);
        QVERIFY((s.mp.centerOfMass - Vec3(1, 2, 3)).norm() < 1e-12);
        QVERIFY(near(s.mp.inertia, Mat3::Identity() / 6.0, 1e-12));  // m a² / 6
    }

    // Scale multiplies each coordinate: the volume by sx sy sz, the centre componentwise.
    void scaleIsApplied() {
        const Vec3 scale(2, 0.5, 3);
        const TriangleMesh m = io::importMesh(kMeshes / "l-prism.obj", scale);
        const Solid s = solidOf(m);
        QVERIFY(std::abs(s.volume - 3.0 * 3.0) < 1e-12);
        QVERIFY((s.mp.centerOfMass - Vec3(5.0 / 6.0, 5.0 / 6.0, 0.5).cwiseProduct(scale)).norm() < 1e-12);
        // The unit cube scaled to a box 2 × 0.5 × 3: the box's closed form.
        const Solid box = solidOf(io::importMesh(kMeshes / "box.stl", scale));
        QVERIFY(std::abs(box.volume - 3.0) < 1e-12);
        const Vec3 d = 3.0 / 12.0 * Vec3(0.25 + 9, 4 + 9, 4 + 0.25);
        QVERIFY(near(box.mp.inertia, Mat3(d.asDiagonal()), 1e-12));
    }

    // A scene with the corner tetrahedron: mass and inertia of its closed form, about the
    // computed centre of mass (not the body origin).
    void tetrahedronBodyFromAScene() {
        QTemporaryDir dir;
        const fs::path base(dir.path().toStdString());
        fs::create_directories(base / "meshes");
        fs::copy_file(kMeshes / "tetrahedron.off", base / "meshes" / "tet.off");
        writeText(base / "tet.json",
                  sceneWithMesh("meshes/tet.off", R"("density": 600, "position": [1, 2, 3])",
                                R"(, "scale": [2, 2, 2])"));
        const SceneDesc scene = io::readSceneFile(base / "tet.json");
        QVERIFY(scene.bodies[1].shape.meshData);
        const World world(scene);
        const BodyModel& b = world.model().bodies[1];
        // Density ρ, legs a = 2: V = a³/6, centre a/4, I = ρ a⁵ [1/80 on the diagonal, 1/480 off it].
        const double rho = 600, a = 2;
        QVERIFY(std::abs(b.mass - rho * a * a * a / 6.0) < 1e-9);
        QVERIFY((b.centerOfMass - Vec3::Constant(a / 4)).norm() < 1e-14);
        Mat3 expected = Mat3::Constant(1.0 / 480.0);
        expected.diagonal().setConstant(1.0 / 80.0);
        expected *= rho * std::pow(a, 5);
        QVERIFY(near(b.inertia, expected, 1e-12 * expected.maxCoeff()));
        QVERIFY((world.state().bodies[1].x - Vec3(1.5, 2.5, 3.5)).norm() < 1e-14);
        QCOMPARE(QString::fromStdString(world.model().notes.at(0)),
                 QString("bodies[1] (rock): the mesh is closed; mass properties come from its surface"));
    }

    // The sample scene: both meshes load relative to the scene file, it compiles, and a
    // body whose mass comes from a mesh falls freely as the closed form says until it lands.
    void sampleSceneRuns() {
        const SceneDesc scene = io::readSceneFile(fs::path(TUMBLE_SCENES_DIR) / "mesh-shapes.json");
        QCOMPARE(scene.bodies[1].shape.collision, MeshCollision::Triangles);
        QCOMPARE(scene.bodies[2].shape.collision, MeshCollision::ConvexHull);
        World world(scene);
        QCOMPARE(world.model().bodies[1].collider.kind, collision::Kind::Mesh);
        QCOMPARE(world.model().bodies[2].collider.kind, collision::Kind::Hull);
        QCOMPARE(world.model().bodies[2].collider.hull->faces.size(), size_t(4));
        const Vec3 x0 = world.state().bodies[2].x;
        const double t = 0.2;  // the tetrahedron is 1 m above the step: no contact yet
        for (int k = 0; k < 48; ++k) world.step(t / 48);
        const Vec3 expected = x0 + 0.5 * scene.settings.gravity * t * t;
        QVERIFY((world.state().bodies[2].x - expected).norm() < 1e-12);
        simulate(world, [](int, const State& s) {
            for (const BodyState& b : s.bodies) QVERIFY(b.x.allFinite() && b.q.coeffs().allFinite());
        });
    }

    void openMeshMassFromHullInAScene() {
        QTemporaryDir dir;
        const fs::path base(dir.path().toStdString());
        fs::copy_file(kMeshes / "open-box.ply", base / "open.ply");
        writeText(base / "open.json", sceneWithMesh("open.ply", R"("mass": 6)", R"(, "scale": [1, 2, 3])"));
        const World world(io::readSceneFile(base / "open.json"));
        const BodyModel& b = world.model().bodies[1];
        QCOMPARE(b.mass, 6.0);
        QVERIFY(b.centerOfMass.norm() < 1e-12);  // the hull is the whole box, centred
        const Vec3 d = 6.0 / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4);
        QVERIFY(near(b.inertia, Mat3(d.asDiagonal()), 1e-12));
        QCOMPARE(
            QString::fromStdString(world.model().notes.at(0)),
            QString("bodies[1] (rock): the mesh is not closed; mass properties come from its convex hull"));
    }

    // Issue 49: an open mesh asked to split into convex parts has its holes filled first
    // (the open box's missing face: one flat fan), and its mass comes from the filled solid,
    // which is the whole box again.
    void openMeshSplitIntoConvexPartsIsFilled() {
        QTemporaryDir dir;
        const fs::path base(dir.path().toStdString());
        fs::copy_file(kMeshes / "open-box.ply", base / "open.ply");
        writeText(base / "open.json", sceneWithMesh("open.ply", R"("mass": 6)",
                                                    R"(, "scale": [1, 2, 3], "collision": "convex-parts")"));
        const World world(io::readSceneFile(base / "open.json"));
        const BodyModel& b = world.model().bodies[1];
        QVERIFY(b.centerOfMass.norm() < 1e-12);
        const Vec3 d = 6.0 / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4);
        QVERIFY(near(b.inertia, Mat3(d.asDiagonal()), 1e-12));
        QCOMPARE(b.collider.kind, collision::Kind::Compound);
        QCOMPARE(int(b.collider.compound->parts.size()), 1);
        const QString note = QString::fromStdString(world.model().notes.at(0));
        QVERIFY2(note.startsWith(
                     "bodies[1] (rock): the mesh was open: its 1 hole was filled (in 1 of its 1 piece)"),
                 qPrintable(note));
    }

    // Issue 49 item 3's spider: 18 pieces left open where they meet, ten edges wound against
    // their neighbours. Its triangles are made to wind alike and its 6 holes filled; in 48
    // parts it is within 5 % of its volume and within the tolerance, upright and turned (16
    // parts are too few for eight bent legs: +29 %, tumble-bench --scene convex-parts).
    void theSpiderSplitsIntoConvexParts_data() {
        QTest::addColumn<bool>("turn");
        QTest::newRow("upright") << false;
        QTest::newRow("turned and shifted") << true;
    }
    void theSpiderSplitsIntoConvexParts() {
        QFETCH(bool, turn);
        TriangleMesh m = io::importMesh(kAssimpModels / "STL" / "Spider_binary.stl");
        const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()));
        if (turn)
            for (Vec3& v : m.vertices) v = q * v + Vec3(3.0, -1.5, 2.25);
        ShapeDesc shape;
        shape.type = ShapeType::Mesh;
        shape.file = "Spider_binary.stl";
        shape.collision = MeshCollision::ConvexParts;
        shape.maxParts = 48;
        shape.meshData = std::make_shared<const TriangleMesh>(m);
        const mesh::ConvexParts p = mesh::convexPartsOfShape(shape);
        qInfo("spider: %zu parts, %+.2f %% volume, reach out %.3f m of %.3f", p.parts.size(),
              100 * (p.partsVolume / p.meshVolume - 1), p.largestPokeOut, p.tolerance);
        QCOMPARE(p.filledHoles, 6);
        QVERIFY(p.withinTolerance);
        QVERIFY(p.partsVolume >= p.meshVolume * (1 - 1e-9));
        QVERIFY2(p.partsVolume < 1.05 * p.meshVolume,
                 qPrintable(QString::number(p.partsVolume / p.meshVolume)));
    }

    void badMeshes_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<QString>("expected");
        QTest::newRow("missing")
            << "meshes/rock.obj"
            << "drop.json: bodies[1].shape.file: meshes/rock.obj: cannot be read (missing, or no "
               "permission)";
        QTest::newRow("a directory")
            << "meshes"
            << "drop.json: bodies[1].shape.file: meshes: is a directory, not a mesh file";
        // What assimp makes of noise depends on the reader it picks; any refusal will do.
        QTest::newRow("garbage obj") << "meshes/garbage.obj"
                                     << "drop.json: bodies[1].shape.file: meshes/garbage.obj: ";
        QTest::newRow("garbage stl")
            << "meshes/garbage.stl"
            << "drop.json: bodies[1].shape.file: meshes/garbage.stl: cannot be read as a mesh: ";
        QTest::newRow("garbage, no extension")
            << "meshes/garbage"
            << "drop.json: bodies[1].shape.file: meshes/garbage: cannot be read as a "
               "mesh: No suitable reader";
        QTest::newRow("empty") << "meshes/empty.stl"
                               << "drop.json: bodies[1].shape.file: meshes/empty.stl: cannot be read";
        QTest::newRow("text, no mesh") << "meshes/words.obj"
                                       << "drop.json: bodies[1].shape.file: meshes/words.obj: holds no mesh";
        const std::string models = kAssimpModels.string();
        QTest::newRow("OBJ points") << QString::fromStdString(models + "/OBJ/testpoints.obj")
                                    << QString::fromStdString(
                                           "drop.json: bodies[1].shape.file: " + models +
                                           "/OBJ/testpoints.obj: holds no triangles (only points or lines)");
        QTest::newRow("OBJ lines") << QString::fromStdString(models + "/OBJ/testline.obj")
                                   << QString::fromStdString(
                                          "drop.json: bodies[1].shape.file: " + models +
                                          "/OBJ/testline.obj: holds no triangles (only points or lines)");
        QTest::newRow("PLY points") << QString::fromStdString(models + "/PLY/points.ply")
                                    << QString::fromStdString("drop.json: bodies[1].shape.file: " + models +
                                                              "/PLY/points.ply: holds no triangles");
        // assimp 5.2 loops for ever on these (found by tests/fuzz): refused before it reads them.
        QTest::newRow("PLY header without end_header")
            << "meshes/noend.ply"
            << "drop.json: bodies[1].shape.file: meshes/noend.ply: is a PLY file whose header has no "
               "end_header line";
        QTest::newRow("PLY end_header only in a comment")
            << "meshes/comment.ply"
            << "drop.json: bodies[1].shape.file: meshes/comment.ply: is a PLY file whose header has no "
               "end_header line";
        QTest::newRow("glTF2 infinite vertex")
            << QString::fromStdString(models + "/glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb")
            << "is not a finite number";
    }

    // Never a crash: a message that names the scene file, the field and the mesh file.
    void badMeshes() {
        QFETCH(QString, file);
        QFETCH(QString, expected);
        QTemporaryDir dir;
        const fs::path base(dir.path().toStdString());
        fs::create_directories(base / "meshes");
        std::string garbage;
        for (int k = 0; k < 4000; ++k) garbage += static_cast<char>((k * 7919 + 13) % 251);
        writeText(base / "meshes" / "garbage.obj", garbage);
        writeText(base / "meshes" / "garbage", garbage);
        writeText(base / "meshes" / "garbage.stl", garbage);
        writeText(base / "meshes" / "empty.stl", "");
        writeText(base / "meshes" / "words.obj", "hello world\nthis is no mesh\n");
        const std::string plyBody =
            "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\n";
        const std::string plyData = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        writeText(base / "meshes" / "noend.ply", "ply\nformat ascii 1.0\n" + plyBody + plyData);
        writeText(base / "meshes" / "comment.ply",
                  "ply\nformat ascii 1.0\ncomment end_header\n" + plyBody + plyData);
        const QString what = inputError(sceneWithMesh(file.toStdString()), base);
        QVERIFY2(what.startsWith(expected) || (!expected.startsWith("drop.json") && what.contains(expected)),
                 qPrintable(what));
    }

    // A flat mesh reads, but a density needs a volume: compile names the field and the file.
    // assimp 5.2 aborts on an internal assertion (its triangulation) reading this PLY from the
    // fuzzer; the read happens in a child process, so the caller gets a message, not a crash.
    void aCrashInTheReaderIsAMessage() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "faces.ply";
        std::ifstream in(kFuzzFinds / "ply-faces-abort-triangulation", std::ios::binary);
        QVERIFY(in);
        in.get();  // the extension byte
        std::ofstream(file, std::ios::binary) << in.rdbuf();
        try {
            tumble::io::importMesh(file);
            QFAIL("read a file assimp crashes on");
        } catch (const tumble::io::InputError& e) {
            QCOMPARE(QString::fromStdString(e.file()), QString::fromStdString(file.string()));
            QVERIFY2(e.message().starts_with("the mesh reader (assimp) crashed on it (signal 6"), e.what());
        }
    }

    // The editor's Cancel: a read stopped from another thread ends within a moment, the
    // reader's child killed, with MeshImportCancelled (not an error of the file).
    void aCancelledReadStopsAtOnce() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "noend.ply";
        writeText(file,
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\n0 0 0\n1 0 0\n0 1 0\n");
        std::atomic<bool> cancel{false};
        tumble::io::MeshImportOptions options;
        options.timeLimit = 60;
        options.refuseKnownHangs = false;  // a reader that would loop until the time limit
        options.cancel = &cancel;
        std::thread user([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(300));
            cancel = true;
        });
        QElapsedTimer clock;
        clock.start();
        bool cancelled = false;
        try {
            tumble::io::importMesh(file, Vec3(1, 1, 1), options);
        } catch (const tumble::io::MeshImportCancelled&) {
            cancelled = true;
        }
        user.join();
        QVERIFY(cancelled);
        QVERIFY2(clock.elapsed() < 5000, qPrintable(QString::number(clock.elapsed())));
        // Not set: the same options read a good file as usual.
        const fs::path good = fs::path(dir.path().toStdString()) / "tri.obj";
        writeText(good, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        cancel = false;
        QCOMPARE(tumble::io::importMesh(good, Vec3(1, 1, 1), options).triangles.size(), size_t(1));
    }

    // A reader that never finishes is killed at the time limit: here a PLY without end_header
    // given to assimp on purpose (importMesh refuses it first otherwise).
    void aReaderThatNeverFinishesIsStopped() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "noend.ply";
        writeText(file,
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\n0 0 0\n1 0 0\n0 1 0\n");
        tumble::io::MeshImportOptions options;
        options.timeLimit = 1.5;
        options.refuseKnownHangs = false;
        QElapsedTimer clock;
        clock.start();
        try {
            tumble::io::importMesh(file, Vec3(1, 1, 1), options);
            QFAIL("a reader that loops for ever returned");
        } catch (const tumble::io::InputError& e) {
            QCOMPARE(QString::fromStdString(e.message()),
                     QString("the mesh reader (assimp) did not finish reading it within 1.5 s; the file is "
                             "damaged or too large"));
        }
        QVERIFY(clock.elapsed() < 60000);
    }

#ifdef TUMBLE_TEST_ASAN
    // With AddressSanitizer (the mesh fuzzer's build): a memory error that the sanitizer
    // finds inside assimp in the reader's child is the reader failing on the file, a message
    // like its crashes (the fuzzer met assimp 5.2 freeing what it never allocated, on a
    // damaged PLY, after some 2 700 inputs); one in Tumble's own code there stays exit
    // status 1, which the fuzz harness reports as a bug.
    void aMemoryErrorInsideTheReaderIsItsOwn() {
        try {
            tumble::io::readMeshInChild("fake.ply", 30, [] {
                // A scene whose one mesh was never allocated: assimp's ~aiScene frees it.
                alignas(64) static unsigned char notAMesh[sizeof(aiMesh)] = {};
                auto* scene = new aiScene();
                scene->mNumMeshes = 1;
                scene->mMeshes = new aiMesh* [1] { reinterpret_cast<aiMesh*>(notAMesh) };
                delete scene;
                return TriangleMesh{};
            });
            QFAIL("the child came back after a bad free inside assimp");
        } catch (const tumble::io::InputError& e) {
            QVERIFY2(
                e.message().starts_with("the mesh reader (assimp) failed on it (a memory error inside the "
                                        "reader)"),
                e.what());
        }
        try {
            tumble::io::readMeshInChild("own.ply", 30, [] {
                char* p = new char[16];
                volatile int off = 1;
                delete[](p + off);  // Tumble's own bad free
                return TriangleMesh{};
            });
            QFAIL("the child came back after a bad free of its own");
        } catch (const tumble::io::InputError& e) {
            QCOMPARE(QString::fromStdString(e.message()),
                     QString("the mesh reader stopped without an answer (exit status 1)"));
        }
    }
#endif

    // assimp reads in a program of its own, not in a fork of the caller (a fork taken on
    // the editor's import thread inherited a lock another thread held, and the sanitized
    // editor's import waited for ever): importMesh finds the build tree's reader and
    // starts it; TUMBLE_MESH_READER names another, and what that program does is what the
    // user hears.
    void theReaderIsAProgramOfItsOwn() {
        const QString reader = QString::fromStdString(tumble::io::meshReaderProgram());
        QVERIFY2(reader.endsWith("/tumble-mesh-reader"), qPrintable(reader));
        QTemporaryDir dir;
        const fs::path good = fs::path(dir.path().toStdString()) / "tri.obj";
        writeText(good, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        const TriangleMesh m = tumble::io::importMesh(good, Vec3(2, 3, 4));
        QCOMPARE(m.triangles.size(), size_t(1));
        QVERIFY(m.vertices.size() == 3 && m.vertices[1] == Vec3(2, 0, 0) && m.vertices[2] == Vec3(0, 3, 0));

        const auto messageWith = [&](const char* program) {
            qputenv("TUMBLE_MESH_READER", program);
            QString what;
            try {
                tumble::io::importMesh(good);
            } catch (const tumble::io::InputError& e) {
                what = QString::fromStdString(e.message());
            }
            qunsetenv("TUMBLE_MESH_READER");
            return what;
        };
        QCOMPARE(messageWith("/bin/false"), QString("the mesh reader stopped without an answer (exit status 1)"));
        QCOMPARE(messageWith("/no/such/reader"),
                 QString("the mesh reader program /no/such/reader cannot be started (No such file or "
                         "directory)"));

        // Run by hand without its arguments or its answer's descriptor: a usage line, status 2.
        QProcess byHand;
        byHand.start(reader, {good.c_str()});
        QVERIFY(byHand.waitForFinished(30000));
        QCOMPARE(byHand.exitCode(), 2);
        QVERIFY(byHand.readAllStandardError().startsWith("usage: tumble-mesh-reader FILE SX SY SZ"));
    }

    // A mesh `file` that names a FIFO is refused at once (opening it for reading would wait
    // for a writer for ever: `tumble --headless` on such a scene hung).
    void aFifoIsNotAMeshFile() {
        QTemporaryDir dir;
        const fs::path fifo = fs::path(dir.path().toStdString()) / "pipe.obj";
        QVERIFY(::mkfifo(fifo.c_str(), 0600) == 0);
        try {
            tumble::io::importMesh(fifo);
            QFAIL("read a FIFO as a mesh");
        } catch (const tumble::io::InputError& e) {
            QCOMPARE(QString::fromStdString(e.file()), QString::fromStdString(fifo.string()));
            QCOMPARE(QString::fromStdString(e.message()),
                     QString("is not a regular file (a pipe, socket or device), not a mesh file"));
        }
    }

    // The child's answer carries the mesh exactly (every bit of every vertex).
    void theChildsMeshIsExact() {
        for (const char* name : {"l-prism.obj", "box.stl", "tetrahedron.off"}) {
            tumble::io::MeshImportOptions here;
            here.timeLimit = 0;
            const Vec3 scale(0.1, 3.0, 1.0 / 3.0);
            const TriangleMesh a = tumble::io::importMesh(kMeshes / name, scale);
            const TriangleMesh b = tumble::io::importMesh(kMeshes / name, scale, here);
            QVERIFY2(!a.triangles.empty(), name);
            QVERIFY2(a.vertices == b.vertices, name);
            QVERIFY2(a.triangles == b.triangles, name);
        }
    }

    void flatMeshWithDensity() {
        const std::string file = (kAssimpModels / "STL/triangle.stl").string();
        const SceneDesc scene = io::parseScene(sceneWithMesh(file), "drop.json", fs::path("."));
        try {
            compile(scene);
            QFAIL("a flat mesh with a density compiled");
        } catch (const SceneError& e) {
            QCOMPARE(QString::fromStdString(e.path()), QString("bodies[1].density"));
            QVERIFY2(QString::fromStdString(e.message())
                         .startsWith(QString::fromStdString(file + ": the mesh encloses no volume")),
                     e.what());
        }
    }

    // Without a base directory no mesh is read, and compile says the mesh was never loaded.
    void parseWithoutBaseDirectory() {
        const SceneDesc scene = io::parseScene(sceneWithMesh("nowhere/rock.obj"), "drop.json");
        QVERIFY(!scene.bodies[1].shape.meshData);
        try {
            compile(scene);
            QFAIL("compiled a mesh that was never loaded");
        } catch (const SceneError& e) {
            QCOMPARE(QString::fromStdString(e.path()), QString("bodies[1].shape.file"));
        }
    }

    // The writer keeps the file name, never the triangles; bodies sharing a file share a mesh.
    void writerLeavesTheMeshOut() {
        const fs::path path = fs::path(TUMBLE_SCENES_DIR) / "mesh-shapes.json";
        SceneDesc scene = io::readSceneFile(path);
        scene.bodies.push_back(scene.bodies[2]);
        scene.bodies.back().name = "twin";
        const std::string text = io::sceneToJson(scene);
        QVERIFY(text.find("\"file\": \"../meshes/tetrahedron.off\"") != std::string::npos);
        QVERIFY(text.find("meshData") == std::string::npos && text.find("vertices") == std::string::npos);
        const SceneDesc back = io::parseScene(text, "again.json", path.parent_path());
        QVERIFY(back == scene);
        QVERIFY(back.bodies[2].shape.meshData == back.bodies[3].shape.meshData);
        QCOMPARE(back.bodies[2].shape.meshData->triangles.size(), size_t(4));
    }
};

QTEST_APPLESS_MAIN(TestMeshImport)
#include "tst_mesh_import.moc"
