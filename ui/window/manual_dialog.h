// Help > Manual: the user's pages (docs/editor.md, scene-format.md, export.md, sweeps.md,
// built into the program) in a browser window beside the editor. Links between them
// follow; a link to a page that is not built in says where to find it.
#pragma once

#include <QDialog>

class QTextBrowser;

namespace tumble::ui {

class ManualDialog : public QDialog {
    Q_OBJECT
public:
    explicit ManualDialog(QWidget* parent = nullptr);
    QTextBrowser* browser() const { return browser_; }

private:
    QTextBrowser* browser_;
};

}  // namespace tumble::ui
