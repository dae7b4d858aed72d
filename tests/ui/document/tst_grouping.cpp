// Group and Ungroup (issue 49 item 4; ui/document/grouping.h): bodies made one compound body
// keep where they are in the world and what they weigh, one undo step each way; what cannot
// be grouped says why.
#include "document/document.h"
#include "document/grouping.h"

#include <tumble/world.h>

#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

BodyDesc box(const std::string& name, const Vec3& half, const Vec3& at, const Quat& q, double mass) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = half;
    b.position = at;
    b.orientation = q;
    b.mass = mass;
    return b;
}

SceneDesc threeBodies() {
    SceneDesc s;
    BodyDesc floor;
    floor.name = "floor";
    floor.motion = Motion::Static;
    floor.shape.type = ShapeType::Plane;
    s.bodies.push_back(floor);
    s.bodies.push_back(box("seat", Vec3(0.3, 0.05, 0.3), Vec3(1, 0.5, 0), Quat::Identity(), 2.0));
    s.bodies.push_back(box("back", Vec3(0.3, 0.3, 0.05), Vec3(1, 0.85, -0.25),
                           Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX())), 1.0));
    BodyDesc ball;
    ball.name = "knob";
    ball.shape.radius = 0.05;
    ball.density = 500.0;
    ball.position = Vec3(1.2, 1.2, -0.25);
    ball.friction = 0.9;
    s.bodies.push_back(ball);
    JointDesc j;
    j.name = "tether";
    j.type = JointType::Ball;
    j.bodyA = "knob";
    j.anchorA = Vec3(0, 0.05, 0);
    j.anchorB = Vec3(1.2, 2.0, -0.25);
    s.joints.push_back(j);
    return s;
}

// The mass of every body of the scene, as compile() makes it.
double totalMass(const SceneDesc& s) {
    const Model m = compile(s);
    double total = 0.0;
    for (const BodyModel& b : m.bodies) total += b.mass;
    return total;
}

}  // namespace

class TestGrouping : public QObject {
    Q_OBJECT
private slots:
    // Grouped, the parts are where the bodies were (each part's world pose is its body's),
    // the mass is the bodies' sum, each part keeps its friction, and a joint to a grouped
    // body holds the same world point; ungrouped, the bodies are back as they were.
    void groupKeepsPlacesAndMasses() {
        const SceneDesc s = threeBodies();
        std::string why;
        const auto grouped = groupBodies(s, {1, 2, 3}, &why);
        QVERIFY2(grouped, why.c_str());
        QCOMPARE(grouped->scene.bodies.size(), size_t(2));
        const BodyDesc& g = grouped->scene.bodies[1];
        QCOMPARE(g.shape.type, ShapeType::Compound);
        QCOMPARE(g.shape.parts.size(), size_t(3));
        for (int k = 0; k < 3; ++k) {
            const BodyDesc& was = s.bodies[size_t(k + 1)];
            const PartDesc& p = g.shape.parts[size_t(k)];
            QVERIFY((g.orientation * p.position + g.position - was.position).norm() < 1e-15);
            QVERIFY(std::abs((g.orientation * p.orientation).angularDistance(was.orientation)) < 1e-12);
            QCOMPARE(*p.friction, was.friction);
        }
        QVERIFY(std::abs(totalMass(grouped->scene) - totalMass(s)) < 1e-12 * totalMass(s));
        // The tether holds the same world point on the knob, now a part.
        const JointDesc& j = grouped->scene.joints.front();
        QCOMPARE(j.bodyA, g.name);
        QVERIFY((g.orientation * j.anchorA + g.position - Vec3(1.2, 1.25, -0.25)).norm() < 1e-15);

        const auto back = ungroupBody(grouped->scene, 1, &why);
        QVERIFY(!back);  // the tether holds it
        SceneDesc untethered = grouped->scene;
        untethered.joints.clear();
        const auto parts = ungroupBody(untethered, 1, &why);
        QVERIFY2(parts, why.c_str());
        QCOMPARE(parts->scene.bodies.size(), size_t(4));
        for (int k = 1; k <= 3; ++k) {
            const BodyDesc &a = parts->scene.bodies[size_t(k)], &b = s.bodies[size_t(k)];
            QCOMPARE(a.name, b.name);
            QVERIFY((a.position - b.position).norm() < 1e-15);
            QVERIFY(a.orientation.angularDistance(b.orientation) < 1e-12);
        }
        QVERIFY(std::abs(totalMass(parts->scene) - totalMass(s)) < 1e-12 * totalMass(s));
    }

    void whatCannotBeGroupedSaysWhy() {
        SceneDesc s = threeBodies();
        std::string why;
        QVERIFY(!groupBodies(s, {1}, &why));
        QVERIFY(why.find("two bodies") != std::string::npos);
        QVERIFY(!groupBodies(s, {0, 1}, &why));
        QVERIFY2(why.find("plane") != std::string::npos, why.c_str());
        s.bodies[2].forces.push_back(ForceDesc{});
        QVERIFY(!groupBodies(s, {1, 2}, &why));
        QVERIFY2(why.find("forces") != std::string::npos, why.c_str());
        QVERIFY(!ungroupBody(s, 1, &why));
        QVERIFY2(why.find("not a compound") != std::string::npos, why.c_str());
    }

    // In the document: one undo step each way, the group selected, then the parts.
    void oneUndoStepEachWay() {
        Document doc;
        doc.replaceScene(threeBodies(), "load", false);
        QString why;
        QVERIFY2(doc.group({1, 2}, &why), qPrintable(why));
        QCOMPARE(doc.bodyCount(), 3);
        QCOMPARE(doc.selection(), QList<int>({1}));
        QCOMPARE(doc.body(1).shape.type, ShapeType::Compound);
        QCOMPARE(doc.undoStack()->undoText(), QString("Group 2 bodies"));
        QVERIFY2(doc.ungroup(1, &why), qPrintable(why));
        QCOMPARE(doc.bodyCount(), 4);
        QCOMPARE(doc.selection(), QList<int>({1, 2}));
        doc.undoStack()->undo();
        QCOMPARE(doc.bodyCount(), 3);
        doc.undoStack()->undo();
        QVERIFY(doc.scene() == threeBodies());
        QVERIFY(!doc.group({3}, &why));
        QVERIFY(!why.isEmpty());
    }
};

QTEST_MAIN(TestGrouping)
#include "tst_grouping.moc"
