// The mass rows (mass or density, centre of mass, inertia) and the forces list of the
// property panel.
#include "panels/property_dock_impl.h"

namespace tumble::ui {

void PropertyDock::Impl::buildMass(QVBoxLayout* layout) {
    QFormLayout* form = group(layout, QObject::tr("Mass"), &massGroup);
    noMass = new QLabel(QObject::tr("Static, kinematic and animated bodies have no mass."));
    noMass->setObjectName("mass.none");
    form->addRow(noMass);

    // Mass or density: a choice and one value.
    auto* box = new QWidget;
    auto* h = new QHBoxLayout(box);
    h->setContentsMargins(0, 0, 0, 0);
    massKind = new QComboBox;
    massKind->setObjectName("mass.kind");
    massKind->addItem(QObject::tr("Mass"), 0);
    massKind->addItem(QObject::tr("Density"), 1);
    mass = new PropertySpinBox;
    mass->setObjectName("mass");
    offerSweep(mass, [this] {
        const auto bodies = selected();
        return bodies.size() == 1 && bodies[0]->density ? QString("density") : QString("mass");
    });
    mass->setSoftMinimum(0.0);
    mass->setSingleStep(0.1);
    h->addWidget(massKind);
    h->addWidget(mass, 1);
    massNote = new QLabel;
    massNote->setObjectName("mass.note");
    auto* v = new QWidget;
    auto* vl = new QVBoxLayout(v);
    vl->setContentsMargins(0, 0, 0, 0);
    vl->addWidget(box);
    vl->addWidget(massNote);
    QWidget* massRow = withError(v, "mass");
    form->addRow(QObject::tr("Mass"), massRow);
    QObject::connect(massKind, &QComboBox::activated, q, [this](int i) {
        const bool density = i == 1;
        apply(
            "mass", density ? QObject::tr("Give density") : QObject::tr("Give mass"),
            [&](BodyDesc& b, int) {
                if (b.motion != Motion::Dynamic || b.density.has_value() == density) return;
                const auto c = computed(b);
                if (density) {
                    // Same mass: density = mass / volume, the volume from the computed unit mass.
                    BodyDesc unit = b;
                    unit.mass.reset();
                    unit.density = 1.0;
                    const auto u = computed(unit);
                    b.density = u && u->mass > 0.0 ? *b.mass / u->mass : 1000.0;
                    b.mass.reset();
                } else {
                    b.mass = c ? c->mass : 1.0;
                    b.density.reset();
                }
            },
            false);
    });
    QObject::connect(mass, &PropertySpinBox::valueChanged, q, [this](double value) {
        const auto bodies = selected();
        const bool density = !bodies.empty() && bodies.front()->density;
        apply("mass", editText(density ? QObject::tr("Set density") : QObject::tr("Set mass"), mass->shownText(value)),
              [&](BodyDesc& b, int) {
            if (b.density)
                b.density = value;
            else if (b.motion == Motion::Dynamic)
                b.mass = value;
        });
    });
    refreshers.push_back([this, form, massRow](const std::vector<const BodyDesc*>& bodies) {
        bool allDynamic = !bodies.empty();
        for (auto* b : bodies) allDynamic = allDynamic && b->motion == Motion::Dynamic;
        form->setRowVisible(noMass, !allDynamic);
        form->setRowVisible(massRow, allDynamic);
        if (!allDynamic) return;
        const auto kind =
            sharedOf<int>(bodies, [](const BodyDesc& b) { return std::optional(b.density ? 1 : 0); });
        {
            const QSignalBlocker block(massKind);
            massKind->setCurrentIndex(kind.value ? *kind.value : -1);
        }
        mass->setSuffix(kind.value && *kind.value == 1 ? " kg/m³" : " kg");
        // Some give a mass, some a density: one number cannot mean both. Choose first.
        mass->setEnabled(kind.value.has_value());
        mass->setToolTip(kind.value ? QString()
                                    : QObject::tr("Some bodies give a mass, some a density: choose one"));
        const auto value =
            sharedOf<double>(bodies, [](const BodyDesc& b) { return b.density ? b.density : b.mass; });
        if (value.value)
            mass->showValue(*value.value);
        else
            mass->showMixed(bodies.front()->density ? *bodies.front()->density
                                                    : bodies.front()->mass.value_or(0.0));
        const auto total = sharedOf<double>(bodies, [this](const BodyDesc& b) -> std::optional<double> {
            const auto c = computed(b);
            return c ? std::optional(c->mass) : std::nullopt;
        });
        massNote->setVisible(kind.value && *kind.value == 1);
        massNote->setText(total.value ? QObject::tr("= %1 kg").arg(*total.value, 0, 'g', 6) : QString());
    });

    // Centre of mass: computed, or given.
    auto* comBox = new QWidget;
    auto* ch = new QHBoxLayout(comBox);
    ch->setContentsMargins(0, 0, 0, 0);
    comOverride = new QCheckBox;
    comOverride->setObjectName("center_of_mass.override");
    comOverride->setToolTip(QObject::tr("Override the centre of mass computed from the shape"));
    com = new VectorEdit("center_of_mass", " m");
    com->setToolTip(QObject::tr("Body frame"));
    ch->addWidget(comOverride);
    ch->addWidget(com, 1);
    QWidget* comRow = withError(comBox, "center_of_mass");
    form->addRow(QObject::tr("Centre of mass"), comRow);
    QObject::connect(comOverride, &QCheckBox::clicked, q, [this](bool on) {
        apply(
            "center_of_mass",
            on ? QObject::tr("Override centre of mass") : QObject::tr("Compute centre of mass"),
            [&](BodyDesc& b, int) {
                if (!on) {
                    b.centerOfMass.reset();
                } else if (!b.centerOfMass) {
                    const auto c = computed(b);
                    b.centerOfMass = c ? c->centerOfMass : Vec3::Zero();
                }
            },
            false);
    });
    QObject::connect(com, &VectorEdit::componentEdited, q, [this](int k, double value) {
        applyPart(
            "center_of_mass", k, editText(QObject::tr("Set centre of mass") + ' ' + axisName(k), com->component(k)->shownText(value)),
            [this, k, value](BodyDesc& b, int) {
                const auto c = computed(b);
                Vec3 p = b.centerOfMass.value_or(c ? c->centerOfMass : Vec3::Zero());
                p[k] = value;
                b.centerOfMass = p;
            },
            QStringLiteral("center_of_mass.%1").arg(k));
    });
    holdable("center_of_mass", [this](bool on) { com->setHeld(on); });

    inertia = new InertiaEdit("inertia");
    QWidget* inertiaRow = withError(inertia, "inertia");
    form->addRow(QObject::tr("Inertia"), inertiaRow);
    auto start = [this](const BodyDesc& b) -> Mat3 {
        if (b.inertia) return *b.inertia;
        const auto c = computed(b);
        return c ? c->inertia : Mat3::Identity();
    };
    QObject::connect(inertia, &InertiaEdit::overrideToggled, q, [this, start](bool on) {
        apply(
            "inertia", on ? QObject::tr("Override inertia") : QObject::tr("Compute inertia"),
            [&](BodyDesc& b, int) {
                if (on)
                    b.inertia = start(b);
                else
                    b.inertia.reset();
            },
            false);
    });
    QObject::connect(inertia, &InertiaEdit::cellEdited, q, [this, start](int i, int j, double value) {
        const int a = std::min(i, j), c = std::max(i, j);
        applyPart(
            "inertia", 3 * a + c,
            editText(QObject::tr("Set inertia") + ' ' + axisName(a) + axisName(c), inertia->cell(a, c)->shownText(value)),
            [start, a, c, value](BodyDesc& b, int) {
                Mat3 m = start(b);
                m(a, c) = m(c, a) = value;
                b.inertia = m;
            },
            QStringLiteral("inertia.%1%2").arg(a).arg(c));
    });
    holdable("inertia", [this](bool on) { inertia->setHeld(on); });
    QObject::connect(com, &VectorEdit::cancelled, q, [this] {
        dropHeld();
        refresh();
    });
    QObject::connect(inertia, &InertiaEdit::cancelled, q, [this] {
        dropHeld();
        refresh();
    });

    refreshers.push_back([this, form, comRow, inertiaRow](const std::vector<const BodyDesc*>& bodies) {
        bool allDynamic = !bodies.empty();
        int comGiven = 0, inertiaGiven = 0;
        for (auto* b : bodies) {
            allDynamic = allDynamic && b->motion == Motion::Dynamic;
            comGiven += b->centerOfMass.has_value();
            inertiaGiven += b->inertia.has_value();
        }
        form->setRowVisible(comRow, allDynamic);
        form->setRowVisible(inertiaRow, allDynamic);
        if (!allDynamic) return;
        const int n = static_cast<int>(bodies.size());
        auto state = [n](int given) {
            return given == 0 ? Qt::Unchecked : given == n ? Qt::Checked : Qt::PartiallyChecked;
        };
        {
            const QSignalBlocker block(comOverride);
            comOverride->setTristate(state(comGiven) == Qt::PartiallyChecked);
            comOverride->setCheckState(state(comGiven));
        }
        com->setEnabled(comGiven == n);
        if (!held.contains("center_of_mass"))
            com->showValue(componentsOf(bodies, [this](const BodyDesc& b) -> std::optional<Vec3> {
                if (b.centerOfMass) return b.centerOfMass;
                const auto c = computed(b);
                return c ? std::optional(c->centerOfMass) : std::nullopt;
            }));
        inertia->showOverride(state(inertiaGiven));
        if (held.contains("inertia")) return;  // the cells keep what was typed
        std::array<std::optional<double>, 9> cells;
        for (int k = 0; k < 9; ++k) {
            cells[static_cast<size_t>(k)] =
                sharedOf<double>(bodies, [&](const BodyDesc& b) -> std::optional<double> {
                    if (b.inertia) return (*b.inertia)(k / 3, k % 3);
                    const auto c = computed(b);
                    return c ? std::optional(c->inertia(k / 3, k % 3)) : std::nullopt;
                }).value;
        }
        inertia->showValue(cells);
    });
}

void PropertyDock::Impl::buildForces(QVBoxLayout* layout) {
    auto* g = new QGroupBox(QObject::tr("Forces, torques and springs"));
    auto* v = new QVBoxLayout(g);
    forcesNote = new QLabel;
    forcesNote->setObjectName("forces.note");
    forcesNote->setWordWrap(true);
    v->addWidget(forcesNote);
    forces = new ForcesEdit;
    v->addWidget(withError(forces, "forces"));
    layout->addWidget(g);
    QObject::connect(forces, &ForcesEdit::forcesEdited, q,
                     [this](const std::vector<ForceDesc>& list, const QString& text, const QString& field) {
                         apply(
                             "forces", text, [&](BodyDesc& b, int) { b.forces = list; }, !field.isEmpty(),
                             field);
                     });
    QObject::connect(forces, &ForcesEdit::editingFinished, q, [this] { ++generation; });
    refreshers.push_back([this](const std::vector<const BodyDesc*>& bodies) {
        const bool one = bodies.size() == 1;
        const bool dynamic = one && bodies[0]->motion == Motion::Dynamic;
        forces->setVisible(dynamic);
        forcesNote->setVisible(!dynamic);
        forcesNote->setText(!one ? QObject::tr("Select one body to edit its forces.")
                                 : QObject::tr("Forces act on dynamic bodies only."));
        if (dynamic) forces->setForces(bodies[0]->forces);
    });
}

}  // namespace tumble::ui
