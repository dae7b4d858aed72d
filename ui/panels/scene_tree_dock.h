// The scene tree dock: the bodies in a list (a compound's parts under it) with extended
// selection shared with the document (and so with the viewport and the property panel),
// and the actions that add, duplicate, delete and rename bodies and parts, in a tool bar
// and a context menu.
#pragma once

#include <tumble/scene.h>

#include <QDockWidget>
#include <QMap>

#include <functional>

class QAction;
class QLabel;
class QMenu;
class QTreeView;

namespace tumble::ui {

class Document;
class SceneTreeModel;
class JointList;

class SceneTreeDock : public QDockWidget {
    Q_OBJECT
public:
    SceneTreeDock(Document* doc, QWidget* parent);

    SceneTreeModel* model() const { return model_; }
    QTreeView* view() const { return view_; }

    /// The actions, for the main window's menus. Add > Mesh... emits importMeshRequested.
    QMenu* addMenu() const { return addMenu_; }
    QAction* addBodyAction(ShapeType type) const { return addActions_.value(type); }
    /// Add Part: one action per shape, for the one selected body (document/part_edits.h).
    QMenu* partMenu() const { return partMenu_; }
    QAction* addPartAction(ShapeType type) const { return partActions_.value(type); }
    QAction* duplicateAction() const { return duplicate_; }
    /// Split into Convex Parts…: the one selected mesh body's split, in a dialog
    /// (import/convex_split_dialog.h).
    QAction* splitAction() const { return split_; }
    QAction* groupAction() const { return group_; }
    QAction* ungroupAction() const { return ungroup_; }
    QAction* deleteAction() const { return delete_; }
    QAction* renameAction() const { return rename_; }
    /// Add Joint: one action per joint type, for the selected bodies (joint_presets.h);
    /// enabled for one or two selected bodies.
    QMenu* jointMenu() const { return jointMenu_; }
    QAction* addJointAction(JointType type) const { return jointActions_.value(type); }

    /// Adds a joint of that type for the selection (joint_presets.h), or says in the dock
    /// why it cannot.
    void addJoint(JointType type);

    /// Adds a body of that shape with the editor's defaults (body_presets.h) and selects it,
    /// placed by the placement set (the main window's: on the surface under the view), else
    /// above everything else. A mesh emits importMeshRequested instead: the mesh comes from a file.
    void addBody(ShapeType type);
    void setPlacement(std::function<BodyDesc(const BodyDesc&)> place) { place_ = std::move(place); }

    /// Copies of the selected bodies, each moved straight up above everything else (a copy
    /// in the same place would start inside its original), as one undo step; selects them.
    void duplicateSelection();

signals:
    void importMeshRequested();

private:
    void selectionFromDocument();
    void selectionFromView();
    void updateActions();
    void showMessage(const QString& text);

    Document* doc_;
    std::function<BodyDesc(const BodyDesc&)> place_;
    SceneTreeModel* model_;
    QTreeView* view_;
    JointList* joints_;
    QLabel* message_;
    QMenu* addMenu_;
    QMap<ShapeType, QAction*> addActions_;
    QMenu* partMenu_;
    QMap<ShapeType, QAction*> partActions_;
    QMenu* jointMenu_;
    QMap<JointType, QAction*> jointActions_;
    QAction* duplicate_;
    QAction* split_;
    QAction* group_;
    QAction* ungroup_;
    QAction* delete_;
    QAction* rename_;
    // Set while the selection is being copied one way, or while rows move: the other
    // direction then stays quiet (no feedback loop, no stale row numbers).
    bool syncing_ = false;
};

}  // namespace tumble::ui
