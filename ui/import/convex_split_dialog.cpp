#include "import/convex_split_dialog.h"

#include "document/document.h"
#include "import/convex_parts_preview.h"

#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>

namespace tumble::ui {

namespace {

QString partsText(std::size_t n) {
    return n == 1 ? QObject::tr("1 convex part") : QObject::tr("%1 convex parts").arg(n);
}

}  // namespace

ConvexSplitDialog::ConvexSplitDialog(Document* doc, int body, QWidget* parent)
    : QDialog(parent), doc_(doc), body_(body), shape_(doc->body(body).shape) {
    setObjectName("convexSplitDialog");
    const QString name = QString::fromStdString(doc->body(body).name);
    setWindowTitle(tr("Split %1 into Convex Parts").arg(name));
    auto* layout = new QVBoxLayout(this);
    auto* intro = new QLabel(
        tr("The mesh %1 (%2 triangles) cut into convex pieces, each a hull, so that it collides by its "
           "own shape: a mug holds what falls in, an arch lets through what passes under.")
            .arg(QFileInfo(QString::fromStdString(shape_.file)).fileName())
            .arg(shape_.meshData ? qsizetype(shape_.meshData->triangles.size()) : 0));
    intro->setWordWrap(true);
    layout->addWidget(intro);

    auto* form = new QFormLayout;
    maxParts_ = new QSpinBox;
    maxParts_->setObjectName("maxParts");
    maxParts_->setRange(1, 256);
    maxParts_->setValue(shape_.maxParts);
    maxParts_->setToolTip(tr("At most this many parts (more: closer to the mesh, slower to collide)"));
    form->addRow(tr("Max parts"), maxParts_);
    tolerance_ = new QDoubleSpinBox;
    tolerance_->setObjectName("tolerance");
    tolerance_->setDecimals(4);
    tolerance_->setRange(0.0, 1e3);
    tolerance_->setSingleStep(0.001);
    tolerance_->setSuffix(" m");
    tolerance_->setSpecialValueText(tr("automatic (1 % of the mesh's size)"));
    tolerance_->setValue(shape_.partsTolerance.value_or(0.0));
    tolerance_->setToolTip(tr("How far a part may reach out of the mesh's solid"));
    form->addRow(tr("Tolerance"), tolerance_);
    layout->addLayout(form);

    preview_ = new ConvexPartsPreview;
    layout->addWidget(preview_, 1);
    progress_ = new QProgressBar;
    progress_->setRange(0, 1000);
    progress_->setTextVisible(false);
    layout->addWidget(progress_);
    status_ = new QLabel;
    status_->setObjectName("splitStatus");
    status_->setWordWrap(true);
    layout->addWidget(status_);

    auto* buttons = new QDialogButtonBox;
    splitButton_ = buttons->addButton(tr("Split Again"), QDialogButtonBox::ActionRole);
    applyButton_ = buttons->addButton(tr("Apply"), QDialogButtonBox::AcceptRole);
    applyButton_->setEnabled(false);
    buttons->addButton(QDialogButtonBox::Cancel);
    layout->addWidget(buttons);
    connect(splitButton_, &QPushButton::clicked, this, &ConvexSplitDialog::split);
    connect(applyButton_, &QPushButton::clicked, this, &ConvexSplitDialog::apply);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);

    poll_ = new QTimer(this);
    poll_->setInterval(50);
    connect(poll_, &QTimer::timeout, this, [this] {
        if (job_) progress_->setValue(job_->permille.load());
    });
    split();
}

ConvexSplitDialog::~ConvexSplitDialog() {
    stop();
}

QString ConvexSplitDialog::status() const {
    return status_->text();
}

void ConvexSplitDialog::stop() {
    if (!thread_) return;
    job_->stop = true;
    join();
}

void ConvexSplitDialog::join() {
    thread_->wait();
    delete thread_;
    thread_ = nullptr;
    poll_->stop();
}

void ConvexSplitDialog::split() {
    stop();
    result_.reset();
    applyButton_->setEnabled(false);
    ShapeDesc shape = shape_;
    shape.maxParts = maxParts_->value();
    shape.partsTolerance = tolerance_->value() > 0.0 ? std::optional(tolerance_->value()) : std::nullopt;
    auto job = std::make_shared<Job>();
    job_ = job;
    // The thread holds the shape (its mesh shared, never changed) and the job, not the dialog.
    thread_ = QThread::create([job, shape] {
        try {
            auto parts =
                std::make_shared<mesh::ConvexParts>(mesh::convexPartsOfShape(shape, [&job](double done) {
                    job->permille = static_cast<int>(1000 * done);
                    return !job->stop.load();
                }));
            job->parts = std::move(parts);
        } catch (const mesh::ConvexPartsStopped&) {
            job->stopped = true;
        } catch (const std::exception& e) {
            job->error = e.what();
        }
    });
    connect(thread_, &QThread::finished, this, [this, job] {
        if (job == job_) finished();
    });
    progress_->setValue(0);
    progress_->show();
    status_->setText(tr("Splitting…"));
    preview_->setParts(nullptr, tr("Splitting…"));
    poll_->start();
    thread_->start();
}

void ConvexSplitDialog::finished() {
    if (!thread_) return;
    join();
    progress_->setValue(1000);
    if (job_->stopped) {
        status_->setText(tr("Stopped."));
        preview_->setParts(nullptr, tr("Stopped."));
        return;
    }
    if (!job_->parts) {
        const QString why = tr("The mesh cannot be split: %1").arg(QString::fromStdString(job_->error));
        status_->setText(why);
        preview_->setParts(nullptr, why);
        return;
    }
    result_ = job_->parts;
    const mesh::ConvexParts& p = *result_;
    const double over = p.meshVolume > 0 ? 100.0 * (p.partsVolume / p.meshVolume - 1.0) : 0.0;
    QString text = tr("%1 in %2 s; their hulls hold %3 % more than the mesh; the farthest a part "
                      "reaches out of it: %4 mm (tolerance %5 mm).")
                       .arg(partsText(p.parts.size()))
                       .arg(p.seconds, 0, 'f', 2)
                       .arg(over, 0, 'f', 1)
                       .arg(1000 * p.largestPokeOut, 0, 'f', 2)
                       .arg(1000 * p.tolerance, 0, 'f', 2);
    if (!p.withinTolerance)
        text += tr(" Max parts was reached before the tolerance: allow more parts, or a larger tolerance.");
    if (p.filledHoles > 0)
        text += p.filledHoles == 1 ? tr(" The mesh was open: 1 hole filled first.")
                                   : tr(" The mesh was open: %1 holes filled first.").arg(p.filledHoles);
    status_->setText(text);
    preview_->setParts(result_);
    applyButton_->setEnabled(true);
}

void ConvexSplitDialog::apply() {
    if (!result_ || body_ < 0 || body_ >= doc_->bodyCount()) return;
    BodyDesc b = doc_->body(body_);
    if (b.shape.type != ShapeType::Mesh || b.shape.meshData != shape_.meshData)
        return;  // (changed meanwhile)
    b.shape.collision = MeshCollision::ConvexParts;
    b.shape.maxParts = result_->options.maxParts;
    b.shape.partsTolerance =
        result_->options.tolerance > 0.0 ? std::optional(result_->options.tolerance) : std::nullopt;
    b.shape.convexParts = result_;
    doc_->setBody(
        body_, b,
        tr("Split %1 into %2").arg(QString::fromStdString(b.name), partsText(result_->parts.size())));
    accept();
}

}  // namespace tumble::ui
