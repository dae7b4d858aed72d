// Numbers people can read (issue 52 item 5): a property field shows six significant digits
// and its unit while it is not edited, rounding's noise as 0; given the focus it shows every
// digit of the value it holds (12 decimals, as the spin box keeps it), and leaving it
// unedited changes nothing.
#include "panels/property_spin_box.h"

#include <QLineEdit>
#include <QSignalSpy>
#include <QVBoxLayout>
#include <QtTest>

using namespace tumble::ui;

class TestPropertySpinBox : public QObject {
    Q_OBJECT
private slots:
    void roundedToReadFullToEdit() {
        QWidget window;
        auto* layout = new QVBoxLayout(&window);
        auto* field = new PropertySpinBox(&window);
        auto* other = new PropertySpinBox(&window);
        layout->addWidget(field);
        layout->addWidget(other);
        field->setSuffix(QStringLiteral(" kg·m²"));
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        window.activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(&window));
        other->setFocus();
        const double sixth = 1.0 / 6.0;
        field->showValue(sixth);
        QCOMPARE(field->text(), QString("0.166667 kg·m²"));
        QSignalSpy changed(field, &QDoubleSpinBox::valueChanged);
        const double held = field->value();  // (a spin box keeps 12 decimals)
        field->setFocus();
        QTRY_VERIFY(field->hasFocus());
        QCOMPARE(field->text(), QString("0.166666666667 kg·m²"));
        other->setFocus();  // left unedited
        QTRY_VERIFY(other->hasFocus());
        QCOMPARE(changed.count(), 0);
        QCOMPARE(field->value(), held);
        QCOMPARE(field->text(), QString("0.166667 kg·m²"));
        // Noise from rounding reads 0; edited, it is what it is.
        field->showValue(-1.1e-11);
        QCOMPARE(field->text(), QString("0 kg·m²"));
        field->setFocus();
        QTRY_VERIFY(field->hasFocus());
        QCOMPARE(field->text(), QString("-1.1e-11 kg·m²"));
        // Typed and entered: the value typed, to the last digit.
        field->selectAll();
        QTest::keyClicks(field, "85.94366927");
        QTest::keyClick(field, Qt::Key_Return);
        QCOMPARE(field->value(), 85.94366927);
        other->setFocus();
        QTRY_VERIFY(other->hasFocus());
        QCOMPARE(field->text(), QString("85.9437 kg·m²"));
        QCOMPARE(field->value(), 85.94366927);
    }

    // A field too narrow for six digits and its unit (an inertia cell, three to a row) shows
    // fewer digits, never a cut unit; given room again, all six. What it holds is unchanged.
    void aNarrowFieldShowsFewerDigitsAndItsUnit() {
        QWidget window;
        auto* layout = new QVBoxLayout(&window);
        auto* field = new PropertySpinBox(&window);
        layout->addWidget(field);
        field->setSuffix(QStringLiteral(" kg·m²"));
        field->setFixedWidth(400);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        field->showValue(0.0260416666666);
        const double held = field->value();
        QCOMPARE(field->text(), QString("0.0260417 kg·m²"));
        const QLineEdit* edit = field->findChild<QLineEdit*>();
        const QFontMetrics fm(edit->font());
        auto fits = [&] {
            const int room = edit->contentsRect().width() - edit->textMargins().left() - edit->textMargins().right();
            return fm.horizontalAdvance(field->text()) <= room;
        };
        // Narrower by the width of "417" and a little: "0.026 kg·m²" still fits.
        const int spare = edit->contentsRect().width() - fm.horizontalAdvance("0.0260417 kg·m²");
        field->setFixedWidth(400 - spare - fm.horizontalAdvance("417") + 12);
        QTRY_VERIFY2(field->text() != QString("0.0260417 kg·m²"), qPrintable(field->text()));
        QVERIFY2(fits(), qPrintable(field->text()));
        QVERIFY2(field->text().endsWith(" kg·m²"), qPrintable(field->text()));
        QVERIFY2(field->text().startsWith("0.026"), qPrintable(field->text()));
        QCOMPARE(field->value(), held);
        field->setFixedWidth(400);
        QTRY_COMPARE(field->text(), QString("0.0260417 kg·m²"));
    }
};

QTEST_MAIN(TestPropertySpinBox)
#include "tst_property_spin_box.moc"
