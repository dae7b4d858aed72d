// A double spin box for the property panels: shows numbers with up to 10 significant
// digits (no fixed decimals that would round a stored value), accepts any finite number
// the locale reads, and can show "—" when the selected bodies disagree ("mixed"). A lower
// bound is soft (setSoftMinimum): the arrows and the wheel stop there, but a number typed
// below it is taken and given to the panel, which refuses it with the engine's message (a
// hard minimum turned a typed "-3" back into the old mass without a word).
#pragma once

#include <QDoubleSpinBox>

#include <functional>
#include <limits>

namespace tumble::ui {

class PropertySpinBox : public QDoubleSpinBox {
    Q_OBJECT
public:
    explicit PropertySpinBox(QWidget* parent = nullptr);

    /// Shows `value` (signals blocked: this is the document speaking, not the user).
    void showValue(double value);
    /// Shows "—": the selected bodies hold different values. Stepping starts from `base`.
    void showMixed(double base = 0.0);
    bool isMixed() const { return mixed_; }

    /// Room for about eight digits and the unit: QDoubleSpinBox sizes itself for its whole
    /// range at twelve decimals, and three such fields in a row did not fit the panel.
    QSize sizeHint() const override;
    QSize minimumSizeHint() const override;

    /// The arrows and the wheel do not step below `min`; typing may (see above).
    void setSoftMinimum(double min);

    /// Six significant digits (a value below 1e-9 of its unit, rounding's noise, as 0) with the
    /// unit always seen: a field too narrow for them shows fewer (down to three), never a
    /// cut unit; while the field has the focus, the shortest text that reads back as exactly
    /// the value it holds, so that leaving it unedited changes nothing.
    QString textFromValue(double value) const override;
    static constexpr int kShownDigits = 6;
    static constexpr int kFewestDigits = 3;
    /// `value` as the field shows it when not focused, with its unit ("25 kg", "85.9437°"):
    /// the words an undo entry gives the value ("Set mass of box-3 to 25 kg").
    QString shownText(double value) const;
    void stepBy(int steps) override;
    StepEnabled stepEnabled() const override;
    double valueFromText(const QString& text) const override;
    QValidator::State validate(QString& text, int& pos) const override;
    void fixup(QString& input) const override;

    static QString mixedText();

    /// Marks the field as part of a value the panel holds back because it would be refused
    /// (a red frame); Esc in a held field emits heldCancelled instead of reaching the panel.
    void setHeld(bool held);
    bool isHeld() const { return held_; }

    /// Adds "Sweep this value…" to the field's context menu, calling `sweep` (the panel
    /// sets it for the values a sweep can vary; `enabled` says whether it can now: one body
    /// selected, say).
    void setSweep(std::function<void()> sweep, std::function<bool()> enabled);

signals:
    /// Esc in a held field: the user gives the held value up.
    void heldCancelled();

protected:
    void contextMenuEvent(QContextMenuEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void focusInEvent(QFocusEvent* event) override;
    void focusOutEvent(QFocusEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;
    void showEvent(QShowEvent* event) override;

private:
    /// The text for the value now: rounded to kShownDigits significant digits while the
    /// field is not being edited, every digit it holds while it is (editing_).
    void render();
    /// `value` to `digits` significant digits, |value| < 1e-9 as 0 (no group separators).
    QString rounded(double value, int digits = kShownDigits) const;
    /// The most significant digits (kShownDigits down to kFewestDigits) whose text and unit
    /// fit the field's width.
    int fittingDigits(double value) const;
    bool editing_ = false;
    std::function<void()> sweep_;
    std::function<bool()> sweepEnabled_;
    QString stripped(const QString& text) const;
    bool mixed_ = false;
    bool held_ = false;
    double softMinimum_ = -std::numeric_limits<double>::infinity();
};

}  // namespace tumble::ui
