// The property panel. Every field is a small binding: a getter that reads the value from
// a body (or says the field does not apply to it) and a setter that writes a new value
// into a copy of the body. Refreshing shows the getters over the selection; an edit runs
// the setter on a copy of each selected body, validates the copies with the engine's own
// tumble::validate, and only then hands them to the document (one body: a merged SetBody
// per field; several: one macro). Widgets are updated under QSignalBlocker (inside
// PropertySpinBox::showValue and friends), so showing a value never edits it back.
#include "panels/property_dock_impl.h"

#include "import/convex_split_dialog.h"
#include "panels/field_guard.h"
#include "panels/joint_panel.h"
#include "panels/live_state_box.h"
#include "sweep/sweep_dialog.h"

#include <tumble/collision_groups.h>

#include <QApplication>

#include <algorithm>

namespace tumble::ui {

void PropertyDock::Impl::build() {
    auto* scroll = new QScrollArea(q);
    scroll->setWidgetResizable(true);
    auto* outer = new QWidget;
    auto* outerLayout = new QVBoxLayout(outer);
    empty = new QLabel(QObject::tr("Select a body or a joint to see its properties."), outer);
    empty->setObjectName("empty");
    empty->setAlignment(Qt::AlignCenter);
    outerLayout->addWidget(empty);
    page = new QWidget(outer);
    outerLayout->addWidget(page);
    jointPage = new JointPanel(doc, outer);
    jointPage->setObjectName("jointPage");
    outerLayout->addWidget(jointPage);
    outerLayout->addStretch(1);
    auto* layout = new QVBoxLayout(page);
    layout->setContentsMargins(0, 0, 0, 0);
    scroll->setWidget(outer);
    q->setWidget(scroll);

    // ---- Body
    QFormLayout* form = group(layout, QObject::tr("Body"));
    name = new QLineEdit;
    name->setObjectName("name");
    name->setPlaceholderText(PropertySpinBox::mixedText());
    QWidget* nameRow = withError(name, "name");
    form->addRow(QObject::tr("Name"), nameRow);
    QObject::connect(name, &QLineEdit::editingFinished, q, [this] {
        name->setModified(false);  // the typing is given: Ctrl+Z now undoes the document's edits
        if (doc->selection().size() != 1) return;
        const std::string text = name->text().trimmed().toStdString();
        if (text == doc->body(doc->selection()[0]).name) return;
        apply(
            "name", QObject::tr("Rename"), [&](BodyDesc& b, int) { b.name = text; }, false);
    });
    refreshers.push_back([this](const std::vector<const BodyDesc*>& bodies) {
        const QSignalBlocker block(name);
        name->setEnabled(bodies.size() == 1);
        name->setText(bodies.size() == 1 ? QString::fromStdString(bodies[0]->name) : QString());
    });

    addChoice<Motion>(
        form, QObject::tr("Motion"), "motion", QObject::tr("Set motion"),
        {{QObject::tr("Dynamic"), Motion::Dynamic},
         {QObject::tr("Static"), Motion::Static},
         {QObject::tr("Kinematic"), Motion::Kinematic},
         {QObject::tr("Animated"), Motion::Animated}},
        [](const BodyDesc& b) { return std::optional<Motion>(b.motion); },
        [this](BodyDesc& b, int index, Motion m) { setMotion(b, index, m); });

    buildPart(layout);

    // ---- Shape
    form = group(layout, QObject::tr("Shape"));
    auto* type = addChoice<ShapeType>(
        form, QObject::tr("Type"), "shape.type", QObject::tr("Set shape type"),
        {{QObject::tr("Sphere"), ShapeType::Sphere},
         {QObject::tr("Box"), ShapeType::Box},
         {QObject::tr("Capsule"), ShapeType::Capsule},
         {QObject::tr("Cylinder"), ShapeType::Cylinder},
         {QObject::tr("Plane"), ShapeType::Plane},
         {QObject::tr("Mesh"), ShapeType::Mesh},
         {QObject::tr("Compound"), ShapeType::Compound}},
        [](const BodyDesc& b) { return std::optional<ShapeType>(b.shape.type); },
        [this](BodyDesc& b, int index, ShapeType t) {
            // A body made a compound starts as one part, its shape as it was (a plane
            // cannot be a part: a box in its place).
            if (t == ShapeType::Compound && b.shape.type != ShapeType::Compound && b.shape.parts.empty()) {
                PartDesc part;
                part.shape = b.shape;
                part.shape.parts.clear();
                if (part.shape.type == ShapeType::Plane) part.shape.type = ShapeType::Box;
                b.shape.parts.push_back(part);
            }
            b.shape.type = t;
            if (t == ShapeType::Plane) setMotion(b, index, Motion::Static);  // planes are static
        });
    type->setToolTip(
        QObject::tr("A plane makes the body static; a mesh comes from File > Import Mesh; a "
                    "compound is several shapes as one body (its parts are in the scene file)"));
    auto has = [](std::initializer_list<ShapeType> list) {
        return [types = std::vector<ShapeType>(list)](const BodyDesc& b) {
            for (ShapeType t : types)
                if (b.shape.type == t) return true;
            return false;
        };
    };
    const auto round = has({ShapeType::Sphere, ShapeType::Capsule, ShapeType::Cylinder});
    addDouble(
        form, QObject::tr("Radius"), "shape.radius", " m", 0.0, 0.05, QObject::tr("Set radius"),
        [round](const BodyDesc& b) { return round(b) ? std::optional(b.shape.radius) : std::nullopt; },
        [](BodyDesc& b, double v) { b.shape.radius = v; });
    const auto tall = has({ShapeType::Capsule, ShapeType::Cylinder});
    addDouble(
        form, QObject::tr("Half height"), "shape.half_height", " m", 0.0, 0.05,
        QObject::tr("Set half height"),
        [tall](const BodyDesc& b) { return tall(b) ? std::optional(b.shape.halfHeight) : std::nullopt; },
        [](BodyDesc& b, double v) { b.shape.halfHeight = v; });
    const auto box = has({ShapeType::Box});
    addVector(
        form, QObject::tr("Half extents"), "shape.half_extents", " m", QObject::tr("Set half extents"),
        [box](const BodyDesc& b) { return box(b) ? std::optional(b.shape.halfExtents) : std::nullopt; },
        [](BodyDesc& b, int k, double v) { b.shape.halfExtents[k] = v; })
        ->setSoftMinimum(0.0);
    const auto plane = has({ShapeType::Plane});
    addVector(
        form, QObject::tr("Normal"), "shape.normal", QString(), QObject::tr("Set plane normal"),
        [plane](const BodyDesc& b) { return plane(b) ? std::optional(b.shape.normal) : std::nullopt; },
        [](BodyDesc& b, int k, double v) { b.shape.normal[k] = v; })
        ->setSingleStep(0.1);
    addDouble(
        form, QObject::tr("Distance"), "shape.distance", " m", -1e12, 0.1, QObject::tr("Set plane distance"),
        [plane](const BodyDesc& b) { return plane(b) ? std::optional(b.shape.distance) : std::nullopt; },
        [](BodyDesc& b, double v) { b.shape.distance = v; });
    const auto mesh = has({ShapeType::Mesh});
    auto* file = new QLineEdit;
    file->setObjectName("shape.file");
    file->setReadOnly(true);
    file->setPlaceholderText(PropertySpinBox::mixedText());
    QWidget* fileRow = withError(file, "shape.file");
    form->addRow(QObject::tr("File"), fileRow);
    refreshers.push_back([form, fileRow, file, mesh](const std::vector<const BodyDesc*>& bodies) {
        const auto s = sharedOf<std::string>(
            bodies, [&](const BodyDesc& b) { return mesh(b) ? std::optional(b.shape.file) : std::nullopt; });
        form->setRowVisible(fileRow, s.applies);
        file->setText(s.value ? QString::fromStdString(*s.value) : QString());
    });
    addVector(
        form, QObject::tr("Scale"), "shape.scale", QStringLiteral("×"), QObject::tr("Set mesh scale"),
        [mesh](const BodyDesc& b) { return mesh(b) ? std::optional(b.shape.scale) : std::nullopt; },
        [](BodyDesc& b, int k, double v) {
            // meshData holds the triangles already scaled: rescale them by new/old.
            const Vec3 old = b.shape.scale;
            b.shape.scale[k] = v;
            if (b.shape.meshData && old[k] > 0.0 && v > 0.0) {
                auto m = std::make_shared<TriangleMesh>(*b.shape.meshData);
                for (Vec3& p : m->vertices) p[k] *= v / old[k];
                b.shape.meshData = std::move(m);
            }
        })
        ->setSoftMinimum(0.0);
    auto* collision = addChoice<MeshCollision>(
        form, QObject::tr("Collision"), "shape.collision", QObject::tr("Set mesh collision"),
        {{QObject::tr("Convex hull"), MeshCollision::ConvexHull},
         {QObject::tr("Triangles"), MeshCollision::Triangles},
         {QObject::tr("Convex parts"), MeshCollision::ConvexParts}},
        [mesh](const BodyDesc& b) { return mesh(b) ? std::optional(b.shape.collision) : std::nullopt; },
        [](BodyDesc& b, int, MeshCollision c) { b.shape.collision = c; });
    // Convex parts for one loaded mesh: made in the Split dialog, in the background, seen
    // before they are applied (several bodies at once are split under a wait cursor).
    QObject::disconnect(collision, &QComboBox::activated, q, nullptr);
    QObject::connect(collision, &QComboBox::activated, q, [this, collision](int i) {
        const MeshCollision c = MeshCollision(collision->itemData(i).toInt());
        const QList<int> sel = doc->selection();
        if (c == MeshCollision::ConvexParts && sel.size() == 1 && doc->body(sel[0]).shape.meshData &&
            doc->body(sel[0]).shape.collision != MeshCollision::ConvexParts) {
            ConvexSplitDialog dialog(doc, sel[0], q->window());
            dialog.exec();
            refresh();  // (cancelled: the combo shows the collision as it is)
            return;
        }
        apply(
            "shape.collision", QObject::tr("Set mesh collision"),
            [c](BodyDesc& b, int) { b.shape.collision = c; }, false);
    });

    buildMass(layout);

    // ---- Material
    form = group(layout, QObject::tr("Material"));
    addDouble(
        form, QObject::tr("Restitution"), "restitution", QString(), 0.0, 0.05, QObject::tr("Set restitution"),
        [](const BodyDesc& b) { return std::optional(b.restitution); },
        [](BodyDesc& b, double v) { b.restitution = v; })
        ->setToolTip(QObject::tr("0: no bounce, 1: elastic"));
    addDouble(
        form, QObject::tr("Friction"), "friction", QString(), 0.0, 0.05, QObject::tr("Set friction"),
        [](const BodyDesc& b) { return std::optional(b.friction); },
        [](BodyDesc& b, double v) { b.friction = v; })
        ->setToolTip(QObject::tr("Coulomb coefficient"));
    addDouble(
        form, QObject::tr("Linear damping"), "linear_damping", " 1/s", 0.0, 0.01,
        QObject::tr("Set linear damping"), [](const BodyDesc& b) { return std::optional(b.linearDamping); },
        [](BodyDesc& b, double v) { b.linearDamping = v; });
    addDouble(
        form, QObject::tr("Angular damping"), "angular_damping", " 1/s", 0.0, 0.01,
        QObject::tr("Set angular damping"), [](const BodyDesc& b) { return std::optional(b.angularDamping); },
        [](BodyDesc& b, double v) { b.angularDamping = v; });

    // Its collision group, one of the scene's (Simulation > Collision Groups names them).
    auto* groupCombo = new QComboBox;
    groupCombo->setObjectName("collision_group");
    groupCombo->setToolTip(QObject::tr("Which bodies it collides with: Simulation > Collision Groups"));
    QWidget* groupRow = withError(groupCombo, "collision_group");
    form->addRow(QObject::tr("Collision group"), groupRow);
    QObject::connect(groupCombo, &QComboBox::activated, q, [this, groupCombo](int i) {
        const std::string name = groupCombo->itemText(i).toStdString();
        apply(
            "collision_group", QObject::tr("Set collision group"),
            [&](BodyDesc& b, int) { b.collisionGroup = name; }, false);
    });
    refreshers.push_back([this, groupCombo](const std::vector<const BodyDesc*>& bodies) {
        const QSignalBlocker block(groupCombo);
        groupCombo->clear();
        for (const std::string& name : collisionGroupNames(doc->scene().settings))
            groupCombo->addItem(QString::fromStdString(name));
        const auto s =
            sharedOf<std::string>(bodies, [](const BodyDesc& b) { return std::optional(b.collisionGroup); });
        groupCombo->setCurrentIndex(s.value ? groupCombo->findText(QString::fromStdString(*s.value)) : -1);
    });

    // ---- Initial state
    form = group(layout, QObject::tr("Initial state"));
    addVector(
        form, QObject::tr("Position"), "position", " m", QObject::tr("Set position"),
        [](const BodyDesc& b) { return std::optional(b.position); },
        [](BodyDesc& b, int k, double v) { b.position[k] = v; })
        ->setSingleStep(0.1);
    auto* orientation = addVector(
        form, QObject::tr("Orientation"), "orientation", QStringLiteral("°"), QObject::tr("Set orientation"),
        [this](const BodyDesc& b) { return std::optional(eulerOf(b)); },
        [this](BodyDesc& b, int k, double v) {
            Vec3 e = eulerOf(b);
            e[k] = v;
            b.orientation = eulerDegreesToQuat(e);
            if (doc->selection().size() == 1) shownEuler = e;
        });
    orientation->setSingleStep(5.0);
    orientation->setToolTip(
        QObject::tr("Euler angles (x, y, z) in degrees: rotate about z, then the new y, then the new x "
                    "(intrinsic Z-Y'-X''; q = Rz(z) Ry(y) Rx(x))"));
    auto* velocity = addVector(
        form, QObject::tr("Velocity"), "velocity", " m/s", QObject::tr("Set velocity"),
        [](const BodyDesc& b) { return std::optional(b.velocity); },
        [](BodyDesc& b, int k, double v) { b.velocity[k] = v; });
    velocity->setToolTip(QObject::tr("World velocity of the centre of mass; a static body cannot move"));
    auto* spin = addVector(
        form, QObject::tr("Angular velocity"), "angular_velocity", " rad/s", QObject::tr("Set angular velocity"),
        [](const BodyDesc& b) { return std::optional(b.angularVelocity); },
        [](BodyDesc& b, int k, double v) { b.angularVelocity[k] = v; });
    spin->setToolTip(QObject::tr("World frame"));
    // An animated body moves as its keys say: no velocity of its own to type.
    refreshers.push_back([velocity, spin](const std::vector<const BodyDesc*>& bodies) {
        const bool keyed = std::any_of(bodies.begin(), bodies.end(),
                                       [](const BodyDesc* b) { return b->motion == Motion::Animated; });
        for (VectorEdit* e : {velocity, spin}) {
            e->setEnabled(!keyed);
            e->setToolTip(keyed ? QObject::tr("An animated body moves as its keys say (Keys, below)")
                          : e == velocity ? QObject::tr("World velocity of the centre of mass; a static body cannot move")
                                          : QObject::tr("World frame"));
        }
    });

    buildForces(layout);
    buildKeys(layout);

    // Editing a field anew (after Enter or leaving it) is a new undo step; a scrub is one.
    for (auto* spin : q->findChildren<PropertySpinBox*>())
        QObject::connect(spin, &PropertySpinBox::editingFinished, q, [this] { ++generation; });
}

PropertyDock::PropertyDock(Document* doc, QWidget* parent)
    : QDockWidget(tr("Properties"), parent), d_(std::make_unique<Impl>()) {
    installFieldGuard();  // the wheel scrolls the panel, not the field under it
    setObjectName("PropertyDock");
    d_->q = this;
    d_->doc = doc;
    d_->build();
    auto selectionMoved = [this] {
        ++d_->generation;
        d_->lastMacro = {};
        d_->dropHeld();
        d_->clearErrors();
        refresh();
    };
    connect(doc, &Document::selectionChanged, this, selectionMoved);
    connect(doc, &Document::sceneReset, this, [this, selectionMoved] {
        d_->stash.clear();
        d_->meshCache.clear();
        selectionMoved();
    });
    connect(doc, &Document::bodyChanged, this, [this](int index) {
        if (d_->doc->selection().contains(index)) refresh();
    });
    connect(doc, &Document::bodyInserted, this, [this] {
        d_->stash.clear();  // indices moved
        refresh();
    });
    connect(doc, &Document::bodyRemoved, this, [this] {
        d_->stash.clear();
        refresh();
    });
    refresh();
}

PropertyDock::~PropertyDock() {
    // A field with the keyboard focus is left when its window closes, and its
    // editingFinished reaches the panel: let that happen while the panel is still whole
    // (a dock closed on its own, as a test does, crashed in the name field's handler).
    if (QWidget* w = QApplication::focusWidget(); w && isAncestorOf(w)) w->clearFocus();
}

void PropertyDock::refresh() {
    d_->refresh();
}

void PropertyDock::setTimeline(Timeline* timeline) {
    if (auto* old = findChild<LiveStateBox*>()) delete old;
    if (!timeline) return;
    auto* layout = static_cast<QVBoxLayout*>(d_->page->layout());
    layout->insertWidget(0, new LiveStateBox(d_->doc, timeline));
}

QString PropertyDock::fieldError(const QString& field) const {
    QLabel* label = d_->errors.value(field);
    return label && !label->isHidden() ? label->text() : QString();
}

void PropertyDock::Impl::openSweep(const QString& key, double value) {
    const auto bodies = selected();
    if (bodies.size() != 1) return;
    auto* dialog = new SweepDialog(doc, QString::fromStdString(bodies[0]->name) + "." + key, value, q);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
}

}  // namespace tumble::ui
