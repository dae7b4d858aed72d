// glTF 2.0 export (tumble/io/gltf_export.h) and the render meshes behind it (tessellate.h):
// the .gltf with its .bin and the .glb pass the Khronos validator with no error; read back
// through assimp they have one node per body with its name and mesh, static bodies where
// they stand, and per moving body translation and rotation keys equal to the simulated
// frames (to float precision) at the frame times. The tessellated shapes enclose the
// shape's volume with outward normals.
#include "gltf_validator.h"

#include <tumble/io/gltf_export.h>
#include <tumble/io/mesh_import.h>
#include <tumble/io/tessellate.h>
#include <tumble/io/trajectory_writer.h>
#include <tumble/mass.h>
#include <tumble/world.h>

#include <assimp/cimport.h>
#include <assimp/scene.h>

#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <map>
#include <numbers>
#include <set>

using namespace tumble;
namespace fs = std::filesystem;

namespace {

const fs::path kMeshes = fs::path(TUMBLE_SCENES_DIR) / ".." / "meshes";

// Every shape and motion: a static ground plane and box, dynamic round shapes with spin and
// an offset centre of mass, a kinematic cylinder, and one mesh shared by a dynamic and a
// static body.
SceneDesc scene() {
    SceneDesc s;
    s.settings.dt = 0.01;
    s.settings.duration = 0.5;
    s.settings.frameRate = 20;
    s.bodies.reserve(16);  // add() hands out references that must stay valid

    auto add = [&](const char* name, Motion motion, ShapeType type, const Vec3& position) -> BodyDesc& {
        BodyDesc b;
        b.name = name;
        b.motion = motion;
        b.shape.type = type;
        b.position = position;
        if (motion == Motion::Dynamic) b.mass = 1.0;
        s.bodies.push_back(b);
        return s.bodies.back();
    };
    BodyDesc& ground = add("ground", Motion::Static, ShapeType::Plane, Vec3::Zero());
    ground.shape.normal = Vec3(0, 1, 0);
    ground.shape.distance = -2;
    BodyDesc& ball = add("ball", Motion::Dynamic, ShapeType::Sphere, Vec3(0, 3, 0));
    ball.shape.radius = 0.3;
    ball.velocity = Vec3(1, 2, 0);
    ball.angularVelocity = Vec3(0, 0, 4);
    BodyDesc& twin = add("twin", Motion::Dynamic, ShapeType::Sphere, Vec3(1, 4, 0));  // the ball's shape
    twin.shape.radius = 0.3;
    BodyDesc& box = add("box", Motion::Dynamic, ShapeType::Box, Vec3(2, 3, 0));
    box.shape.halfExtents = Vec3(0.5, 0.25, 0.1);
    box.centerOfMass = Vec3(0.2, 0, 0);
    box.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    box.angularVelocity = Vec3(0.3, 4, 0.1);
    BodyDesc& capsule = add("capsule", Motion::Dynamic, ShapeType::Capsule, Vec3(-2, 3, 0));
    capsule.shape.radius = 0.2;
    capsule.shape.halfHeight = 0.4;
    capsule.angularVelocity = Vec3(2, 0, 1);
    BodyDesc& wheel = add("wheel", Motion::Kinematic, ShapeType::Cylinder, Vec3(0, 0, 3));
    wheel.shape.radius = 0.5;
    wheel.shape.halfHeight = 0.1;
    wheel.velocity = Vec3(0.5, 0, 0);
    wheel.angularVelocity = Vec3(0, 2, 0);
    BodyDesc& post = add("post", Motion::Static, ShapeType::Box, Vec3(4, 0.5, -2));
    post.orientation = Quat(Eigen::AngleAxisd(1.0, Vec3(1, 1, 0).normalized()));

    auto tetra =
        std::make_shared<TriangleMesh>(io::importMesh(kMeshes / "tetrahedron.off", Vec3(0.4, 0.4, 0.4)));
    BodyDesc& rock = add("rock", Motion::Dynamic, ShapeType::Mesh, Vec3(0, 5, 0));
    rock.shape.file = "tetrahedron.off";
    rock.shape.meshData = tetra;
    rock.angularVelocity = Vec3(0.5, 1, 0);
    BodyDesc& stone = add("stone", Motion::Static, ShapeType::Mesh, Vec3(-3, 0, 0));
    stone.shape = rock.shape;
    return s;
}

std::vector<State> run(const SceneDesc& s, io::TrajectoryWriter& writer) {
    World world(s);
    std::vector<State> frames;
    writer.begin(world.model(), s, frameCount(world.model().settings), world.model().settings.frameRate);
    simulate(world, [&](int k, const State& st) {
        frames.push_back(st);
        writer.frame(k, st);
    });
    writer.finish();
    return frames;
}

// Float precision: the file holds 32-bit floats.
bool close(double a, double b) {
    return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b));
}

bool close(const aiVector3D& a, const Vec3& b) {
    return close(a.x, b.x()) && close(a.y, b.y()) && close(a.z, b.z());
}

// q and -q are the same rotation.
bool close(const aiQuaternion& a, const Quat& b) {
    const double s = (a.w * b.w() + a.x * b.x() + a.y * b.y() + a.z * b.z()) < 0 ? -1.0 : 1.0;
    return close(s * a.w, b.w()) && close(s * a.x, b.x()) && close(s * a.y, b.y()) && close(s * a.z, b.z());
}

QByteArray text(const Vec3& v) {
    return QByteArray::number(v.x(), 'g', 9) + ", " + QByteArray::number(v.y(), 'g', 9) + ", " +
           QByteArray::number(v.z(), 'g', 9);
}

struct Box3 {
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
};

Box3 bounds(const aiMesh& m) {
    Box3 b;
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
        const Vec3 v(m.mVertices[i].x, m.mVertices[i].y, m.mVertices[i].z);
        b.lo = b.lo.cwiseMin(v);
        b.hi = b.hi.cwiseMax(v);
    }
    return b;
}

// Volume enclosed by a triangle surface (the divergence theorem over its triangles).
double volume(const io::RenderMesh& m) {
    double v = 0;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const Vec3 &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]],
                   &c = m.positions[m.indices[t + 2]];
        v += a.dot(b.cross(c)) / 6.0;
    }
    return v;
}

}  // namespace

class TestGltfExport : public QObject {
    Q_OBJECT

private slots:
    void exportReadsBack_data() {
        QTest::addColumn<bool>("binary");
        QTest::newRow("gltf") << false;
        QTest::newRow("glb") << true;
    }

    void exportReadsBack() {
        QFETCH(bool, binary);
        QTemporaryDir dir;
        const QString name = binary ? "run.glb" : "run.gltf";
        const fs::path file = fs::path(dir.path().toStdString()) / name.toStdString();
        const SceneDesc s = scene();
        const Model model = compile(s);
        auto writer = io::makeTrajectoryWriter(file);
        QVERIFY(dynamic_cast<io::GltfTrajectoryWriter*>(writer.get()));
        const std::vector<State> frames = run(s, *writer);
        QCOMPARE(frames.size(), size_t(11));

        const QStringList files = QDir(dir.path()).entryList(QDir::Files | QDir::Hidden, QDir::Name);
        QCOMPARE(files, binary ? QStringList({"run.glb"}) : QStringList({"run.bin", "run.gltf"}));
        if (!binary) {
            QFile f(dir.filePath("run.gltf"));
            QVERIFY(f.open(QIODevice::ReadOnly));
            const QJsonObject doc = QJsonDocument::fromJson(f.readAll()).object();
            QCOMPARE(doc.value("buffers").toArray().at(0).toObject().value("uri").toString(),
                     QString("run.bin"));
            QCOMPARE(doc.value("asset").toObject().value("version").toString(), QString("2.0"));
        }
        TUMBLE_VERIFY_GLTF_VALID(dir.filePath(name));
        // Not even a warning or a note (an unknown extension, a degenerate triangle).
        const tumble::test::ValidatorReport report = tumble::test::validateGltf(dir.filePath(name));
        QVERIFY2(report.ran && report.messages.isEmpty(), qPrintable(report.messages));

        const aiScene* ai = aiImportFile(file.c_str(), 0);
        QVERIFY2(ai, aiGetErrorString());
        std::unique_ptr<const aiScene, void (*)(const aiScene*)> guard(ai, aiReleaseImport);

        // One node per body, with its name and its mesh.
        QCOMPARE(ai->mRootNode->mNumChildren, unsigned(s.bodies.size()));
        std::map<std::string, const aiNode*> nodes;
        for (unsigned i = 0; i < ai->mRootNode->mNumChildren; ++i) {
            const aiNode* n = ai->mRootNode->mChildren[i];
            nodes[n->mName.C_Str()] = n;
            QCOMPARE(n->mNumMeshes, 1u);
            const aiMesh* m = ai->mMeshes[n->mMeshes[0]];
            QVERIFY(m->mNumVertices > 0 && m->mNumFaces > 0 && m->HasNormals());
        }
        for (const BodyDesc& b : s.bodies) QVERIFY2(nodes.count(b.name), b.name.c_str());
        auto meshOf = [&](const char* body) -> const aiMesh& {
            return *ai->mMeshes[nodes.at(body)->mMeshes[0]];
        };

        // The meshes are the shapes, in the body frame.
        QVERIFY(close(bounds(meshOf("ball")).hi.norm(), Vec3::Constant(0.3).norm()));
        QVERIFY(close(bounds(meshOf("ball")).hi.y(), 0.3) && close(bounds(meshOf("ball")).lo.y(), -0.3));
        QVERIFY((bounds(meshOf("box")).hi - Vec3(0.5, 0.25, 0.1)).norm() < 1e-6);
        QVERIFY((bounds(meshOf("box")).lo + Vec3(0.5, 0.25, 0.1)).norm() < 1e-6);
        QVERIFY(close(bounds(meshOf("capsule")).hi.y(), 0.6) && close(bounds(meshOf("capsule")).hi.x(), 0.2));
        QVERIFY(close(bounds(meshOf("wheel")).hi.y(), 0.1) && close(bounds(meshOf("wheel")).hi.x(), 0.5));
        const Box3 plane = bounds(meshOf("ground"));
        QVERIFY(close(plane.lo.y(), -2) && close(plane.hi.y(), -2) && plane.hi.x() - plane.lo.x() >= 20);
        const aiMesh& rock = meshOf("rock");
        for (unsigned i = 0; i < rock.mNumVertices; ++i) {
            double nearest = 1e300;
            QCOMPARE(s.bodies[7].name, std::string("rock"));
            for (const Vec3& v : s.bodies[7].shape.meshData->vertices) {
                nearest = std::min(
                    nearest,
                    (Vec3(rock.mVertices[i].x, rock.mVertices[i].y, rock.mVertices[i].z) - v).norm());
            }
            QVERIFY(nearest < 1e-6);
        }
        QCOMPARE(nodes.at("rock")->mMeshes[0], nodes.at("stone")->mMeshes[0]);  // one mesh, shared
        QCOMPARE(nodes.at("ball")->mMeshes[0], nodes.at("twin")->mMeshes[0]);
        QVERIFY(nodes.at("box")->mMeshes[0] != nodes.at("post")->mMeshes[0]);  // other sizes
        QCOMPARE(ai->mNumMeshes, unsigned(s.bodies.size() - 2));

        // Every node starts where its body is at frame 0; static ones stay there.
        for (size_t i = 0; i < s.bodies.size(); ++i) {
            aiVector3D scaling, position;
            aiQuaternion rotation;
            nodes.at(s.bodies[i].name)->mTransformation.Decompose(scaling, rotation, position);
            const BodyState& b0 = frames[0].bodies[i];
            QVERIFY2(close(position, bodyFramePosition(model.bodies[i], b0)), s.bodies[i].name.c_str());
            QVERIFY2(close(rotation, b0.q), s.bodies[i].name.c_str());
            QVERIFY(close(scaling, Vec3(1, 1, 1)));
        }

        // One animation, a translation and a rotation channel per moving body.
        QCOMPARE(ai->mNumAnimations, 1u);
        const aiAnimation& anim = *ai->mAnimations[0];
        std::set<std::string> animated;
        for (unsigned c = 0; c < anim.mNumChannels; ++c)
            animated.insert(anim.mChannels[c]->mNodeName.C_Str());
        QCOMPARE(animated, (std::set<std::string>{"ball", "twin", "box", "capsule", "wheel", "rock"}));
        QCOMPARE(anim.mNumChannels, 6u);
        for (unsigned c = 0; c < anim.mNumChannels; ++c) {
            const aiNodeAnim& ch = *anim.mChannels[c];
            const std::string body = ch.mNodeName.C_Str();
            const int i = int(std::find_if(s.bodies.begin(), s.bodies.end(),
                                           [&](const BodyDesc& b) { return b.name == body; }) -
                              s.bodies.begin());
            QCOMPARE(ch.mNumPositionKeys, 11u);
            QCOMPARE(ch.mNumRotationKeys, 11u);
            for (unsigned k = 0; k < 11; ++k) {
                const QByteArray where = QByteArray(body.c_str()) + ", frame " + QByteArray::number(k);
                const BodyState& bs = frames[k].bodies[i];
                const Vec3 p = bodyFramePosition(model.bodies[i], bs);
                QVERIFY2(close(ch.mPositionKeys[k].mTime / anim.mTicksPerSecond, k / 20.0), where);
                QVERIFY2(close(ch.mRotationKeys[k].mTime / anim.mTicksPerSecond, k / 20.0), where);
                const aiVector3D& t = ch.mPositionKeys[k].mValue;
                QVERIFY2(close(t, p), where + ": " + text(Vec3(t.x, t.y, t.z)) + " against " + text(p));
                QVERIFY2(close(ch.mRotationKeys[k].mValue, bs.q), where);
                if (k > 0) {  // consecutive keys on the same side (q and -q are one rotation)
                    const aiQuaternion &a = ch.mRotationKeys[k - 1].mValue, &b = ch.mRotationKeys[k].mValue;
                    QVERIFY2(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z > 0, where);
                }
            }
            // The motion is there: every moving body has left its first pose by the end.
            const BodyModel& b = model.bodies[i];
            QVERIFY2((bodyFramePosition(b, frames[10].bodies[i]) - bodyFramePosition(b, frames[0].bodies[i]))
                                 .norm() > 1e-3 ||
                         frames[10].bodies[i].q.angularDistance(frames[0].bodies[i].q) > 1e-3,
                     body.c_str());
        }
    }

    // A frame range with a step and a body subset: only those nodes, keys at those times.
    void selection() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "part.glb";
        const SceneDesc s = scene();
        const Model model = compile(s);
        io::ExportOptions options;
        options.firstFrame = 2;
        options.lastFrame = 8;
        options.frameStep = 2;
        options.bodies = {1, 0};
        auto writer = io::makeTrajectoryWriter(file, options);
        const std::vector<State> frames = run(s, *writer);
        TUMBLE_VERIFY_GLTF_VALID(QString::fromStdString(file.string()));

        const aiScene* ai = aiImportFile(file.c_str(), 0);
        QVERIFY2(ai, aiGetErrorString());
        std::unique_ptr<const aiScene, void (*)(const aiScene*)> guard(ai, aiReleaseImport);
        QCOMPARE(ai->mRootNode->mNumChildren, 2u);
        QCOMPARE(QString(ai->mRootNode->mChildren[0]->mName.C_Str()), QString("ball"));
        QCOMPARE(QString(ai->mRootNode->mChildren[1]->mName.C_Str()), QString("ground"));
        QCOMPARE(ai->mNumAnimations, 1u);
        QCOMPARE(ai->mAnimations[0]->mNumChannels, 1u);
        const aiNodeAnim& ch = *ai->mAnimations[0]->mChannels[0];
        QCOMPARE(ch.mNumPositionKeys, 4u);
        for (unsigned n = 0; n < 4; ++n) {
            const int k = 2 + 2 * int(n);
            QVERIFY(close(ch.mPositionKeys[n].mTime / ai->mAnimations[0]->mTicksPerSecond, k / 20.0));
            QVERIFY(
                close(ch.mPositionKeys[n].mValue, bodyFramePosition(model.bodies[1], frames[k].bodies[1])));
            QVERIFY(close(ch.mRotationKeys[n].mValue, frames[k].bodies[1].q));
        }
        // The ball starts at its pose of frame 2, the first exported.
        aiVector3D scaling, position;
        aiQuaternion rotation;
        ai->mRootNode->mChildren[0]->mTransformation.Decompose(scaling, rotation, position);
        QVERIFY(close(position, bodyFramePosition(model.bodies[1], frames[2].bodies[1])));
    }

    // The validator's report is read, not assumed: a broken file has errors.
    void validatorFindsErrors() {
        QTemporaryDir dir;
        QFile f(dir.filePath("broken.gltf"));
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"nodes": [{"mesh": 3}], "scene": 0})");
        f.close();
        const tumble::test::ValidatorReport r = tumble::test::validateGltf(f.fileName());
        QVERIFY2(r.ran, qPrintable(r.problem));
        QVERIFY2(r.errors >= 1, qPrintable(r.messages));
        QVERIFY2(r.messages.contains("'asset' must be defined"), qPrintable(r.messages));
    }

    // The root node is named after the file, never as a body: the ball's channels must move
    // the ball, not the whole scene.
    void rootNamedAsABody() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "ball.glb";
        const SceneDesc s = scene();
        auto writer = io::makeTrajectoryWriter(file);
        run(s, *writer);
        const aiScene* ai = aiImportFile(file.c_str(), 0);
        QVERIFY2(ai, aiGetErrorString());
        std::unique_ptr<const aiScene, void (*)(const aiScene*)> guard(ai, aiReleaseImport);
        QCOMPARE(QString(ai->mRootNode->mName.C_Str()), QString("ball scene"));
        QCOMPARE(ai->mRootNode->mNumChildren, unsigned(s.bodies.size()));
        const aiNode* ball = ai->mRootNode->FindNode("ball");
        QVERIFY(ball && ball != ai->mRootNode && ball->mNumMeshes == 1);
        TUMBLE_VERIFY_GLTF_VALID(QString::fromStdString(file.string()));
    }

    // A compound is a node that moves, with a child node per part placed in its frame and
    // the part's mesh: the world pose of each part's mesh is the body's pose times the part's.
    void compoundPartsAreChildNodes() {
        QTemporaryDir dir;
        const fs::path file = fs::path(dir.path().toStdString()) / "cart.glb";
        SceneDesc s;
        s.settings.dt = 0.01;
        s.settings.duration = 0.3;
        s.settings.frameRate = 10;
        BodyDesc cart;
        cart.name = "cart";
        cart.shape.type = ShapeType::Compound;
        cart.mass = 3.0;
        cart.position = Vec3(1, 2, 3);
        cart.angularVelocity = Vec3(0.5, 1, 0);
        PartDesc deck;
        deck.name = "deck";
        deck.shape.type = ShapeType::Box;
        deck.shape.halfExtents = Vec3(0.5, 0.05, 0.3);
        deck.position = Vec3(0, 0.2, 0);
        deck.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
        PartDesc wheel;
        wheel.shape.type = ShapeType::Cylinder;
        wheel.shape.radius = 0.1;
        wheel.shape.halfHeight = 0.02;
        wheel.position = Vec3(0.4, 0, 0.3);
        wheel.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()));
        cart.shape.parts = {deck, wheel, wheel};
        cart.shape.parts[2].position.z() = -0.3;
        s.bodies.push_back(cart);
        auto writer = io::makeTrajectoryWriter(file);
        const std::vector<State> frames = run(s, *writer);
        TUMBLE_VERIFY_GLTF_VALID(QString::fromStdString(file.string()));
        const aiScene* ai = aiImportFile(file.c_str(), 0);
        QVERIFY2(ai, aiGetErrorString());
        std::unique_ptr<const aiScene, void (*)(const aiScene*)> guard(ai, aiReleaseImport);
        const aiNode* node = ai->mRootNode->FindNode("cart");
        QVERIFY(node && node->mNumMeshes == 0);
        QCOMPARE(node->mNumChildren, 3u);
        QCOMPARE(QString(node->mChildren[0]->mName.C_Str()), QString("cart deck"));
        QCOMPARE(QString(node->mChildren[1]->mName.C_Str()), QString("cart part 1"));
        QCOMPARE(ai->mNumMeshes, 2u);  // the two wheels share one
        for (unsigned j = 0; j < 3; ++j) {
            const aiNode* child = node->mChildren[j];
            QCOMPARE(child->mNumMeshes, 1u);
            aiVector3D scaling, position;
            aiQuaternion rotation;
            child->mTransformation.Decompose(scaling, rotation, position);
            QVERIFY(close(position, cart.shape.parts[j].position));
            QVERIFY(close(rotation, cart.shape.parts[j].orientation));
        }
        // The deck's mesh is its box, in its own frame.
        const Box3 deckBox = bounds(*ai->mMeshes[node->mChildren[0]->mMeshes[0]]);
        QVERIFY(close(deckBox.hi.x(), 0.5) && close(deckBox.hi.y(), 0.05) && close(deckBox.hi.z(), 0.3));
        QCOMPARE(ai->mAnimations[0]->mNumChannels, 1u);
        QCOMPARE(QString(ai->mAnimations[0]->mChannels[0]->mNodeName.C_Str()), QString("cart"));
    }

    // An unwritable .bin or .gltf fails at begin(), before any run, and leaves nothing.
    void unwritable() {
        QTemporaryDir dir;
        const SceneDesc s = scene();
        const Model model = compile(s);
        auto writer = io::makeTrajectoryWriter(fs::path(dir.path().toStdString()) / "no" / "t.gltf");
        QVERIFY_THROWS_EXCEPTION(std::runtime_error, writer->begin(model, s, 11, 20));
        QCOMPARE(QDir(dir.path()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot),
                 QStringList());
    }

    void tessellatedVolumes_data() {
        QTest::addColumn<int>("type");
        QTest::addColumn<double>("exact");
        const double pi = std::numbers::pi;
        QTest::newRow("sphere") << int(ShapeType::Sphere) << 4.0 / 3.0 * pi * 0.3 * 0.3 * 0.3;
        QTest::newRow("box") << int(ShapeType::Box) << 8 * 0.5 * 0.25 * 0.1;
        QTest::newRow("capsule") << int(ShapeType::Capsule) << pi * 0.3 * 0.3 * 0.8 + 4.0 / 3.0 * pi * 0.027;
        QTest::newRow("cylinder") << int(ShapeType::Cylinder) << pi * 0.3 * 0.3 * 0.8;
    }

    // Closed surfaces around the shape's volume, counter-clockwise from outside (a positive
    // volume), unit normals on the outer side of every triangle, converging as segments grow.
    void tessellatedVolumes() {
        QFETCH(int, type);
        QFETCH(double, exact);
        ShapeDesc shape;
        shape.type = ShapeType(type);
        shape.radius = 0.3;
        shape.halfHeight = 0.4;
        shape.halfExtents = Vec3(0.5, 0.25, 0.1);
        double previous = 1e300;
        for (int segments : {8, 32, 128}) {
            const io::RenderMesh m = io::tessellate(shape, segments);
            QCOMPARE(m.normals.size(), m.positions.size());
            QCOMPARE(m.indices.size() % 3, size_t(0));
            for (std::uint32_t i : m.indices) QVERIFY(i < m.positions.size());
            for (size_t t = 0; t < m.indices.size(); t += 3) {
                const Vec3 &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]],
                           &c = m.positions[m.indices[t + 2]];
                const Vec3 face = (b - a).cross(c - a);
                QVERIFY2(face.norm() > 0, "degenerate triangle");
                for (int j = 0; j < 3; ++j) {
                    const Vec3& n = m.normals[m.indices[t + j]];
                    QVERIFY(std::abs(n.norm() - 1) < 1e-12);
                    QVERIFY2(n.dot(face) > 0, "a normal points inwards");
                }
            }
            const double error = std::abs(volume(m) - exact) / exact;
            if (shape.type == ShapeType::Box)
                QVERIFY(error < 1e-12);
            else
                QVERIFY2(error < previous, QByteArray::number(error));
            previous = error;
        }
        QVERIFY2(previous < 2e-3, QByteArray::number(previous));
    }

    void tessellatedPlane() {
        ShapeDesc shape;
        shape.type = ShapeType::Plane;
        shape.normal = Vec3(1, 2, 2) / 3.0;
        shape.distance = 1.5;
        const io::RenderMesh m = io::tessellate(shape, 32, 7);
        QCOMPARE(m.indices.size(), size_t(6));
        for (size_t i = 0; i < m.positions.size(); ++i) {
            QVERIFY(std::abs(m.positions[i].dot(shape.normal) - 1.5) < 1e-12);
            QVERIFY((m.normals[i] - shape.normal).norm() < 1e-12);
            QVERIFY(std::abs((m.positions[i] - 1.5 * shape.normal).cwiseAbs().maxCoeff()) <=
                    7 * std::sqrt(2.0));
        }
        const Vec3 face = (m.positions[m.indices[1]] - m.positions[m.indices[0]])
                              .cross(m.positions[m.indices[2]] - m.positions[m.indices[0]]);
        QVERIFY(face.dot(shape.normal) > 0);                              // facing the free side
        QVERIFY(std::abs(face.norm() / 2 + 0 - 0.5 * (14 * 14)) < 1e-9);  // half of a 14 m square
    }

    void tessellatedMesh() {
        ShapeDesc shape;
        shape.type = ShapeType::Mesh;
        auto mesh = std::make_shared<TriangleMesh>();
        mesh->vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
        mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        shape.meshData = mesh;
        const io::RenderMesh m = io::tessellate(shape);
        QCOMPARE(m.positions.size(), size_t(12));  // flat: three vertices a triangle
        QVERIFY(std::abs(volume(m) - 1.0 / 6.0) < 1e-15);
        QVERIFY((m.normals[0] - Vec3(0, 0, -1)).norm() < 1e-15);
        QVERIFY((m.normals[9] - Vec3(1, 1, 1).normalized()).norm() < 1e-15);
        shape.meshData.reset();
        QVERIFY(io::tessellate(shape).indices.empty());
    }
};

QTEST_GUILESS_MAIN(TestGltfExport)  // QProcess (the validator) wants an application
#include "tst_gltf_export.moc"
