// Renders a page of the manual (Markdown) to a standalone HTML page for the installed docs,
// with Qt's own Markdown reader: the same reading of the page as Help > Manual's browser.
// Links to other pages (x.md, x.md#part) are turned into links to their HTML pages.
//
//   tumble-md-to-html IN.md OUT.html
//
// A build tool (packaging/CMakeLists.txt); not installed.
#include <QFile>
#include <QGuiApplication>
#include <QRegularExpression>
#include <QSaveFile>
#include <QTextDocument>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: tumble-md-to-html IN.md OUT.html\n");
        return 2;
    }
    // No window: fonts and text layout need a QGuiApplication, not a display.
    qputenv("QT_QPA_PLATFORM", "offscreen");
    QGuiApplication app(argc, argv);
    QFile in(QString::fromLocal8Bit(argv[1]));
    if (!in.open(QIODevice::ReadOnly)) {
        std::fprintf(stderr, "tumble-md-to-html: cannot read %s: %s\n", argv[1], qPrintable(in.errorString()));
        return 1;
    }
    QTextDocument doc;
    doc.setMarkdown(QString::fromUtf8(in.readAll()));
    QString html = doc.toHtml();
    html.replace(QRegularExpression(R"(href="([^":/#]+)\.md(#[^"]*)?")"), R"(href="\1.html\2")");
    QSaveFile out(QString::fromLocal8Bit(argv[2]));
    if (!out.open(QIODevice::WriteOnly) || out.write(html.toUtf8()) < 0 || !out.commit()) {
        std::fprintf(stderr, "tumble-md-to-html: cannot write %s: %s\n", argv[2], qPrintable(out.errorString()));
        return 1;
    }
    return 0;
}
