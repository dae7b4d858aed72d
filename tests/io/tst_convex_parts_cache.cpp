// The convex parts' sidecar (tumble/io/convex_parts_cache.h, issue 49 item 3): a scene's
// mesh split once and kept beside the scene, keyed by the mesh's content and the options;
// a run from the kept parts is the run from parts just made, bit for bit; an edited mesh,
// changed options or a broken sidecar make them again.
#include "../engine/test_meshes.h"

#include <tumble/convex_parts.h>
#include <tumble/io/convex_parts_cache.h>
#include <tumble/io/scene_file.h>
#include <tumble/world.h>

#include <QTemporaryDir>
#include <QtTest>

#include <cstring>
#include <filesystem>
#include <fstream>

using namespace tumble;
namespace fs = std::filesystem;

namespace {

void writeObj(const TriangleMesh& m, const fs::path& file) {
    std::ofstream out(file);
    out.precision(17);
    for (const Vec3& v : m.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const auto& t : m.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

// A mug split into convex parts, dynamic, tipped over on the floor, and a ball dropped into it.
SceneDesc mugScene() {
    SceneDesc s;
    BodyDesc floor;
    floor.name = "floor";
    floor.motion = Motion::Static;
    floor.shape.type = ShapeType::Plane;
    s.bodies.push_back(floor);
    BodyDesc cup;
    cup.name = "mug";
    cup.shape.type = ShapeType::Mesh;
    cup.shape.file = "mug.obj";
    cup.shape.collision = MeshCollision::ConvexParts;
    cup.shape.maxParts = 12;
    cup.density = 800.0;
    cup.position = Vec3(0, 0.05, 0);
    cup.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
    s.bodies.push_back(cup);
    BodyDesc ball;
    ball.name = "ball";
    ball.shape.radius = 0.1;
    ball.mass = 0.1;
    ball.position = Vec3(0.1, 1.6, 0);
    s.bodies.push_back(ball);
    return s;
}

State runOf(const SceneDesc& scene) {
    World w(scene);
    for (int k = 0; k < 240; ++k) w.step(1.0 / 240.0);
    return w.state();
}

bool sameBits(const State& a, const State& b) {
    for (size_t i = 0; i < a.bodies.size(); ++i) {
        const BodyState &x = a.bodies[i], &y = b.bodies[i];
        if (std::memcmp(x.x.data(), y.x.data(), sizeof(double) * 3) != 0 ||
            std::memcmp(x.q.coeffs().data(), y.q.coeffs().data(), sizeof(double) * 4) != 0)
            return false;
    }
    return true;
}

}  // namespace

class TestConvexPartsCache : public QObject {
    Q_OBJECT
private slots:
    void madeOnceKeptAndTakenBack() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        writeObj(test::mug(0.4, 1.0, 0.3, 0.8, 24), folder / "mug.obj");
        const fs::path file = folder / "drop.json";
        io::writeSceneFile(mugScene(), file);
        QCOMPARE(QString::fromStdString(io::convexPartsCachePath(file).filename().string()),
                 QString("drop.convex-parts.json"));

        // No sidecar yet: no parts; made, then kept.
        SceneDesc first = io::readSceneFile(file);
        QVERIFY(!first.bodies[1].shape.convexParts);
        QCOMPARE(io::makeConvexParts(first, "drop.json"), 1);
        QVERIFY(first.bodies[1].shape.convexParts);
        QVERIFY(first.bodies[1].shape.convexParts->parts.size() <= 12);
        io::writeConvexPartsCache(first, io::convexPartsCachePath(file));
        QVERIFY(fs::exists(io::convexPartsCachePath(file)));

        // Read again: the parts come from the sidecar, the same hulls to the bit, and the run
        // is the run of the parts just made.
        SceneDesc second = io::readSceneFile(file);
        QVERIFY(second.bodies[1].shape.convexParts);
        QCOMPARE(io::makeConvexParts(second, "drop.json"), 0);
        const auto& a = first.bodies[1].shape.convexParts->parts;
        const auto& b = second.bodies[1].shape.convexParts->parts;
        QCOMPARE(a.size(), b.size());
        for (size_t k = 0; k < a.size(); ++k) {
            QCOMPARE(a[k].vertices.size(), b[k].vertices.size());
            QVERIFY(std::memcmp(a[k].vertices.data(), b[k].vertices.data(),
                                a[k].vertices.size() * sizeof(Vec3)) == 0);
            QCOMPARE(a[k].faceVertices, b[k].faceVertices);
        }
        QVERIFY(sameBits(runOf(first), runOf(second)));
        // And the run that makes its parts in compile() (a scene built in code) too.
        SceneDesc none = second;
        none.bodies[1].shape.convexParts.reset();
        QVERIFY(sameBits(runOf(none), runOf(second)));

        // Other options: not the kept parts.
        SceneDesc other = io::readSceneFile(file);
        other.bodies[1].shape.maxParts = 8;
        QVERIFY(!mesh::convexPartsFit(*other.bodies[1].shape.convexParts, other.bodies[1].shape));
        QCOMPARE(io::makeConvexParts(other, "drop.json"), 1);

        // An edited mesh file: the sidecar's entry does not fit it.
        writeObj(test::mug(0.4, 1.2, 0.3, 0.8, 24), folder / "mug.obj");
        SceneDesc edited = io::readSceneFile(file);
        QVERIFY(!edited.bodies[1].shape.convexParts);
    }

    // A broken sidecar is passed over, saying why; its parts are made again.
    void brokenSidecarIsPassedOver() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        writeObj(test::mug(0.4, 1.0, 0.3, 0.8, 16), folder / "mug.obj");
        const fs::path file = folder / "drop.json";
        io::writeSceneFile(mugScene(), file);
        for (
            const char* text :
            {"{ not json",
             R"({"format": "tumble-convex-parts", "version": 1, "entries": [)"
             R"({"mesh_hash": "00", "max_parts": 12, "tolerance": 0, "resolution": 48,)"
             R"( "parts": [{"vertices": [[0,0,0]], "faces": [{"normal": [0,0,1], "offset": 0, "vertices": [0, 5, 9]}]}]}]})"}) {
            std::ofstream(io::convexPartsCachePath(file)) << text;
            SceneDesc s = io::parseScene(io::sceneToJson(mugScene()), "drop.json", folder);
            std::string problem;
            QCOMPARE(io::readConvexPartsCache(s, io::convexPartsCachePath(file), &problem), 0);
            QVERIFY2(problem.find("the convex parts are made again") != std::string::npos, problem.c_str());
            QVERIFY(!s.bodies[1].shape.convexParts);
            QCOMPARE(io::makeConvexParts(s, "drop.json"), 1);
        }
    }

    // A mesh that filling its holes does not close (a fin on an edge two triangles already
    // share) cannot be split: refused naming the field. (An open mug is filled and split:
    // tst_io_mesh_import, tst_engine_mesh_holes.)
    void aMeshThatCannotBeClosedIsRefused() {
        QTemporaryDir dir;
        const fs::path folder = dir.path().toStdString();
        TriangleMesh open = test::mug(0.4, 1.0, 0.3, 0.8, 16);
        open.vertices.push_back(Vec3(2, 2, 2));
        open.triangles.push_back({open.triangles[0][0], open.triangles[0][1], int(open.vertices.size()) - 1});
        writeObj(open, folder / "mug.obj");
        const fs::path file = folder / "drop.json";
        io::writeSceneFile(mugScene(), file);
        SceneDesc s = io::readSceneFile(file);
        try {
            io::makeConvexParts(s, "drop.json");
            QFAIL("made parts of a mesh that bounds no solid");
        } catch (const io::InputError& e) {
            QCOMPARE(QString::fromStdString(e.field()), QString("bodies[1].shape.collision"));
            QVERIFY2(std::string(e.what()).find("did not close it") != std::string::npos, e.what());
        }
    }
};

QTEST_APPLESS_MAIN(TestConvexPartsCache)
#include "tst_convex_parts_cache.moc"
