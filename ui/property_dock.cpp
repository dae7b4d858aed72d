// The property panel. Every field is a small binding: a getter that reads the value from
// a body (or says the field does not apply to it) and a setter that writes a new value
// into a copy of the body. Refreshing shows the getters over the selection; an edit runs
// the setter on a copy of each selected body, validates the copies with the engine's own
// tumble::validate, and only then hands them to the document (one body: a merged SetBody
// per field; several: one macro). Widgets are updated under QSignalBlocker (inside
// PropertySpinBox::showValue and friends), so showing a value never edits it back.
#include "property_dock.h"

#include "document.h"
#include "forces_edit.h"
#include "inertia_edit.h"
#include "property_euler.h"
#include "property_spin_box.h"
#include "vector_edit.h"

#include <tumble/errors.h>
#include <tumble/mass.h>
#include <tumble/model.h>

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHash>
#include <QLabel>
#include <QLineEdit>
#include <QMap>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QUndoStack>
#include <QVBoxLayout>

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <tuple>

namespace tumble::ui {

namespace {

using Change = std::function<void(BodyDesc&, int index)>;

// A value every selected body agrees on, or none ("—"); `applies` is false when the field
// means nothing for at least one of them (the row is hidden).
template <class T>
struct Shared {
    bool applies = false;
    std::optional<T> value;
};

template <class T, class Get>
Shared<T> sharedOf(const std::vector<const BodyDesc*>& bodies, Get get) {
    Shared<T> s;
    if (bodies.empty()) return s;
    s.applies = true;
    bool same = true;
    std::optional<T> first;
    for (const BodyDesc* b : bodies) {
        const std::optional<T> v = get(*b);
        if (!v) return Shared<T>{};
        if (!first)
            first = v;
        else if (!(*first == *v))
            same = false;
    }
    if (same) s.value = first;
    return s;
}

std::array<std::optional<double>, 3> componentsOf(
    const std::vector<const BodyDesc*>& bodies,
    const std::function<std::optional<Vec3>(const BodyDesc&)>& get) {
    std::array<std::optional<double>, 3> out;
    for (int k = 0; k < 3; ++k) {
        out[static_cast<size_t>(k)] =
            sharedOf<double>(bodies, [&](const BodyDesc& b) -> std::optional<double> {
                const auto v = get(b);
                return v ? std::optional<double>((*v)[k]) : std::nullopt;
            }).value;
    }
    return out;
}

QLabel* errorLabel(QWidget* parent, const QString& key) {
    auto* label = new QLabel(parent);
    label->setObjectName(key + ".error");
    label->setStyleSheet("color: #c62828;");
    label->setWordWrap(true);
    label->hide();
    return label;
}

// What the mass properties of a body would be without its overrides.
struct Computed {
    double mass = 0.0;
    Vec3 centerOfMass = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
};

bool isPrimitive(ShapeType t) {
    return t != ShapeType::Plane && t != ShapeType::Mesh;
}

}  // namespace

struct PropertyDock::Impl {
    PropertyDock* q = nullptr;
    Document* doc = nullptr;
    QWidget* page = nullptr;
    QLabel* empty = nullptr;
    std::vector<std::function<void(const std::vector<const BodyDesc*>&)>> refreshers;
    QMap<QString, QLabel*> errors;
    int generation = 1;  // a new merge id per field after each editingFinished

    // A multi-selection edit is a macro; consecutive edits of the same field on the same
    // selection replace the previous macro (undo it, push again) so a scrub is one step.
    struct LastMacro {
        int mergeId = 0;
        QList<int> selection;
        int index = -1;
        const QUndoCommand* command = nullptr;
    } lastMacro;

    // Motion switches clear what the new motion may not have; switching back restores it.
    struct Stash {
        bool hasMass = false;
        std::optional<double> mass, density;
        std::optional<Mat3> inertia;
        std::optional<Vec3> centerOfMass;
        std::vector<ForceDesc> forces;
        bool hasVelocity = false;
        Vec3 velocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
    };
    QHash<int, Stash> stash;

    // Unit-density mass properties of meshes (compiling a mesh builds its hull: cache it).
    std::map<std::tuple<const void*, double, double, double, int>, std::optional<Computed>> meshCache;

    // Euler angles last shown for a single selection, kept while they still describe the
    // body's quaternion (so 0/120/0 does not jump to its equivalent 180/60/180).
    Vec3 shownEuler = Vec3::Zero();

    QComboBox* massKind = nullptr;
    PropertySpinBox* mass = nullptr;
    QLabel* massNote = nullptr;
    QLabel* noMass = nullptr;
    QGroupBox* massGroup = nullptr;
    QCheckBox* comOverride = nullptr;
    VectorEdit* com = nullptr;
    InertiaEdit* inertia = nullptr;
    ForcesEdit* forces = nullptr;
    QLabel* forcesNote = nullptr;
    QLineEdit* name = nullptr;

    std::vector<const BodyDesc*> selected() const {
        std::vector<const BodyDesc*> out;
        for (int i : doc->selection())
            if (i >= 0 && i < doc->bodyCount()) out.push_back(&doc->body(i));
        return out;
    }

    std::optional<Computed> computed(const BodyDesc& b) {
        if (b.motion != Motion::Dynamic || (!b.mass && !b.density)) return std::nullopt;
        if (isPrimitive(b.shape.type)) {
            const double m = b.mass ? *b.mass : *b.density * shapeVolume(b.shape);
            if (!std::isfinite(m) || !(m > 0.0)) return std::nullopt;
            const MassProperties mp = primitiveMassProperties(b.shape, m);
            if (!mp.inertia.allFinite()) return std::nullopt;
            return Computed{mp.mass, mp.centerOfMass, mp.inertia};
        }
        if (b.shape.type != ShapeType::Mesh || !b.shape.meshData) return std::nullopt;
        const auto key = std::make_tuple(static_cast<const void*>(b.shape.meshData.get()), b.shape.scale.x(),
                                         b.shape.scale.y(), b.shape.scale.z(), int(b.shape.collision));
        auto it = meshCache.find(key);
        if (it == meshCache.end()) {
            std::optional<Computed> unit;
            try {
                SceneDesc s;
                BodyDesc c;
                c.name = "mesh";
                c.shape = b.shape;
                c.density = 1.0;
                s.bodies.push_back(c);
                const Model m = compile(s);
                unit = Computed{m.bodies[0].mass, m.bodies[0].centerOfMass, m.bodies[0].inertia};
            } catch (const std::exception&) {
            }
            it = meshCache.emplace(key, unit).first;
        }
        if (!it->second) return std::nullopt;
        Computed c = *it->second;  // density 1: mass is the volume
        const double density = b.mass ? *b.mass / c.mass : *b.density;
        c.mass *= density;
        c.inertia *= density;
        return c;
    }

    Vec3 eulerOf(const BodyDesc& b) const {
        if (doc->selection().size() == 1 &&
            sameRotation(eulerDegreesToQuat(shownEuler), b.orientation, 1e-12))
            return shownEuler;
        return quatToEulerDegrees(b.orientation);
    }

    void setMotion(BodyDesc& b, int index, Motion m) {
        if (b.motion == m) return;
        Stash& s = stash[index];
        if (b.motion == Motion::Dynamic) {
            s.hasMass = true;
            s.mass = b.mass;
            s.density = b.density;
            s.inertia = b.inertia;
            s.centerOfMass = b.centerOfMass;
            s.forces = b.forces;
            b.mass.reset();
            b.density.reset();
            b.inertia.reset();
            b.centerOfMass.reset();
            b.forces.clear();
        }
        if (m == Motion::Static) {
            s.hasVelocity = true;
            s.velocity = b.velocity;
            s.angularVelocity = b.angularVelocity;
            b.velocity = b.angularVelocity = Vec3::Zero();
        } else if (b.motion == Motion::Static && s.hasVelocity) {
            b.velocity = s.velocity;
            b.angularVelocity = s.angularVelocity;
        }
        if (m == Motion::Dynamic) {
            if (s.hasMass) {
                b.mass = s.mass;
                b.density = s.density;
                b.inertia = s.inertia;
                b.centerOfMass = s.centerOfMass;
                b.forces = s.forces;
            }
            if (!b.mass && !b.density) b.mass = 1.0;
        }
        b.motion = m;
    }

    void showError(const QString& key, const QString& message) {
        QLabel* label = errors.value(key);
        if (!label) return;
        label->setText(message);
        label->setVisible(!message.isEmpty());
    }

    void clearErrors() {
        for (QLabel* l : errors) {
            l->clear();
            l->hide();
        }
    }

    int mergeIdFor(const QString& key) const {
        return static_cast<int>((qHash(key) ^ (static_cast<size_t>(generation) * 0x9e3779b9u)) & 0x3fffffff) |
               1;
    }

    // Applies `change` to every selected body, if the result is a valid scene. `key` names the
    // field (its error label); `merge` makes consecutive edits of it one undo step.
    bool apply(const QString& key, const QString& text, const Change& change, bool merge = true,
               const QString& mergeKey = QString()) {
        const QList<int> sel = doc->selection();
        if (sel.isEmpty()) return false;
        QUndoStack* stack = doc->undoStack();
        const int mergeId = merge ? mergeIdFor(mergeKey.isEmpty() ? key : mergeKey) : 0;
        bool undone = false;
        if (sel.size() > 1 && mergeId && lastMacro.mergeId == mergeId && lastMacro.selection == sel &&
            stack->index() == lastMacro.index && stack->index() > 0 && !stack->canRedo() &&
            stack->command(stack->index() - 1) == lastMacro.command) {
            stack->undo();  // the previous step of this scrub: replaced below
            undone = true;
        }
        std::vector<BodyDesc> bodies;
        SceneDesc check;  // the changed bodies alone: other bodies' problems are not this field's
        for (int i : sel) {
            BodyDesc b = doc->body(i);
            change(b, i);
            bodies.push_back(b);
            check.bodies.push_back(b);
        }
        QString error;
        try {
            validate(check);
        } catch (const SceneError& e) {
            QString path = QString::fromStdString(e.path());
            const int dot = path.indexOf('.');
            path = dot >= 0 && path.startsWith("bodies[") ? path.mid(dot + 1) : QString();
            error = QString::fromStdString(e.message());
            if (!path.isEmpty() && !path.startsWith(key)) error = path + ": " + error;
            if (sel.size() > 1) {
                // Name the body the message is about.
                const QString full = QString::fromStdString(e.path());
                const int open = full.indexOf('['), close = full.indexOf(']');
                const int k = open >= 0 && close > open ? full.mid(open + 1, close - open - 1).toInt() : 0;
                if (k >= 0 && k < static_cast<int>(bodies.size()))
                    error = QString::fromStdString(bodies[static_cast<size_t>(k)].name) + ": " + error;
            }
        }
        if (error.isEmpty() && key == "name") {
            for (size_t n = 0; n < bodies.size(); ++n) {
                for (int j = 0; j < doc->bodyCount(); ++j) {
                    if (!sel.contains(j) && doc->body(j).name == bodies[n].name) {
                        error = QObject::tr("'%1' is already the name of another body")
                                    .arg(QString::fromStdString(bodies[n].name));
                    }
                }
            }
        }
        if (!error.isEmpty()) {
            if (undone) stack->redo();
            showError(key, error);
            refresh();  // back to the last good values
            return false;
        }
        showError(key, QString());
        if (sel.size() == 1) {
            doc->setBody(sel[0], bodies[0], text, mergeId);
        } else {
            QList<int> changed;
            for (int n = 0; n < sel.size(); ++n)
                if (!(bodies[static_cast<size_t>(n)] == doc->body(sel[n]))) changed.append(n);
            if (!changed.isEmpty()) {
                doc->beginMacro(text);
                for (int n : changed) doc->setBody(sel[n], bodies[static_cast<size_t>(n)], text);
                doc->endMacro();
                lastMacro = {mergeId, sel, stack->index(), stack->command(stack->index() - 1)};
            } else {
                lastMacro = {};
            }
        }
        refresh();
        return true;
    }

    void refresh() {
        const auto bodies = selected();
        empty->setVisible(bodies.empty());
        page->setVisible(!bodies.empty());
        if (bodies.size() == 1 && doc->selection().size() == 1) shownEuler = eulerOf(*bodies[0]);
        for (const auto& r : refreshers) r(bodies);
    }

    // ---- Building the rows.

    // The editor and its error label, one under the other, as the field of a form row.
    QWidget* withError(QWidget* editor, const QString& key) {
        auto* box = new QWidget;
        auto* layout = new QVBoxLayout(box);
        layout->setContentsMargins(0, 0, 0, 0);
        layout->setSpacing(1);
        layout->addWidget(editor);
        QLabel* error = errorLabel(box, key);
        layout->addWidget(error);
        errors.insert(key, error);
        return box;
    }

    PropertySpinBox* addDouble(QFormLayout* form, const QString& label, const QString& key,
                               const QString& suffix, double min, double step, const QString& text,
                               std::function<std::optional<double>(const BodyDesc&)> get,
                               std::function<void(BodyDesc&, double)> set) {
        auto* spin = new PropertySpinBox;
        spin->setObjectName(key);
        spin->setSuffix(suffix);
        spin->setMinimum(min);
        spin->setSingleStep(step);
        QWidget* row = withError(spin, key);
        form->addRow(label, row);
        QObject::connect(spin, &PropertySpinBox::valueChanged, q, [this, key, text, set](double v) {
            apply(key, text, [&](BodyDesc& b, int) { set(b, v); });
        });
        refreshers.push_back([form, row, spin, get](const std::vector<const BodyDesc*>& bodies) {
            const Shared<double> s = sharedOf<double>(bodies, get);
            form->setRowVisible(row, s.applies);
            if (!s.applies) return;
            if (s.value)
                spin->showValue(*s.value);
            else
                spin->showMixed(get(*bodies.front()).value_or(0.0));
        });
        return spin;
    }

    VectorEdit* addVector(QFormLayout* form, const QString& label, const QString& key, const QString& suffix,
                          const QString& text, std::function<std::optional<Vec3>(const BodyDesc&)> get,
                          std::function<void(BodyDesc&, int, double)> set) {
        auto* edit = new VectorEdit(key, suffix);
        QWidget* row = withError(edit, key);
        form->addRow(label, row);
        QObject::connect(edit, &VectorEdit::componentEdited, q, [this, key, text, set](int k, double v) {
            apply(
                key, text, [&](BodyDesc& b, int) { set(b, k, v); }, true, key + "." + QString::number(k));
        });
        refreshers.push_back([form, row, edit, get](const std::vector<const BodyDesc*>& bodies) {
            const Shared<Vec3> s = sharedOf<Vec3>(bodies, get);
            form->setRowVisible(row, s.applies);
            if (s.applies)
                edit->showValue(componentsOf(bodies, get), get(*bodies.front()).value_or(Vec3::Zero()));
        });
        return edit;
    }

    template <class E>
    QComboBox* addChoice(QFormLayout* form, const QString& label, const QString& key, const QString& text,
                         const QList<std::pair<QString, E>>& items,
                         std::function<std::optional<E>(const BodyDesc&)> get,
                         std::function<void(BodyDesc&, int, E)> set) {
        auto* combo = new QComboBox;
        combo->setObjectName(key);
        for (const auto& [name, value] : items) combo->addItem(name, int(value));
        QWidget* row = withError(combo, key);
        form->addRow(label, row);
        QObject::connect(combo, &QComboBox::activated, q, [this, combo, key, text, set](int i) {
            const E value = E(combo->itemData(i).toInt());
            apply(
                key, text, [&](BodyDesc& b, int index) { set(b, index, value); }, false);
        });
        refreshers.push_back([form, row, combo, get](const std::vector<const BodyDesc*>& bodies) {
            const auto s = sharedOf<E>(bodies, get);
            form->setRowVisible(row, s.applies);
            const QSignalBlocker block(combo);
            combo->setCurrentIndex(s.value ? combo->findData(int(*s.value)) : -1);
        });
        return combo;
    }

    static QFormLayout* group(QVBoxLayout* layout, const QString& title, QGroupBox** box = nullptr) {
        auto* g = new QGroupBox(title);
        auto* form = new QFormLayout(g);
        form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
        layout->addWidget(g);
        if (box) *box = g;
        return form;
    }

    void build();
    void buildMass(QVBoxLayout* layout);
    void buildForces(QVBoxLayout* layout);
};

void PropertyDock::Impl::build() {
    auto* scroll = new QScrollArea(q);
    scroll->setWidgetResizable(true);
    auto* outer = new QWidget;
    auto* outerLayout = new QVBoxLayout(outer);
    empty = new QLabel(QObject::tr("Select a body to see its properties."), outer);
    empty->setObjectName("empty");
    empty->setAlignment(Qt::AlignCenter);
    outerLayout->addWidget(empty);
    page = new QWidget(outer);
    outerLayout->addWidget(page);
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
         {QObject::tr("Kinematic"), Motion::Kinematic}},
        [](const BodyDesc& b) { return std::optional<Motion>(b.motion); },
        [this](BodyDesc& b, int index, Motion m) { setMotion(b, index, m); });

    // ---- Shape
    form = group(layout, QObject::tr("Shape"));
    auto* type = addChoice<ShapeType>(
        form, QObject::tr("Type"), "shape.type", QObject::tr("Set shape type"),
        {{QObject::tr("Sphere"), ShapeType::Sphere},
         {QObject::tr("Box"), ShapeType::Box},
         {QObject::tr("Capsule"), ShapeType::Capsule},
         {QObject::tr("Cylinder"), ShapeType::Cylinder},
         {QObject::tr("Plane"), ShapeType::Plane},
         {QObject::tr("Mesh"), ShapeType::Mesh}},
        [](const BodyDesc& b) { return std::optional<ShapeType>(b.shape.type); },
        [this](BodyDesc& b, int index, ShapeType t) {
            b.shape.type = t;
            if (t == ShapeType::Plane) setMotion(b, index, Motion::Static);  // planes are static
        });
    type->setToolTip(QObject::tr("A plane makes the body static; a mesh comes from File > Import Mesh"));
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
        ->setRange(0.0, 1e12);
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
        ->setRange(0.0, 1e12);
    addChoice<MeshCollision>(
        form, QObject::tr("Collision"), "shape.collision", QObject::tr("Set mesh collision"),
        {{QObject::tr("Convex hull"), MeshCollision::ConvexHull},
         {QObject::tr("Triangles"), MeshCollision::Triangles}},
        [mesh](const BodyDesc& b) { return mesh(b) ? std::optional(b.shape.collision) : std::nullopt; },
        [](BodyDesc& b, int, MeshCollision c) { b.shape.collision = c; });

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

    // ---- Initial state
    form = group(layout, QObject::tr("Initial state"));
    addVector(
        form, QObject::tr("Position"), "position", " m", QObject::tr("Move"),
        [](const BodyDesc& b) { return std::optional(b.position); },
        [](BodyDesc& b, int k, double v) { b.position[k] = v; })
        ->setSingleStep(0.1);
    auto* orientation = addVector(
        form, QObject::tr("Orientation"), "orientation", QStringLiteral("°"), QObject::tr("Rotate"),
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
    addVector(
        form, QObject::tr("Velocity"), "velocity", " m/s", QObject::tr("Set velocity"),
        [](const BodyDesc& b) { return std::optional(b.velocity); },
        [](BodyDesc& b, int k, double v) { b.velocity[k] = v; })
        ->setToolTip(QObject::tr("World velocity of the centre of mass; a static body cannot move"));
    addVector(
        form, QObject::tr("Angular velocity"), "angular_velocity", " rad/s",
        QObject::tr("Set angular velocity"),
        [](const BodyDesc& b) { return std::optional(b.angularVelocity); },
        [](BodyDesc& b, int k, double v) { b.angularVelocity[k] = v; })
        ->setToolTip(QObject::tr("World frame"));

    buildForces(layout);

    // Editing a field anew (after Enter or leaving it) is a new undo step; a scrub is one.
    for (auto* spin : q->findChildren<PropertySpinBox*>())
        QObject::connect(spin, &PropertySpinBox::editingFinished, q, [this] { ++generation; });
}

void PropertyDock::Impl::buildMass(QVBoxLayout* layout) {
    QFormLayout* form = group(layout, QObject::tr("Mass"), &massGroup);
    noMass = new QLabel(QObject::tr("Static and kinematic bodies have no mass."));
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
    mass->setMinimum(0.0);
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
        apply("mass", QObject::tr("Set mass"), [&](BodyDesc& b, int) {
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
        apply(
            "center_of_mass", QObject::tr("Set centre of mass"),
            [&](BodyDesc& b, int) {
                const auto c = computed(b);
                Vec3 p = b.centerOfMass.value_or(c ? c->centerOfMass : Vec3::Zero());
                p[k] = value;
                b.centerOfMass = p;
            },
            true, QStringLiteral("center_of_mass.%1").arg(k));
    });

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
        apply(
            "inertia", QObject::tr("Set inertia"),
            [&](BodyDesc& b, int) {
                Mat3 m = start(b);
                m(i, j) = m(j, i) = value;
                b.inertia = m;
            },
            true, QStringLiteral("inertia.%1%2").arg(std::min(i, j)).arg(std::max(i, j)));
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
        com->showValue(componentsOf(bodies, [this](const BodyDesc& b) -> std::optional<Vec3> {
            if (b.centerOfMass) return b.centerOfMass;
            const auto c = computed(b);
            return c ? std::optional(c->centerOfMass) : std::nullopt;
        }));
        inertia->showOverride(state(inertiaGiven));
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

PropertyDock::PropertyDock(Document* doc, QWidget* parent)
    : QDockWidget(tr("Properties"), parent), d_(std::make_unique<Impl>()) {
    setObjectName("PropertyDock");
    d_->q = this;
    d_->doc = doc;
    d_->build();
    auto selectionMoved = [this] {
        ++d_->generation;
        d_->lastMacro = {};
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

PropertyDock::~PropertyDock() = default;

void PropertyDock::refresh() {
    d_->refresh();
}

QString PropertyDock::fieldError(const QString& field) const {
    QLabel* label = d_->errors.value(field);
    return label && !label->isHidden() ? label->text() : QString();
}

}  // namespace tumble::ui
