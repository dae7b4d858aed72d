// The viewport: one entity per body that follows edits and undo; a click at a body's
// projected position selects it, Ctrl+click toggles, the sky selects nothing; framing puts
// the selection in the middle; the picking ray casts against closed-form hits; spheres and
// cylinders are drawn coarser when there are many; no multisampling on a software renderer.
#include "document/document.h"
#include "viewport/viewport.h"
#include "viewport/viewport_instances.h"
#include "viewport/viewport_raycast.h"
#include "viewport_test_util.h"

#include <tumble/mass.h>

#include <Qt3DCore/QEntity>

#include <QMatrix4x4>
#include <QUndoStack>
#include <QScreen>
#include <QWindow>
#include <QtTest>

#include <cmath>
#include <memory>

using namespace tumble;
using namespace tumble::ui;
using tumble::test::body;
using tumble::test::projected;

namespace {

// The ground (0), a sphere (1) at (0, 1, 0) and a box (2) at (2, 0.5, 0), seen from +z.
struct Fixture {
    Document doc;
    std::unique_ptr<Viewport> view;
    Fixture() {
        doc.addBody(body("ball", ShapeType::Sphere, Vec3(0, 1, 0)));
        doc.addBody(body("crate", ShapeType::Box, Vec3(2, 0.5, 0)));
        view = std::make_unique<Viewport>(&doc);
        view->resize(640, 480);
        view->show();
        view->setCamera(QVector3D(1, 0.5f, 0), 8.0f, 0.0f, 20.0f);
    }
};

constexpr double kTol = 1e-12;

}  // namespace

class TestViewport : public QObject {
    Q_OBJECT
private slots:
    void oneEntityPerBodyFollowingEditsAndUndo() {
        Document doc;
        Viewport view(&doc);
        QCOMPARE(view.entityCount(), doc.bodyCount());  // the ground
        doc.addBody(body("a", ShapeType::Sphere, Vec3(0, 1, 0)));
        doc.addBody(body("b", ShapeType::Capsule, Vec3(1, 1, 0)));
        doc.addBody(body("c", ShapeType::Cylinder, Vec3(2, 1, 0)));
        QCOMPARE(view.entityCount(), 4);
        doc.removeBodies({1, 2});
        QCOMPARE(view.entityCount(), 2);
        doc.undoStack()->undo();
        QCOMPARE(view.entityCount(), 4);
        doc.duplicateBodies({1, 2, 3});
        QCOMPARE(view.entityCount(), 7);
        doc.undoStack()->undo();
        doc.undoStack()->undo();
        QCOMPARE(view.entityCount(), 3);
        QString error;
        QVERIFY2(doc.open(":/scenes/tower-20.json", &error), qPrintable(error));
        QVERIFY(doc.bodyCount() > 20);
        QCOMPARE(view.entityCount(), doc.bodyCount());
    }

    void aMeshBodyIsDrawnAndPickedByItsTriangles() {
        // A single triangle in the body's x-y plane, facing +z, the body at (0, 1, 0).
        auto mesh = std::make_shared<TriangleMesh>();
        mesh->vertices = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)};
        mesh->triangles = {{0, 1, 2}};
        Document doc;
        BodyDesc b = body("tri", ShapeType::Mesh, Vec3(0, 1, 0));
        b.shape.file = "tri.obj";
        b.shape.meshData = mesh;
        doc.addBody(b);
        Viewport view(&doc);
        view.resize(400, 300);
        view.setCamera(QVector3D(0, 1, 0), 5.0f, 0.0f, 0.0f);
        QCOMPARE(view.entityCount(), 2);
        QCOMPARE(view.bodyAt(projected(view, Vec3(0, 0.5, 0))), 1);     // inside the triangle
        QCOMPARE(view.bodyAt(projected(view, Vec3(0.9, 1.9, 0))), -1);  // beside it, above the horizon
    }

    void clickAtAProjectedBodySelectsIt() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        const QPoint ball = projected(*f.view, Vec3(0, 1, 0));
        const QPoint crate = projected(*f.view, Vec3(2, 0.5, 0));
        QVERIFY(f.view->rect().contains(ball));
        QVERIFY(f.view->rect().contains(crate));
        // The ground lies behind both: the nearest hit wins.
        QCOMPARE(f.view->bodyAt(ball), 1);
        QCOMPARE(f.view->bodyAt(crate), 2);

        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::NoModifier, ball);
        QCOMPARE(f.doc.selection(), QList<int>({1}));
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::ControlModifier, crate);
        QCOMPARE(f.doc.selection(), QList<int>({1, 2}));
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::ControlModifier, ball);
        QCOMPARE(f.doc.selection(), QList<int>({2}));
        // A plain click replaces the selection.
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::NoModifier, ball);
        QCOMPARE(f.doc.selection(), QList<int>({1}));
        // In front of the ground plane, below the bodies: the ground.
        const QPoint ground = projected(*f.view, Vec3(1, 0, 2));
        QCOMPARE(f.view->bodyAt(ground), 0);
    }

    void clickOnTheSkySelectsNothing() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({1, 2});
        const QPoint sky(f.view->width() / 2, 3);  // looking down 20°: the top edge is above the horizon
        QCOMPARE(f.view->bodyAt(sky), -1);
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::ControlModifier, sky);
        QCOMPARE(f.doc.selection(), QList<int>({1, 2}));  // Ctrl on nothing keeps it
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::NoModifier, sky);
        QVERIFY(f.doc.selection().isEmpty());
    }

    // Issue 21 item 7: a click on the ground (the floor around the bodies) is a click on
    // empty space: it clears the selection and does not select the ground; the ground
    // selected from the Scene list is tinted, not lit up in the selection's yellow.
    void aClickOnTheGroundClearsTheSelection() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({1});
        const QPoint floor = projected(*f.view, Vec3(-1.5, 0, 2.5));  // on the ground (in a cell), before the bodies
        QCOMPARE(f.view->bodyAt(floor), 0);                       // the ray meets the ground there
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::NoModifier, floor);
        QVERIFY(f.doc.selection().isEmpty());
        QTest::mouseClick(f.view->renderWindow(), Qt::LeftButton, Qt::ControlModifier, floor);
        QVERIFY(f.doc.selection().isEmpty());
        f.doc.setSelection({0});  // as the Scene list does
        // Until the frame with the selected ground is on screen (its tint is yellowish: blue
        // under green, where the unselected ground is bluish), then: not lit up.
        QColor c;
        for (int tries = 0; tries < 200; ++tries) {
            QTest::qWait(50);
            c = f.view->screen()->grabWindow(f.view->winId()).toImage().pixelColor(floor);
            if (c.blue() + 5 < c.green()) break;
        }
        const QString rgb = QString("rgb(%1, %2, %3)").arg(c.red()).arg(c.green()).arg(c.blue());
        QVERIFY2(c.blue() + 5 < c.green(), qPrintable("the selected ground is not tinted: " + rgb));
        QVERIFY2(c.red() < 120 && c.green() < 120, qPrintable(rgb));
    }

    void aDragOrbitsInsteadOfSelecting() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        const QPoint ball = projected(*f.view, Vec3(0, 1, 0));
        const QVector3D eye = f.view->cameraPosition();
        QTest::mousePress(f.view->renderWindow(), Qt::LeftButton, Qt::NoModifier, ball);
        QTest::mouseMove(f.view->renderWindow(), ball + QPoint(60, 0));
        QTest::mouseRelease(f.view->renderWindow(), Qt::LeftButton, Qt::NoModifier, ball + QPoint(60, 0));
        QVERIFY(f.doc.selection().isEmpty());
        QVERIFY((f.view->cameraPosition() - eye).length() > 0.5f);
        QVERIFY(qFuzzyCompare(f.view->cameraDistance(), 8.0f));  // an orbit keeps the distance
    }

    void frameSelectionCentresTheSelectedBody() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        f.doc.setSelection({2});
        f.view->renderWindow()->requestActivate();
        QTest::keyClick(f.view->renderWindow(), Qt::Key_F);
        QVector3D c = f.view->projectToWidget(QVector3D(2, 0.5f, 0));
        QVERIFY(std::abs(c.x() - f.view->width() / 2.0f) < 1.0f);
        QVERIFY(std::abs(c.y() - f.view->height() / 2.0f) < 1.0f);
        // Close in on the box (bounding radius sqrt(0.75), framed by the box around that
        // sphere, half diagonal 1.5): nearer than the fixture's 8 m, and outside the box.
        QVERIFY(f.view->cameraDistance() > 1.5f && f.view->cameraDistance() < 5.0f);
        QCOMPARE(f.view->bodyAt(QPoint(f.view->width() / 2, f.view->height() / 2)), 2);

        // Frame all (A): both bodies in view, the ground ignored.
        QTest::keyClick(f.view->renderWindow(), Qt::Key_A);
        for (const Vec3& p : {Vec3(0, 1, 0), Vec3(2, 0.5, 0)}) {
            QVERIFY(f.view->rect().contains(projected(*f.view, p)));
        }
        QCOMPARE(f.view->bodyAt(projected(*f.view, Vec3(0, 1, 0))), 1);
    }

    void pickingFollowsEditsAndPoses() {
        Fixture f;
        QVERIFY(QTest::qWaitForWindowExposed(f.view.get()));
        const QPoint ball = projected(*f.view, Vec3(0, 1, 0));
        BodyDesc moved = f.doc.body(1);
        moved.position = Vec3(-3, 1, 0);
        f.doc.setBody(1, moved, "Move");
        QCOMPARE(f.view->entityCount(), 3);
        QCOMPARE(f.view->bodyAt(ball), 0);  // now the ground behind where it was
        QCOMPARE(f.view->bodyAt(projected(*f.view, Vec3(-3, 1, 0))), 1);
        f.doc.undoStack()->undo();
        QCOMPARE(f.view->bodyAt(ball), 1);
    }

    // ---- The ray casts against closed forms.

    void raySphereFromOutsideHitsAtDistanceMinusRadius() {
        const Ray ray{Vec3(0, 0, 10), Vec3(0, 0, -1)};
        QCOMPARE(*raySphere(ray, Vec3(0, 0, 0), 2.0), 8.0);
        // Off-centre by b: the chord gives d - sqrt(r² - b²).
        const Ray off{Vec3(1, 0, 10), Vec3(0, 0, -1)};
        QVERIFY(std::abs(*raySphere(off, Vec3::Zero(), 2.0) - (10.0 - std::sqrt(3.0))) < kTol);
        QVERIFY(!raySphere(Ray{Vec3(2.5, 0, 10), Vec3(0, 0, -1)}, Vec3::Zero(), 2.0));
        QVERIFY(!raySphere(Ray{Vec3(0, 0, 10), Vec3(0, 0, 1)}, Vec3::Zero(), 2.0));      // pointing away
        QCOMPARE(*raySphere(Ray{Vec3::Zero(), Vec3(1, 0, 0)}, Vec3::Zero(), 2.0), 2.0);  // from inside
    }

    void rayBoxHitsTheNearFace() {
        const Vec3 h(1, 2, 3);
        QCOMPARE(*rayBox(Ray{Vec3(10, 0, 0), Vec3(-1, 0, 0)}, h), 9.0);
        QCOMPARE(*rayBox(Ray{Vec3(0.5, -10, 0.5), Vec3(0, 1, 0)}, h), 8.0);
        // Diagonal at the corner region: enters through x = 1 at t = (5 - 1) * sqrt(2).
        const Vec3 d = Vec3(-1, 0, -1).normalized();
        QVERIFY(std::abs(*rayBox(Ray{Vec3(5, 0, 5.5), d}, h) - 4.0 * std::sqrt(2.0)) < 1e-9);
        QVERIFY(!rayBox(Ray{Vec3(10, 2.5, 0), Vec3(-1, 0, 0)}, h));
    }

    void rayPlaneHitsFromEitherSide() {
        const Vec3 n(0, 1, 0);
        QCOMPARE(*rayPlane(Ray{Vec3(0, 5, 0), Vec3(0, -1, 0)}, n, 1.0), 4.0);
        QCOMPARE(*rayPlane(Ray{Vec3(0, -5, 0), Vec3(0, 1, 0)}, n, 1.0), 6.0);
        const Vec3 d = Vec3(1, -1, 0).normalized();  // 45°: the path is sqrt(2) times the height
        QVERIFY(std::abs(*rayPlane(Ray{Vec3(0, 3, 0), d}, n, 0.0) - 3.0 * std::sqrt(2.0)) < 1e-12);
        QVERIFY(!rayPlane(Ray{Vec3(0, 5, 0), Vec3(1, 0, 0)}, n, 0.0));  // parallel
        QVERIFY(!rayPlane(Ray{Vec3(0, 5, 0), Vec3(0, 1, 0)}, n, 0.0));  // up into the sky
    }

    void rayCapsuleSideAndCaps() {
        const double r = 0.5, h = 1.0;
        // The side: a horizontal ray at y = 0.7 (within the segment) meets x = r.
        QCOMPARE(*rayCapsule(Ray{Vec3(5, 0.7, 0), Vec3(-1, 0, 0)}, r, h), 4.5);
        // The top cap along the axis: y = h + r.
        QCOMPARE(*rayCapsule(Ray{Vec3(0, 10, 0), Vec3(0, -1, 0)}, r, h), 10.0 - 1.5);
        // The cap off-axis at x = 0.3: y = h + sqrt(r² - 0.09) = 1.4.
        QVERIFY(std::abs(*rayCapsule(Ray{Vec3(0.3, 10, 0), Vec3(0, -1, 0)}, r, h) - 8.6) < kTol);
        // A horizontal ray through the cap region, y = 1.3: x = sqrt(r² - 0.09) = 0.4.
        QVERIFY(std::abs(*rayCapsule(Ray{Vec3(5, 1.3, 0), Vec3(-1, 0, 0)}, r, h) - 4.6) < kTol);
        QVERIFY(!rayCapsule(Ray{Vec3(5, 1.6, 0), Vec3(-1, 0, 0)}, r, h));   // above the top
        QVERIFY(!rayCapsule(Ray{Vec3(0.6, 10, 0), Vec3(0, -1, 0)}, r, h));  // beside it
    }

    void rayCylinderSideAndCaps() {
        const double r = 0.5, h = 1.0;
        QCOMPARE(*rayCylinder(Ray{Vec3(5, 0.9, 0), Vec3(-1, 0, 0)}, r, h), 4.5);
        QCOMPARE(*rayCylinder(Ray{Vec3(0.3, 10, 0), Vec3(0, -1, 0)}, r, h), 9.0);  // flat cap
        QVERIFY(!rayCylinder(Ray{Vec3(5, 1.1, 0), Vec3(-1, 0, 0)}, r, h));         // a capsule would hit here
    }

    void rayTriangleAndMesh() {
        const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
        QCOMPARE(*rayTriangle(Ray{Vec3(0.5, 0.5, 3), Vec3(0, 0, -1)}, a, b, c), 3.0);
        QCOMPARE(*rayTriangle(Ray{Vec3(0.5, 0.5, -3), Vec3(0, 0, 1)}, a, b, c), 3.0);  // back face
        QVERIFY(!rayTriangle(Ray{Vec3(1.5, 1.5, 3), Vec3(0, 0, -1)}, a, b, c));  // beyond the hypotenuse
        // A unit cube mesh: the nearest of its triangles.
        TriangleMesh cube;
        for (int i = 0; i < 8; ++i)
            cube.vertices.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
        QCOMPARE(*rayMesh(Ray{Vec3(0.2, 0.1, 9), Vec3(0, 0, -1)}, cube), 8.0);
        QCOMPARE(*rayMesh(Ray{Vec3(-9, 0.3, 0.2), Vec3(1, 0, 0)}, cube), 8.0);
    }

    void rayShapeUsesThePose() {
        ShapeDesc rod;
        rod.type = ShapeType::Box;
        rod.halfExtents = Vec3(1, 0.2, 0.2);
        // Turned 90° about z, the rod stands along y: from above it is met at y = 1 + 3.
        const Quat q(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
        const Ray down{Vec3(3, 10, 0), Vec3(0, -1, 0)};
        QVERIFY(std::abs(*rayShape(down, rod, Vec3(3, 5, 0), q) - 4.0) < 1e-9);
        QVERIFY(std::abs(*rayShape(down, rod, Vec3(3, 5, 0), Quat::Identity()) - 4.8) < 1e-9);
        // A tilted plane through the origin with normal (1, 1, 0)/sqrt2 and distance 1.
        ShapeDesc plane;
        plane.type = ShapeType::Plane;
        plane.normal = Vec3(1, 1, 0).normalized();
        plane.distance = 1.0;
        const auto t = rayShape(Ray{Vec3(0, 10, 0), Vec3(0, -1, 0)}, plane, Vec3::Zero(), Quat::Identity());
        QVERIFY(std::abs(*t - (10.0 - std::sqrt(2.0))) < 1e-9);
        // A mesh body with no triangles loaded is never hit.
        ShapeDesc mesh;
        mesh.type = ShapeType::Mesh;
        QVERIFY(!rayShape(down, mesh, Vec3::Zero(), Quat::Identity()));
    }

    void everyShapeKindIsDrawnAndPickedAtItsCentre() {
        // Under TUMBLE_VIEWPORT_SHOW_MS the view stays up that long, for a screenshot.
        auto tetra = std::make_shared<TriangleMesh>();
        tetra->vertices = {Vec3(0.6, -0.4, 0.6), Vec3(-0.6, -0.4, 0.6), Vec3(0, -0.4, -0.7), Vec3(0, 0.7, 0)};
        tetra->triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};  // outward
        Document doc;                                                     // the ground plane is body 0
        doc.addBody(body("sphere", ShapeType::Sphere, Vec3(-3, 0.5, 0)));
        BodyDesc box = body("box", ShapeType::Box, Vec3(-1.5, 0.5, 0));
        box.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitY()));
        doc.addBody(box);
        BodyDesc capsule = body("capsule", ShapeType::Capsule, Vec3(0, 1.0, 0));
        capsule.shape.radius = 0.4;
        doc.addBody(capsule);
        doc.addBody(body("cylinder", ShapeType::Cylinder, Vec3(1.5, 0.5, 0)));
        BodyDesc mesh = body("mesh", ShapeType::Mesh, Vec3(3, 0.4, 0));
        mesh.shape.file = "tetra.obj";
        mesh.shape.meshData = tetra;
        doc.addBody(mesh);

        Viewport view(&doc);
        view.resize(960, 640);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setCamera(QVector3D(0, 0.5f, 0), 9.0f, 20.0f, 25.0f);
        doc.setSelection({3});
        QCOMPARE(view.entityCount(), 6);
        for (int i = 1; i < doc.bodyCount(); ++i) {
            QCOMPARE(view.bodyAt(projected(view, doc.body(i).position)), i);
        }
        const int ms = qEnvironmentVariableIntValue("TUMBLE_VIEWPORT_SHOW_MS");
        if (ms > 0) QTest::qWait(ms);
    }

    // Issue 21 item 1: a mesh body that comes after the view is up (a scene opened, a mesh
    // imported) is drawn: the pixels where its centre projects take its colour (the orange
    // of a dynamic body, lit), where the ground's grey was before.
    void meshesAddedOrOpenedAfterStartAreDrawn() {
        auto slab = std::make_shared<TriangleMesh>();  // a 2 x 2 x 0.5 box facing the camera
        for (int k = 0; k < 8; ++k) slab->vertices.push_back(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 0.25 : -0.25));
        slab->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                           {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
        Document doc;  // the ground alone
        Viewport view(&doc);
        view.resize(480, 360);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setCamera(QVector3D(0, 1.5f, 0), 7.0f, 0.0f, 10.0f);
        QTest::qWait(300);  // frames drawn before any mesh exists
        auto orangeAt = [&](const Vec3& p) {
            const QPoint at = projected(view, p);
            QImage shot;
            for (int tries = 0; tries < 200; ++tries) {  // until a frame with it is on screen (10 s)
                QTest::qWait(50);
                shot = view.screen()->grabWindow(view.winId()).toImage();
                const QColor c = shot.pixelColor(at);
                if (c.red() > c.blue() + 60) return true;
            }
            const QColor c = shot.pixelColor(at);
            qWarning("at (%d, %d): rgb(%d, %d, %d)", at.x(), at.y(), c.red(), c.green(), c.blue());
            return false;
        };
        BodyDesc b = body("slab", ShapeType::Mesh, Vec3(0, 1.5, 0));
        b.shape.file = "slab.obj";
        b.shape.meshData = slab;
        doc.addBody(b);  // as Import Mesh adds one
        QVERIFY(orangeAt(Vec3(0, 1.5, 0)));
        // A scene opened from a file (File > Open), its meshes loaded then.
        QString error;
        QVERIFY2(doc.open(QStringLiteral(TUMBLE_SCENES_DIR "/mesh-shapes.json"), &error), qPrintable(error));
        int tetra = -1;
        for (int i = 0; i < doc.bodyCount(); ++i)
            if (doc.body(i).motion == Motion::Dynamic && doc.body(i).shape.type == ShapeType::Mesh) tetra = i;
        QVERIFY(tetra >= 0);
        const Vec3 at = doc.body(tetra).position;
        view.setCamera(QVector3D(float(at.x()), float(at.y()), float(at.z())), 3.0f, 0.0f, 10.0f);
        QVERIFY(orangeAt(doc.body(tetra).position));
    }

    // Issue 49: a compound's mesh part is drawn (the pixels at its centre take the body's
    // orange); a click on the compound selects it, a second click goes into it and selects
    // the part under the pointer, a click on its other part that one.
    void aCompoundsMeshPartIsDrawnAndAClickPicksAPart() {
        auto slab = std::make_shared<TriangleMesh>();  // a 1 x 1 x 0.25 box facing the camera
        for (int k = 0; k < 8; ++k)
            slab->vertices.push_back(Vec3(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.125 : -0.125));
        slab->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                           {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
        Document doc;
        BodyDesc c = body("pair", ShapeType::Compound, Vec3(0, 1.5, 0));
        c.shape.parts.resize(2);
        c.shape.parts[0].name = "slab";
        c.shape.parts[0].shape.type = ShapeType::Mesh;
        c.shape.parts[0].shape.file = "slab.obj";
        c.shape.parts[0].shape.meshData = slab;
        c.shape.parts[0].position = Vec3(-0.8, 0, 0);
        c.shape.parts[1].name = "block";
        c.shape.parts[1].shape.type = ShapeType::Box;
        c.shape.parts[1].shape.halfExtents = Vec3(0.3, 0.3, 0.3);
        c.shape.parts[1].position = Vec3(0.8, 0, 0);
        const int pair = doc.addBody(c);
        Viewport view(&doc);
        view.resize(480, 360);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        view.setCamera(QVector3D(0, 1.5f, 0), 6.0f, 0.0f, 10.0f);
        const QPoint slabAt = projected(view, Vec3(-0.8, 1.5, 0)),
                     blockAt = projected(view, Vec3(0.8, 1.5, 0));
        bool orange = false;
        for (int tries = 0; tries < 200 && !orange; ++tries) {  // until a frame with it is on screen
            QTest::qWait(50);
            const QColor px = view.screen()->grabWindow(view.winId()).toImage().pixelColor(slabAt);
            orange = px.red() > px.blue() + 60;
        }
        QVERIFY2(orange, "the mesh part is not drawn");
        QTest::mouseClick(view.renderWindow(), Qt::LeftButton, Qt::NoModifier, slabAt);
        QCOMPARE(doc.selection(), QList<int>{pair});
        QCOMPARE(doc.selectedPart(), -1);
        QTest::mouseClick(view.renderWindow(), Qt::LeftButton, Qt::NoModifier, slabAt);
        QCOMPARE(doc.selectedPart(), 0);
        QTest::mouseClick(view.renderWindow(), Qt::LeftButton, Qt::NoModifier, blockAt);
        QCOMPARE(doc.selectedPart(), 1);
        QCOMPARE(doc.selection(), QList<int>{pair});
        // Empty space clears both.
        QTest::mouseClick(view.renderWindow(), Qt::LeftButton, Qt::NoModifier, QPoint(view.width() / 2, 3));
        QVERIFY(doc.selection().isEmpty());
        QCOMPARE(doc.selectedPart(), -1);
    }

    void spheresAndCylindersGetCoarserAsTheyGrowInNumber() {
        using K = ViewportInstances::Kind;
        // A few: full detail (a sphere of 24 rings and 32 slices, a cylinder of 32 slices).
        QCOMPARE(ViewportInstances::trianglesPerCopy(K::Sphere, 1), 2 * 32 * 23);
        QCOMPARE(ViewportInstances::trianglesPerCopy(K::Sphere, 100), 2 * 32 * 23);
        QCOMPARE(ViewportInstances::trianglesPerCopy(K::Cylinder, 100), 4 * 32);
        QCOMPARE(ViewportInstances::trianglesPerCopy(K::Box, 5000), 12);  // boxes never change
        // Never finer as the count grows; within the budget of 250 000 triangles a kind
        // until the coarsest level (6 rings, 10 slices; 8 slices).
        for (K kind : {K::Sphere, K::Cylinder}) {
            int previous = ViewportInstances::trianglesPerCopy(kind, 1);
            for (int n = 1; n <= 20000; n += 1 + n / 8) {
                const int t = ViewportInstances::trianglesPerCopy(kind, n);
                QVERIFY(t <= previous);
                QVERIFY(long(n) * t <= 250000 || t == (kind == K::Sphere ? 2 * 10 * 5 : 4 * 8));
                previous = t;
            }
        }
        QVERIFY(ViewportInstances::trianglesPerCopy(K::Sphere, 1000) < 2 * 32 * 23 / 4);

        // What is drawn follows the count at each commit, back up to full detail too.
        Qt3DCore::QEntity root;
        ViewportInstances instances(&root);
        for (int n : {3, 400, 3000, 2}) {
            instances.clear();
            for (int i = 0; i < n; ++i) {
                QMatrix4x4 m;
                m.translate(float(i), 0, 0);
                instances.add(K::Sphere, m, {Qt::red, Qt::darkRed, 0.5f});
                instances.add(K::Cylinder, m, {Qt::red, Qt::darkRed, 0.5f});
            }
            instances.commit();
            QCOMPARE(instances.count(K::Sphere), n);
            QCOMPARE(instances.drawnTrianglesPerCopy(K::Sphere),
                     ViewportInstances::trianglesPerCopy(K::Sphere, n));
            QCOMPARE(instances.drawnTrianglesPerCopy(K::Cylinder),
                     ViewportInstances::trianglesPerCopy(K::Cylinder, n));
        }
    }

    void multisamplingIsOffOnASoftwareRenderer() {
        for (const char* name :
             {"llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe", "Software Rasterizer", "Mesa X11 swrast"}) {
            QVERIFY2(Viewport::isSoftwareRenderer(name), name);
        }
        for (const char* name :
             {"Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "NVIDIA GeForce RTX 3060/PCIe/SSE2",
              "AMD Radeon RX 6600 (navy_flounder, LLVM 15.0.6, DRM 3.49, 6.1.0)", ""}) {
            QVERIFY2(!Viewport::isSoftwareRenderer(name), name);
        }
        if (qEnvironmentVariableIsSet("TUMBLE_VIEWPORT_SAMPLES")) return;  // set by hand
        Document doc;
        Viewport view(&doc);
        view.resize(320, 240);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        const QString renderer = Viewport::glRenderer();
        QVERIFY(!renderer.isEmpty());
        QCOMPARE(view.samples(), Viewport::isSoftwareRenderer(renderer) ? 0 : 4);
        QCOMPARE(view.renderWindow()->format().samples(), view.samples());
    }

    // Qt 6.4's frame jobs race with each other on a view's lights (QTBUG-111427) and on a
    // capture's requests; the viewport asks Qt3D for one job thread before its first
    // window (limitQt3dJobThreads in viewport.cpp). Qt3D reads the variable once, at the
    // first aspect engine, so it must be in place by the time a Viewport exists.
    void qt3dPreparesFramesOnOneThread() {
        Document doc;
        Viewport view(&doc);
        QCOMPARE(qgetenv("QT3D_MAX_THREAD_COUNT"), QByteArray("1"));
    }
};

QTEST_MAIN(TestViewport)
#include "tst_viewport.moc"
