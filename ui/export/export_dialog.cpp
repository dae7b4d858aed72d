#include "export/export_dialog.h"

#include "export/image_exporter.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <QStandardPaths>

namespace tumble::ui {

QString exportExtension(ExportDialog::Kind kind) {
    switch (kind) {
        case ExportDialog::Kind::Csv: return QStringLiteral("csv");
        case ExportDialog::Kind::Json: return QStringLiteral("json");
        case ExportDialog::Kind::Gltf: return QStringLiteral("gltf");
        case ExportDialog::Kind::Glb: return QStringLiteral("glb");
        case ExportDialog::Kind::Images: return QString();
        case ExportDialog::Kind::Video: return QStringLiteral("mp4");
    }
    return QString();
}

namespace {

bool isTrajectory(ExportDialog::Kind k) {
    return k != ExportDialog::Kind::Images && k != ExportDialog::Kind::Video;
}

QWidget* row(QWidget* a, QWidget* b = nullptr, QWidget* c = nullptr) {
    auto* w = new QWidget;
    auto* l = new QHBoxLayout(w);
    l->setContentsMargins(0, 0, 0, 0);
    for (QWidget* x : {a, b, c})
        if (x) l->addWidget(x);
    return w;
}

}  // namespace

ExportDialog::ExportDialog(const QStringList& bodyNames, int frames, double frameRate,
                           const QString& sceneName, QWidget* parent)
    : QDialog(parent), frames_(frames), frameRate_(frameRate) {
    setWindowTitle(tr("Export"));
    kind_ = new QComboBox;
    kind_->setObjectName("kind");
    kind_->addItem(tr("Trajectory, CSV (.csv)"), int(Kind::Csv));
    kind_->addItem(tr("Trajectory, JSON (.json)"), int(Kind::Json));
    kind_->addItem(tr("Animation, glTF 2.0 (.gltf + .bin)"), int(Kind::Gltf));
    kind_->addItem(tr("Animation, glTF 2.0 binary (.glb)"), int(Kind::Glb));
    kind_->addItem(tr("Image sequence (PNG per frame)"), int(Kind::Images));
    kind_->addItem(tr("Video (MP4, needs ffmpeg)"), int(Kind::Video));
    target_ = new QLineEdit;
    target_->setObjectName("target");
    auto* browse = new QPushButton(tr("Browse..."));
    first_ = new QSpinBox;
    first_->setObjectName("first");
    last_ = new QSpinBox;
    last_->setObjectName("last");
    for (QSpinBox* s : {first_, last_}) s->setRange(0, std::max(0, frames - 1));
    last_->setValue(std::max(0, frames - 1));
    step_ = new QSpinBox;
    step_->setObjectName("step");
    step_->setRange(1, std::max(1, frames));
    step_->setPrefix(tr("every "));
    step_->setSuffix(tr(" frame(s)"));
    rate_ = new QLabel;
    bodies_ = new QListWidget;
    bodies_->setObjectName("bodies");
    for (const QString& name : bodyNames) {
        auto* item = new QListWidgetItem(name, bodies_);
        item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
        item->setCheckState(Qt::Checked);
    }
    bodies_->setMaximumHeight(140);
    jointForces_ = new QCheckBox(tr("Add each joint's force and couple on its first body"));
    jointForces_->setObjectName("jointForces");
    jointForces_->setToolTip(tr("CSV: in a second file, NAME-joints.csv, beside the trajectory; JSON: in each frame"));
    width_ = new QSpinBox;
    width_->setObjectName("width");
    height_ = new QSpinBox;
    height_->setObjectName("height");
    for (QSpinBox* s : {width_, height_}) {
        s->setRange(16, 8192);
        s->setSuffix(tr(" px"));
    }
    width_->setValue(1280);
    height_->setValue(720);
    problem_ = new QLabel;
    problem_->setObjectName("problem");
    problem_->setStyleSheet(QStringLiteral("color: #b00020"));
    problem_->setWordWrap(true);
    buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    buttons_->button(QDialogButtonBox::Ok)->setText(tr("Export"));

    auto* form = new QFormLayout(this);
    form->addRow(tr("Format"), kind_);
    form->addRow(tr("To"), row(target_, browse));
    form->addRow(tr("Frames"), row(first_, new QLabel(tr("to")), last_));
    form->addRow(tr("Sampling"), row(step_, rate_));
    bodiesRow_ = bodies_;
    form->addRow(tr("Bodies"), bodies_);
    form->addRow(tr("Joints"), jointForces_);
    jointsLabel_ = form->labelForField(jointForces_);
    setHasJoints(false);
    sizeRow_ = row(width_, new QLabel(QStringLiteral("×")), height_);
    form->addRow(tr("Image size"), sizeRow_);
    form->addRow(problem_);
    form->addRow(buttons_);

    connect(buttons_, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(browse, &QPushButton::clicked, this, &ExportDialog::browse);
    connect(kind_, &QComboBox::currentIndexChanged, this, [this] {
        // Keep the name, change the extension (or drop it for a folder of images).
        const QFileInfo f(target_->text());
        if (!target_->text().isEmpty()) {
            const QString ext = exportExtension(kind());
            const QString base =
                QDir(f.path()).filePath(f.completeBaseName().isEmpty() ? f.fileName() : f.completeBaseName());
            target_->setText(ext.isEmpty() ? base : base + "." + ext);
        }
        update();
    });
    for (QSpinBox* s : {first_, last_, step_, width_, height_})
        connect(s, &QSpinBox::valueChanged, this, &ExportDialog::update);
    connect(target_, &QLineEdit::textChanged, this, &ExportDialog::update);
    connect(bodies_, &QListWidget::itemChanged, this, &ExportDialog::update);
    restore(sceneName);
    update();
}

ExportDialog::Kind ExportDialog::kind() const {
    return static_cast<Kind>(kind_->currentData().toInt());
}

void ExportDialog::setKind(Kind k) {
    kind_->setCurrentIndex(kind_->findData(int(k)));
}

QString ExportDialog::target() const {
    return target_->text().trimmed();
}

void ExportDialog::setTarget(const QString& path) {
    target_->setText(path);
}

void ExportDialog::setFrameRange(int first, int last, int step) {
    first_->setValue(first);
    last_->setValue(last);
    step_->setValue(step);
}

void ExportDialog::setBodiesChecked(const QList<int>& bodies) {
    for (int i = 0; i < bodies_->count(); ++i)
        bodies_->item(i)->setCheckState(bodies.contains(i) ? Qt::Checked : Qt::Unchecked);
}

QSize ExportDialog::imageSize() const {
    return QSize(width_->value(), height_->value());
}

io::ExportOptions ExportDialog::options() const {
    io::ExportOptions o;
    o.firstFrame = first_->value();
    o.lastFrame = last_->value();
    o.frameStep = step_->value();
    bool all = true;
    for (int i = 0; i < bodies_->count(); ++i) {
        if (bodies_->item(i)->checkState() == Qt::Checked)
            o.bodies.push_back(i);
        else
            all = false;
    }
    if (all) o.bodies.clear();
    o.jointForces = jointForces_->isVisibleTo(this) && jointForces_->isEnabled() && jointForces_->isChecked();
    return o;
}

void ExportDialog::setHasJoints(bool has) {
    jointForces_->setVisible(has);
    if (jointsLabel_) jointsLabel_->setVisible(has);
}

void ExportDialog::setJointForces(bool on) {
    jointForces_->setChecked(on);
}

QString ExportDialog::problem() const {
    const Kind k = kind();
    if (target().isEmpty()) return tr("Choose where to export to.");
    if (first_->value() > last_->value()) return tr("The first frame is after the last.");
    if (isTrajectory(k) && options().bodies.empty()) {
        bool any = false;
        for (int i = 0; i < bodies_->count(); ++i) any = any || bodies_->item(i)->checkState() == Qt::Checked;
        if (!any) return tr("Choose at least one body.");
    }
    if (k == Kind::Video && ImageExporter::ffmpegPath().isEmpty())
        return tr(
            "A video needs ffmpeg, which is not installed (apt-get install ffmpeg); an image sequence does "
            "not.");
    if (k == Kind::Video && (width_->value() % 2 || height_->value() % 2))
        return tr("A video needs an even width and height.");
    if (k != Kind::Images && QFileInfo(target()).suffix().toLower() != exportExtension(k))
        return tr("The file name must end in .%1 for this format.").arg(exportExtension(k));
    const QString dir =
        k == Kind::Images ? QFileInfo(target()).absolutePath() : QFileInfo(target()).absolutePath();
    if (!QFileInfo(dir).isDir()) return tr("%1: no such folder.").arg(dir);
    return QString();
}

void ExportDialog::update() {
    const Kind k = kind();
    const int count = (last_->value() - first_->value()) / step_->value() + 1;
    rate_->setText(
        tr("%1 frames at %2 frames/s").arg(std::max(0, count)).arg(frameRate_ / step_->value(), 0, 'g', 4));
    bodiesRow_->setEnabled(isTrajectory(k));
    jointForces_->setEnabled(k == Kind::Csv || k == Kind::Json);  // glTF has no place for them
    sizeRow_->setEnabled(!isTrajectory(k));
    const QString p = problem();
    problem_->setText(p);
    problem_->setVisible(!p.isEmpty());
    buttons_->button(QDialogButtonBox::Ok)->setEnabled(p.isEmpty());
}

void ExportDialog::browse() {
    const Kind k = kind();
    QString path;
    if (k == Kind::Images) {
        path = QFileDialog::getExistingDirectory(this, tr("Export images into"), target());
    } else {
        const QString ext = exportExtension(k);
        path = QFileDialog::getSaveFileName(this, tr("Export to"), target(), tr("*.%1").arg(ext));
        if (!path.isEmpty() && QFileInfo(path).suffix().toLower() != ext) path += "." + ext;
    }
    if (!path.isEmpty()) target_->setText(path);
}

// Where an export goes when the dialog opens: the last export's folder while it is still
// there; else beside the scene's file (a saved scene: `scene` is then its path; a sample's
// is inside the program); else Documents when the home has one, else the home itself (a
// fresh machine has no ~/Documents, and the first export was refused for it).
QString ExportDialog::startFolder(const QString& remembered, const QString& scene) {
    if (!remembered.isEmpty() && QFileInfo(remembered).isDir()) return remembered;
    const QFileInfo file(scene);
    if (!scene.startsWith(QLatin1Char(':')) && file.isAbsolute() && QFileInfo(file.absolutePath()).isWritable())
        return file.absolutePath();
    const QString documents = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
    return QFileInfo(documents).isDir() ? documents : QDir::homePath();
}

void ExportDialog::restore(const QString& sceneName) {
    QSettings s;
    s.beginGroup(QStringLiteral("export"));
    setKind(static_cast<Kind>(s.value("kind", int(Kind::Csv)).toInt()));
    step_->setValue(s.value("step", 1).toInt());
    width_->setValue(s.value("width", 1280).toInt());
    height_->setValue(s.value("height", 720).toInt());
    const QString dir = startFolder(s.value("folder").toString(), sceneName);
    const QString base = QFileInfo(sceneName).completeBaseName().isEmpty()
                             ? QStringLiteral("untitled")
                             : QFileInfo(sceneName).completeBaseName();
    const QString ext = exportExtension(kind());
    target_->setText(QDir(dir).filePath(ext.isEmpty() ? base + "-frames" : base + "." + ext));
}

void ExportDialog::accept() {
    if (!problem().isEmpty()) return;
    QSettings s;
    s.beginGroup(QStringLiteral("export"));
    s.setValue("kind", int(kind()));
    s.setValue("step", step_->value());
    s.setValue("width", width_->value());
    s.setValue("height", height_->value());
    s.setValue("folder", QFileInfo(target()).absolutePath());
    QDialog::accept();
}

}  // namespace tumble::ui
