// Simulation > Collision Groups (issue 50 item 3): the scene's collision groups, named,
// added, renamed and removed, and the table of which groups collide, ticks in a matrix as
// in a layer matrix. OK applies it all as one undo step: a renamed group's bodies follow
// it, a removed group's bodies go to "default".
#pragma once

#include <tumble/scene.h>

#include <QDialog>

#include <string>
#include <vector>

class QTableWidget;
class QListWidget;
class QLabel;

namespace tumble::ui {

class Document;

/// The groups as the dialog edits them: each one's name now and the name it had in the
/// scene ("" for a group added here), and which pairs collide (symmetric).
struct GroupTable {
    std::vector<std::string> names, was;
    std::vector<std::vector<char>> collides;

    static GroupTable of(const SceneDesc& scene);
    /// The scene with these groups: settings.collision_groups and groups_apart, and each
    /// body's group renamed with its group or "default" when its group went. An empty or
    /// repeated name: nothing, with the reason in `why`.
    bool applyTo(SceneDesc& scene, std::string* why) const;
    void add(const std::string& name);
    void remove(int group);  // never "default" (0)
};

class CollisionGroupsDialog : public QDialog {
    Q_OBJECT
public:
    CollisionGroupsDialog(Document* doc, QWidget* parent = nullptr);
    GroupTable& table() { return table_; }
    /// Applies the table to the document as one undo step; false (and a message on the
    /// dialog) when a name is empty or repeated.
    bool apply();
    void rebuild();  // the list and the matrix from the table

private:
    Document* doc_;
    GroupTable table_;
    QListWidget* list_;
    QTableWidget* matrix_;
    QLabel* problem_;
};

}  // namespace tumble::ui
