// Editing a compound body part by part (issue 49 item 4): Add Part and Remove Part (one undo
// step each, what cannot be done says why), a part selected from the Scene list (its row
// under its body) or by a click on the selected body, its panel (shape, pose in the body's
// frame, its own material or the body's) and its handles, which move and turn it in its
// body's frame: checked against the closed form in a turned body.
#include "document/document.h"
#include "document/part_edits.h"
#include "panel_test_util.h"
#include "panels/property_dock.h"
#include "panels/property_spin_box.h"
#include "panels/scene_tree_dock.h"
#include "panels/scene_tree_model.h"
#include "panels/vector_edit.h"
#include "viewport/viewport_handles.h"

#include <tumble/model.h>

#include <QAbstractItemModelTester>
#include <QAction>
#include <QCheckBox>
#include <QGroupBox>
#include <QItemSelectionModel>
#include <QLabel>
#include <QLineEdit>
#include <QTreeView>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

BodyDesc crate(const Quat& q = Quat::Identity()) {
    BodyDesc b;
    b.name = "crate";
    b.shape.type = ShapeType::Box;
    b.shape.halfExtents = Vec3(0.4, 0.2, 0.3);
    b.position = Vec3(1, 2, 3);
    b.orientation = q;
    b.mass = 6.0;
    return b;
}

BodyDesc table() {
    BodyDesc b = crate();
    b.name = "table";
    b.shape = ShapeDesc{};
    b.shape.type = ShapeType::Compound;
    for (const auto& [name, x] : {std::pair{"left", -0.5}, std::pair{"right", 0.5}}) {
        PartDesc p;
        p.name = name;
        p.shape.type = ShapeType::Box;
        p.shape.halfExtents = Vec3(0.1, 0.5, 0.1);
        p.position = Vec3(x, 0, 0);
        b.shape.parts.push_back(p);
    }
    return b;
}

const Quat kTurned = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()));

Model compiled(const BodyDesc& b) {
    SceneDesc s;
    s.bodies.push_back(b);
    return compile(s);
}

}  // namespace

class TestParts : public QObject {
    Q_OBJECT
private slots:
    // A box body given a sphere part becomes a compound: the box as it was ("base", at the
    // frame), the sphere (radius 0.25) on top of it; the body keeps its mass, now shared by
    // volume, and its centre moves to the parts' centre of volume (closed form).
    void addPartMakesACompoundOnTop() {
        std::string why;
        const auto out = withPartAdded(crate(kTurned), ShapeType::Sphere, &why);
        QVERIFY2(out, why.c_str());
        QCOMPARE(out->shape.type, ShapeType::Compound);
        QCOMPARE(int(out->shape.parts.size()), 2);
        const PartDesc& base = out->shape.parts[0];
        QCOMPARE(base.name, std::string("base"));
        QCOMPARE(base.shape.type, ShapeType::Box);
        QVERIFY(base.shape.halfExtents == Vec3(0.4, 0.2, 0.3));
        QVERIFY(base.position == Vec3::Zero());
        const PartDesc& ball = out->shape.parts[1];
        QCOMPARE(ball.name, std::string("sphere"));
        QCOMPARE(ball.shape.radius, 0.25);
        QVERIFY((ball.position - Vec3(0, 0.2 + 0.25, 0)).norm() < 1e-15);
        QVERIFY(out->position == crate().position && out->orientation.coeffs() == kTurned.coeffs());
        const Model m = compiled(*out);
        QVERIFY(std::abs(m.bodies[0].mass - 6.0) < 1e-12);
        const double vBox = 8 * 0.4 * 0.2 * 0.3, vBall = 4.0 / 3.0 * M_PI * std::pow(0.25, 3);
        const Vec3 com = Vec3(0, 0.45 * vBall / (vBox + vBall), 0);
        QVERIFY2((m.bodies[0].centerOfMass - com).norm() < 1e-12,
                 qPrintable(QString::number(m.bodies[0].centerOfMass.y(), 'g', 17)));
        // A second sphere goes on top of the first, named apart.
        const auto again = withPartAdded(*out, ShapeType::Sphere, &why);
        QVERIFY(again);
        QCOMPARE(again->shape.parts[2].name, std::string("sphere-2"));
        QVERIFY((again->shape.parts[2].position - Vec3(0, 0.45 + 0.25 + 0.25, 0)).norm() < 1e-15);
    }

    void whatCannotBeDoneSaysWhy() {
        std::string why;
        BodyDesc floor;
        floor.name = "floor";
        floor.motion = Motion::Static;
        floor.shape.type = ShapeType::Plane;
        QVERIFY(!withPartAdded(floor, ShapeType::Box, &why));
        QVERIFY2(why.find("plane") != std::string::npos, why.c_str());
        QVERIFY(!withPartAdded(crate(), ShapeType::Plane, &why));
        QVERIFY(!withoutPart(crate(), 0, &why));
        QVERIFY2(why.find("no such part") != std::string::npos, why.c_str());
        BodyDesc one = table();
        one.shape.parts.pop_back();
        QVERIFY(!withoutPart(one, 0, &why));
        QVERIFY2(why.find("at least one part") != std::string::npos, why.c_str());
        const auto fewer = withoutPart(table(), 0, &why);
        QVERIFY(fewer);
        QCOMPARE(int(fewer->shape.parts.size()), 1);
        QCOMPARE(fewer->shape.parts[0].name, std::string("right"));
    }

    // Each is one undo step; the new part is selected; an undo takes the part selection
    // away with the part.
    void documentAddsAndRemovesPartsInOneStep() {
        Document doc;
        const int t = doc.addBody(table());
        doc.undoStack()->clear();
        QString why;
        QCOMPARE(doc.addPart(t, ShapeType::Cylinder, &why), 2);
        QCOMPARE(doc.selection(), QList<int>{t});
        QCOMPARE(doc.selectedPart(), 2);
        QCOMPARE(doc.undoStack()->count(), 1);
        QVERIFY(doc.undoStack()->undoText().contains("cylinder"));
        doc.undoStack()->undo();
        QCOMPARE(int(doc.body(t).shape.parts.size()), 2);
        QCOMPARE(doc.selectedPart(), -1);
        QCOMPARE(doc.selection(), QList<int>{t});
        QVERIFY(doc.removePart(t, 0, &why));
        QCOMPARE(doc.body(t).shape.parts[0].name, std::string("right"));
        QCOMPARE(doc.undoStack()->undoText(), QString("Remove left from table"));
        doc.undoStack()->undo();
        QVERIFY(doc.body(t) == table());
        // Selecting bodies or removing the body drops the part selection.
        doc.selectPart(t, 1);
        QCOMPARE(doc.selectedPart(), 1);
        doc.setSelection({t});
        QCOMPARE(doc.selectedPart(), -1);
        doc.selectPart(t, 1);
        doc.removeBodies({t});
        QCOMPARE(doc.selectedPart(), -1);
        QVERIFY(doc.selection().isEmpty());
        // A part index the body does not have selects the body alone.
        const int c = doc.addBody(crate());
        doc.selectPart(c, 0);
        QCOMPARE(doc.selection(), QList<int>{c});
        QCOMPARE(doc.selectedPart(), -1);
    }

    // The parts are rows under their body; a part row selected alone selects the part, and
    // the document's part selection selects the row; the rows follow Add Part, Delete and
    // undo; a part is renamed in its row.
    void sceneListShowsAndSelectsParts() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        QAbstractItemModelTester tester(dock.model(), QAbstractItemModelTester::FailureReportingMode::QtTest);
        const int c = doc.addBody(crate());
        const int t = doc.addBody(table());
        SceneTreeModel* model = dock.model();
        QCOMPARE(model->rowCount(model->index(c, 0)), 0);
        QCOMPARE(model->rowCount(model->index(t, 0)), 2);
        QCOMPARE(model->partIndex(t, 1).data().toString(), QString("right"));
        QCOMPARE(model->partIndex(t, 1, SceneTreeModel::ShapeColumn).data().toString(), QString("box"));

        dock.view()->selectionModel()->select(
            model->partIndex(t, 1), QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
        QCOMPARE(doc.selection(), QList<int>{t});
        QCOMPARE(doc.selectedPart(), 1);
        doc.selectPart(t, 0);
        QVERIFY(dock.view()->selectionModel()->isRowSelected(0, model->index(t, 0)));
        QVERIFY(!dock.view()->selectionModel()->isRowSelected(t, QModelIndex()));

        // Add Part from the menu: a row more, the new one selected.
        dock.addPartAction(ShapeType::Box)->trigger();
        QCOMPARE(model->rowCount(model->index(t, 0)), 3);
        QCOMPARE(doc.selectedPart(), 2);
        QVERIFY(dock.view()->selectionModel()->isRowSelected(2, model->index(t, 0)));
        // Delete with a part selected removes the part, not the body.
        const int bodies = doc.bodyCount();
        dock.deleteAction()->trigger();
        QCOMPARE(doc.bodyCount(), bodies);
        QCOMPARE(model->rowCount(model->index(t, 0)), 2);
        doc.undoStack()->undo();
        QCOMPARE(model->rowCount(model->index(t, 0)), 3);
        // Add Part on a plain body makes it a compound: its rows appear.
        doc.setSelection({c});
        dock.addPartAction(ShapeType::Sphere)->trigger();
        QCOMPARE(model->rowCount(model->index(c, 0)), 2);
        QCOMPARE(model->index(c, SceneTreeModel::ShapeColumn).data().toString(), QString("compound"));
        // The last part is not deleted: the list says why.
        doc.selectPart(c, 1);
        dock.deleteAction()->trigger();
        doc.selectPart(c, 0);
        dock.deleteAction()->trigger();
        QCOMPARE(int(doc.body(c).shape.parts.size()), 1);
        auto* message = dock.findChild<QLabel*>("sceneTreeMessage");
        QVERIFY2(message->text().contains("at least one part"), qPrintable(message->text()));
        // Renamed in its row: one undo step.
        QVERIFY(model->setData(model->partIndex(t, 0), "leg"));
        QCOMPARE(doc.body(t).shape.parts[0].name, std::string("leg"));
        doc.undoStack()->undo();
        QCOMPARE(doc.body(t).shape.parts[0].name, std::string("left"));
    }

    // A selected part row stays on its body when a body before it goes and comes back (Qt
    // moves only top-level rows' kept indexes), and on its part when undo changes the number
    // of parts under it.
    void selectedPartRowFollowsItsBody() {
        Document doc;
        SceneTreeDock dock(&doc, nullptr);
        QAbstractItemModelTester tester(dock.model(), QAbstractItemModelTester::FailureReportingMode::QtTest);
        const int c = doc.addBody(crate());
        const int t = doc.addBody(table());
        doc.undoStack()->clear();
        QItemSelectionModel* sm = dock.view()->selectionModel();
        auto selectedPart = [&]() -> std::pair<int, int> {
            const QModelIndexList rows = sm->selectedRows();
            if (rows.size() != 1) return {-1, -1};
            return {SceneTreeModel::bodyOf(rows[0]), SceneTreeModel::partOf(rows[0])};
        };
        doc.selectPart(t, 1);
        QCOMPARE(selectedPart(), std::make_pair(t, 1));
        doc.removeBodies({c});  // the table moves up a row; its part stays selected
        QCOMPARE(doc.selection(), QList<int>{t - 1});
        QCOMPARE(selectedPart(), std::make_pair(t - 1, 1));
        doc.undoStack()->undo();  // and down again
        QCOMPARE(doc.selection(), QList<int>{t});
        QCOMPARE(selectedPart(), std::make_pair(t, 1));
        QVERIFY(dock.model()->flags(sm->selectedRows().value(0)) & Qt::ItemIsSelectable);
        // Undo of Add Part while part 0 is selected: the rows are made again, the part stays.
        QString why;
        QCOMPARE(doc.addPart(t, ShapeType::Box, &why), 2);
        doc.selectPart(t, 0);
        doc.undoStack()->undo();
        QCOMPARE(doc.selectedPart(), 0);
        QCOMPARE(selectedPart(), std::make_pair(t, 0));
    }

    // The Part group shows the selected part; its edits go to that part (one step a field),
    // refused values name the part's field, and the body's computed mass properties follow.
    void panelEditsThePart() {
        Document doc;
        PropertyDock dock(&doc);
        const int t = doc.addBody(table());
        doc.setSelection({t});
        auto* group = dock.findChild<QGroupBox*>("partGroup");
        QVERIFY(group->isHidden());
        doc.selectPart(t, 1);
        QVERIFY(!group->isHidden());
        QVERIFY2(group->title().contains("right"), qPrintable(group->title()));
        auto* x = test::field<PropertySpinBox>(dock, "part.position.x");
        QCOMPARE(x->value(), 0.5);
        x->setValue(0.9);
        QCOMPARE(doc.body(t).shape.parts[1].position.x(), 0.9);
        QCOMPARE(doc.body(t).shape.parts[0].position.x(), -0.5);
        // The centre of mass shown is the parts' (equal boxes: halfway, (0.9 - 0.5) / 2).
        auto* com = test::field<VectorEdit>(dock, "center_of_mass");
        QVERIFY2(std::abs(com->value().x() - 0.2) < 1e-9, qPrintable(QString::number(com->value().x())));
        // Its own density, ticked, starts at its share of the body's 6 kg (75 kg/m³ for the
        // 0.04 m³ of each box): nothing moves. At 100 kg/m³ it weighs 4 kg, the other part
        // the 2 kg left: the centre goes to (4 * 0.9 - 2 * 0.5) / 6.
        auto* density = test::field<PropertySpinBox>(dock, "part.density");
        QVERIFY(!density->isEnabled());
        QVERIFY(std::abs(density->value() - 75.0) < 1e-9);
        test::field<QCheckBox>(dock, "part.density.own")->setChecked(true);
        QVERIFY(std::abs(doc.body(t).shape.parts[1].density.value_or(0) - 75.0) < 1e-9);
        QVERIFY(std::abs(com->value().x() - 0.2) < 1e-9);
        QVERIFY(density->isEnabled());
        density->setValue(100.0);
        QVERIFY2(std::abs(com->value().x() - 2.6 / 6.0) < 1e-9,
                 qPrintable(QString::number(com->value().x())));
        // More than the body's mass in one part is refused, saying so.
        density->setValue(200.0);
        QCOMPARE(doc.body(t).shape.parts[1].density.value_or(0), 100.0);
        QVERIFY2(!dock.fieldError("part.density").isEmpty(), "no message");
        // A negative half extent is refused naming the part's field; nothing changes.
        const BodyDesc before = doc.body(t);
        test::field<PropertySpinBox>(dock, "part.shape.half_extents.y")->setValue(-1.0);
        QVERIFY(doc.body(t) == before);
        const QString error = dock.fieldError("part.shape.half_extents");
        QVERIFY2(error.contains("parts[1]"), qPrintable(error));
        // The part's name from the panel.
        auto* name = test::field<QLineEdit>(dock, "part.name");
        name->setText("strut");
        emit name->editingFinished();
        QCOMPARE(doc.body(t).shape.parts[1].name, std::string("strut"));
        QVERIFY(group->title().contains("strut"));
    }

    // Handles move a part along a world axis and turn it about a world axis through its own
    // origin, in a turned body; the body does not move.
    void handlesMoveAndTurnThePartInATurnedBody() {
        BodyDesc b = table();
        b.orientation = kTurned;
        const Vec3 axis = Vec3(0.3, -1, 0.2).normalized();
        const Vec3 before = handles::partOrigin(b, 1);
        const BodyDesc moved = handles::partMoved(b, 1, axis, 0.35);
        QVERIFY((handles::partOrigin(moved, 1) - (before + 0.35 * axis)).norm() < 1e-14);
        QVERIFY(moved.position == b.position && moved.orientation.coeffs() == b.orientation.coeffs());
        QVERIFY(moved.shape.parts[0] == b.shape.parts[0]);
        const BodyDesc turned = handles::partRotated(b, 1, axis, 0.8);
        QVERIFY((handles::partOrigin(turned, 1) - before).norm() < 1e-14);
        const Quat world = kTurned * turned.shape.parts[1].orientation;
        const Quat expected = Quat(Eigen::AngleAxisd(0.8, axis)) * kTurned * b.shape.parts[1].orientation;
        QVERIFY(world.angularDistance(expected) < 1e-12);
    }
};

QTEST_MAIN(TestParts)
#include "tst_parts.moc"
