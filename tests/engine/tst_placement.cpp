// travelToTouch (tumble/placement.h), what the editor's building tools set bodies down with:
// closed-form distances for a box on a floor, a turned box, a sphere on a box, a compound's
// lowest part, a way clear or too short, a body already touching, and the bodies it must not
// stop on (another collision layer, its joint's partner). Every case also in worlds turned
// and shifted as a whole, the direction turned with them: the same distance.
#include <tumble/contact_query.h>
#include <tumble/model.h>
#include <tumble/placement.h>

#include "scene_builders.h"
#include "turned_world.h"

#include <QtTest>

#include <cmath>
#include <numbers>
#include <optional>

using namespace tumble;
using namespace tumble::test;

namespace {

BodyDesc floorPlane() { return groundPlane(0.5, 0.5); }

BodyDesc box(const std::string& name, const Vec3& half, const Vec3& at, const Quat& q = Quat::Identity()) {
    BodyDesc b = boxBody(name, half, 1.0);
    b.position = at;
    b.orientation = q;
    return b;
}

BodyDesc sphere(const std::string& name, double r, const Vec3& at) {
    BodyDesc b = sphereBody(name, r, 1.0);
    b.position = at;
    return b;
}

// The travel of `body` along `down` in `scene`, and in worlds turned and shifted (seeds 1-3)
// with the direction turned: each must be `expected` within the model's touch tolerance (or
// all nothing when `expected` is).
void expectTravel(const SceneDesc& scene, int body, const Vec3& down, double most, std::optional<double> expected) {
    for (std::uint64_t seed : {0, 1, 2, 3}) {
        const WorldPose pose = seed ? randomWorldPose(seed) : WorldPose{};
        const SceneDesc s = seed ? turnedScene(scene, pose) : scene;
        const Model model = compile(s);
        const State state = initialState(model, s);
        const std::optional<double> got = travelToTouch(model, state, body, pose.direction(down), most);
        const QString where = QStringLiteral("seed %1").arg(seed);
        QVERIFY2(got.has_value() == expected.has_value(), qPrintable(where));
        if (!expected) continue;
        // Conservative advancement stops within the tolerance of touching, never past it.
        const double tolerance = touchTolerance(model);
        QVERIFY2(*got <= *expected + 1e-12 && *got >= *expected - 1.01 * tolerance - 1e-12,
                 qPrintable(where + QStringLiteral(": %1 against %2").arg(*got, 0, 'g', 17).arg(*expected, 0, 'g', 17)));
    }
}

}  // namespace

class TestPlacement : public QObject {
    Q_OBJECT
private slots:
    void boxOntoFloor() {
        SceneDesc s;
        s.bodies = {floorPlane(), box("b", Vec3(0.5, 0.25, 0.75), Vec3(1, 3, -2))};
        expectTravel(s, 1, -Vec3::UnitY(), 100.0, 3.0 - 0.25);
    }

    void turnedBoxOntoFloor() {
        // A cube turned 45° about z stands on an edge: its lowest point is 0.5 √2 below its centre.
        SceneDesc s;
        const Quat q(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()));
        s.bodies = {floorPlane(), box("b", Vec3(0.5, 0.5, 0.5), Vec3(0, 2, 0), q)};
        expectTravel(s, 1, -Vec3::UnitY(), 100.0, 2.0 - 0.5 * std::sqrt(2.0));
    }

    void sphereOntoBox() {
        SceneDesc s;
        s.bodies = {floorPlane(), box("table", Vec3(1, 0.5, 1), Vec3(0, 0.5, 0)), sphere("ball", 0.3, Vec3(0.4, 4, -0.2))};
        expectTravel(s, 2, -Vec3::UnitY(), 100.0, 4.0 - 1.0 - 0.3);
        // Sideways it meets nothing; down but not far enough, nothing either.
        expectTravel(s, 2, Vec3::UnitX(), 100.0, std::nullopt);
        expectTravel(s, 2, -Vec3::UnitY(), 2.0, std::nullopt);
    }

    void compoundByItsLowestPart() {
        // A slab on a post: the post's foot, 0.9 below the frame, meets the floor first.
        BodyDesc table;
        table.name = "table";
        table.shape.type = ShapeType::Compound;
        table.shape.parts.resize(2);
        table.shape.parts[0].shape.type = ShapeType::Box;
        table.shape.parts[0].shape.halfExtents = Vec3(0.5, 0.05, 0.5);
        table.shape.parts[0].position = Vec3(0, 0.45, 0);
        table.shape.parts[1].shape.type = ShapeType::Box;
        table.shape.parts[1].shape.halfExtents = Vec3(0.05, 0.45, 0.05);
        table.shape.parts[1].position = Vec3(0, -0.45, 0);
        table.position = Vec3(0, 5, 0);
        table.mass = 2.0;
        SceneDesc s;
        s.bodies = {floorPlane(), table};
        expectTravel(s, 1, -Vec3::UnitY(), 100.0, 5.0 - 0.9);
    }

    void touchingAlreadyGoesNowhere() {
        SceneDesc s;
        s.bodies = {floorPlane(), box("a", Vec3(0.5, 0.5, 0.5), Vec3(0, 0.5, 0)),
                    box("b", Vec3(0.5, 0.5, 0.5), Vec3(0.2, 0.8, 0))};  // b overlaps a
        expectTravel(s, 1, -Vec3::UnitY(), 10.0, 0.0);
        expectTravel(s, 2, -Vec3::UnitY(), 10.0, 0.0);
    }

    void otherLayersAndJointPartnersAreNotInTheWay() {
        SceneDesc s;
        s.settings.collisionGroups = {"ghosts"};
        s.settings.groupsApart = {{"ghosts", "default"}};
        BodyDesc ghost = box("ghost", Vec3(2, 0.1, 2), Vec3(0, 1, 0));
        ghost.motion = Motion::Static;
        ghost.mass.reset();
        ghost.collisionGroup = "ghosts";
        s.bodies = {floorPlane(), ghost, box("b", Vec3(0.5, 0.5, 0.5), Vec3(0, 3, 0))};
        expectTravel(s, 2, -Vec3::UnitY(), 100.0, 2.5);  // through the ghost's layer to the floor
        // A shelf joined to the box by a ball joint does not stop it either (the step keeps
        // joined bodies from colliding); the same shelf without the joint does.
        SceneDesc j = s;
        j.bodies[1].collisionGroup = "default";
        j.bodies[1].name = "shelf";
        expectTravel(j, 2, -Vec3::UnitY(), 100.0, 3.0 - 0.5 - 1.1);
        JointDesc ball;
        ball.name = "pin";
        ball.bodyA = "b";
        ball.bodyB = "shelf";
        j.joints.push_back(ball);
        expectTravel(j, 2, -Vec3::UnitY(), 100.0, 2.5);
    }

    void badArgumentsGiveNothing() {
        SceneDesc s;
        s.bodies = {floorPlane(), box("b", Vec3(0.5, 0.5, 0.5), Vec3(0, 3, 0))};
        const Model model = compile(s);
        const State state = initialState(model, s);
        QVERIFY(!travelToTouch(model, state, 5, -Vec3::UnitY(), 10.0));
        QVERIFY(!travelToTouch(model, state, -1, -Vec3::UnitY(), 10.0));
        QVERIFY(!travelToTouch(model, state, 1, Vec3::Zero(), 10.0));
        QVERIFY(!travelToTouch(model, state, 1, -Vec3::UnitY(), -1.0));
        QVERIFY(!travelToTouch(model, state, 1, -Vec3::UnitY(), std::numeric_limits<double>::infinity()));
    }
};

QTEST_APPLESS_MAIN(TestPlacement)
#include "tst_placement.moc"
