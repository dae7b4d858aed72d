// The keys of an animated body (issue 50 item 2): its interpolation and its list of keys,
// shown when one animated body is selected.
#include "panels/property_dock_impl.h"

#include <QComboBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QVBoxLayout>

namespace tumble::ui {

void PropertyDock::Impl::buildKeys(QVBoxLayout* layout) {
    auto* g = new QGroupBox(QObject::tr("Keys"));
    g->setObjectName("keys.box");
    keysBox = g;
    auto* v = new QVBoxLayout(g);
    auto* form = new QFormLayout;
    v->addLayout(form);
    addChoice<KeyInterpolation>(
        form, QObject::tr("Interpolation"), "interpolation", QObject::tr("Set interpolation"),
        {{QObject::tr("Linear"), KeyInterpolation::Linear},
         {QObject::tr("Smooth"), KeyInterpolation::Smooth}},
        [](const BodyDesc& b) { return std::optional<KeyInterpolation>(b.interpolation); },
        [](BodyDesc& b, int, KeyInterpolation k) { b.interpolation = k; })
        ->setToolTip(QObject::tr("Linear: straight at constant speed between keys; smooth: eased in and out, "
                                 "without a jump in speed at a key"));
    keys = new KeysEdit;
    v->addWidget(withError(keys, "keys"));
    layout->addWidget(g);
    QObject::connect(keys, &KeysEdit::keysEdited, q,
                     [this](const std::vector<BodyKey>& list, const QString& text, const QString& field) {
                         apply(
                             "keys", text, [&](BodyDesc& b, int) { b.keys = list; }, !field.isEmpty(), field);
                     });
    QObject::connect(keys, &KeysEdit::editingFinished, q, [this] { ++generation; });
    refreshers.push_back([this](const std::vector<const BodyDesc*>& bodies) {
        const bool animated = bodies.size() == 1 && bodies[0]->motion == Motion::Animated;
        keysBox->setVisible(animated);
        if (animated) keys->setKeys(bodies[0]->keys);
    });
}

}  // namespace tumble::ui
