#include "panels/scene_tree_dock.h"

#include "document/body_presets.h"
#include "document/document.h"
#include "document/joint_presets.h"
#include "import/convex_split_dialog.h"
#include "panels/joint_list.h"
#include "panels/scene_tree_model.h"

#include <QAction>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QMenu>
#include <QToolBar>
#include <QToolButton>
#include <QTreeView>
#include <QVBoxLayout>

namespace tumble::ui {

SceneTreeDock::SceneTreeDock(Document* doc, QWidget* parent)
    : QDockWidget(tr("Scene"), parent), doc_(doc), model_(new SceneTreeModel(doc, this)) {
    setObjectName(QStringLiteral("sceneTreeDock"));

    view_ = new QTreeView;
    view_->setObjectName(QStringLiteral("sceneTreeView"));
    view_->setModel(model_);
    view_->setRootIsDecorated(true);  // a compound opens on its parts
    view_->setUniformRowHeights(true);
    view_->setAllColumnsShowFocus(true);
    view_->setSelectionMode(QAbstractItemView::ExtendedSelection);
    view_->setSelectionBehavior(QAbstractItemView::SelectRows);
    view_->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
    view_->setContextMenuPolicy(Qt::CustomContextMenu);
    // The names whole (they were cut to "tetrah..." beside a long shape text): the shape
    // takes what is left and elides, its whole text in the row's tooltip.
    view_->header()->setSectionResizeMode(SceneTreeModel::NameColumn, QHeaderView::ResizeToContents);
    view_->header()->setSectionResizeMode(SceneTreeModel::MotionColumn, QHeaderView::ResizeToContents);
    view_->header()->setSectionResizeMode(SceneTreeModel::ShapeColumn, QHeaderView::Stretch);
    view_->header()->setStretchLastSection(true);
    // Size the fitted columns from the rows in view only: by default Qt measures up to 1000
    // rows on every change of any row (the move of one body took 5 ms at 1000 bodies).
    view_->header()->setResizeContentsPrecision(0);

    // ---- Actions.
    addMenu_ = new QMenu(tr("&Add Body"), this);
    const struct {
        ShapeType type;
        const char* text;
    } kinds[] = {
        {ShapeType::Sphere, QT_TR_NOOP("&Sphere")},
        {ShapeType::Box, QT_TR_NOOP("&Box")},
        {ShapeType::Capsule, QT_TR_NOOP("&Capsule")},
        {ShapeType::Cylinder, QT_TR_NOOP("C&ylinder")},
        {ShapeType::Plane, QT_TR_NOOP("&Plane")},
        {ShapeType::Compound, QT_TR_NOOP("C&ompound")},
        {ShapeType::Mesh, QT_TR_NOOP("&Mesh from File...")},
    };
    for (const auto& k : kinds) {
        QAction* a = addMenu_->addAction(tr(k.text));
        if (k.type == ShapeType::Mesh) addMenu_->insertSeparator(a);
        const ShapeType type = k.type;
        a->setStatusTip(type == ShapeType::Mesh
                            ? tr("Import a mesh file as a new body")
                            : tr("Add a %1 body").arg(QString::fromLatin1(toString(type))));
        connect(a, &QAction::triggered, this, [this, type] { addBody(type); });
        addActions_.insert(type, a);
    }
    partMenu_ = new QMenu(tr("Add &Part"), this);
    for (const auto& k : kinds) {
        if (k.type == ShapeType::Plane || k.type == ShapeType::Mesh || k.type == ShapeType::Compound)
            continue;
        QAction* a = partMenu_->addAction(tr(k.text));
        const ShapeType type = k.type;
        a->setStatusTip(tr("Add a %1 part to the selected body (it becomes a compound)")
                            .arg(QString::fromLatin1(toString(type))));
        connect(a, &QAction::triggered, this, [this, type] {
            if (doc_->selection().size() != 1) return;
            QString why;
            if (doc_->addPart(doc_->selection().front(), type, &why) < 0)
                showMessage(tr("No part added: %1.").arg(why));
        });
        partActions_.insert(type, a);
    }
    jointMenu_ = new QMenu(tr("Add &Joint"), this);
    const struct {
        JointType type;
        const char* text;
        const char* tip;
    } joints[] = {
        {JointType::Ball, QT_TR_NOOP("&Ball"), QT_TR_NOOP("Hold the bodies together at a point, free to turn")},
        {JointType::Hinge, QT_TR_NOOP("&Hinge"), QT_TR_NOOP("Let the bodies turn about a vertical axis only")},
        {JointType::Slider, QT_TR_NOOP("&Slider"), QT_TR_NOOP("Let the bodies slide along the x axis only")},
        {JointType::Fixed, QT_TR_NOOP("&Fixed"), QT_TR_NOOP("Weld the bodies into one")},
        {JointType::Distance, QT_TR_NOOP("&Distance (Rod)"), QT_TR_NOOP("Keep the bodies' origins as far apart as now")},
        {JointType::Rope, QT_TR_NOOP("&Rope"), QT_TR_NOOP("Keep the bodies' origins at most as far apart as now")},
        {JointType::SixAxis, QT_TR_NOOP("Si&x-axis"),
         QT_TR_NOOP("Hold the bodies in all six axes; free, limit or drive each in the joint panel")},
    };
    for (const auto& k : joints) {
        QAction* a = jointMenu_->addAction(tr(k.text));
        const JointType type = k.type;
        a->setStatusTip(tr(k.tip) + tr(" (one body selected: to the world)"));
        connect(a, &QAction::triggered, this, [this, type] { addJoint(type); });
        jointActions_.insert(type, a);
    }

    duplicate_ = new QAction(tr("D&uplicate"), this);
    duplicate_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_D));
    duplicate_->setShortcutContext(Qt::WindowShortcut);
    duplicate_->setStatusTip(tr("Copy the selected bodies"));
    connect(duplicate_, &QAction::triggered, this, &SceneTreeDock::duplicateSelection);

    delete_ = new QAction(tr("&Delete"), this);
    delete_->setShortcut(QKeySequence::Delete);
    delete_->setShortcutContext(Qt::WindowShortcut);
    delete_->setStatusTip(tr("Remove the selected bodies, or the selected part or joint"));
    connect(delete_, &QAction::triggered, this, [this] {
        QString why;
        if (doc_->selectedJoint() >= 0)
            doc_->removeJoint(doc_->selectedJoint());
        else if (doc_->selectedPart() >= 0) {
            if (!doc_->removePart(doc_->selection().front(), doc_->selectedPart(), &why))
                showMessage(tr("The part stays: %1.").arg(why));
        } else
            doc_->removeBodies(doc_->selection());
    });

    split_ = new QAction(tr("Split into Con&vex Parts..."), this);
    split_->setStatusTip(
        tr("Cut the selected mesh body into convex parts, so it collides by its own concave shape"));
    connect(split_, &QAction::triggered, this, [this] {
        if (doc_->selection().size() != 1) return;
        ConvexSplitDialog dialog(doc_, doc_->selection().front(), window());
        dialog.exec();
    });

    group_ = new QAction(tr("&Group"), this);
    group_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_G));
    group_->setShortcutContext(Qt::WindowShortcut);
    group_->setStatusTip(tr("Make the selected bodies one body of several parts, each where it is"));
    connect(group_, &QAction::triggered, this, [this] {
        QString why;
        if (!doc_->group(doc_->selection(), &why)) showMessage(why);
    });
    ungroup_ = new QAction(tr("U&ngroup"), this);
    ungroup_->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_G));
    ungroup_->setShortcutContext(Qt::WindowShortcut);
    ungroup_->setStatusTip(tr("Make the selected compound body a body per part"));
    connect(ungroup_, &QAction::triggered, this, [this] {
        const QList<int> rows = doc_->selection();
        QString why;
        if (rows.size() == 1 && !doc_->ungroup(rows.front(), &why)) showMessage(why);
    });

    rename_ = new QAction(tr("&Rename"), this);
    rename_->setShortcut(QKeySequence(Qt::Key_F2));
    rename_->setShortcutContext(Qt::WindowShortcut);
    connect(rename_, &QAction::triggered, this, [this] {
        const QModelIndex current = view_->currentIndex();
        if (current.isValid()) view_->edit(model_->index(current.row(), SceneTreeModel::NameColumn));
    });
    // The shortcuts work wherever the focus is in the window (the 3D view, the timeline, any
    // dock); a text field with the focus (a rename's line editor, a property) takes the keys it
    // edits with first, by its ShortcutOverride.
    addAction(duplicate_);
    addAction(group_);
    addAction(ungroup_);
    addAction(delete_);
    addAction(rename_);

    auto* tools = new QToolBar;
    tools->setIconSize(QSize(16, 16));
    auto* addButton = new QToolButton;
    addButton->setText(tr("Add"));
    addButton->setToolTip(tr("Add a body"));
    addButton->setMenu(addMenu_);
    addButton->setPopupMode(QToolButton::InstantPopup);
    tools->addWidget(addButton);
    auto* jointButton = new QToolButton;
    jointButton->setObjectName(QStringLiteral("addJointButton"));
    jointButton->setText(tr("Joint"));
    jointButton->setToolTip(tr("Join the selected bodies (one: to the world)"));
    jointButton->setMenu(jointMenu_);
    jointButton->setPopupMode(QToolButton::InstantPopup);
    tools->addWidget(jointButton);
    tools->addAction(duplicate_);
    tools->addAction(delete_);

    message_ = new QLabel;
    message_->setObjectName(QStringLiteral("sceneTreeMessage"));
    message_->setWordWrap(true);
    message_->setStyleSheet(QStringLiteral("color: #b00020"));
    message_->hide();

    auto* body = new QWidget;
    auto* layout = new QVBoxLayout(body);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(2);
    layout->addWidget(tools);
    layout->addWidget(view_);
    joints_ = new JointList(doc_);
    layout->addWidget(joints_);
    layout->addWidget(message_);
    setWidget(body);

    connect(view_, &QWidget::customContextMenuRequested, this, [this](const QPoint& pos) {
        QMenu menu(this);
        menu.addMenu(addMenu_);
        menu.addMenu(partMenu_);
        menu.addSeparator();
        menu.addAction(rename_);
        menu.addAction(duplicate_);
        menu.addAction(group_);
        menu.addAction(ungroup_);
        menu.addAction(split_);
        menu.addAction(delete_);
        rename_->setEnabled(view_->indexAt(pos).isValid());
        menu.exec(view_->viewport()->mapToGlobal(pos));
    });
    connect(model_, &SceneTreeModel::renameRefused, this, &SceneTreeDock::showMessage);

    // ---- Selection, both ways. While rows are inserted or removed the view's selection
    // model reports changes in terms of old rows: those are ignored, and once the rows have
    // moved the document's selection (already moved too) is copied to the view.
    connect(view_->selectionModel(), &QItemSelectionModel::selectionChanged, this,
            &SceneTreeDock::selectionFromView);
    connect(view_->selectionModel(), &QItemSelectionModel::currentChanged, this,
            [this](const QModelIndex& current) { rename_->setEnabled(current.isValid()); });
    connect(doc_, &Document::selectionChanged, this, &SceneTreeDock::selectionFromDocument);
    connect(model_, &QAbstractItemModel::rowsInserted, this, &SceneTreeDock::selectionFromDocument);
    connect(model_, &QAbstractItemModel::rowsRemoved, this, &SceneTreeDock::selectionFromDocument);
    connect(model_, &QAbstractItemModel::modelReset, this, &SceneTreeDock::selectionFromDocument);
    // Any other edit clears a refusal message: it is about the last thing the user did.
    connect(doc_, &Document::bodyChanged, this, [this] { message_->hide(); });

    selectionFromDocument();
}

void SceneTreeDock::addBody(ShapeType type) {
    if (type == ShapeType::Mesh) {
        emit importMeshRequested();
        return;
    }
    message_->hide();
    BodyDesc body = presetBody(type, doc_->scene());
    if (place_ && type != ShapeType::Plane) body = place_(body);
    const int index = doc_->addBody(body);
    doc_->setSelection({index});
}

void SceneTreeDock::duplicateSelection() {
    const QList<int> rows = doc_->selection();
    if (rows.isEmpty()) return;
    message_->hide();
    double top = pileTop(doc_->scene());
    QList<BodyDesc> copies;
    for (int i : rows) {
        BodyDesc copy = placedAbove(doc_->body(i), top);
        if (copy.shape.type != ShapeType::Plane) top = copy.position.y() + halfHeightAboveOrigin(copy);
        copies.append(std::move(copy));
    }
    doc_->beginMacro(rows.size() == 1
                         ? tr("Duplicate %1").arg(QString::fromStdString(doc_->body(rows[0]).name))
                         : tr("Duplicate %n bodies", nullptr, int(rows.size())));
    QList<int> added;
    for (const BodyDesc& copy : copies) added.append(doc_->addBody(copy));
    doc_->endMacro();
    doc_->setSelection(added);
}

void SceneTreeDock::selectionFromDocument() {
    if (syncing_) return;
    syncing_ = true;
    QItemSelection selection;
    const QList<int>& rows = doc_->selection();
    const int part = doc_->selectedPart();
    QModelIndex current;
    if (part >= 0 && rows.size() == 1) {
        view_->expand(model_->index(rows.front(), 0));
        current = model_->partIndex(rows.front(), part);
        selection.select(current, model_->partIndex(rows.front(), part, SceneTreeModel::ColumnCount - 1));
    } else {
        for (int row : rows)
            selection.select(model_->index(row, 0), model_->index(row, SceneTreeModel::ColumnCount - 1));
        if (!rows.isEmpty()) current = model_->index(rows.last(), 0);
    }
    QItemSelectionModel* sm = view_->selectionModel();
    sm->select(selection, QItemSelectionModel::ClearAndSelect);
    const QModelIndex now = sm->currentIndex();
    const bool currentShown =
        part >= 0 ? now.isValid() && now.sibling(now.row(), 0) == current
                  : SceneTreeModel::partOf(now) < 0 && rows.contains(SceneTreeModel::bodyOf(now));
    if (current.isValid() && !currentShown) {
        sm->setCurrentIndex(current, QItemSelectionModel::NoUpdate);
        view_->scrollTo(current);
    }
    syncing_ = false;
    updateActions();
}

// A part row selected alone selects that part (and its body); otherwise the rows' bodies.
void SceneTreeDock::selectionFromView() {
    if (syncing_ || model_->rowsChanging()) return;
    syncing_ = true;
    QList<int> rows;
    QList<std::pair<int, int>> parts;
    for (const QModelIndex& index : view_->selectionModel()->selection().indexes()) {
        const int body = SceneTreeModel::bodyOf(index), part = SceneTreeModel::partOf(index);
        if (!rows.contains(body)) rows.append(body);
        if (part >= 0 && !parts.contains(std::pair(body, part))) parts.append({body, part});
    }
    if (rows.size() == 1 && parts.size() == 1)
        doc_->selectPart(parts.front().first, parts.front().second);
    else
        doc_->setSelection(rows);
    syncing_ = false;
    updateActions();
}

void SceneTreeDock::updateActions() {
    const bool any = !doc_->selection().isEmpty();
    duplicate_->setEnabled(any);
    delete_->setEnabled(any || doc_->selectedJoint() >= 0);
    jointMenu_->setEnabled(any && doc_->selection().size() <= 2);
    partMenu_->setEnabled(doc_->selection().size() == 1 &&
                          doc_->body(doc_->selection().front()).shape.type != ShapeType::Plane);
    group_->setEnabled(doc_->selection().size() >= 2);
    split_->setEnabled(doc_->selection().size() == 1 && doc_->selectedPart() < 0 &&
                       doc_->body(doc_->selection().front()).shape.type == ShapeType::Mesh &&
                       doc_->body(doc_->selection().front()).shape.meshData);
    ungroup_->setEnabled(doc_->selection().size() == 1 &&
                         doc_->body(doc_->selection().front()).shape.type == ShapeType::Compound);
}

void SceneTreeDock::addJoint(JointType type) {
    const QList<int> sel = doc_->selectionInPickOrder();
    std::string why;
    const auto joint = presetJoint(type, doc_->scene(), std::vector<int>(sel.begin(), sel.end()), &why);
    if (!joint) {
        showMessage(tr("No joint added: %1.").arg(QString::fromStdString(why)));
        return;
    }
    showMessage(QString());
    doc_->addJoint(*joint);
}

void SceneTreeDock::showMessage(const QString& text) {
    message_->setText(text);
    message_->setVisible(!text.isEmpty());
}

}  // namespace tumble::ui
