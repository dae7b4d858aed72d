// An animated body's keys in the property panel (issue 50 item 2): a list in time order to
// add to and remove from, and an editor for the current key (time, position, rotation in
// degrees). Every change is offered to the owner as the whole new list (keysEdited); the
// owner validates it, and either stores it in the document or puts the old list back with
// setKeys. A key whose time is moved past another's is put in its place in time order.
#pragma once

#include <tumble/scene.h>

#include <QWidget>

#include <functional>
#include <vector>

class QListWidget;
class QPushButton;

namespace tumble::ui {

class PropertySpinBox;
class VectorEdit;

class KeysEdit : public QWidget {
    Q_OBJECT
public:
    explicit KeysEdit(QWidget* parent = nullptr);

    /// Shows `keys` (signals blocked), keeping the current entry when it still exists.
    void setKeys(const std::vector<BodyKey>& keys);
    const std::vector<BodyKey>& keys() const { return keys_; }
    int currentIndex() const;
    void setCurrentIndex(int index);

    /// What the Add and Remove buttons do: a key 1 s after the last, where the last is; the
    /// current key, unless it is the only one.
    void addKey();
    void removeCurrent();

signals:
    /// The list the user asked for. `field` names what changed, e.g. "keys[1].time"; the
    /// same field edited again in a row is one undo step.
    void keysEdited(const std::vector<BodyKey>& keys, const QString& text, const QString& field);
    void editingFinished();

private:
    void showCurrent();
    void edit(const QString& field, const QString& text, const std::function<void(BodyKey&)>& change);
    static QString summary(const BodyKey& k);

    std::vector<BodyKey> keys_;
    QListWidget* list_ = nullptr;
    QPushButton* add_ = nullptr;
    QPushButton* remove_ = nullptr;
    QWidget* editor_ = nullptr;
    PropertySpinBox* time_ = nullptr;
    VectorEdit* position_ = nullptr;
    VectorEdit* rotation_ = nullptr;
};

}  // namespace tumble::ui
