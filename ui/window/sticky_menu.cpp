#include "window/sticky_menu.h"

#include <QAction>
#include <QKeyEvent>
#include <QMouseEvent>

namespace tumble::ui {

StickyMenu::StickyMenu(const QString& title, QWidget* parent) : QMenu(title, parent) {}

void StickyMenu::mouseReleaseEvent(QMouseEvent* event) {
    QAction* a = actionAt(event->position().toPoint());
    if (event->button() == Qt::LeftButton && a && a->isCheckable() && a->isEnabled()) {
        a->trigger();
        event->accept();
        return;
    }
    QMenu::mouseReleaseEvent(event);
}

void StickyMenu::keyPressEvent(QKeyEvent* event) {
    QAction* a = activeAction();
    const bool press = event->key() == Qt::Key_Space || event->key() == Qt::Key_Return || event->key() == Qt::Key_Enter;
    if (press && a && a->isCheckable() && a->isEnabled()) {
        a->trigger();
        event->accept();
        return;
    }
    QMenu::keyPressEvent(event);
}

}  // namespace tumble::ui
