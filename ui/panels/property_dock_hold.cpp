// Vectors and matrices edited as one value (see `held` in property_dock_impl.h): a part
// whose edit would leave the value refused is held with the others typed so far, and the
// value reaches the document only whole and valid.
#include "panels/property_dock_impl.h"

namespace tumble::ui {

namespace {

// The engine's reason as the panel says it: the field's own words where it has them.
QString inPanelWords(const QString& key, const QString& reason) {
    if (key == "shape.normal" && reason.contains("must not be zero"))
        return QObject::tr("The normal cannot be zero: give it a direction.");
    if (key == "inertia" && reason.contains("triangle inequality"))
        return QObject::tr(
            "No body has these moments of inertia: the largest principal moment cannot "
            "exceed the sum of the other two.");
    if (key == "inertia" && reason.contains("positive definite"))
        return QObject::tr("The principal moments of inertia must all be greater than 0.");
    if ((key == "shape.half_extents" || key == "shape.scale") && reason.contains("greater than 0"))
        return QObject::tr("Each component must be greater than 0.");
    return reason;
}

}  // namespace

void PropertyDock::Impl::holdable(const QString& key, std::function<void(bool)> mark) {
    markHeld.insert(key, std::move(mark));
}

bool PropertyDock::Impl::applyPart(const QString& key, int part, const QString& text, const Change& change,
                                   const QString& mergeKey) {
    const QList<int> sel = doc->selection();
    if (sel.isEmpty()) return false;
    std::vector<std::pair<int, Change>> parts = held.value(key);
    std::erase_if(parts, [part](const auto& p) { return p.first == part; });
    parts.emplace_back(part, change);
    const Change whole = [parts](BodyDesc& b, int index) {
        for (const auto& p : parts) p.second(b, index);
    };
    const std::vector<BodyDesc> bodies = changedBodies(whole);
    const QString reason = refusal(key, bodies);
    const auto mark = markHeld.value(key);
    if (!reason.isEmpty()) {
        held.insert(key, parts);
        if (mark) mark(true);
        showError(key, inPanelWords(key, reason) + ' ' + QObject::tr("(Esc: back to the last valid value)"));
        return false;  // the fields stay as typed
    }
    held.remove(key);
    if (mark) mark(false);
    // The bodies as checked (a setter may read the panel's state, as the Euler angles do:
    // running it again need not give the same body).
    const Change take = [&](BodyDesc& b, int index) { b = bodies[static_cast<size_t>(sel.indexOf(index))]; };
    return apply(key, text, take, true, mergeKey);
}

void PropertyDock::Impl::dropHeld() {
    for (auto it = held.cbegin(); it != held.cend(); ++it) {
        if (const auto mark = markHeld.value(it.key())) mark(false);
        showError(it.key(), QString());
    }
    held.clear();
}

}  // namespace tumble::ui
