#include "panels/property_spin_box.h"

#include <QContextMenuEvent>
#include <QFontMetrics>
#include <QFocusEvent>
#include <QKeyEvent>
#include <QLineEdit>
#include <QLocale>
#include <QMenu>
#include <QSignalBlocker>
#include <QStyle>
#include <QStyleOptionSpinBox>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::ui {

PropertySpinBox::PropertySpinBox(QWidget* parent) : QDoubleSpinBox(parent) {
    // Decimals only limit the rounding QDoubleSpinBox applies to every value; the text is
    // ours (textFromValue), so keep them high enough to never change a stored number visibly.
    setDecimals(12);
    setRange(-1e12, 1e12);
    setKeyboardTracking(false);  // typing commits on Enter or focus out; arrows/wheel scrub
    setAccelerated(true);
    setCorrectionMode(QAbstractSpinBox::CorrectToPreviousValue);
    connect(this, &QDoubleSpinBox::valueChanged, this, [this] { mixed_ = false; });
    // Typing the number the box holds under "—" changes no value, but it is still an edit:
    // the user wants every selected body to take it.
    connect(this, &QAbstractSpinBox::editingFinished, this, [this] {
        if (!mixed_ || stripped(text()) == mixedText()) return;
        bool ok = false;
        locale().toDouble(stripped(text()), &ok);
        if (!ok) return;
        mixed_ = false;
        emit valueChanged(value());
    });
}

void PropertySpinBox::showValue(double value) {
    const QSignalBlocker block(this);
    mixed_ = false;
    setValue(value);
    const bool special = !specialValueText().isEmpty() && this->value() == minimum();  // "no bound"
    lineEdit()->setText(special ? specialValueText() : textFromValue(this->value()) + suffix());
    lineEdit()->setCursorPosition(0);  // a long number shows its first digits, not its unit
}

void PropertySpinBox::showMixed(double base) {
    const QSignalBlocker block(this);
    setValue(base);
    mixed_ = true;
    lineEdit()->setText(prefix() + mixedText() + suffix());
}

void PropertySpinBox::setHeld(bool held) {
    held_ = held;
    setStyleSheet(held ? QStringLiteral("QAbstractSpinBox { border: 1px solid #c62828; }") : QString());
}

void PropertySpinBox::keyPressEvent(QKeyEvent* event) {
    if (held_ && event->key() == Qt::Key_Escape) {
        emit heldCancelled();
        return;
    }
    QDoubleSpinBox::keyPressEvent(event);
}

namespace {

// The width of `text` in a spin box like `box` (its frame and arrows included).
QSize spinSizeFor(const QDoubleSpinBox& box, const QString& text) {
    QStyleOptionSpinBox opt;
    opt.initFrom(&box);
    opt.buttonSymbols = box.buttonSymbols();
    opt.frame = box.hasFrame();
    opt.subControls = QStyle::SC_SpinBoxFrame | QStyle::SC_SpinBoxEditField | QStyle::SC_SpinBoxUp | QStyle::SC_SpinBoxDown;
    const QFontMetrics fm(box.font());
    const QSize content(fm.horizontalAdvance(text) + 4, std::max(fm.height(), 14));
    return box.style()->sizeFromContents(QStyle::CT_SpinBox, &opt, content, &box);
}

}  // namespace

QSize PropertySpinBox::sizeHint() const {
    ensurePolished();
    return spinSizeFor(*this, QStringLiteral("-0.0000000") + suffix());
}

QSize PropertySpinBox::minimumSizeHint() const {
    ensurePolished();
    return spinSizeFor(*this, QStringLiteral("-0.00") + suffix());
}

void PropertySpinBox::setSoftMinimum(double min) {
    softMinimum_ = min;
}

void PropertySpinBox::stepBy(int steps) {
    // A step down from at or above the soft minimum stops on it.
    const double to = value() + steps * singleStep();
    if (steps < 0 && value() >= softMinimum_ && to < softMinimum_) {
        setValue(softMinimum_);
        return;
    }
    QDoubleSpinBox::stepBy(steps);
}

QAbstractSpinBox::StepEnabled PropertySpinBox::stepEnabled() const {
    StepEnabled e = QDoubleSpinBox::stepEnabled();
    if (!mixed_ && value() <= softMinimum_) e &= ~StepDownEnabled;
    return e;
}

QString PropertySpinBox::mixedText() {
    return QStringLiteral("—");
}

QString PropertySpinBox::shownText(double value) const {
    if (!specialValueText().isEmpty() && value == minimum()) return specialValueText();
    return rounded(value) + suffix();
}

QString PropertySpinBox::rounded(double value, int digits) const {
    if (std::abs(value) < 1e-9) value = 0.0;  // rounding's noise (-1.1e-11°) shows as 0
    if (value == 0.0) value = 0.0;            // no "-0"
    QString t = locale().toString(value, 'g', digits);
    t.remove(locale().groupSeparator());
    return t;
}

int PropertySpinBox::fittingDigits(double value) const {
    // The room the line edit gives its text (its frame and text margins off); before the
    // field is laid out (no width yet), every shown digit.
    const QLineEdit* edit = lineEdit();
    const int room = edit->contentsRect().width() - edit->textMargins().left() - edit->textMargins().right() - 4;
    if (!edit->isVisible() || room <= 0) return kShownDigits;
    const QFontMetrics fm(edit->font());
    for (int digits = kShownDigits; digits > kFewestDigits; --digits)
        if (fm.horizontalAdvance(rounded(value, digits) + suffix()) <= room) return digits;
    return kFewestDigits;
}

void PropertySpinBox::resizeEvent(QResizeEvent* event) {
    QDoubleSpinBox::resizeEvent(event);
    render();  // the digits that fit the new width
}

void PropertySpinBox::showEvent(QShowEvent* event) {
    QDoubleSpinBox::showEvent(event);
    render();
}

QString PropertySpinBox::textFromValue(double value) const {
    if (value == 0.0) value = 0.0;  // no "-0"
    auto text = [&](int digits) {
        QString t = locale().toString(value, 'g', digits);
        t.remove(locale().groupSeparator());
        return t;
    };
    if (!editing_) return rounded(value, fittingDigits(value));
    for (int digits = kShownDigits;; ++digits) {  // the shortest that reads back exactly
        const QString t = text(digits);
        bool ok = false;
        if (digits >= 17 || (locale().toDouble(t, &ok) == value && ok)) return t;
    }
}

void PropertySpinBox::render() {
    if (mixed_ || (!specialValueText().isEmpty() && value() == minimum())) return;
    if (editing_ && hasFocus() && lineEdit()->isModified()) return;  // (being typed into)
    const QSignalBlocker block(this);
    lineEdit()->setText(textFromValue(value()) + suffix());
}

void PropertySpinBox::focusInEvent(QFocusEvent* event) {
    editing_ = true;
    render();  // every digit, to edit
    QDoubleSpinBox::focusInEvent(event);
}

void PropertySpinBox::focusOutEvent(QFocusEvent* event) {
    QDoubleSpinBox::focusOutEvent(event);  // (reads what was typed, at full precision)
    editing_ = false;
    render();
    lineEdit()->setCursorPosition(0);
}

QString PropertySpinBox::stripped(const QString& text) const {
    QString t = text;
    if (!prefix().isEmpty() && t.startsWith(prefix())) t.remove(0, prefix().size());
    if (!suffix().isEmpty() && t.endsWith(suffix())) t.chop(suffix().size());
    return t.trimmed();
}

double PropertySpinBox::valueFromText(const QString& text) const {
    bool ok = false;
    const double v = locale().toDouble(stripped(text), &ok);
    return ok ? v : value();
}

QValidator::State PropertySpinBox::validate(QString& text, int&) const {
    const QString t = stripped(text);
    if (t == mixedText()) return QValidator::Intermediate;
    bool ok = false;
    const double v = locale().toDouble(t, &ok);
    if (ok && std::isfinite(v))
        return v >= minimum() && v <= maximum() ? QValidator::Acceptable : QValidator::Intermediate;
    // Partial input on the way to a number: "", "-", "1e", "1.".
    return QValidator::Intermediate;
}

void PropertySpinBox::fixup(QString& input) const {
    if (mixed_) input = prefix() + mixedText() + suffix();
}

void PropertySpinBox::setSweep(std::function<void()> sweep, std::function<bool()> enabled) {
    sweep_ = std::move(sweep);
    sweepEnabled_ = std::move(enabled);
}

// The line edit's own menu and the steps, as QAbstractSpinBox makes them, and the sweep.
void PropertySpinBox::contextMenuEvent(QContextMenuEvent* event) {
    if (!sweep_) {
        QDoubleSpinBox::contextMenuEvent(event);
        return;
    }
    QMenu* menu = lineEdit()->createStandardContextMenu();
    menu->setAttribute(Qt::WA_DeleteOnClose);
    menu->addSeparator();
    const StepEnabled steps = stepEnabled();
    menu->addAction(tr("&Step up"), this, [this] { stepBy(1); })->setEnabled(steps & StepUpEnabled);
    menu->addAction(tr("Step &down"), this, [this] { stepBy(-1); })->setEnabled(steps & StepDownEnabled);
    // The field's own command first, with an icon, above the text editing ones (at the end,
    // under Undo, Cut, Copy and Paste, users missed it).
    auto* sweep = new QAction(style()->standardIcon(QStyle::SP_MediaSeekForward), tr("S&weep this value…"), menu);
    connect(sweep, &QAction::triggered, this, [this] { sweep_(); });
    sweep->setObjectName("sweepThisValue");
    sweep->setEnabled(!sweepEnabled_ || sweepEnabled_());
    QAction* first = menu->actions().value(0);
    menu->insertAction(first, sweep);
    menu->insertSeparator(first);
    menu->popup(event->globalPos());
    event->accept();
}

}  // namespace tumble::ui
