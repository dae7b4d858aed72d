// Shift while dragging a move handle (issue 52 item 2): the dragged body is set down on what
// is under it. settledAt and the Settler a drag keeps (the scene compiled once) give the same
// closed-form rests: a unit box over a table rests on its top, beside it on the floor, started
// inside it is lifted onto it; turned about the vertical it rests as high; kept apart from the
// table it falls through to the floor. Every case also in worlds turned and shifted as a whole
// (gravity too): the turned answer.
#include "document/placement.h"

#include "../../engine/scene_builders.h"
#include "../../engine/turned_world.h"

#include <QtTest>

#include <cmath>
#include <numbers>

using namespace tumble;
using namespace tumble::test;
using namespace tumble::ui;

namespace {

// The floor (0), a static table 2 x 1 x 2 m with its top at y = 1 (1) and a unit box (2).
SceneDesc tableScene() {
    SceneDesc s;
    BodyDesc table = boxBody("table", Vec3(1, 0.5, 1), 1.0);
    table.motion = Motion::Static;
    table.mass.reset();
    table.density.reset();
    table.position = Vec3(0, 0.5, 0);
    BodyDesc cube = boxBody("cube", Vec3(0.5, 0.5, 0.5), 1.0);
    cube.position = Vec3(4, 3, 0);
    s.bodies = {groundPlane(0.5, 0.5), table, cube};
    return s;
}

// Where the cube settles when dragged to `to` (and turned to `q`), by a Settler made at the
// drag's start and by settledAt, in the world and in three turned and shifted ones: each
// must be `expected` (turned with its world) within the touch tolerance's reach (1e-4 m).
void expectRest(const SceneDesc& scene, const Vec3& to, const Quat& q, const Vec3& expected) {
    for (std::uint64_t seed : {0, 1, 2, 3}) {
        const WorldPose pose = seed ? randomWorldPose(seed) : WorldPose{};
        const SceneDesc s = seed ? turnedScene(scene, pose) : scene;
        BodyDesc moved = s.bodies[2];
        moved.position = pose.point(to);
        moved.orientation = pose.orientation(q);
        const Settler settler(s, 2);
        const Vec3 want = pose.point(expected);
        for (const Vec3& got : {settler.settle(moved).position, settledAt(s, 2, moved).position}) {
            QVERIFY2((got - want).norm() < 1e-4, qPrintable(QString("seed %1: (%2, %3, %4) against (%5, %6, %7)")
                                                                .arg(seed)
                                                                .arg(got.x())
                                                                .arg(got.y())
                                                                .arg(got.z())
                                                                .arg(want.x())
                                                                .arg(want.y())
                                                                .arg(want.z())));
        }
    }
}

}  // namespace

class TestSettle : public QObject {
    Q_OBJECT
private slots:
    void onTheTableBesideItAndLiftedOutOfIt() {
        const SceneDesc s = tableScene();
        expectRest(s, Vec3(0.2, 5, -0.3), Quat::Identity(), Vec3(0.2, 1.5, -0.3));  // on the top
        expectRest(s, Vec3(3, 5, 0), Quat::Identity(), Vec3(3, 0.5, 0));            // the floor
        expectRest(s, Vec3(0, 0.3, 0), Quat::Identity(), Vec3(0, 1.5, 0));          // inside: lifted
        expectRest(s, Vec3(3, -2, 0), Quat::Identity(), Vec3(3, 0.5, 0));           // under the floor
    }

    // A turn about the vertical keeps its height (the Settler compiles the turned body).
    void turnedAboutTheVertical() {
        const Quat q(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()));
        expectRest(tableScene(), Vec3(0, 4, 0), q, Vec3(0, 1.5, 0));
        // On its edge, turned 45° about z: its lowest edge 0.5 √2 below its centre.
        const Quat edge(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
        expectRest(tableScene(), Vec3(4, 4, 0), edge, Vec3(4, 0.5 * std::sqrt(2.0), 0));
    }

    // Kept apart from the table (the scene's no_collide), the cube passes it to the floor.
    void passesABodyItIsKeptApartFrom() {
        SceneDesc s = tableScene();
        s.noCollide.push_back({"table", "cube"});
        expectRest(s, Vec3(0, 5, 0), Quat::Identity(), Vec3(0, 0.5, 0));
    }

    // A settler answers many moves from one compile: the cube dragged across the table's
    // edge steps down from its top to the floor.
    void oneSettlerForAWholeDrag() {
        const SceneDesc s = tableScene();
        const Settler settler(s, 2);
        BodyDesc moved = s.bodies[2];
        for (double x = -0.4; x <= 3.0; x += 0.3) {  // (never on the edge, x = 1.5)
            moved.position = Vec3(x, 2.5, 0);
            const double y = settler.settle(moved).position.y();
            // On the top while any of its bottom is over it (|x| < 1.5), else on the floor.
            const double want = std::abs(x) < 1.5 ? 1.5 : 0.5;
            QVERIFY2(std::abs(y - want) < 1e-4, qPrintable(QString("x %1: y %2").arg(x).arg(y)));
        }
    }
};

QTEST_MAIN(TestSettle)
#include "tst_settle.moc"
