#include "import/import_options_dialog.h"

#include <tumble/model.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>

#include <algorithm>
#include <cmath>

namespace tumble::ui {

namespace {

constexpr double kUnitScale[] = {1.0, 0.01, 0.001, 0.0254};

// The mass of the body the mesh makes at scale 1, as the engine computes it (the solid
// when the surface is closed, else its convex hull); 0 when it has none.
double massAtUnitScale(const std::shared_ptr<const TriangleMesh>& mesh, double density) {
    try {
        SceneDesc s;
        BodyDesc b;
        b.name = "mesh";
        b.shape.type = ShapeType::Mesh;
        b.shape.file = "mesh";
        b.shape.meshData = mesh;
        b.density = density;
        s.bodies.push_back(b);
        return compile(s).bodies[0].mass;
    } catch (const std::exception&) {
        return 0.0;
    }
}

QString metres(double v) {
    return QLocale().toString(v, 'g', 3);
}

// Four significant digits without an exponent where one reads it better (80 963 kg, not
// 8.096e+04), with one outside 1e-3 ... 1e9.
QString readable(double v) {
    if (!(v > 0.0) || v < 1e-3 || v >= 1e9) return QLocale().toString(v, 'g', 4);
    const int decimals = std::max(0, 3 - int(std::floor(std::log10(v))));
    return QLocale().toString(v, 'f', decimals);
}

}  // namespace

ImportOptionsDialog::ImportOptionsDialog(const QString& fileName, std::shared_ptr<const TriangleMesh> mesh,
                                         double density, QWidget* parent)
    : QDialog(parent), mesh_(std::move(mesh)), density_(density) {
    setWindowTitle(tr("Import %1").arg(fileName));
    if (mesh_ && !mesh_->vertices.empty()) {
        Vec3 lo = mesh_->vertices.front(), hi = lo;
        for (const Vec3& v : mesh_->vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        extent_ = hi - lo;
    }
    unitMass_ = massAtUnitScale(mesh_, density_);

    auto* form = new QFormLayout(this);
    units_ = new QComboBox(this);
    units_->setObjectName("units");
    units_->addItems({tr("metres"), tr("centimetres"), tr("millimetres"), tr("inches")});
    form->addRow(tr("File units"), units_);
    auto* fitRow = new QWidget(this);
    auto* h = new QHBoxLayout(fitRow);
    h->setContentsMargins(0, 0, 0, 0);
    fit_ = new QCheckBox(tr("Scale to fit"), fitRow);
    fit_->setObjectName("fit");
    fitSize_ = new QDoubleSpinBox(fitRow);
    fitSize_->setObjectName("fitSize");
    fitSize_->setRange(0.001, 1000.0);
    fitSize_->setDecimals(3);
    fitSize_->setValue(1.0);
    fitSize_->setSuffix(tr(" m"));
    fitSize_->setEnabled(false);
    h->addWidget(fit_);
    h->addWidget(fitSize_, 1);
    form->addRow(tr("Size"), fitRow);
    size_ = new QLabel(this);
    size_->setObjectName("size");
    form->addRow(tr("Body"), size_);
    mass_ = new QLabel(this);
    mass_->setObjectName("mass");
    mass_->setWordWrap(true);
    form->addRow(tr("Mass"), mass_);
    collision_ = new QComboBox(this);
    collision_->setObjectName("collision");
    collision_->addItem(tr("Convex hull"), int(MeshCollision::ConvexHull));
    collision_->addItem(tr("Triangles (concave allowed)"), int(MeshCollision::Triangles));
    collision_->addItem(tr("Convex parts (split it now, concave allowed)"), int(MeshCollision::ConvexParts));
    collision_->setItemData(2, tr("Split into convex hulls in the background, seen before they are applied"),
                            Qt::ToolTipRole);
    form->addRow(tr("Collision"), collision_);
    auto* note = new QLabel(tr("Set down on the surface under the view's centre."), this);
    note->setWordWrap(true);
    form->addRow(note);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
    form->addRow(buttons);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(units_, &QComboBox::currentIndexChanged, this, &ImportOptionsDialog::update);
    connect(fit_, &QCheckBox::toggled, this, [this](bool on) {
        fitSize_->setEnabled(on);
        units_->setEnabled(!on);
        update();
    });
    connect(fitSize_, &QDoubleSpinBox::valueChanged, this, &ImportOptionsDialog::update);
    update();
}

void ImportOptionsDialog::setUnits(Units units) {
    units_->setCurrentIndex(int(units));
}

void ImportOptionsDialog::setFit(double m) {
    if (m > 0.0) fitSize_->setValue(m);
    fit_->setChecked(m > 0.0);
}

void ImportOptionsDialog::setConvexHull(bool hull) {
    collision_->setCurrentIndex(hull ? 0 : 1);
}

double ImportOptionsDialog::scale() const {
    const double largest = extent_.maxCoeff();
    if (fit_->isChecked() && largest > 0.0) return fitSize_->value() / largest;
    return kUnitScale[std::clamp(units_->currentIndex(), 0, 3)];
}

MeshCollision ImportOptionsDialog::collision() const {
    return MeshCollision(collision_->currentData().toInt());
}

bool ImportOptionsDialog::convexHull() const {
    return collision() == MeshCollision::ConvexHull;
}

Vec3 ImportOptionsDialog::size() const {
    return extent_ * scale();
}

double ImportOptionsDialog::mass() const {
    return unitMass_ * std::pow(scale(), 3);
}

QString ImportOptionsDialog::sizeText() const {
    const Vec3 s = size();
    return tr("%1 × %2 × %3 m").arg(metres(s.x()), metres(s.y()), metres(s.z()));
}

QString ImportOptionsDialog::massText() const {
    if (!(unitMass_ > 0.0)) return tr("none: the mesh encloses no volume");
    return tr("%1 kg at %2 kg/m³ (change it in the Properties panel)")
        .arg(readable(mass()), QLocale().toString(density_, 'g', 6));
}

void ImportOptionsDialog::update() {
    size_->setText(sizeText());
    mass_->setText(massText());
}

}  // namespace tumble::ui
