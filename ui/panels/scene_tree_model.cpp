#include "panels/scene_tree_model.h"

#include <QColor>

#include "document/document.h"
#include "document/part_edits.h"

#include <QFileInfo>

namespace tumble::ui {

SceneTreeModel::SceneTreeModel(Document* doc, QObject* parent) : QAbstractItemModel(parent), doc_(doc) {
    rebuild();
    connect(doc_, &Document::bodyInserted, this, [this](int i) {
        changing_ = true;
        beginInsertRows({}, i, i);
        rows_.insert(i, rowOf(i));
        movePartIndexes(i, +1);  // (before the views hear of the new row)
        endInsertRows();
        changing_ = false;
    });
    connect(doc_, &Document::bodyRemoved, this, [this](int i) {
        changing_ = true;
        beginRemoveRows({}, i, i);
        rows_.removeAt(i);
        movePartIndexes(i + 1, -1);  // (the removed body's own parts Qt lets go of)
        endRemoveRows();
        changing_ = false;
    });
    connect(doc_, &Document::bodyChanged, this, &SceneTreeModel::bodyChanged);
    connect(doc_, &Document::sceneReset, this, [this] {
        changing_ = true;
        beginResetModel();
        rebuild();
        endResetModel();
        changing_ = false;
    });
}

// A part row's internal id is its body's row + 1: Qt moves the kept indexes of the top-level
// rows when a body comes or goes, not those of their children, so the parts of the bodies
// from `from` on (their rows before the change) are moved here (a selected part of a later body stayed on the
// old row number: the wrong body's part, or past the end).
void SceneTreeModel::movePartIndexes(int from, int delta) {
    QModelIndexList before, after;
    for (const QModelIndex& x : persistentIndexList()) {
        if (!x.isValid() || !x.internalId()) continue;
        const int body = static_cast<int>(x.internalId()) - 1;
        if (body < from) continue;
        before << x;
        after << createIndex(x.row(), x.column(), quintptr(body + delta + 1));
    }
    if (!before.isEmpty()) changePersistentIndexList(before, after);
}

// Body rows have the internal id 0; part rows their body's row + 1.
int SceneTreeModel::bodyOf(const QModelIndex& index) {
    if (!index.isValid()) return -1;
    return index.internalId() ? static_cast<int>(index.internalId()) - 1 : index.row();
}

int SceneTreeModel::partOf(const QModelIndex& index) {
    return index.isValid() && index.internalId() ? index.row() : -1;
}

QModelIndex SceneTreeModel::partIndex(int body, int part, int column) const {
    return index(part, column, index(body, 0));
}

void SceneTreeModel::bodyChanged(int i) {
    Row row = rowOf(i);
    const QModelIndex parent = index(i, 0);
    const auto before = rows_[i].parts.size(), after = row.parts.size();
    if (before != after) {
        // Parts added or removed: the part rows go and come back (a part's row number is
        // its index, so every row after the change moves anyway).
        changing_ = true;
        if (before > 0) {
            beginRemoveRows(parent, 0, static_cast<int>(before) - 1);
            rows_[i].parts.clear();
            rows_[i].partShapes.clear();
            endRemoveRows();
        }
        if (after > 0) {
            beginInsertRows(parent, 0, static_cast<int>(after) - 1);
            rows_[i] = row;
            endInsertRows();
        }
        changing_ = false;
    }
    rows_[i] = row;
    emit dataChanged(index(i, 0), index(i, ColumnCount - 1));
    if (after > 0)
        emit dataChanged(partIndex(i, 0), partIndex(i, static_cast<int>(after) - 1, ColumnCount - 1));
}

SceneTreeModel::Row SceneTreeModel::rowOf(int i) const {
    const BodyDesc& b = doc_->body(i);
    Row r;
    r.name = QString::fromStdString(b.name);
    r.motion = b.motion;
    r.shape = b.shape.type;
    if (b.shape.type == ShapeType::Mesh)
        r.meshFile = QFileInfo(QString::fromStdString(b.shape.file)).fileName();
    const Vec3& p = b.position;
    r.tip =
        tr("%1\n%2 %3\nposition (%4, %5, %6) m")
            .arg(r.name, QString::fromLatin1(toString(b.motion)), QString::fromLatin1(toString(b.shape.type)))
            .arg(p.x(), 0, 'g', 4)
            .arg(p.y(), 0, 'g', 4)
            .arg(p.z(), 0, 'g', 4);
    if (b.mass) r.tip += tr("\nmass %1 kg").arg(*b.mass, 0, 'g', 4);
    if (b.shape.type == ShapeType::Compound) {
        for (size_t k = 0; k < b.shape.parts.size(); ++k) {
            const PartDesc& p = b.shape.parts[k];
            r.parts.append(QString::fromStdString(partLabel(p, static_cast<int>(k))));
            r.partShapes.append(p.shape.type == ShapeType::Mesh
                                    ? QStringLiteral("mesh (%1)")
                                          .arg(QFileInfo(QString::fromStdString(p.shape.file)).fileName())
                                    : QString::fromLatin1(toString(p.shape.type)));
        }
    }
    if (b.density) r.tip += tr("\ndensity %1 kg/m³").arg(*b.density, 0, 'g', 4);
    if (b.shape.type == ShapeType::Mesh && !b.shape.meshData) {
        r.meshMissing = true;
        r.tip += tr("\nThe mesh file %1 could not be read: the body is not drawn and the scene cannot be "
                    "simulated until the file is back (reopen the scene) or the body is removed.")
                     .arg(QString::fromStdString(b.shape.file));
    }
    return r;
}

void SceneTreeModel::rebuild() {
    rows_.clear();
    for (int i = 0; i < doc_->bodyCount(); ++i) rows_.append(rowOf(i));
}

QModelIndex SceneTreeModel::index(int row, int column, const QModelIndex& parent) const {
    if (column < 0 || column >= ColumnCount || row < 0) return {};
    if (!parent.isValid()) return row < rows_.size() ? createIndex(row, column, quintptr(0)) : QModelIndex();
    if (parent.internalId() || parent.row() >= rows_.size() || row >= rows_[parent.row()].parts.size())
        return {};
    return createIndex(row, column, quintptr(parent.row() + 1));
}

QModelIndex SceneTreeModel::parent(const QModelIndex& child) const {
    if (!child.isValid() || !child.internalId()) return {};
    return createIndex(static_cast<int>(child.internalId()) - 1, 0, quintptr(0));
}

int SceneTreeModel::rowCount(const QModelIndex& parent) const {
    if (!parent.isValid()) return static_cast<int>(rows_.size());
    if (parent.internalId() || parent.column() != 0 || parent.row() >= rows_.size()) return 0;
    return static_cast<int>(rows_[parent.row()].parts.size());
}

int SceneTreeModel::columnCount(const QModelIndex&) const {
    return ColumnCount;
}

QVariant SceneTreeModel::data(const QModelIndex& index, int role) const {
    if (!index.isValid() || bodyOf(index) >= rows_.size()) return {};
    const Row& r = rows_[bodyOf(index)];
    if (const int part = partOf(index); part >= 0) {
        if (part >= r.parts.size() || (role != Qt::DisplayRole && role != Qt::EditRole)) return {};
        switch (index.column()) {
            case NameColumn: return r.parts[part];
            case MotionColumn: return tr("part");
            case ShapeColumn: return r.partShapes[part];
        }
        return {};
    }
    switch (role) {
        case Qt::DisplayRole:
        case Qt::EditRole:
            switch (index.column()) {
                case NameColumn: return r.name;
                case MotionColumn: return QString::fromLatin1(toString(r.motion));
                case ShapeColumn:
                    if (r.meshMissing) return tr("mesh (%1: missing)").arg(r.meshFile);
                    return r.meshFile.isEmpty() ? QString::fromLatin1(toString(r.shape))
                                                : QStringLiteral("mesh (%1)").arg(r.meshFile);
            }
            break;
        case Qt::ToolTipRole: return r.tip;
        case Qt::ForegroundRole:
            if (r.meshMissing) return QColor(0xb0, 0x00, 0x20);
            break;
        default: break;
    }
    return {};
}

QVariant SceneTreeModel::headerData(int section, Qt::Orientation orientation, int role) const {
    if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
    switch (section) {
        case NameColumn: return tr("Name");
        case MotionColumn: return tr("Motion");
        case ShapeColumn: return tr("Shape");
    }
    return {};
}

Qt::ItemFlags SceneTreeModel::flags(const QModelIndex& index) const {
    if (!index.isValid() || bodyOf(index) >= rows_.size()) return Qt::NoItemFlags;
    Qt::ItemFlags f = Qt::ItemIsEnabled | Qt::ItemIsSelectable;
    if (partOf(index) >= 0 || rows_[bodyOf(index)].parts.isEmpty()) f |= Qt::ItemNeverHasChildren;
    if (index.column() == NameColumn) f |= Qt::ItemIsEditable;
    return f;
}

QString SceneTreeModel::nameProblem(int row, const QString& name) const {
    if (name.trimmed().isEmpty()) return tr("A body needs a name.");
    for (int i = 0; i < doc_->bodyCount(); ++i) {
        if (i != row && QString::fromStdString(doc_->body(i).name) == name)
            return tr("'%1' is already the name of another body.").arg(name);
    }
    return {};
}

bool SceneTreeModel::setData(const QModelIndex& index, const QVariant& value, int role) {
    if (role != Qt::EditRole || !index.isValid() || index.column() != NameColumn ||
        bodyOf(index) >= rows_.size())
        return false;
    const QString name = value.toString().trimmed();
    if (const int part = partOf(index); part >= 0) {
        BodyDesc b = doc_->body(bodyOf(index));
        if (b.shape.type != ShapeType::Compound || part >= static_cast<int>(b.shape.parts.size()))
            return false;
        PartDesc& p = b.shape.parts[static_cast<size_t>(part)];
        if (name.toStdString() == p.name) return true;
        const QString old = QString::fromStdString(partLabel(p, part));
        p.name = name.toStdString();
        doc_->setBody(bodyOf(index), b,
                      tr("Rename %1 to %2").arg(old, QString::fromStdString(partLabel(p, part))));
        return true;
    }
    const int row = index.row();
    const QString old = QString::fromStdString(doc_->body(row).name);
    if (name == old) return true;
    if (const QString problem = nameProblem(row, name); !problem.isEmpty()) {
        emit renameRefused(problem);
        return false;
    }
    BodyDesc b = doc_->body(row);
    b.name = name.toStdString();
    doc_->setBody(row, b, tr("Rename %1 to %2").arg(old, name));
    return true;
}

}  // namespace tumble::ui
