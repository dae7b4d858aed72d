#include "panels/scene_tree_model.h"

#include <QColor>

#include "document/document.h"

#include <QFileInfo>

namespace tumble::ui {

SceneTreeModel::SceneTreeModel(Document* doc, QObject* parent) : QAbstractItemModel(parent), doc_(doc) {
    rebuild();
    connect(doc_, &Document::bodyInserted, this, [this](int i) {
        changing_ = true;
        beginInsertRows({}, i, i);
        rows_.insert(i, rowOf(i));
        endInsertRows();
        changing_ = false;
    });
    connect(doc_, &Document::bodyRemoved, this, [this](int i) {
        changing_ = true;
        beginRemoveRows({}, i, i);
        rows_.removeAt(i);
        endRemoveRows();
        changing_ = false;
    });
    connect(doc_, &Document::bodyChanged, this, [this](int i) {
        rows_[i] = rowOf(i);
        emit dataChanged(index(i, 0), index(i, ColumnCount - 1));
    });
    connect(doc_, &Document::sceneReset, this, [this] {
        changing_ = true;
        beginResetModel();
        rebuild();
        endResetModel();
        changing_ = false;
    });
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
    if (parent.isValid() || row < 0 || row >= rows_.size() || column < 0 || column >= ColumnCount) return {};
    return createIndex(row, column);
}

QModelIndex SceneTreeModel::parent(const QModelIndex&) const {
    return {};
}

int SceneTreeModel::rowCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : static_cast<int>(rows_.size());
}

int SceneTreeModel::columnCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : ColumnCount;
}

QVariant SceneTreeModel::data(const QModelIndex& index, int role) const {
    if (!index.isValid() || index.row() >= rows_.size()) return {};
    const Row& r = rows_[index.row()];
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
    if (!index.isValid()) return Qt::NoItemFlags;
    Qt::ItemFlags f = Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemNeverHasChildren;
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
        index.row() >= rows_.size())
        return false;
    const QString name = value.toString().trimmed();
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
