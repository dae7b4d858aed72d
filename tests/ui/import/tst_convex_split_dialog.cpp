// Split into Convex Parts (issue 49 item 4): the split is made in the background as the
// dialog opens, pictured part by part in colours with its figures, and applied to the body
// as one undo step with the very parts shown (nothing made again); a mesh that bounds no
// solid says why; a dialog closed while it splits stops the split.
#include "../helpers/choose_file.h"
#include "document/document.h"
#include "import/convex_parts_preview.h"
#include "import/convex_split_dialog.h"
#include "import/import_options_dialog.h"
#include "panels/property_dock.h"
#include "window/main_window.h"

#include "../panels/panel_test_util.h"

#include "../../engine/test_meshes.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QFileDialog>
#include <QSpinBox>
#include <QTimer>
#include <QUndoStack>
#include <QtTest>

using namespace tumble;
using namespace tumble::ui;

namespace {

int addMeshBody(Document& doc, TriangleMesh mesh) {
    BodyDesc b;
    b.name = "bracket";
    b.shape.type = ShapeType::Mesh;
    b.shape.file = "bracket.obj";
    b.shape.meshData = std::make_shared<const TriangleMesh>(std::move(mesh));
    b.density = 1000.0;
    b.position = Vec3(0, 1, 0);
    const int i = doc.addBody(b);
    doc.undoStack()->clear();
    return i;
}

}  // namespace

class TestConvexSplitDialog : public QObject {
    Q_OBJECT
private slots:
    // A U-bracket splits into its three boxes; the picture shows all three; Apply gives the
    // body those parts (the same object) in one undo step, and undo gives its hull back.
    void aBracketIsSplitShownAndApplied() {
        Document doc;
        const int i = addMeshBody(doc, test::uBracket(1.0, 0.2, 0.6, 0.4));
        ConvexSplitDialog dialog(&doc, i);
        dialog.show();
        QTRY_VERIFY_WITH_TIMEOUT(!dialog.running(), 60000);
        QVERIFY2(dialog.result(), qPrintable(dialog.status()));
        QCOMPARE(int(dialog.result()->parts.size()), 3);
        QVERIFY2(dialog.status().startsWith("3 convex parts"), qPrintable(dialog.status()));
        QVERIFY(std::abs(dialog.result()->partsVolume / dialog.result()->meshVolume - 1.0) < 1e-9);
        dialog.preview()->grab();  // paints it
        QCOMPARE(dialog.preview()->partsDrawn(), 3);
        const auto shown = dialog.result();
        dialog.apply();
        const ShapeDesc& s = doc.body(i).shape;
        QCOMPARE(s.collision, MeshCollision::ConvexParts);
        QCOMPARE(s.convexParts.get(), shown.get());
        QCOMPARE(doc.undoStack()->count(), 1);
        QCOMPARE(doc.undoStack()->undoText(), QString("Split bracket into 3 convex parts"));
        doc.undoStack()->undo();
        QCOMPARE(doc.body(i).shape.collision, MeshCollision::ConvexHull);
    }

    // Fewer parts asked for: made again with them; the figures say the tolerance was not met.
    void splitAgainWithOtherOptions() {
        Document doc;
        const int i = addMeshBody(doc, test::uBracket(1.0, 0.2, 0.6, 0.4));
        ConvexSplitDialog dialog(&doc, i);
        QTRY_VERIFY_WITH_TIMEOUT(!dialog.running(), 60000);
        dialog.maxPartsField()->setValue(2);
        dialog.split();
        QTRY_VERIFY_WITH_TIMEOUT(!dialog.running(), 60000);
        QVERIFY(dialog.result());
        QCOMPARE(int(dialog.result()->parts.size()), 2);
        QVERIFY2(dialog.status().contains("Max parts was reached"), qPrintable(dialog.status()));
        dialog.apply();
        QCOMPARE(doc.body(i).shape.maxParts, 2);
    }

    // Convex parts chosen in the property panel for one mesh body: the dialog opens, and
    // what it applies is the body's collision.
    void thePanelsCollisionChoiceOpensIt() {
        Document doc;
        PropertyDock dock(&doc);
        const int i = addMeshBody(doc, test::uBracket(1.0, 0.2, 0.6, 0.4));
        doc.setSelection({i});
        bool opened = false;
        QTimer::singleShot(0, [&] {
            auto* d = qobject_cast<ConvexSplitDialog*>(QApplication::activeModalWidget());
            if (!d) return;
            opened = true;
            for (int k = 0; k < 3000 && d->running(); ++k) QTest::qWait(20);
            d->apply();
        });
        test::choose(dock, "shape.collision", "Convex parts");
        QVERIFY(opened);
        QCOMPARE(doc.body(i).shape.collision, MeshCollision::ConvexParts);
        QVERIFY(doc.body(i).shape.convexParts);
        QCOMPARE(int(doc.body(i).shape.convexParts->parts.size()), 3);
        QCOMPARE(doc.undoStack()->count(), 1);
    }

    // File > Import Mesh with Convex parts chosen: the body comes in, then the Split dialog
    // opens on it, and what it applies is the new body's collision (the mug sample's mesh).
    void importWithConvexPartsSplitsTheNewBody() {
        MainWindow w;
        w.show();
        QVERIFY(QTest::qWaitForWindowExposed(&w));
        const int before = w.document()->bodyCount();
        QAction* import = nullptr;
        for (QAction* a : w.findChildren<QAction*>())
            if (a->text() == "&Import Mesh...") import = a;
        QVERIFY(import);
        bool chose = false, split = false;
        QTimer poll;
        poll.setInterval(20);
        connect(&poll, &QTimer::timeout, &w, [&] {
            QWidget* modal = QApplication::activeModalWidget();
            if (auto* files = qobject_cast<QFileDialog*>(modal)) {
                tumble::test::chooseFile(files, TUMBLE_SCENES_DIR "/../meshes/mug.obj");
            } else if (auto* options = qobject_cast<ImportOptionsDialog*>(modal); options && !chose) {
                chose = true;
                auto* collision = options->findChild<QComboBox*>("collision");
                collision->setCurrentIndex(collision->findData(int(MeshCollision::ConvexParts)));
                options->accept();
            } else if (auto* dialog = qobject_cast<ConvexSplitDialog*>(modal); dialog && !dialog->running()) {
                split = true;
                dialog->apply();
            }
        });
        poll.start();
        import->trigger();
        QTRY_VERIFY_WITH_TIMEOUT(split, 60000);
        poll.stop();
        QCOMPARE(w.document()->bodyCount(), before + 1);
        const ShapeDesc& s = w.document()->body(before).shape;
        QCOMPARE(s.collision, MeshCollision::ConvexParts);
        QVERIFY(s.convexParts && s.convexParts->parts.size() > 1);
    }

    // A bracket with a face left out: its hole is filled and it splits as the closed one,
    // and the status says so.
    void anOpenMeshIsFilledAndSplit() {
        Document doc;
        TriangleMesh open = test::uBracket(1.0, 0.2, 0.6, 0.4);
        open.triangles.pop_back();
        open.triangles.pop_back();
        const int i = addMeshBody(doc, open);
        ConvexSplitDialog dialog(&doc, i);
        QTRY_VERIFY_WITH_TIMEOUT(!dialog.running(), 60000);
        QVERIFY(dialog.result());
        QCOMPARE(int(dialog.result()->parts.size()), 3);
        QVERIFY2(dialog.status().contains("1 hole filled"), qPrintable(dialog.status()));
    }

    // A fin (a triangle on an edge two others already share) cannot be closed: the dialog
    // says why and applies nothing.
    void anUnclosableMeshSaysWhy() {
        Document doc;
        TriangleMesh open = test::uBracket(1.0, 0.2, 0.6, 0.4);
        const auto edge = open.triangles.front();
        open.vertices.push_back(Vec3(5, 5, 5));
        open.triangles.push_back({edge[0], edge[1], static_cast<int>(open.vertices.size()) - 1});
        const int i = addMeshBody(doc, open);
        ConvexSplitDialog dialog(&doc, i);
        QTRY_VERIFY_WITH_TIMEOUT(!dialog.running(), 60000);
        QVERIFY(!dialog.result());
        QVERIFY2(dialog.status().contains("not closed"), qPrintable(dialog.status()));
        dialog.apply();  // nothing to apply
        QCOMPARE(doc.undoStack()->count(), 0);
    }

    // Closed while it splits a 10 000-triangle torus (seconds of work): the split stops at
    // its next step and the dialog goes (this returning at all is the test: a split left
    // running would hold the destructor for its whole length, or crash on a dialog gone).
    void closingStopsTheSplit() {
        Document doc;
        const int i = addMeshBody(doc, test::torus(1.0, 0.3, 100, 50));
        auto* dialog = new ConvexSplitDialog(&doc, i);
        QVERIFY(dialog->running());
        QTest::qWait(100);
        delete dialog;
        QCOMPARE(doc.undoStack()->count(), 0);
    }
};

QTEST_MAIN(TestConvexSplitDialog)
#include "tst_convex_split_dialog.moc"
