// Answering the modal message boxes that a call under test opens (polling, since they
// open inside the call).
#pragma once

#include <QAbstractButton>
#include <QApplication>
#include <QMessageBox>
#include <QTimer>
#include <QtTest>

#include <functional>
#include <memory>

namespace tumble::ui::test {

// Answers the next modal message box with the button `pick` chooses once it is up
// (polling, since it opens inside the call under test), and records its text.
inline void answerNextMessageBox(std::function<QAbstractButton*(QMessageBox*)> pick, QString* text) {
    auto attempt = std::make_shared<std::function<void(int)>>();
    *attempt = [pick, text, attempt](int left) {
        if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
            if (text) *text = box->text();
            if (QAbstractButton* b = pick(box)) QTest::mouseClick(b, Qt::LeftButton);
            *attempt = nullptr;  // break the cycle
            return;
        }
        if (left > 0) {
            QTimer::singleShot(20, [attempt, left] {
                if (*attempt) (*attempt)(left - 1);
            });
        } else {
            *attempt = nullptr;
        }
    };
    QTimer::singleShot(0, [attempt] {
        if (*attempt) (*attempt)(250);
    });  // up to 5 s
}

inline void answerNextMessageBox(QMessageBox::StandardButton button, QString* text) {
    answerNextMessageBox([button](QMessageBox* box) { return box->button(button); }, text);
}

// ... with the button labelled `label` (the recovery prompt's Recover, Discard, Later).
inline void answerNextMessageBox(const QString& label, QString* text) {
    answerNextMessageBox(
        [label](QMessageBox* box) -> QAbstractButton* {
            for (QAbstractButton* b : box->buttons())
                if (b->text() == label) return b;
            return nullptr;
        },
        text);
}

}  // namespace tumble::ui::test
