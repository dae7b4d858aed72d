// Choosing a file in an open QFileDialog (Qt's own, non-native) as a user typing its path
// would. QFileDialog::selectFile leaves the file name field as it is while that field has
// the keyboard focus (Qt 6.4), and whether it has depends on when the window became
// active: tests that chose by selectFile and pressed Open hung at random, the dialog open
// with an empty name (tst_main_window's import, 2026-12-06).
#pragma once

#include <QFileDialog>
#include <QLineEdit>
#include <QMetaObject>
#include <QString>

namespace tumble::test {

/// Puts `path` in the dialog's file name field (and selects it), then accepts, as Open or
/// Save does.
inline void chooseFile(QFileDialog* dialog, const QString& path) {
    dialog->selectFile(path);
    if (auto* name = dialog->findChild<QLineEdit*>(QStringLiteral("fileNameEdit"))) name->setText(path);
    QMetaObject::invokeMethod(dialog, "accept");
}

}  // namespace tumble::ui::test
