// A double spin box for the property panels: shows numbers with up to 10 significant
// digits (no fixed decimals that would round a stored value), accepts any finite number
// the locale reads, and can show "—" when the selected bodies disagree ("mixed").
#pragma once

#include <QDoubleSpinBox>

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

    QString textFromValue(double value) const override;
    double valueFromText(const QString& text) const override;
    QValidator::State validate(QString& text, int& pos) const override;
    void fixup(QString& input) const override;

    static QString mixedText();

private:
    QString stripped(const QString& text) const;
    bool mixed_ = false;
};

}  // namespace tumble::ui
