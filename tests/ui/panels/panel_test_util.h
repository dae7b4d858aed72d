// What the property panels' suites do to a panel as a user would: find a named field (the
// test stops, naming it, when there is none) and choose an item of a combo box by its text.
#pragma once

#include <QComboBox>
#include <QWidget>
#include <QtTest>

namespace tumble::test {

template <class T>
T* field(const QWidget& panel, const QString& name) {
    T* w = panel.findChild<T*>(name);
    if (!w) qFatal("no widget %s", qPrintable(name));
    return w;
}

/// Picks `text` in the combo box `comboName` as a click on it does (activated()).
inline void choose(const QWidget& panel, const QString& comboName, const QString& text) {
    auto* combo = field<QComboBox>(panel, comboName);
    const int i = combo->findText(text);
    if (i < 0) qFatal("no item %s in %s", qPrintable(text), qPrintable(comboName));
    combo->setCurrentIndex(i);
    emit combo->activated(i);
}

}  // namespace tumble::test
