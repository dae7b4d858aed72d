#include "panels/joint_list.h"

#include "document/document.h"

#include <QHeaderView>
#include <QLabel>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace tumble::ui {

namespace {

// "door – post", or "bob – world" for a joint to the world.
QString bodiesOf(const JointDesc& j) {
    return QStringLiteral("%1 – %2")
        .arg(QString::fromStdString(j.bodyA), j.bodyB.empty() ? JointList::tr("world") : QString::fromStdString(j.bodyB));
}

}  // namespace

JointList::JointList(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    title_ = new QLabel(tr("Joints"));
    view_ = new QTreeWidget;
    view_->setObjectName(QStringLiteral("jointListView"));
    view_->setColumnCount(ColumnCount);
    view_->setHeaderLabels({tr("Name"), tr("Type"), tr("Bodies")});
    view_->setRootIsDecorated(false);
    view_->setUniformRowHeights(true);
    view_->setAllColumnsShowFocus(true);
    view_->setSelectionMode(QAbstractItemView::SingleSelection);
    view_->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
    view_->header()->setStretchLastSection(true);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 4, 0, 0);
    layout->setSpacing(2);
    layout->addWidget(title_);
    layout->addWidget(view_);
    setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Maximum);  // the bodies' list takes the room

    connect(view_, &QTreeWidget::itemSelectionChanged, this, [this] {
        if (syncing_) return;
        const QList<QTreeWidgetItem*> items = view_->selectedItems();
        if (!items.isEmpty()) doc_->selectJoint(view_->indexOfTopLevelItem(items.first()));
        else if (doc_->selectedJoint() >= 0) doc_->selectJoint(-1);
    });
    connect(doc_, &Document::jointsChanged, this, &JointList::rebuild);
    connect(doc_, &Document::sceneReset, this, &JointList::rebuild);
    connect(doc_, &Document::selectionChanged, this, &JointList::selectionFromDocument);
    rebuild();
}

void JointList::rebuild() {
    syncing_ = true;
    view_->clear();
    for (int i = 0; i < doc_->jointCount(); ++i) {
        const JointDesc& j = doc_->joint(i);
        auto* item = new QTreeWidgetItem(
            {QString::fromStdString(j.name), QString::fromLatin1(toString(j.type)), bodiesOf(j)});
        item->setToolTip(NameColumn, tr("%1 joint %2 between %3").arg(item->text(TypeColumn), item->text(NameColumn), item->text(BodiesColumn)));
        view_->addTopLevelItem(item);
    }
    // Only as tall as its rows need, up to eight (the bodies' list takes the rest), and not
    // there at all in a scene without joints.
    const int rows = std::min(doc_->jointCount(), 8);
    const int rowHeight = view_->sizeHintForRow(0) > 0 ? view_->sizeHintForRow(0) : fontMetrics().height() + 4;
    view_->setFixedHeight(view_->header()->sizeHint().height() + rows * rowHeight + 2 * view_->frameWidth());
    setVisible(doc_->jointCount() > 0);
    syncing_ = false;
    selectionFromDocument();
}

void JointList::selectionFromDocument() {
    if (syncing_) return;
    syncing_ = true;
    const int j = doc_->selectedJoint();
    view_->clearSelection();
    if (j >= 0 && j < view_->topLevelItemCount()) {
        QTreeWidgetItem* item = view_->topLevelItem(j);
        item->setSelected(true);
        view_->setCurrentItem(item);
        view_->scrollToItem(item);
    }
    syncing_ = false;
}

}  // namespace tumble::ui
