// Issue 50 item 3 in the editor: a body's Collision group in the Properties, the Collision
// Groups dialog's names and matrix applied as one undo step (bodies follow a renamed group,
// go to "default" when theirs is removed), and the pairs kept apart following a body's
// rename and delete, as a user would meet them.
#include "document/document.h"
#include "document/grouping.h"
#include "panel_test_util.h"
#include "panels/collision_groups_dialog.h"
#include "panels/property_dock.h"

#include <tumble/model.h>

#include <QComboBox>
#include <QTableWidget>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;
using namespace tumble::test;

namespace {

BodyDesc ball(const std::string& name, double x) {
    BodyDesc b;
    b.name = name;
    b.shape.type = ShapeType::Sphere;
    b.shape.radius = 0.2;
    b.mass = 1.0;
    b.position = Vec3(x, 1, 0);
    return b;
}

}  // namespace

class TestCollisionGroupsUi : public QObject {
    Q_OBJECT

private slots:
    // The panel lists the scene's groups; choosing one is one undo step.
    void aBodysGroupIsChosenInTheProperties() {
        Document doc;
        SceneDesc s;
        s.settings.collisionGroups = {"debris", "fence"};
        s.bodies = {ball("a", 0), ball("b", 1)};
        doc.replaceScene(s, "", false);
        PropertyDock dock(&doc);
        doc.setSelection({0});
        auto* combo = field<QComboBox>(dock, "collision_group");
        QCOMPARE(combo->count(), 3);
        QCOMPARE(combo->itemText(0), QString("default"));
        QCOMPARE(combo->currentText(), QString("default"));
        choose(dock, "collision_group", "fence");
        QCOMPARE(doc.body(0).collisionGroup, std::string("fence"));
        QCOMPARE(doc.undoStack()->count(), 1);
        doc.undoStack()->undo();
        QCOMPARE(doc.body(0).collisionGroup, std::string("default"));
    }

    // The dialog: a group added and renamed, one pair unticked in the matrix, a group
    // removed; OK is one undo step, the scene compiles and keeps the pair apart.
    void theDialogEditsGroupsAsOneStep() {
        Document doc;
        SceneDesc s;
        s.settings.collisionGroups = {"debris", "old"};
        s.bodies = {ball("a", 0), ball("b", 1), ball("c", 2)};
        s.bodies[0].collisionGroup = "debris";
        s.bodies[1].collisionGroup = "old";
        doc.replaceScene(s, "", false);
        CollisionGroupsDialog dialog(&doc);
        GroupTable& t = dialog.table();
        QCOMPARE(int(t.names.size()), 3);
        t.names[1] = "pebbles";  // renamed: body a follows
        t.remove(2);             // "old" goes: body b to default
        t.add("fence");
        dialog.rebuild();
        auto* matrix = field<QTableWidget>(dialog, "groupMatrix");
        QCOMPARE(matrix->rowCount(), 3);
        // Untick pebbles (row 1) against fence (row 2), as a click on the box does.
        matrix->item(2, 1)->setCheckState(Qt::Unchecked);
        QVERIFY(!t.collides[1][2] && !t.collides[2][1]);
        QVERIFY(matrix->item(1, 2)->flags() == Qt::NoItemFlags);  // the upper half is the lower's mirror
        QVERIFY(dialog.apply());
        QCOMPARE(doc.undoStack()->count(), 1);
        QCOMPARE(doc.scene().settings.collisionGroups, (std::vector<std::string>{"pebbles", "fence"}));
        QCOMPARE(doc.scene().settings.groupsApart.size(), size_t(1));
        QCOMPARE(doc.scene().settings.groupsApart[0], (std::array<std::string, 2>{"pebbles", "fence"}));
        QCOMPARE(doc.body(0).collisionGroup, std::string("pebbles"));
        QCOMPARE(doc.body(1).collisionGroup, std::string("default"));
        const Model m = compile(doc.scene());
        QVERIFY(m.filtered);
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().settings.collisionGroups, (std::vector<std::string>{"debris", "old"}));
        QCOMPARE(doc.body(1).collisionGroup, std::string("old"));
    }

    // Two groups of one name are refused on the dialog, and nothing is applied.
    void aRepeatedNameIsRefused() {
        Document doc;
        SceneDesc s;
        s.bodies = {ball("a", 0)};
        doc.replaceScene(s, "", false);
        CollisionGroupsDialog dialog(&doc);
        dialog.table().add("x");
        dialog.table().add("x");
        QVERIFY(!dialog.apply());
        QCOMPARE(doc.undoStack()->count(), 0);
    }

    // Edit > Keep Selected Apart: every two of the selected bodies, one undo step; Let
    // Selected Collide takes them away; the scene compiles with the pairs filtered.
    void selectedBodiesAreKeptApart() {
        Document doc;
        SceneDesc s;
        s.bodies = {ball("a", 0), ball("b", 1), ball("c", 2)};
        doc.replaceScene(s, "", false);
        QVERIFY(doc.keepApart({0, 1, 2}, true));
        QCOMPARE(doc.scene().noCollide.size(), size_t(3));
        QCOMPARE(doc.undoStack()->count(), 1);
        QVERIFY(!doc.keepApart({0, 1}, true));  // already so: nothing
        const Model m = compile(doc.scene());
        QVERIFY(m.filtered && !m.mayCollide(0, 2));
        QVERIFY(doc.keepApart({1, 0}, false));
        QCOMPARE(doc.scene().noCollide.size(), size_t(2));
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().noCollide.size(), size_t(3));
    }

    // A body renamed takes its pairs kept apart along; a body deleted takes them away; each
    // undone with its edit. Grouping two bodies gives the group their pairs.
    void pairsKeptApartFollowTheirBodies() {
        Document doc;
        SceneDesc s;
        s.bodies = {ball("a", 0), ball("b", 1), ball("c", 2)};
        s.noCollide = {{"a", "b"}, {"b", "c"}};
        doc.replaceScene(s, "", false);
        BodyDesc renamed = doc.body(1);
        renamed.name = "bee";
        doc.setBody(1, renamed, "Rename");
        QCOMPARE(doc.scene().noCollide[0], (std::array<std::string, 2>{"a", "bee"}));
        QCOMPARE(doc.undoStack()->count(), 1);
        doc.removeBodies({2});
        QCOMPARE(doc.scene().noCollide.size(), size_t(1));
        compile(doc.scene());  // still a valid scene
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().noCollide.size(), size_t(2));
        doc.undoStack()->undo();
        QCOMPARE(doc.scene().noCollide[0], (std::array<std::string, 2>{"a", "b"}));
        std::string why;
        const auto grouped = groupBodies(doc.scene(), {0, 1}, &why);
        QVERIFY2(grouped, why.c_str());
        QCOMPARE(grouped->scene.noCollide.size(), size_t(1));  // (a, b) inside the group goes
        QCOMPARE(grouped->scene.noCollide[0][1], std::string("c"));
        compile(grouped->scene);
    }
};

QTEST_MAIN(TestCollisionGroupsUi)
#include "tst_collision_groups_ui.moc"
