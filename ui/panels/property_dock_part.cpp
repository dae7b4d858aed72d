// The property panel's Part group: the selected part of a compound body (a part row of the
// scene tree): its name, shape, pose in the body's frame and its own material. Each field is
// a binding on the body, as the others are (property_dock.cpp), so an edit is validated with
// the engine's rules and is one undo step of the body; the body's computed mass, centre and
// inertia (the Mass group) follow.
#include "panels/property_dock_impl.h"

#include "document/part_edits.h"

#include <QStandardItemModel>

namespace tumble::ui {

namespace {

bool isPartShape(ShapeType t) {
    return t == ShapeType::Sphere || t == ShapeType::Box || t == ShapeType::Capsule ||
           t == ShapeType::Cylinder || t == ShapeType::Mesh;
}

// The density a part without its own has: the body's, or its share of the body's mass by
// volume (the mass less what the parts of their own density weigh, over the others' volume);
// none when a volume is not known here (a mesh part) or there is no share.
std::optional<double> inheritedDensity(const BodyDesc& b) {
    if (b.density) return b.density;
    if (!b.mass) return std::nullopt;
    double own = 0.0, volume = 0.0;
    for (const PartDesc& p : b.shape.parts) {
        if (p.shape.type == ShapeType::Mesh) return std::nullopt;
        const double v = shapeVolume(p.shape);
        if (p.density)
            own += *p.density * v;
        else
            volume += v;
    }
    const double d = (*b.mass - own) / volume;
    return std::isfinite(d) && d > 0.0 ? std::optional(d) : std::nullopt;
}

}  // namespace

const PartDesc* PropertyDock::Impl::partIn(const BodyDesc& b) const {
    const int k = doc->selectedPart();
    if (k < 0 || doc->selection().size() != 1 || b.shape.type != ShapeType::Compound ||
        k >= static_cast<int>(b.shape.parts.size()))
        return nullptr;
    return &b.shape.parts[static_cast<size_t>(k)];
}

PartDesc& PropertyDock::Impl::partIn(BodyDesc& b) const {
    const int k = doc->selectedPart();
    if (b.shape.type == ShapeType::Compound && k >= 0 && k < static_cast<int>(b.shape.parts.size()))
        return b.shape.parts[static_cast<size_t>(k)];
    // A field's value given after its part was deselected (editingFinished comes late): it
    // goes nowhere, and the body is left as it is.
    static PartDesc nowhere;
    nowhere = PartDesc{};
    return nowhere;
}

QString PropertyDock::Impl::partKey(const QString& field) const {
    return QStringLiteral("shape.parts[%1].%2").arg(doc->selectedPart()).arg(field);
}

void PropertyDock::Impl::buildPart(QVBoxLayout* layout) {
    QGroupBox* box = nullptr;
    QFormLayout* form = group(layout, QObject::tr("Part"), &box);
    box->setObjectName("partGroup");
    box->setToolTip(
        QObject::tr("The part selected in the scene list; its position and orientation are in "
                    "its body's frame"));
    refreshers.push_back([this, box](const std::vector<const BodyDesc*>& bodies) {
        const PartDesc* p = bodies.size() == 1 ? partIn(*bodies[0]) : nullptr;
        box->setVisible(p != nullptr);
        if (p)
            box->setTitle(QObject::tr("Part %1 of %2")
                              .arg(QString::fromStdString(partLabel(*p, doc->selectedPart())),
                                   QString::fromStdString(bodies[0]->name)));
    });

    auto* partName = new QLineEdit;
    partName->setObjectName("part.name");
    partName->setPlaceholderText(QObject::tr("(none)"));
    form->addRow(QObject::tr("Name"), withError(partName, "part.name"));
    QObject::connect(partName, &QLineEdit::editingFinished, q, [this, partName] {
        partName->setModified(false);
        if (doc->selection().size() != 1 || !partIn(doc->body(doc->selection()[0]))) return;
        const std::string text = partName->text().trimmed().toStdString();
        if (text == partIn(doc->body(doc->selection()[0]))->name) return;
        apply(
            "part.name", QObject::tr("Rename part"), [&](BodyDesc& b, int) { partIn(b).name = text; }, false);
    });
    refreshers.push_back([this, partName](const std::vector<const BodyDesc*>& bodies) {
        const PartDesc* p = bodies.size() == 1 ? partIn(*bodies[0]) : nullptr;
        const QSignalBlocker block(partName);
        partName->setText(p ? QString::fromStdString(p->name) : QString());
    });

    // ---- Shape
    auto* type = addChoice<ShapeType>(
        form, QObject::tr("Type"), "part.shape.type", QObject::tr("Set part shape"),
        {{QObject::tr("Sphere"), ShapeType::Sphere},
         {QObject::tr("Box"), ShapeType::Box},
         {QObject::tr("Capsule"), ShapeType::Capsule},
         {QObject::tr("Cylinder"), ShapeType::Cylinder},
         {QObject::tr("Mesh"), ShapeType::Mesh}},
        [this](const BodyDesc& b) {
            const PartDesc* p = partIn(b);
            return p && isPartShape(p->shape.type) ? std::optional(p->shape.type) : std::nullopt;
        },
        [this](BodyDesc& b, int, ShapeType t) { partIn(b).shape.type = t; });
    // A mesh part comes from a file (Group a mesh body into the compound): not a choice here.
    if (auto* items = qobject_cast<QStandardItemModel*>(type->model()))
        items->item(type->findData(int(ShapeType::Mesh)))->setEnabled(false);
    refreshers.push_back([this, type](const std::vector<const BodyDesc*>& bodies) {
        const PartDesc* p = bodies.size() == 1 ? partIn(*bodies[0]) : nullptr;
        type->setEnabled(p && p->shape.type != ShapeType::Mesh);
    });

    auto partHas = [this](std::initializer_list<ShapeType> list) {
        return [this, types = std::vector<ShapeType>(list)](const BodyDesc& b) -> const PartDesc* {
            const PartDesc* p = partIn(b);
            if (p)
                for (ShapeType t : types)
                    if (p->shape.type == t) return p;
            return nullptr;
        };
    };
    auto sweepAs = [this](PropertySpinBox* spin, const QString& field) {
        offerSweep(spin, [this, field] { return partKey(field); });
    };
    auto sweepVector = [&](VectorEdit* edit, const QString& field) {
        for (int k = 0; k < 3; ++k) sweepAs(edit->component(k), QStringLiteral("%1[%2]").arg(field).arg(k));
    };
    const auto round = partHas({ShapeType::Sphere, ShapeType::Capsule, ShapeType::Cylinder});
    sweepAs(
        addDouble(
            form, QObject::tr("Radius"), "part.shape.radius", " m", 0.0, 0.05, QObject::tr("Set part radius"),
            [round](const BodyDesc& b) {
                const PartDesc* p = round(b);
                return p ? std::optional(p->shape.radius) : std::nullopt;
            },
            [this](BodyDesc& b, double v) { partIn(b).shape.radius = v; }),
        "shape.radius");
    const auto tall = partHas({ShapeType::Capsule, ShapeType::Cylinder});
    sweepAs(addDouble(
                form, QObject::tr("Half height"), "part.shape.half_height", " m", 0.0, 0.05,
                QObject::tr("Set part half height"),
                [tall](const BodyDesc& b) {
                    const PartDesc* p = tall(b);
                    return p ? std::optional(p->shape.halfHeight) : std::nullopt;
                },
                [this](BodyDesc& b, double v) { partIn(b).shape.halfHeight = v; }),
            "shape.half_height");
    const auto box3 = partHas({ShapeType::Box});
    auto* extents = addVector(
        form, QObject::tr("Half extents"), "part.shape.half_extents", " m",
        QObject::tr("Set part half extents"),
        [box3](const BodyDesc& b) {
            const PartDesc* p = box3(b);
            return p ? std::optional(p->shape.halfExtents) : std::nullopt;
        },
        [this](BodyDesc& b, int k, double v) { partIn(b).shape.halfExtents[k] = v; });
    extents->setSoftMinimum(0.0);
    sweepVector(extents, "shape.half_extents");
    const auto mesh = partHas({ShapeType::Mesh});
    auto* file = new QLineEdit;
    file->setObjectName("part.shape.file");
    file->setReadOnly(true);
    QWidget* fileRow = withError(file, "part.shape.file");
    form->addRow(QObject::tr("File"), fileRow);
    refreshers.push_back([form, fileRow, file, mesh](const std::vector<const BodyDesc*>& bodies) {
        const PartDesc* p = bodies.size() == 1 ? mesh(*bodies[0]) : nullptr;
        form->setRowVisible(fileRow, p != nullptr);
        file->setText(p ? QString::fromStdString(p->shape.file) : QString());
    });

    // ---- Pose in the body's frame
    auto* position = addVector(
        form, QObject::tr("Position"), "part.position", " m", QObject::tr("Move part"),
        [this](const BodyDesc& b) {
            const PartDesc* p = partIn(b);
            return p ? std::optional(p->position) : std::nullopt;
        },
        [this](BodyDesc& b, int k, double v) { partIn(b).position[k] = v; });
    position->setSingleStep(0.05);
    sweepVector(position, "position");
    auto* orientation = addVector(
        form, QObject::tr("Orientation"), "part.orientation", QStringLiteral("°"), QObject::tr("Rotate part"),
        [this](const BodyDesc& b) {
            const PartDesc* p = partIn(b);
            return p ? std::optional(quatToEulerDegrees(p->orientation)) : std::nullopt;
        },
        [this](BodyDesc& b, int k, double v) {
            Vec3 e = quatToEulerDegrees(partIn(b).orientation);
            e[k] = v;
            partIn(b).orientation = eulerDegreesToQuat(e);
        });
    orientation->setSingleStep(5.0);
    orientation->setToolTip(
        QObject::tr("Euler angles (x, y, z) in degrees in the body's frame, as the "
                    "body's own orientation"));

    // ---- Its own material, or the body's
    struct Own {
        const char* label;
        const char* key;
        const char* suffix;
        double step;
        std::optional<double> PartDesc::*field;
        std::function<std::optional<double>(const BodyDesc&)> inherited;
        const char* tip;
    };
    const Own owns[] = {
        {QT_TR_NOOP("Density"), "density", " kg/m³", 100.0, &PartDesc::density, inheritedDensity,
         QT_TR_NOOP("Ticked: the part's own density; else the body's density, or its share of the body's "
                    "mass by volume")},
        {QT_TR_NOOP("Friction"), "friction", "", 0.05, &PartDesc::friction,
         [](const BodyDesc& b) { return std::optional(b.friction); },
         QT_TR_NOOP("Ticked: the part's own Coulomb coefficient; else the body's")},
        {QT_TR_NOOP("Restitution"), "restitution", "", 0.05, &PartDesc::restitution,
         [](const BodyDesc& b) { return std::optional(b.restitution); },
         QT_TR_NOOP("Ticked: the part's own restitution; else the body's")},
    };
    for (const Own& own : owns)
        addOwnValue(form, own.label, own.key, own.suffix, own.step, own.field, own.inherited, own.tip);
}

// A part's value that may be its own or the body's: a tick for "its own" and the value
// (the body's, greyed, while unticked).
void PropertyDock::Impl::addOwnValue(QFormLayout* form, const char* label, const QString& field,
                                     const QString& suffix, double step,
                                     std::optional<double> PartDesc::*member,
                                     const std::function<std::optional<double>(const BodyDesc&)>& inherited,
                                     const char* tip) {
    const QString key = "part." + field;
    auto* row = new QWidget;
    auto* h = new QHBoxLayout(row);
    h->setContentsMargins(0, 0, 0, 0);
    auto* own = new QCheckBox(QObject::tr("own"));
    own->setObjectName(key + ".own");
    auto* spin = new PropertySpinBox;
    spin->setObjectName(key);
    spin->setSuffix(suffix);
    spin->setSoftMinimum(0.0);
    spin->setSingleStep(step);
    offerSweep(spin, [this, field] { return partKey(field); });
    h->addWidget(own);
    h->addWidget(spin, 1);
    row->setToolTip(QObject::tr(tip));
    QWidget* shown = withError(row, key);
    form->addRow(QObject::tr(label), shown);
    const QString text = QObject::tr("Set part %1").arg(field);
    QObject::connect(own, &QCheckBox::toggled, q, [this, key, text, member, inherited, spin](bool on) {
        apply(
            key, text,
            [&](BodyDesc& b, int) {
                // Ticked, it starts at what it was: the same body, now said part by part.
                partIn(b).*member = on ? std::optional(inherited(b).value_or(spin->value())) : std::nullopt;
            },
            false);
    });
    QObject::connect(spin, &PropertySpinBox::valueChanged, q, [this, key, text, member](double v) {
        apply(key, text, [&](BodyDesc& b, int) { partIn(b).*member = v; });
    });
    refreshers.push_back(
        [this, form, shown, own, spin, member, inherited](const std::vector<const BodyDesc*>& bodies) {
            const PartDesc* p = bodies.size() == 1 ? partIn(*bodies[0]) : nullptr;
            form->setRowVisible(shown, p != nullptr);
            if (!p) return;
            const QSignalBlocker block(own);
            own->setChecked((p->*member).has_value());
            spin->setEnabled((p->*member).has_value());
            if (const std::optional<double> v = (p->*member) ? p->*member : inherited(*bodies[0]))
                spin->showValue(*v);
            else
                spin->showMixed();
        });
}

}  // namespace tumble::ui
