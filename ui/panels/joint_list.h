// The scene's joints, listed under the bodies in the Scene dock: name, type and the bodies
// each joins. Clicking one selects it (the property panel then shows the joint); the list
// follows the document (adds, edits, deletes, undo, a body renamed).
#pragma once

#include <QWidget>

class QLabel;
class QTreeWidget;

namespace tumble::ui {

class Document;

class JointList : public QWidget {
    Q_OBJECT
public:
    enum Column { NameColumn, TypeColumn, BodiesColumn, ColumnCount };
    explicit JointList(Document* doc, QWidget* parent = nullptr);
    QTreeWidget* view() const { return view_; }

private:
    void rebuild();
    void selectionFromDocument();

    Document* doc_;
    QLabel* title_;
    QTreeWidget* view_;
    bool syncing_ = false;
};

}  // namespace tumble::ui
