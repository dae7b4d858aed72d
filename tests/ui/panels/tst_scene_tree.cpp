// The scene tree: its rows follow the document through add, duplicate, delete, rename and
// undo; a taken or empty name is refused; the selection is the document's, both ways.
#include "document/body_presets.h"
#include "document/document.h"
#include "document/joint_presets.h"
#include "panels/scene_tree_dock.h"
#include "panels/scene_tree_model.h"

#include <tumble/world.h>

#include <QAbstractItemModelTester>
#include <QAction>
#include <QItemSelectionModel>
#include <QLabel>
#include <QLineEdit>
#include <QMainWindow>
#include <QMenu>
#include <QSignalSpy>
#include <QTreeView>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

QStringList names(const QAbstractItemModel& m) {
    QStringList out;
    for (int r = 0; r < m.rowCount(); ++r) out << m.index(r, SceneTreeModel::NameColumn).data().toString();
    return out;
}

QStringList documentNames(const Document& doc) {
    QStringList out;
    for (int i = 0; i < doc.bodyCount(); ++i) out << QString::fromStdString(doc.body(i).name);
    return out;
}

QList<int> viewRows(const QTreeView* view) {
    QList<int> rows;
    for (const QModelIndex& i : view->selectionModel()->selectedRows()) rows << i.row();
    std::sort(rows.begin(), rows.end());
    return rows;
}

// Lowest and highest world y of an upright primitive.
double bottom(const BodyDesc& b) {
    return b.position.y() - halfHeightAboveOrigin(b);
}
double top(const BodyDesc& b) {
    return b.position.y() + halfHeightAboveOrigin(b);
}

}  // namespace

class TestSceneTree : public QObject {
    Q_OBJECT
private slots:
    void columnsShowNameMotionShape() {
        Document doc;
        SceneTreeModel model(&doc);
        QAbstractItemModelTester tester(&model, QAbstractItemModelTester::FailureReportingMode::QtTest);
        QCOMPARE(model.rowCount(), 1);
        QCOMPARE(model.columnCount(), 3);
        QCOMPARE(model.index(0, SceneTreeModel::NameColumn).data().toString(), QString("ground"));
        QCOMPARE(model.index(0, SceneTreeModel::MotionColumn).data().toString(), QString("static"));
        QCOMPARE(model.index(0, SceneTreeModel::ShapeColumn).data().toString(), QString("plane"));
        QVERIFY(model.flags(model.index(0, SceneTreeModel::NameColumn)) & Qt::ItemIsEditable);
        QVERIFY(!(model.flags(model.index(0, SceneTreeModel::ShapeColumn)) & Qt::ItemIsEditable));
    }

    // Issue 21 item 10: a body's name is shown whole in a dock of the window's default
    // width (260 px) beside a long shape text, which gives way instead.
    void namesAreShownWhole() {
        Document doc;
        BodyDesc b;
        b.name = "tetrahedron";
        b.shape.type = ShapeType::Mesh;
        b.shape.file = "/work/models/tetrahedron.off";
        b.mass = 1.0;
        doc.addBody(b);
        QMainWindow window;
        auto* dock = new SceneTreeDock(&doc, &window);
        window.setCentralWidget(new QWidget);
        window.addDockWidget(Qt::LeftDockWidgetArea, dock);
        window.resize(800, 400);
        window.resizeDocks({dock}, {260}, Qt::Horizontal);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        QTreeView* view = dock->view();
        const QModelIndex name = view->model()->index(1, SceneTreeModel::NameColumn);
        const int needed = view->fontMetrics().horizontalAdvance(name.data().toString());
        QVERIFY2(view->visualRect(name).width() >= needed,
                 qPrintable(QString("%1 px for %2").arg(view->visualRect(name).width()).arg(needed)));
    }

    void rowsFollowAddDuplicateDeleteAndUndo() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        QAbstractItemModelTester tester(dock.model(), QAbstractItemModelTester::FailureReportingMode::QtTest);
        QSignalSpy inserted(dock.model(), &QAbstractItemModel::rowsInserted);
        QSignalSpy removed(dock.model(), &QAbstractItemModel::rowsRemoved);

        dock.addBodyAction(ShapeType::Sphere)->trigger();
        dock.addBodyAction(ShapeType::Box)->trigger();
        dock.addBodyAction(ShapeType::Capsule)->trigger();
        dock.addBodyAction(ShapeType::Cylinder)->trigger();
        QCOMPARE(inserted.count(), 4);
        QCOMPARE(names(*dock.model()), QStringList({"ground", "sphere", "box", "capsule", "cylinder"}));
        QCOMPARE(doc.selection(), QList<int>({4}));  // the new body is the selection
        QCOMPARE(dock.model()->index(2, SceneTreeModel::ShapeColumn).data().toString(), QString("box"));

        // Sensible defaults: 1 kg, above the ground, none overlapping the one before.
        for (int i = 1; i < doc.bodyCount(); ++i) {
            QCOMPARE(doc.body(i).mass.value_or(0.0), 1.0);
            QVERIFY(bottom(doc.body(i)) > 0.0);
            if (i > 1)
                QVERIFY2(bottom(doc.body(i)) > top(doc.body(i - 1)), qPrintable(documentNames(doc)[i]));
        }

        // Duplicate the selection (sphere and box): copies at the end, selected.
        doc.setSelection({1, 2});
        dock.duplicateAction()->trigger();
        QCOMPARE(names(*dock.model()),
                 QStringList({"ground", "sphere", "box", "capsule", "cylinder", "sphere-2", "box-2"}));
        QCOMPARE(doc.selection(), QList<int>({5, 6}));
        QCOMPARE(viewRows(dock.view()), QList<int>({5, 6}));
        QCOMPARE(doc.undoStack()->undoText(), QString("Duplicate 2 bodies"));
        // The copies keep everything but their height: they start above the pile.
        for (int k : {0, 1}) {
            const BodyDesc& original = doc.body(1 + k);
            const BodyDesc& copy = doc.body(5 + k);
            QCOMPARE(copy.shape, original.shape);
            QCOMPARE(copy.position.x(), original.position.x());
            QCOMPARE(copy.mass, original.mass);
            for (int i = 1; i < 5 + k; ++i) QVERIFY(bottom(copy) > top(doc.body(i)));
        }

        // Delete box and capsule.
        doc.setSelection({2, 3});
        dock.deleteAction()->trigger();
        QCOMPARE(removed.count(), 2);
        QCOMPARE(names(*dock.model()), QStringList({"ground", "sphere", "cylinder", "sphere-2", "box-2"}));
        QCOMPARE(names(*dock.model()), documentNames(doc));
        QVERIFY(doc.selection().isEmpty());
        QVERIFY(viewRows(dock.view()).isEmpty());
        QVERIFY(!dock.deleteAction()->isEnabled());

        // Undo the delete, the duplicate, then two adds; redo one.
        doc.undoStack()->undo();
        QCOMPARE(names(*dock.model()),
                 QStringList({"ground", "sphere", "box", "capsule", "cylinder", "sphere-2", "box-2"}));
        doc.undoStack()->undo();
        QCOMPARE(names(*dock.model()), QStringList({"ground", "sphere", "box", "capsule", "cylinder"}));
        doc.undoStack()->undo();
        doc.undoStack()->undo();
        QCOMPARE(names(*dock.model()), QStringList({"ground", "sphere", "box"}));
        doc.undoStack()->redo();
        QCOMPARE(names(*dock.model()), QStringList({"ground", "sphere", "box", "capsule"}));
        QCOMPARE(names(*dock.model()), documentNames(doc));
    }

    void aPlaneIsStaticAndAMeshAsksForAFile() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        QSignalSpy importRequested(&dock, &SceneTreeDock::importMeshRequested);
        dock.addBodyAction(ShapeType::Plane)->trigger();
        QCOMPARE(doc.bodyCount(), 2);
        QCOMPARE(doc.body(1).motion, Motion::Static);
        QVERIFY(!doc.body(1).mass && !doc.body(1).density);  // the engine refuses mass on a static body
        dock.addBodyAction(ShapeType::Mesh)->trigger();
        QCOMPARE(importRequested.count(), 1);
        QCOMPARE(doc.bodyCount(), 2);
    }

    void theDeleteKeyDeletesTheSelection() {
        Document doc;
        QMainWindow window;
        auto* dock = new SceneTreeDock(&doc, &window);
        window.addDockWidget(Qt::LeftDockWidgetArea, dock);
        window.show();
        window.activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(&window));
        dock->addBody(ShapeType::Sphere);
        dock->addBody(ShapeType::Box);
        doc.setSelection({1});
        dock->view()->setFocus();
        QTest::keyClick(dock->view(), Qt::Key_Delete);
        QCOMPARE(documentNames(doc), QStringList({"ground", "box"}));
        QCOMPARE(names(*dock->model()), QStringList({"ground", "box"}));
        doc.undoStack()->undo();
        QCOMPARE(names(*dock->model()), QStringList({"ground", "sphere", "box"}));
    }

    void renameInPlaceReachesTheDocumentAndUndoes() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        dock.addBody(ShapeType::Sphere);
        SceneTreeModel* model = dock.model();
        const QModelIndex name = model->index(1, SceneTreeModel::NameColumn);
        QVERIFY(model->setData(name, QString("  ball ")));  // trimmed
        QCOMPARE(doc.body(1).name, std::string("ball"));
        QCOMPARE(name.data().toString(), QString("ball"));
        QCOMPARE(doc.undoStack()->undoText(), QString("Rename sphere to ball"));
        doc.undoStack()->undo();
        QCOMPARE(doc.body(1).name, std::string("sphere"));
        QCOMPARE(name.data().toString(), QString("sphere"));
        doc.undoStack()->redo();
        QCOMPARE(name.data().toString(), QString("ball"));
    }

    void renameThroughTheViewsEditor() {
        Document doc;
        QMainWindow window;
        auto* dock = new SceneTreeDock(&doc, &window);
        window.addDockWidget(Qt::LeftDockWidgetArea, dock);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        dock->addBody(ShapeType::Box);
        const QModelIndex name = dock->model()->index(1, SceneTreeModel::NameColumn);
        dock->view()->edit(name);
        auto* editor = dock->view()->findChild<QLineEdit*>();
        QVERIFY(editor);
        editor->selectAll();
        QTest::keyClicks(editor, "crate");
        QTest::keyClick(editor, Qt::Key_Return);
        QTRY_COMPARE(doc.body(1).name, std::string("crate"));  // the delegate commits queued
        doc.undoStack()->undo();
        QCOMPARE(doc.body(1).name, std::string("box"));
    }

    // Add Joint: two selected bodies get a joint between them at the midpoint of their
    // positions (a hinge about the vertical), one body a joint to the world at its place,
    // each one undo step with a unique name; the joint runs (the hinged pair turns about y
    // only); nothing selected: the menu is off; two static bodies: a message, no joint.
    void addJointForTheSelection() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        QVERIFY(!dock.jointMenu()->isEnabled());
        BodyDesc a = presetBody(ShapeType::Box, doc.scene()), b = a;
        a.name = "left";
        a.position = Vec3(-1, 2, 0);
        b.name = "right";
        b.position = Vec3(1, 2, 0);
        b.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
        doc.addBody(a);
        doc.addBody(b);
        doc.setSelection({1, 2});
        QVERIFY(dock.jointMenu()->isEnabled());
        dock.addJointAction(JointType::Hinge)->trigger();
        QCOMPARE(doc.scene().joints.size(), size_t(1));
        JointDesc j = doc.scene().joints[0];
        QCOMPARE(j.name, std::string("hinge"));
        // The first picked is the base (B), the second the part that moves on it (A).
        QCOMPARE(j.bodyA, std::string("right"));
        QCOMPARE(j.bodyB, std::string("left"));
        // Both anchors at the midpoint (0, 2, 0), the axes along the world's y.
        QVERIFY((b.position + b.orientation * j.anchorA - Vec3(0, 2, 0)).norm() < 1e-12);
        QVERIFY((a.position + a.orientation * j.anchorB - Vec3(0, 2, 0)).norm() < 1e-12);
        QVERIFY(j.axisA && (b.orientation * *j.axisA - Vec3::UnitY()).norm() < 1e-12);
        QCOMPARE(doc.undoStack()->undoText(), QString("Add hinge joint"));

        doc.setSelection({2});
        dock.addJointAction(JointType::Hinge)->trigger();
        QCOMPARE(doc.scene().joints.size(), size_t(2));
        QCOMPARE(doc.scene().joints[1].name, std::string("hinge-2"));
        QVERIFY(doc.scene().joints[1].bodyB.empty());  // to the world, at its place
        QVERIFY((doc.scene().joints[1].anchorB - b.position).norm() < 1e-12);
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().joints.size(), size_t(1));

        // The pair on its hinge, in free fall and tumbling (a quarter of a second: before it
        // reaches the ground), turns one against the other about the hinge's axis only (as
        // the hinge is turned now).
        SceneDesc run = doc.scene();
        run.bodies[1].angularVelocity = Vec3(1, 1, 0);
        World w(run);
        for (int k = 0; k < 15; ++k) w.step(1.0 / 60.0);
        const Vec3 wa = derive(w.model().bodies[1], w.state().bodies[1]).omega;
        const Vec3 wb = derive(w.model().bodies[2], w.state().bodies[2]).omega;
        const Vec3 axis = w.state().bodies[2].q * *j.axisA;
        const Vec3 across = (wa - wb) - (wa - wb).dot(axis) * axis;
        QVERIFY2(across.norm() < 1e-9 && std::abs((wa - wb).dot(axis)) > 0.1, qPrintable(QString::number(across.norm())));

        doc.setSelection({});
        QVERIFY(!dock.jointMenu()->isEnabled());
        doc.setSelection({0});  // the static ground alone
        dock.addJointAction(JointType::Ball)->trigger();
        QCOMPARE(doc.scene().joints.size(), size_t(1));
        auto* message = dock.findChild<QLabel*>("sceneTreeMessage");
        QVERIFY(message && !message->isHidden());
        QCOMPARE(message->text(), QString("No joint added: a joint needs a dynamic body among those selected."));
    }

    // Issue 51 item 2: the base is the body picked first, whatever the bodies' order in the
    // scene; a hinge's motor at +1 rad/s then turns the part picked second at +1 rad/s the
    // right-hand way about the axis (no gravity; the base static). Swapping the bodies keeps
    // the motion: the same run to rounding.
    void theFirstPickedIsTheBaseAndSwapKeepsTheMotion() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        BodyDesc wheel = presetBody(ShapeType::Cylinder, doc.scene()),
                 post = presetBody(ShapeType::Box, doc.scene());
        wheel.name = "wheel";
        wheel.position = Vec3(0, 2, 0);
        post.name = "post";
        post.motion = Motion::Static;
        post.mass.reset();
        post.density.reset();
        post.position = Vec3(0, 1, 0);
        doc.addBody(wheel);  // 1
        doc.addBody(post);   // 2
        Settings settings = doc.scene().settings;
        settings.gravity = Vec3::Zero();
        doc.setSettings(settings, "No gravity");
        doc.setSelection({2});     // the post first,
        doc.setSelection({2, 1});  // then the wheel
        QCOMPARE(doc.selectionInPickOrder(), QList<int>({2, 1}));
        dock.addJointAction(JointType::Hinge)->trigger();
        JointDesc hinge = doc.scene().joints.at(0);
        QCOMPARE(hinge.bodyA, std::string("wheel"));
        QCOMPARE(hinge.bodyB, std::string("post"));
        hinge.motor = JointDesc::Motor{1.0, 100.0};
        hinge.limits = std::array<double, 2>{-0.5, 2.0};
        doc.setJoint(0, hinge, "Motor");
        auto spin = [](const SceneDesc& scene) {  // the wheel's spin about the world's y after 1 s
            World w(scene);
            for (int k = 0; k < 60; ++k) w.step(1.0 / 60);
            return derive(w.model().bodies[1], w.state().bodies[1]).omega;
        };
        SceneDesc run = doc.scene();
        run.settings.dt = 1.0 / 60;
        const Vec3 w = spin(run);
        QVERIFY2((w - Vec3(0, 1, 0)).norm() < 1e-9,
                 qPrintable(QString("%1 %2 %3").arg(w.x()).arg(w.y()).arg(w.z())));
        // Swapped: the post is A, the wheel the base; the motor and limits change sign.
        const std::optional<JointDesc> swapped = swappedJoint(doc.scene(), hinge);
        QVERIFY(swapped);
        QCOMPARE(swapped->bodyA, std::string("post"));
        QCOMPARE(swapped->motor->speed, -1.0);
        QVERIFY(*swapped->limits == (std::array<double, 2>{-2.0, 0.5}));
        run.joints[0] = *swapped;
        QVERIFY2((spin(run) - w).norm() < 1e-12, "the same motion");
        // With the wheel picked first, it is the base, and the hinge's bodies go the other way.
        doc.setSelection({});
        doc.setSelection({1});
        doc.setSelection({1, 2});
        dock.addJointAction(JointType::Hinge)->trigger();
        QCOMPARE(doc.scene().joints.at(1).bodyA, std::string("wheel"));  // the post cannot move
        QVERIFY(!swappedJoint(doc.scene(), JointDesc{}));                // nothing to swap with the world
    }

    void aTakenOrEmptyNameIsRefused() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        dock.addBody(ShapeType::Sphere);
        SceneTreeModel* model = dock.model();
        const int steps = doc.undoStack()->count();
        QSignalSpy refused(model, &SceneTreeModel::renameRefused);
        QSignalSpy changed(model, &QAbstractItemModel::dataChanged);
        const QModelIndex name = model->index(1, SceneTreeModel::NameColumn);

        QVERIFY(!model->setData(name, QString("ground")));
        QCOMPARE(refused.count(), 1);
        QVERIFY(refused.at(0).at(0).toString().contains("already the name"));
        auto* message = dock.findChild<QLabel*>("sceneTreeMessage");
        QVERIFY(message);
        QVERIFY(!message->isHidden());
        QCOMPARE(message->text(), refused.at(0).at(0).toString());

        QVERIFY(!model->setData(name, QString("   ")));
        QCOMPARE(refused.count(), 2);

        QCOMPARE(doc.body(1).name, std::string("sphere"));
        QCOMPARE(name.data().toString(), QString("sphere"));
        QCOMPARE(doc.undoStack()->count(), steps);
        QCOMPARE(changed.count(), 0);
        // Other columns are not editable through the model.
        QVERIFY(!model->setData(model->index(1, SceneTreeModel::ShapeColumn), QString("box")));
    }

    void viewSelectionSetsTheDocuments() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        dock.addBody(ShapeType::Sphere);
        dock.addBody(ShapeType::Box);
        dock.addBody(ShapeType::Capsule);
        QSignalSpy docSelection(&doc, &Document::selectionChanged);
        QItemSelectionModel* sm = dock.view()->selectionModel();
        SceneTreeModel* model = dock.model();

        sm->select(model->index(1, 0), QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
        QCOMPARE(doc.selection(), QList<int>({1}));
        sm->select(model->index(3, 0), QItemSelectionModel::Select | QItemSelectionModel::Rows);
        QCOMPARE(doc.selection(), QList<int>({1, 3}));
        QCOMPARE(docSelection.count(), 2);  // one per change, no echo
        sm->clearSelection();
        QVERIFY(doc.selection().isEmpty());

        // A click selects; a control-click extends.
        QTreeView* view = dock.view();
        dock.resize(400, 300);
        dock.show();
        QVERIFY(QTest::qWaitForWindowExposed(&dock));
        QTest::mouseClick(view->viewport(), Qt::LeftButton, {},
                          view->visualRect(model->index(2, 0)).center());
        QCOMPARE(doc.selection(), QList<int>({2}));
        QTest::mouseClick(view->viewport(), Qt::LeftButton, Qt::ControlModifier,
                          view->visualRect(model->index(0, 0)).center());
        QCOMPARE(doc.selection(), QList<int>({0, 2}));
    }

    void documentSelectionSetsTheViews() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        dock.addBody(ShapeType::Sphere);
        dock.addBody(ShapeType::Box);
        dock.addBody(ShapeType::Capsule);
        QSignalSpy docSelection(&doc, &Document::selectionChanged);
        doc.setSelection({0, 2});
        QCOMPARE(viewRows(dock.view()), QList<int>({0, 2}));
        QCOMPARE(docSelection.count(), 1);  // the view did not write it back
        QCOMPARE(doc.selection(), QList<int>({0, 2}));

        // A removal before the selection shifts it in both.
        doc.setSelection({3});
        doc.removeBodies({1});
        QCOMPARE(doc.selection(), QList<int>({2}));
        QCOMPARE(viewRows(dock.view()), QList<int>({2}));
        QCOMPARE(dock.model()->index(2, 0).data().toString(), QString("capsule"));

        // Removing the selected body empties both.
        doc.removeBodies({2});
        QVERIFY(doc.selection().isEmpty());
        QVERIFY(viewRows(dock.view()).isEmpty());
    }

    void followsADocumentThatIsOpened() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        QAbstractItemModelTester tester(dock.model(), QAbstractItemModelTester::FailureReportingMode::QtTest);
        QString error;
        QVERIFY2(doc.open(":/scenes/newtons-cradle.json", &error), qPrintable(error));
        QCOMPARE(names(*dock.model()), documentNames(doc));
        QVERIFY(doc.bodyCount() > 2);
        doc.newScene();
        QCOMPARE(names(*dock.model()), QStringList({"ground"}));
    }

    void aBodyChangeUpdatesItsRow() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        dock.addBody(ShapeType::Sphere);
        QSignalSpy changed(dock.model(), &QAbstractItemModel::dataChanged);
        BodyDesc b = doc.body(1);
        b.motion = Motion::Kinematic;
        b.mass.reset();
        doc.setBody(1, b, "Make kinematic");
        QCOMPARE(changed.count(), 1);
        QCOMPARE(changed.at(0).at(0).value<QModelIndex>().row(), 1);
        QCOMPARE(dock.model()->index(1, SceneTreeModel::MotionColumn).data().toString(),
                 QString("kinematic"));
        doc.undoStack()->undo();
        QCOMPARE(dock.model()->index(1, SceneTreeModel::MotionColumn).data().toString(), QString("dynamic"));
    }
};

QTEST_MAIN(TestSceneTree)
#include "tst_scene_tree.moc"
