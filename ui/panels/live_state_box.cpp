#include "panels/live_state_box.h"

#include "document/document.h"
#include "panels/property_euler.h"
#include "timeline/timeline.h"

#include <tumble/model.h>

#include <QFormLayout>
#include <QLabel>

namespace tumble::ui {

namespace {

QString vectorText(const Vec3& v, int decimals, const QString& unit) {
    return QStringLiteral("%1, %2, %3 %4")
        .arg(v.x(), 0, 'f', decimals)
        .arg(v.y(), 0, 'f', decimals)
        .arg(v.z(), 0, 'f', decimals)
        .arg(unit);
}

}  // namespace

LiveStateBox::LiveStateBox(Document* document, Timeline* timeline, QWidget* parent)
    : QGroupBox(tr("At the playhead (read-only)"), parent), doc_(document), timeline_(timeline) {
    setObjectName(QStringLiteral("liveState"));
    auto* form = new QFormLayout(this);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    frame_ = addRow(form, tr("Time"), "frame");
    position_ = addRow(form, tr("Position"), "position");
    orientation_ = addRow(form, tr("Orientation"), "orientation");
    velocity_ = addRow(form, tr("Velocity"), "velocity");
    omega_ = addRow(form, tr("Angular velocity"), "angular_velocity");
    kinetic_ = addRow(form, tr("Kinetic energy"), "kinetic_energy");
    sleeping_ = addRow(form, tr("Sleeping"), "sleeping");
    position_->setToolTip(tr("World position of the body frame origin, as in the scene file"));
    orientation_->setToolTip(
        tr("Euler angles x, y, z in degrees (Z-Y'-X'', as the initial orientation above)"));
    connect(timeline_, &Timeline::currentFrameChanged, this, &LiveStateBox::refresh);
    connect(doc_, &Document::selectionChanged, this, &LiveStateBox::refresh);
    refresh();
}

QLabel* LiveStateBox::addRow(QFormLayout* form, const QString& label, const QString& name) {
    auto* value = new QLabel;
    value->setObjectName(name);
    value->setTextInteractionFlags(Qt::TextSelectableByMouse);
    form->addRow(label, value);
    return value;
}

QString LiveStateBox::valueText(const QString& row) const {
    const auto* label = findChild<QLabel*>(row);
    return label ? label->text() : QString();
}

void LiveStateBox::refresh() {
    const QList<int>& sel = doc_->selection();
    const std::shared_ptr<const Model> model = timeline_->model();
    const State& s = timeline_->currentState();
    const bool shown = sel.size() == 1 && model && timeline_->hasCurrentState() &&
                       sel[0] < static_cast<int>(s.bodies.size()) &&
                       sel[0] < static_cast<int>(model->bodies.size());
    setVisible(shown);
    if (!shown) return;
    const auto i = static_cast<std::size_t>(sel[0]);
    const BodyModel& b = model->bodies[i];
    const BodyState& st = s.bodies[i];
    const Derived d = derive(b, st);
    frame_->setText(tr("%1 s (frame %2)%3")
                        .arg(s.time, 0, 'f', 3)
                        .arg(timeline_->currentFrame())
                        .arg(timeline_->isStale() ? tr(", before the last edit") : QString()));
    position_->setText(vectorText(bodyFramePosition(b, st), 4, QStringLiteral("m")));
    orientation_->setText(vectorText(quatToEulerDegrees(st.q), 2, QStringLiteral("°")));
    velocity_->setText(vectorText(d.v, 4, QStringLiteral("m/s")));
    omega_->setText(vectorText(d.omega, 4, QStringLiteral("rad/s")));
    const double ke = b.motion == Motion::Dynamic ? 0.5 * st.P.dot(d.v) + 0.5 * st.L.dot(d.omega) : 0.0;
    kinetic_->setText(QStringLiteral("%1 J").arg(ke, 0, 'g', 6));
    sleeping_->setText(s.isAsleep(sel[0]) ? tr("yes") : tr("no"));
}

}  // namespace tumble::ui
