// The inside of PropertyDock, shared by property_dock.cpp (the dock, the body, shape,
// material and state rows) and property_dock_mass.cpp (the mass and forces rows).
#pragma once

#include "panels/property_dock.h"

#include "document/document.h"
#include "panels/field_guard.h"
#include "panels/forces_edit.h"
#include "panels/inertia_edit.h"
#include "panels/keys_edit.h"
#include "panels/property_euler.h"
#include "panels/property_spin_box.h"
#include "panels/vector_edit.h"

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

namespace property_detail {

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

inline std::array<std::optional<double>, 3> componentsOf(
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

inline QLabel* errorLabel(QWidget* parent, const QString& key) {
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

inline bool isPrimitive(ShapeType t) {
    return t != ShapeType::Plane && t != ShapeType::Mesh;
}

}  // namespace property_detail

using namespace property_detail;

struct PropertyDock::Impl {
    PropertyDock* q = nullptr;
    Document* doc = nullptr;
    QWidget* page = nullptr;
    QWidget* jointPage = nullptr;
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
        std::vector<BodyKey> keys;  // an animated body's, while it is something else
        KeyInterpolation interpolation = KeyInterpolation::Linear;
    };
    QHash<int, Stash> stash;

    // Unit-density mass properties of meshes (compiling a mesh builds its hull: cache it).
    std::map<std::tuple<const void*, double, double, double, int>, std::optional<Computed>> meshCache;

    // A vector or matrix whose edit would be refused part way (a plane normal turned from y
    // to z passes through zero; an inertia tensor between two valid ones breaks the triangle
    // inequality) is held: its fields keep what was typed, framed red, the message under them
    // says why in the panel's words, and each further edit of the same value is tried
    // together with the held parts, until the whole is valid (then it is applied as one edit)
    // or Esc gives it up. By field key, then by part (a component or a cell) in edit order.
    QHash<QString, std::vector<std::pair<int, Change>>> held;
    QHash<QString, std::function<void(bool)>> markHeld;  // frames a held field red, or not

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
    KeysEdit* keys = nullptr;  // an animated body's (property_dock_keys.cpp)
    QWidget* keysBox = nullptr;
    QLabel* forcesNote = nullptr;
    QLineEdit* name = nullptr;

    std::vector<const BodyDesc*> selected() const {
        std::vector<const BodyDesc*> out;
        for (int i : doc->selection())
            if (i >= 0 && i < doc->bodyCount()) out.push_back(&doc->body(i));
        return out;
    }

    std::optional<Computed> computed(const BodyDesc& b) {
        if (b.motion != Motion::Dynamic) return std::nullopt;
        if (b.shape.type == ShapeType::Compound) {
            // The parts' sum, as compile makes it (each part may have its own density).
            try {
                SceneDesc s;
                BodyDesc c = b;
                c.forces.clear();
                c.inertia.reset();
                c.centerOfMass.reset();
                s.bodies.push_back(c);
                const Model m = compile(s);
                return Computed{m.bodies[0].mass, m.bodies[0].centerOfMass, m.bodies[0].inertia};
            } catch (const std::exception&) {
                return std::nullopt;
            }
        }
        if (!b.mass && !b.density) return std::nullopt;
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
        // Static and animated bodies have no velocity of their own; only animated ones keys.
        const auto still = [](Motion x) { return x == Motion::Static || x == Motion::Animated; };
        if (still(m) && !still(b.motion)) {
            s.hasVelocity = true;
            s.velocity = b.velocity;
            s.angularVelocity = b.angularVelocity;
            b.velocity = b.angularVelocity = Vec3::Zero();
        } else if (!still(m) && still(b.motion) && s.hasVelocity) {
            b.velocity = s.velocity;
            b.angularVelocity = s.angularVelocity;
        }
        if (b.motion == Motion::Animated) {
            s.keys = std::move(b.keys);
            s.interpolation = b.interpolation;
            b.keys.clear();
        }
        if (m == Motion::Animated) {
            b.keys = std::move(s.keys);
            b.interpolation = s.interpolation;
            s.keys.clear();
            // Its first key: where it stands, at the start.
            if (b.keys.empty()) b.keys.push_back({0.0, b.position, b.orientation});
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

    // An edit's undo entry: "Set mass of box-3 to 25 kg", "Set mass of 3 bodies to 25 kg".
    QString editText(const QString& what, const QString& value) const {
        const QList<int> sel = doc->selection();
        const QString who = sel.size() == 1 && sel[0] >= 0 && sel[0] < doc->bodyCount()
                                ? QString::fromStdString(doc->body(sel[0]).name)
                                : QObject::tr("%n bodies", nullptr, static_cast<int>(sel.size()));
        return Document::editText(what, who, value);
    }
    // A component's words: "x", "y", "z".
    static QString axisName(int k) { return QString(QChar(u'x' + k)); }

    // The selected bodies with `change` made, in selection order.
    std::vector<BodyDesc> changedBodies(const Change& change) const {
        std::vector<BodyDesc> bodies;
        for (int i : doc->selection()) {
            BodyDesc b = doc->body(i);
            change(b, i);
            bodies.push_back(b);
        }
        return bodies;
    }

    // Why the selected bodies, changed into `bodies`, would be refused ("" if they would
    // not): the engine's message without the file's path, naming the body when several are
    // selected. Only the changed bodies are checked: other bodies' problems are not this
    // field's.
    QString refusal(const QString& key, const std::vector<BodyDesc>& bodies) const {
        const QList<int> sel = doc->selection();
        SceneDesc check;
        check.settings = doc->scene().settings;  // (its collision groups, for a body's)
        check.bodies = bodies;
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
            for (const BodyDesc& b : bodies) {
                for (int j = 0; j < doc->bodyCount(); ++j) {
                    if (!sel.contains(j) && doc->body(j).name == b.name) {
                        error = QObject::tr("'%1' is already the name of another body")
                                    .arg(QString::fromStdString(b.name));
                    }
                }
            }
        }
        return error;
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
        const std::vector<BodyDesc> bodies = changedBodies(change);
        const QString error = refusal(key, bodies);
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
        const bool joint = doc->selectedJoint() >= 0;  // its own page (joint_panel.h)
        empty->setVisible(bodies.empty() && !joint);
        page->setVisible(!bodies.empty());
        if (jointPage) jointPage->setVisible(joint);
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
        whenFieldLeft(editor, [this, key] {
            if (!held.contains(key)) showError(key, QString());  // a held value keeps its reason
        });
        return box;
    }

    // "Sweep this value…" on a field of one selected body: `key` as tumble sweep names it
    // after the body's name ("restitution", "shape.radius", "velocity[1]"); a function for
    // the mass field, whose key is mass or density as the body has it.
    void offerSweep(PropertySpinBox* spin, const std::function<QString()>& key) {
        spin->setSweep([this, spin, key] { openSweep(key(), spin->value()); },
                       [this] { return selected().size() == 1 && doc->selection().size() == 1; });
    }
    void openSweep(const QString& key, double value);  // (property_dock.cpp)

    PropertySpinBox* addDouble(QFormLayout* form, const QString& label, const QString& key,
                               const QString& suffix, double min, double step, const QString& text,
                               std::function<std::optional<double>(const BodyDesc&)> get,
                               std::function<void(BodyDesc&, double)> set) {
        auto* spin = new PropertySpinBox;
        spin->setObjectName(key);
        offerSweep(spin, [key] { return key; });
        spin->setSuffix(suffix);
        spin->setSoftMinimum(min);
        spin->setSingleStep(step);
        QWidget* row = withError(spin, key);
        form->addRow(label, row);
        QObject::connect(spin, &PropertySpinBox::valueChanged, q, [this, spin, key, text, set](double v) {
            apply(key, editText(text, spin->shownText(v)), [&](BodyDesc& b, int) { set(b, v); });
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
        if (key != "orientation")  // (Euler angles here; the file holds a quaternion)
            for (int k = 0; k < 3; ++k) offerSweep(edit->component(k), [key, k] { return QString("%1[%2]").arg(key).arg(k); });
        QWidget* row = withError(edit, key);
        form->addRow(label, row);
        QObject::connect(edit, &VectorEdit::componentEdited, q, [this, edit, key, text, set](int k, double v) {
            applyPart(
                key, k, editText(text + ' ' + axisName(k), edit->component(k)->shownText(v)),
                [set, k, v](BodyDesc& b, int) { set(b, k, v); },
                key + "." + QString::number(k));
        });
        holdable(key, [edit](bool on) { edit->setHeld(on); });
        QObject::connect(edit, &VectorEdit::cancelled, q, [this] {
            dropHeld();
            refresh();
        });
        refreshers.push_back([this, key, form, row, edit, get](const std::vector<const BodyDesc*>& bodies) {
            const Shared<Vec3> s = sharedOf<Vec3>(bodies, get);
            form->setRowVisible(row, s.applies);
            if (s.applies && !held.contains(key))
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
                key, editText(text, combo->itemText(i)), [&](BodyDesc& b, int index) { set(b, index, value); },
                false);
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

    // (property_dock_hold.cpp)
    bool applyPart(const QString& key, int part, const QString& text, const Change& change,
                   const QString& mergeKey);
    void dropHeld();
    void holdable(const QString& key, std::function<void(bool)> mark);

    void build();
    // (property_dock_part.cpp) The selected part of the one selected body, or none; its
    // sweep key ("shape.parts[2].<field>").
    const PartDesc* partIn(const BodyDesc& b) const;
    PartDesc& partIn(BodyDesc& b) const;
    QString partKey(const QString& field) const;
    void buildPart(QVBoxLayout* layout);
    void addOwnValue(QFormLayout* form, const char* label, const QString& field, const QString& suffix,
                     double step, std::optional<double> PartDesc::*member,
                     const std::function<std::optional<double>(const BodyDesc&)>& inherited, const char* tip);
    void buildMass(QVBoxLayout* layout);
    void buildForces(QVBoxLayout* layout);
    void buildKeys(QVBoxLayout* layout);
};

}  // namespace tumble::ui
