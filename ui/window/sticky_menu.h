// A menu whose check boxes can be ticked one after another: a checkable item toggles where
// it is and the menu stays open (the View menu's overlays took three openings for three).
// Other items act and close the menu as usual.
#pragma once

#include <QMenu>

namespace tumble::ui {

class StickyMenu : public QMenu {
    Q_OBJECT
public:
    explicit StickyMenu(const QString& title, QWidget* parent = nullptr);

protected:
    void mouseReleaseEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
};

}  // namespace tumble::ui
