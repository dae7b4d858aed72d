#include "panels/collision_groups_dialog.h"

#include "document/document.h"

#include <tumble/collision_groups.h>

#include <QDialogButtonBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <set>

namespace tumble::ui {

GroupTable GroupTable::of(const SceneDesc& scene) {
    GroupTable t;
    t.names = collisionGroupNames(scene.settings);
    t.was = t.names;
    const size_t n = t.names.size();
    t.collides.assign(n, std::vector<char>(n, 1));
    auto index = [&](const std::string& name) {
        return static_cast<size_t>(std::find(t.names.begin(), t.names.end(), name) - t.names.begin());
    };
    for (const auto& pair : scene.settings.groupsApart) {
        const size_t a = index(pair[0]), b = index(pair[1]);
        if (a < n && b < n) t.collides[a][b] = t.collides[b][a] = 0;
    }
    return t;
}

void GroupTable::add(const std::string& name) {
    names.push_back(name);
    was.push_back("");
    for (auto& row : collides) row.push_back(1);
    collides.emplace_back(names.size(), 1);
}

void GroupTable::remove(int group) {
    if (group <= 0 || group >= static_cast<int>(names.size())) return;
    names.erase(names.begin() + group);
    was.erase(was.begin() + group);
    collides.erase(collides.begin() + group);
    for (auto& row : collides) row.erase(row.begin() + group);
}

bool GroupTable::applyTo(SceneDesc& scene, std::string* why) const {
    std::set<std::string> seen;
    for (const std::string& name : names) {
        if (name.empty()) {
            if (why) *why = "a group has no name";
            return false;
        }
        if (!seen.insert(name).second) {
            if (why) *why = "'" + name + "' names two groups";
            return false;
        }
    }
    if (static_cast<int>(names.size()) > kMostCollisionGroups) {
        if (why) *why = "at most " + std::to_string(kMostCollisionGroups) + " groups";
        return false;
    }
    Settings& s = scene.settings;
    s.collisionGroups.clear();
    for (size_t k = 1; k < names.size(); ++k) s.collisionGroups.push_back(names[k]);  // "default" is implied
    s.groupsApart.clear();
    for (size_t a = 0; a < names.size(); ++a)
        for (size_t b = a; b < names.size(); ++b)
            if (!collides[a][b]) s.groupsApart.push_back({names[a], names[b]});
    for (BodyDesc& body : scene.bodies) {
        const auto it = std::find(was.begin(), was.end(), body.collisionGroup);
        body.collisionGroup = it == was.end() ? "default" : names[static_cast<size_t>(it - was.begin())];
    }
    return true;
}

CollisionGroupsDialog::CollisionGroupsDialog(Document* doc, QWidget* parent)
    : QDialog(parent), doc_(doc), table_(GroupTable::of(doc->scene())) {
    setWindowTitle(tr("Collision Groups"));
    auto* layout = new QVBoxLayout(this);
    auto* intro = new QLabel(
        tr("Each body is in one group (its Collision group in the Properties). Bodies of two groups "
           "collide where the matrix is ticked; untick a pair to let them pass through each other."));
    intro->setWordWrap(true);
    layout->addWidget(intro);
    auto* row = new QHBoxLayout;
    auto* left = new QVBoxLayout;
    list_ = new QListWidget;
    list_->setObjectName("groupList");
    left->addWidget(list_);
    auto* add = new QPushButton(tr("Add Group"));
    add->setObjectName("addGroup");
    auto* remove = new QPushButton(tr("Remove Group"));
    remove->setObjectName("removeGroup");
    left->addWidget(add);
    left->addWidget(remove);
    row->addLayout(left);
    matrix_ = new QTableWidget;
    matrix_->setObjectName("groupMatrix");
    row->addWidget(matrix_, 1);
    layout->addLayout(row);
    problem_ = new QLabel;
    problem_->setStyleSheet("color: #b00020");
    layout->addWidget(problem_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    layout->addWidget(buttons);

    connect(add, &QPushButton::clicked, this, [this] {
        std::string name = "group";
        for (int k = 2; std::find(table_.names.begin(), table_.names.end(), name) != table_.names.end(); ++k)
            name = "group " + std::to_string(k);
        table_.add(name);
        rebuild();
        list_->setCurrentRow(list_->count() - 1);
        list_->editItem(list_->currentItem());
    });
    connect(remove, &QPushButton::clicked, this, [this] {
        table_.remove(list_->currentRow());
        rebuild();
    });
    connect(list_, &QListWidget::itemChanged, this, [this](QListWidgetItem* item) {
        const int k = list_->row(item);
        if (k > 0 && k < static_cast<int>(table_.names.size()))
            table_.names[k] = item->text().trimmed().toStdString();
        rebuild();
    });
    connect(matrix_, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
        const int a = item->row(), b = item->column();
        const char on = item->checkState() == Qt::Checked;
        table_.collides[a][b] = table_.collides[b][a] = on;
        rebuild();
    });
    connect(buttons, &QDialogButtonBox::accepted, this, [this] {
        if (apply()) accept();
    });
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    rebuild();
}

void CollisionGroupsDialog::rebuild() {
    const QSignalBlocker blockList(list_), blockMatrix(matrix_);
    list_->clear();
    const int n = static_cast<int>(table_.names.size());
    QStringList labels;
    for (int k = 0; k < n; ++k) {
        const QString name = QString::fromStdString(table_.names[k]);
        auto* item = new QListWidgetItem(name);
        if (k > 0) item->setFlags(item->flags() | Qt::ItemIsEditable);  // "default" keeps its name
        list_->addItem(item);
        labels << name;
    }
    matrix_->clear();
    matrix_->setRowCount(n);
    matrix_->setColumnCount(n);
    matrix_->setHorizontalHeaderLabels(labels);
    matrix_->setVerticalHeaderLabels(labels);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            auto* item = new QTableWidgetItem;
            // The lower triangle and the diagonal: the matrix is symmetric.
            if (b <= a) {
                item->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled);
                item->setCheckState(table_.collides[a][b] ? Qt::Checked : Qt::Unchecked);
                item->setToolTip(tr("%1 and %2 collide").arg(labels[a], labels[b]));
            } else {
                item->setFlags(Qt::NoItemFlags);
            }
            matrix_->setItem(a, b, item);
        }
    matrix_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
}

bool CollisionGroupsDialog::apply() {
    SceneDesc scene = doc_->scene();
    std::string why;
    if (!table_.applyTo(scene, &why)) {
        problem_->setText(QString::fromStdString(why));
        return false;
    }
    if (!(scene == doc_->scene())) doc_->replaceScene(scene, tr("Set collision groups"), true);
    return true;
}

}  // namespace tumble::ui
