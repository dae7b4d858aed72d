#include "window/shortcuts_dialog.h"

#include <QAction>
#include <QDialogButtonBox>
#include <QHeaderView>
#include <QMenu>
#include <QMenuBar>
#include <QTableWidget>
#include <QVBoxLayout>

namespace tumble::ui {

namespace {

QString plain(QString text) {
    text.remove(QLatin1Char('&'));
    return text;
}

void collect(const QMenu* menu, const QString& path, QList<ShortcutRow>& rows) {
    for (QAction* a : menu->actions()) {
        if (a->isSeparator()) continue;
        if (a->menu()) {
            collect(a->menu(), path + QStringLiteral(" > ") + plain(a->menu()->title()), rows);
            continue;
        }
        QString text = a->text();
        QString keys;
        if (const int tab = text.indexOf(QLatin1Char('\t')); tab >= 0) {
            keys = text.mid(tab + 1);
            text.truncate(tab);
        }
        QStringList all;
        for (const QKeySequence& k : a->shortcuts()) all << k.toString(QKeySequence::NativeText);
        if (!all.isEmpty()) keys = all.join(QStringLiteral(", "));
        if (!keys.isEmpty()) rows.append({path, plain(text), keys});
    }
}

}  // namespace

QList<ShortcutRow> shortcutRows(const QMenuBar* bar) {
    QList<ShortcutRow> rows;
    for (QAction* a : bar->actions())
        if (a->menu()) collect(a->menu(), plain(a->menu()->title()), rows);
    return rows;
}

ShortcutsDialog::ShortcutsDialog(const QList<ShortcutRow>& rows, QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("Keyboard Shortcuts"));
    auto* table = new QTableWidget(int(rows.size()), 3, this);
    table->setObjectName(QStringLiteral("shortcuts"));
    table->setHorizontalHeaderLabels({tr("Menu"), tr("Command"), tr("Keys")});
    table->verticalHeader()->hide();
    table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table->setSelectionBehavior(QAbstractItemView::SelectRows);
    for (int r = 0; r < int(rows.size()); ++r) {
        table->setItem(r, 0, new QTableWidgetItem(rows[r].menu));
        table->setItem(r, 1, new QTableWidgetItem(rows[r].command));
        table->setItem(r, 2, new QTableWidgetItem(rows[r].keys));
    }
    table->resizeColumnsToContents();
    table->resizeRowsToContents();
    table->horizontalHeader()->setStretchLastSection(true);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(table);
    layout->addWidget(buttons);
    resize(620, 520);
}

}  // namespace tumble::ui
