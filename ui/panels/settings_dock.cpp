#include "panels/settings_dock.h"

#include "document/document.h"
#include "panels/field_guard.h"

#include <tumble/errors.h>
#include <tumble/integrators.h>
#include <tumble/model.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QVBoxLayout>

namespace tumble::ui {

namespace {

const char* const kPaths[SettingsDock::FieldCount] = {
    "settings.gravity",           "settings.gravity",      "settings.gravity",    "settings.dt",
    "settings.duration",          "settings.integrator",   "settings.frame_rate", "settings.sleeping",
    "settings.solver_iterations", "settings.energy_guard", "settings.impacts",
};

QLabel* newMessage(const QString& name) {
    auto* label = new QLabel;
    label->setObjectName(name);
    label->setWordWrap(true);
    label->setStyleSheet(QStringLiteral("color: #b00020"));
    label->hide();
    return label;
}

// A field and its message under it, as one row of the form.
QWidget* withMessage(QWidget* field, QLabel* message) {
    auto* box = new QWidget;
    auto* layout = new QVBoxLayout(box);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(1);
    layout->addWidget(field);
    layout->addWidget(message);
    box->setFocusProxy(field);  // the label's mnemonic reaches the field
    return box;
}

QDoubleSpinBox* newSpin(const QString& name, double min, double max, int decimals, double step,
                        const QString& suffix) {
    auto* spin = new QDoubleSpinBox;
    spin->setObjectName(name);
    spin->setRange(min, max);
    spin->setDecimals(decimals);
    spin->setSingleStep(step);
    spin->setSuffix(suffix);
    spin->setKeyboardTracking(false);  // typing "0.0" on the way to "0.005" is not an edit
    spin->setAccelerated(true);
    return spin;
}

}  // namespace

SettingsDock::SettingsDock(Document* doc, QWidget* parent)
    : QDockWidget(tr("Scene Settings"), parent), doc_(doc) {
    installFieldGuard();  // the wheel scrolls the panel, not the field under it
    setObjectName(QStringLiteral("settingsDock"));

    auto* form = new QFormLayout;
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);

    // Gravity: three components, one above the other (a row of three is too wide for a
    // dock), each its own field for merging, one message.
    auto* gravityRow = new QWidget;
    auto* gravityLayout = new QVBoxLayout(gravityRow);
    gravityLayout->setSpacing(2);
    gravityLayout->setContentsMargins(0, 0, 0, 0);
    const char* axes[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        gravity_[k] = newSpin(QStringLiteral("gravity%1").arg(QChar(u'X' + k)), -1e4, 1e4, 3, 0.1,
                              QStringLiteral(" m/s²"));
        gravity_[k]->setPrefix(QStringLiteral("%1 ").arg(QLatin1String(axes[k])));
        gravity_[k]->setToolTip(tr("Gravity, %1 component (m/s²)").arg(QLatin1String(axes[k])));
        gravityLayout->addWidget(gravity_[k]);
    }
    gravityRow->setFocusProxy(gravity_[0]);
    gravityMessage_ = newMessage(QStringLiteral("gravityMessage"));
    form->addRow(tr("&Gravity"), withMessage(gravityRow, gravityMessage_));

    step_ = newSpin(QStringLiteral("step"), 0.0, 10.0, 6, 0.0001, QStringLiteral(" s"));
    step_->setToolTip(tr("The integration time step (s)"));
    stepMessage_ = newMessage(QStringLiteral("stepMessage"));
    QWidget* stepRow = withMessage(step_, stepMessage_);
    // What the step is when it is not dt (a dt longer than a frame steps once a frame).
    stepNote_ = new QLabel;
    stepNote_->setObjectName(QStringLiteral("step.note"));
    stepNote_->setWordWrap(true);
    stepNote_->setStyleSheet(QStringLiteral("color: palette(dark)"));
    stepNote_->hide();
    stepRow->layout()->addWidget(stepNote_);
    form->addRow(tr("&Step"), stepRow);

    duration_ = newSpin(QStringLiteral("duration"), 0.0, 1e7, 3, 0.5, QStringLiteral(" s"));
    duration_->setToolTip(tr("How long the simulation runs (s)"));
    durationMessage_ = newMessage(QStringLiteral("durationMessage"));
    form->addRow(tr("&Duration"), withMessage(duration_, durationMessage_));

    integrator_ = new QComboBox;
    integrator_->setObjectName(QStringLiteral("integrator"));
    integrator_->addItem(tr("Default (%1)").arg(QLatin1String(defaultIntegrator().name)), QString());
    integrator_->setItemData(0, QString::fromLatin1(defaultIntegrator().description), Qt::ToolTipRole);
    for (const IntegratorInfo& info : integrators()) {
        integrator_->addItem(tr("%1 (order %2)").arg(QLatin1String(info.name)).arg(info.order),
                             QString::fromLatin1(info.name));
        integrator_->setItemData(integrator_->count() - 1, QString::fromLatin1(info.description),
                                 Qt::ToolTipRole);
    }
    integratorMessage_ = newMessage(QStringLiteral("integratorMessage"));
    form->addRow(tr("&Integrator"), withMessage(integrator_, integratorMessage_));

    frameRate_ = newSpin(QStringLiteral("frameRate"), 0.0, 1e5, 2, 1.0, QStringLiteral(" frames/s"));
    frameRate_->setToolTip(tr("Frames recorded (and shown) per second of simulated time (1/s)"));
    frameRateMessage_ = newMessage(QStringLiteral("frameRateMessage"));
    form->addRow(tr("&Frame rate"), withMessage(frameRate_, frameRateMessage_));

    sleeping_ = new QCheckBox(tr("Bodies at rest fall asleep"));
    sleeping_->setObjectName(QStringLiteral("sleeping"));
    sleepingMessage_ = newMessage(QStringLiteral("sleepingMessage"));
    form->addRow(tr("S&leeping"), withMessage(sleeping_, sleepingMessage_));

    iterations_ = new QSpinBox;
    iterations_->setObjectName(QStringLiteral("iterations"));
    iterations_->setRange(0, 10000);
    iterations_->setSuffix(tr(" per step"));
    iterations_->setKeyboardTracking(false);
    iterations_->setToolTip(tr("Velocity iterations of the contact solver per step"));
    iterationsMessage_ = newMessage(QStringLiteral("iterationsMessage"));
    form->addRow(tr("Solver i&terations"), withMessage(iterations_, iterationsMessage_));

    energyGuard_ = new QCheckBox(tr("Stop a run whose energy runs away"));
    energyGuard_->setObjectName(QStringLiteral("energyGuard"));
    energyGuard_->setToolTip(
        tr("A run that blows up (a step too large for a stiff spring, say) stops early with the body, "
           "the time and the likely cause; off, only a state that is no longer finite stops it"));
    energyGuardMessage_ = newMessage(QStringLiteral("energyGuardMessage"));
    form->addRow(tr("Energy g&uard"), withMessage(energyGuard_, energyGuardMessage_));

    impacts_ = new QComboBox;
    impacts_->setObjectName(QStringLiteral("impacts"));
    impacts_->addItem(tr("At their moment"), int(ImpactTiming::Exact));
    impacts_->setItemData(0,
                          tr("The step is cut at each moment of impact: bounce heights and the order of "
                             "impacts are right at any step"),
                          Qt::ToolTipRole);
    impacts_->addItem(tr("At the end of the step"), int(ImpactTiming::EndOfStep));
    impacts_->setItemData(1,
                          tr("Resolved where the step ends, as most engines do: several times faster for "
                             "piles of thousands of bodies; bounce heights off by about speed × step"),
                          Qt::ToolTipRole);
    impactsMessage_ = newMessage(QStringLiteral("impactsMessage"));
    form->addRow(tr("I&mpacts"), withMessage(impacts_, impactsMessage_));

    auto* body = new QWidget;
    auto* outer = new QVBoxLayout(body);
    outer->addLayout(form);
    outer->addStretch(1);
    auto* scroll = new QScrollArea;
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    scroll->setWidget(body);
    setWidget(scroll);

    refresh();

    // ---- Edits.
    for (int k = 0; k < 3; ++k) {
        const Field f = static_cast<Field>(GravityX + k);
        connect(gravity_[k], &QDoubleSpinBox::valueChanged, this, [this, f] { edit(f); });
        connect(gravity_[k], &QDoubleSpinBox::editingFinished, this, [this, f] { ++generation_[f]; });
    }
    connect(step_, &QDoubleSpinBox::valueChanged, this, [this] { edit(Step); });
    connect(step_, &QDoubleSpinBox::editingFinished, this, [this] { ++generation_[Step]; });
    connect(duration_, &QDoubleSpinBox::valueChanged, this, [this] { edit(Duration); });
    connect(duration_, &QDoubleSpinBox::editingFinished, this, [this] { ++generation_[Duration]; });
    connect(frameRate_, &QDoubleSpinBox::valueChanged, this, [this] { edit(FrameRate); });
    connect(frameRate_, &QDoubleSpinBox::editingFinished, this, [this] { ++generation_[FrameRate]; });
    connect(iterations_, &QSpinBox::valueChanged, this, [this] { edit(Iterations); });
    connect(iterations_, &QSpinBox::editingFinished, this, [this] { ++generation_[Iterations]; });
    connect(integrator_, &QComboBox::currentIndexChanged, this, [this] { edit(Integrator); });
    connect(sleeping_, &QCheckBox::toggled, this, [this] { edit(Sleeping); });
    connect(energyGuard_, &QCheckBox::toggled, this, [this] { edit(EnergyGuard); });
    connect(impacts_, &QComboBox::currentIndexChanged, this, [this] { edit(Impacts); });

    // ---- The document's changes (undo, redo, open) come back to the fields.
    connect(doc_, &Document::settingsChanged, this, &SettingsDock::refresh);
    connect(doc_, &Document::sceneReset, this, [this] {
        clearMessages();
        generation_.fill(0);
        refresh();
    });
}

QLabel* SettingsDock::messageLabel(Field field) const {
    switch (field) {
        case GravityX:
        case GravityY:
        case GravityZ: return gravityMessage_;
        case Step: return stepMessage_;
        case Duration: return durationMessage_;
        case Integrator: return integratorMessage_;
        case FrameRate: return frameRateMessage_;
        case Sleeping: return sleepingMessage_;
        case Iterations: return iterationsMessage_;
        case EnergyGuard: return energyGuardMessage_;
        case Impacts: return impactsMessage_;
        case FieldCount: break;
    }
    return nullptr;
}

QString SettingsDock::message(Field field) const {
    const QLabel* label = messageLabel(field);
    return label ? label->text() : QString();
}

QString SettingsDock::editText(Field field) const {
    switch (field) {
        case GravityX:
        case GravityY:
        case GravityZ:
            return tr("Set gravity %1 to %2").arg(QChar(u'x' + (field - GravityX)), gravity_[field - GravityX]->text());
        case Step: return tr("Set time step to %1").arg(step_->text());
        case Duration: return tr("Set duration to %1").arg(duration_->text());
        case Integrator: return tr("Set integrator to %1").arg(integrator_->currentText());
        case FrameRate: return tr("Set frame rate to %1").arg(frameRate_->text());
        case Sleeping: return sleeping_->isChecked() ? tr("Turn sleeping on") : tr("Turn sleeping off");
        case Iterations: return tr("Set solver iterations to %1").arg(iterations_->text());
        case EnergyGuard:
            return energyGuard_->isChecked() ? tr("Turn the energy guard on")
                                             : tr("Turn the energy guard off");
        case Impacts: return tr("Set impact timing to %1").arg(impacts_->currentText());
        case FieldCount: break;
    }
    return {};
}

void SettingsDock::edit(Field field) {
    Settings s = doc_->scene().settings;
    switch (field) {
        case GravityX:
        case GravityY:
        case GravityZ: s.gravity[field - GravityX] = gravity_[field - GravityX]->value(); break;
        case Step: s.dt = step_->value(); break;
        case Duration: s.duration = duration_->value(); break;
        case Integrator: s.integrator = integrator_->currentData().toString().toStdString(); break;
        case FrameRate: s.frameRate = frameRate_->value(); break;
        case Sleeping: s.sleeping = sleeping_->isChecked(); break;
        case Iterations: s.solverIterations = iterations_->value(); break;
        case EnergyGuard: s.energyGuard = energyGuard_->isChecked(); break;
        case Impacts: s.impacts = static_cast<ImpactTiming>(impacts_->currentData().toInt()); break;
        case FieldCount: return;
    }
    if (!trySetSettings(field, s)) refresh();  // back to the last good value
}

bool SettingsDock::trySetSettings(Field field, const Settings& settings) {
    QLabel* label = messageLabel(field);
    // The settings checks do not look at the bodies; leaving them out keeps a scrub cheap
    // and keeps a problem in some body from blocking the settings.
    SceneDesc probe;
    probe.settings = settings;
    try {
        validate(probe);
    } catch (const SceneError& e) {
        // The engine's words; the field path too when the culprit is another field (a
        // duration that, at this frame rate, is too many frames).
        const QString text = e.path() == kPaths[field] ? QString::fromStdString(e.message())
                                                       : QString::fromStdString(e.what());
        label->setText(text);
        label->show();
        return false;
    }
    label->clear();
    label->hide();
    // Spin boxes merge a scrub; a check box or a combo box change is a step of its own.
    const bool merges = field != Integrator && field != Sleeping && field != EnergyGuard && field != Impacts;
    const int mergeId = merges ? 1 + field + FieldCount * generation_[field] : 0;
    doc_->setSettings(settings, editText(field), mergeId);
    return true;
}

void SettingsDock::refresh() {
    const Settings& s = doc_->scene().settings;
    for (int k = 0; k < 3; ++k) {
        const QSignalBlocker block(gravity_[k]);
        gravity_[k]->setValue(s.gravity[k]);
    }
    {
        const QSignalBlocker block(step_);
        step_->setValue(s.dt);
    }
    const std::string note = s.dt > 0.0 && s.frameRate > 0.0 ? stepNote(s) : std::string();
    stepNote_->setText(QString::fromStdString(note));
    stepNote_->setVisible(!note.empty());
    {
        const QSignalBlocker block(duration_);
        duration_->setValue(s.duration);
    }
    {
        const QSignalBlocker block(integrator_);
        const int index = integrator_->findData(QString::fromStdString(s.integrator));
        integrator_->setCurrentIndex(index < 0 ? 0 : index);
    }
    {
        const QSignalBlocker block(frameRate_);
        frameRate_->setValue(s.frameRate);
    }
    {
        const QSignalBlocker block(sleeping_);
        sleeping_->setChecked(s.sleeping);
    }
    {
        const QSignalBlocker block(iterations_);
        iterations_->setValue(s.solverIterations);
    }
    {
        const QSignalBlocker block(energyGuard_);
        energyGuard_->setChecked(s.energyGuard);
    }
    {
        const QSignalBlocker block(impacts_);
        impacts_->setCurrentIndex(impacts_->findData(int(s.impacts)));
    }
}

void SettingsDock::clearMessages() {
    for (int f = 0; f < FieldCount; ++f) {
        QLabel* label = messageLabel(static_cast<Field>(f));
        label->clear();
        label->hide();
    }
}

}  // namespace tumble::ui
