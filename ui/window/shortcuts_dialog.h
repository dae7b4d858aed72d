// Help > Keyboard Shortcuts (F1): every key of the window, read from the menus' actions
// themselves (so the list cannot go stale): the menu, the command and its keys. An item
// whose key belongs to a part of the window (the viewport's F, A, W, E) shows it after a
// tab in its text, and is listed the same way.
#pragma once

#include <QDialog>
#include <QList>
#include <QString>

class QMenuBar;

namespace tumble::ui {

struct ShortcutRow {
    QString menu, command, keys;
};

/// The rows of every menu of `bar` (submenus as "View > Overlays"), in menu order.
QList<ShortcutRow> shortcutRows(const QMenuBar* bar);

class ShortcutsDialog : public QDialog {
    Q_OBJECT
public:
    /// `rows`: shortcutRows of the window's menu bar and the keys no menu holds (the
    /// viewport's camera keys).
    ShortcutsDialog(const QList<ShortcutRow>& rows, QWidget* parent = nullptr);
};

}  // namespace tumble::ui
