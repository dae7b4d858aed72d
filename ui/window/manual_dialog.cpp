#include "window/manual_dialog.h"

#include <QDesktopServices>
#include <QFile>
#include <QHBoxLayout>
#include <QPushButton>
#include <QTextBrowser>
#include <QVBoxLayout>

namespace tumble::ui {

ManualDialog::ManualDialog(QWidget* parent) : QDialog(parent), browser_(new QTextBrowser(this)) {
    setWindowTitle(tr("Tumble Manual"));
    setAttribute(Qt::WA_DeleteOnClose);
    resize(900, 700);
    browser_->setObjectName("manual");
    browser_->setOpenLinks(false);
    auto* layout = new QVBoxLayout(this);
    auto* bar = new QHBoxLayout;
    auto* back = new QPushButton(tr("Back"), this);
    auto* home = new QPushButton(tr("Editor"), this);
    back->setEnabled(false);
    bar->addWidget(back);
    bar->addWidget(home);
    for (const auto& [text, page] : {std::pair{tr("Scene files"), "scene-format.md"}, std::pair{tr("Export"), "export.md"},
                                     std::pair{tr("Sweeps"), "sweeps.md"}}) {
        auto* b = new QPushButton(text, this);
        connect(b, &QPushButton::clicked, this, [this, page = QString(page)] {
            browser_->setSource(QUrl("qrc:/docs/" + page), QTextDocument::MarkdownResource);
        });
        bar->addWidget(b);
    }
    bar->addStretch();
    layout->addLayout(bar);
    layout->addWidget(browser_);
    connect(back, &QPushButton::clicked, browser_, &QTextBrowser::backward);
    connect(browser_, &QTextBrowser::backwardAvailable, back, &QPushButton::setEnabled);
    connect(home, &QPushButton::clicked, this, [this] {
        browser_->setSource(QUrl("qrc:/docs/editor.md"), QTextDocument::MarkdownResource);
    });
    // Pages built in open here; the web's in the system browser; others are named.
    connect(browser_, &QTextBrowser::anchorClicked, this, [this](const QUrl& link) {
        if (link.scheme() == "http" || link.scheme() == "https") {
            QDesktopServices::openUrl(link);
            return;
        }
        const QUrl target = browser_->source().resolved(link);
        if (QFile::exists(":" + target.path())) {
            browser_->setSource(target, QTextDocument::MarkdownResource);
            return;
        }
        browser_->setToolTip(tr("%1 is in the docs folder of Tumble's sources").arg(link.toString()));
    });
    browser_->setSource(QUrl("qrc:/docs/editor.md"), QTextDocument::MarkdownResource);
}

}  // namespace tumble::ui
