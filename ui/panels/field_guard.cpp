#include "panels/field_guard.h"

#include <QAbstractScrollArea>
#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QFocusEvent>
#include <QKeyEvent>
#include <QLineEdit>
#include <QScrollBar>
#include <QWheelEvent>

namespace tumble::ui {

namespace {

class WheelGuard : public QObject {
public:
    using QObject::QObject;

protected:
    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() == QEvent::ShortcutOverride && watched->isWidgetType())
            return passUndoKeys(static_cast<QWidget*>(watched), static_cast<QKeyEvent*>(event));
        if (event->type() != QEvent::Wheel || !watched->isWidgetType()) return false;
        auto* w = static_cast<QWidget*>(watched);
        // The field itself, or a part of it (a spin box's line edit).
        QWidget* field = w;
        while (field && !isField(field)) field = field->parentWidget();
        if (!field || field->hasFocus() || field->isAncestorOf(QApplication::focusWidget())) return false;
        auto* wheel = static_cast<QWheelEvent*>(event);
        if (wheel->modifiers() & Qt::ControlModifier) return false;
        // The scroll area that holds the field (not one inside it, such as a combo's list).
        QWidget* up = field->parentWidget();
        while (up && !qobject_cast<QAbstractScrollArea*>(up)) up = up->parentWidget();
        auto* area = qobject_cast<QAbstractScrollArea*>(up);
        if (!area) return false;
        QScrollBar* bar = wheel->angleDelta().y() != 0 ? area->verticalScrollBar() : area->horizontalScrollBar();
        QWheelEvent forwarded(bar->mapFromGlobal(wheel->globalPosition()), wheel->globalPosition(),
                              wheel->pixelDelta(), wheel->angleDelta(), wheel->buttons(), wheel->modifiers(),
                              wheel->phase(), wheel->inverted(), wheel->source());
        QApplication::sendEvent(bar, &forwarded);
        return true;  // the field's value stays
    }

private:
    // Filtered without being accepted, the override leaves the keys to the window's
    // shortcuts (Edit > Undo, Edit > Redo).
    static bool passUndoKeys(QWidget* w, QKeyEvent* key) {
        if (!key->matches(QKeySequence::Undo) && !key->matches(QKeySequence::Redo)) return false;
        for (QWidget* up = w; up; up = up->parentWidget())
            if (qobject_cast<QAbstractSpinBox*>(up)) return true;  // a number field
        auto* text = qobject_cast<QLineEdit*>(w);
        return text && !text->isReadOnly() && !text->isModified();  // typing not yet given: its own undo
    }

    static bool isField(const QWidget* w) {
        return qobject_cast<const QAbstractSpinBox*>(w) || qobject_cast<const QComboBox*>(w) ||
               (qobject_cast<const QAbstractSlider*>(w) && !qobject_cast<const QScrollBar*>(w));
    }
};

class LeaveWatch : public QObject {
public:
    LeaveWatch(QObject* parent, std::function<void()> left) : QObject(parent), left_(std::move(left)) {}

protected:
    bool eventFilter(QObject*, QEvent* event) override {
        if (event->type() == QEvent::FocusOut) {
            const Qt::FocusReason why = static_cast<QFocusEvent*>(event)->reason();
            if (why != Qt::PopupFocusReason && why != Qt::ActiveWindowFocusReason) left_();
        }
        return false;
    }

private:
    std::function<void()> left_;
};

}  // namespace

void whenFieldLeft(QWidget* editor, std::function<void()> left) {
    auto* watch = new LeaveWatch(editor, std::move(left));
    QList<QWidget*> fields = editor->findChildren<QWidget*>();
    fields.prepend(editor);
    for (QWidget* w : fields)
        if (w->focusPolicy() != Qt::NoFocus) w->installEventFilter(watch);
}

void installFieldGuard() {
    static WheelGuard* guard = nullptr;
    if (guard || !qApp) return;
    guard = new WheelGuard(qApp);
    qApp->installEventFilter(guard);
}

}  // namespace tumble::ui
