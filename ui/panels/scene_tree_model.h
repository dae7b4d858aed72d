// The scene's bodies as an item model: one row per body, columns name, motion and shape,
// and under a compound body one row per part (name, "part", shape).
// A thin adapter over the Document: it keeps a copy of what it shows (name, motion,
// shape) so that rows can be announced before they change, as the model/view contract
// wants, although the document reports inserts and removals after the fact.
#pragma once

#include <tumble/scene.h>

#include <QAbstractItemModel>
#include <QList>

namespace tumble::ui {

class Document;

class SceneTreeModel : public QAbstractItemModel {
    Q_OBJECT
public:
    enum Column { NameColumn, MotionColumn, ShapeColumn, ColumnCount };

    explicit SceneTreeModel(Document* doc, QObject* parent = nullptr);

    Document* document() const { return doc_; }

    /// The body a row stands for (a part row: its body's), or -1 for an invalid index.
    static int bodyOf(const QModelIndex& index);
    /// The part a row stands for, or -1 for a body row.
    static int partOf(const QModelIndex& index);
    /// The row of part `part` of body `body` (column `column`).
    QModelIndex partIndex(int body, int part, int column = 0) const;

    QModelIndex index(int row, int column, const QModelIndex& parent = {}) const override;
    QModelIndex parent(const QModelIndex& child) const override;
    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation, int role = Qt::DisplayRole) const override;
    Qt::ItemFlags flags(const QModelIndex& index) const override;
    /// Renames a body or a part (name column only): one undo step. A body's name that is
    /// empty or already another body's is refused (returns false, renameRefused says why).
    bool setData(const QModelIndex& index, const QVariant& value, int role = Qt::EditRole) override;

    /// True between the begin and the end of an insert, removal or reset: views and
    /// selection models then still speak of the old rows.
    bool rowsChanging() const { return changing_; }

    /// Why `name` cannot be the name of body `row`, or an empty string if it can.
    QString nameProblem(int row, const QString& name) const;

signals:
    void renameRefused(const QString& message);

private:
    struct Row {
        QString name;
        Motion motion = Motion::Dynamic;
        ShapeType shape = ShapeType::Sphere;
        QString meshFile;
        bool meshMissing = false;  // a mesh body whose file could not be read
        QString tip;
        QStringList parts, partShapes;  // a compound's parts: names as shown, shapes
    };
    Row rowOf(int body) const;
    void bodyChanged(int body);
    void movePartIndexes(int from, int delta);
    void rebuild();

    Document* doc_;
    QList<Row> rows_;
    bool changing_ = false;
};

}  // namespace tumble::ui
