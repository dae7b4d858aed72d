// The choices of File > Import Mesh, made with the mesh already read: what the file's
// units are (metres, centimetres, millimetres, inches), or a size to fit its largest side
// to, and the collision; the dialog shows the body's size in metres and its mass at the
// import's density as they change (a spider STL in millimetres read as metres weighed 81
// tonnes, and nothing said so).
#pragma once

#include <tumble/mass.h>
#include <tumble/scene.h>

#include <QDialog>

#include <memory>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;

namespace tumble::ui {

class ImportOptionsDialog : public QDialog {
    Q_OBJECT
public:
    enum class Units { Metres, Centimetres, Millimetres, Inches };

    /// `mesh` as read (file units, unscaled); `density` the body's (kg/m³).
    ImportOptionsDialog(const QString& fileName, std::shared_ptr<const TriangleMesh> mesh, double density,
                        QWidget* parent = nullptr);

    void setUnits(Units units);
    /// Fit the largest side to `metres` (0: off, the units decide).
    void setFit(double metres);
    void setConvexHull(bool hull);

    /// The factor from file units to metres the choices give.
    double scale() const;
    bool convexHull() const;
    /// The collision chosen: convex hull, triangles, or convex parts (made after the import,
    /// in the Split into Convex Parts dialog).
    MeshCollision collision() const;
    /// The body's size, x × y × z in metres, and its mass at the density (what the labels show).
    Vec3 size() const;
    double mass() const;
    QString sizeText() const;
    QString massText() const;

private:
    void update();

    std::shared_ptr<const TriangleMesh> mesh_;
    double density_;
    Vec3 extent_ = Vec3::Zero();  // the mesh's bounding box in file units
    double unitMass_ = 0.0;       // its mass at scale 1 (the solid, or its hull when not closed)
    QComboBox* units_;
    QCheckBox* fit_;
    QDoubleSpinBox* fitSize_;
    QComboBox* collision_;
    QLabel* size_;
    QLabel* mass_;
};

}  // namespace tumble::ui
