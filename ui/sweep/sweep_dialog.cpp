#include "sweep/sweep_dialog.h"

#include "document/document.h"
#include "panels/property_spin_box.h"

#include <tumble/io/scene_file.h>

#include <QChart>
#include <QChartView>
#include <QCheckBox>
#include <QComboBox>
#include <QCoreApplication>
#include <QDateTime>
#include <QDialogButtonBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineSeries>
#include <QProgressBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QScatterSeries>
#include <QSpinBox>
#include <QSplitter>
#include <QStandardPaths>
#include <QTableWidget>
#include <QValueAxis>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::ui {

namespace {

QString& executable() {
    static QString program;
    return program;
}

// (The property panel's spin box: numbers as typed, no trailing zeros.)
PropertySpinBox* numberBox(double value) {
    auto* box = new PropertySpinBox;
    box->setValue(value);
    return box;
}

QSpinBox* countBox(int value) {
    auto* box = new QSpinBox;
    box->setRange(1, 10000);
    box->setValue(value);
    return box;
}

QString number(double v) { return QString::number(v, 'g', 12); }

// One CSV line's cells (quoted cells may hold commas and doubled quotes).
QStringList csvCells(const QString& line) {
    QStringList cells;
    QString cell;
    bool quoted = false;
    for (int i = 0; i < line.size(); ++i) {
        const QChar c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cell += '"', ++i;
            else if (c == '"') quoted = false;
            else cell += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            cells << cell;
            cell.clear();
        } else {
            cell += c;
        }
    }
    cells << cell;
    return cells;
}

}  // namespace

void SweepDialog::setExecutable(const QString& program) { executable() = program; }

QStringList SweepDialog::sweepablePaths(const Document& doc) {
    QStringList paths = {"settings.dt", "settings.duration", "settings.solver_iterations"};
    const QJsonObject scene = QJsonDocument::fromJson(QByteArray::fromStdString(io::sceneToJson(doc.scene()))).object();
    for (const QJsonValue& b : scene.value("bodies").toArray()) {
        const QJsonObject body = b.toObject();
        if (body.value("motion").toString() != "dynamic") continue;
        const QString name = body.value("name").toString();
        auto add = [&](const QString& key, const QJsonValue& v) {
            if (v.isDouble()) paths << name + "." + key;
            if (v.isArray() && key != "orientation")
                for (int i = 0; i < v.toArray().size(); ++i)
                    if (v.toArray()[i].isDouble()) paths << QString("%1.%2[%3]").arg(name, key).arg(i);
        };
        for (auto it = body.begin(); it != body.end(); ++it) {
            if (it.key() == "shape") {
                const QJsonObject shape = it.value().toObject();
                for (auto s = shape.begin(); s != shape.end(); ++s) add("shape." + s.key(), s.value());
            } else if (it.key() != "inertia" && it.key() != "forces") {
                add(it.key(), it.value());
            }
        }
    }
    return paths;
}

SweepDialog::SweepDialog(Document* doc, const QString& path, double value, QWidget* parent)
    : QDialog(parent), doc_(doc), path_(path) {
    setWindowTitle(tr("Sweep %1").arg(path));
    setObjectName("sweepDialog");
    auto* layout = new QVBoxLayout(this);

    auto* form = new QFormLayout;
    auto* first = new QHBoxLayout;
    // Around the value, half to one and a half times it (0 to 1 from 0); a restitution
    // stays within [0, 1].
    double low = value == 0.0 ? 0.0 : 0.5 * value, high = value == 0.0 ? 1.0 : 1.5 * value;
    if (path.endsWith(".restitution")) {
        low = std::clamp(low, 0.0, 1.0);
        high = std::clamp(high, 0.0, 1.0);
    }
    from_ = numberBox(std::min(low, high));
    to_ = numberBox(std::max(low, high));
    count_ = countBox(5);
    from_->setObjectName("from");
    to_->setObjectName("to");
    count_->setObjectName("count");
    first->addWidget(from_);
    first->addWidget(new QLabel(tr("to")));
    first->addWidget(to_);
    first->addWidget(new QLabel(tr("in")));
    first->addWidget(count_);
    first->addWidget(new QLabel(tr("values")));
    form->addRow(path, first);

    auto* secondRow = new QHBoxLayout;
    second_ = new QCheckBox(tr("and"));
    second_->setObjectName("second");
    path2_ = new QComboBox;
    path2_->setObjectName("secondPath");
    for (const QString& p : sweepablePaths(*doc))
        if (p != path) path2_->addItem(p);
    from2_ = numberBox(0.0);
    to2_ = numberBox(1.0);
    count2_ = countBox(3);
    for (QWidget* w : {static_cast<QWidget*>(path2_), static_cast<QWidget*>(from2_), static_cast<QWidget*>(to2_),
                       static_cast<QWidget*>(count2_)})
        w->setEnabled(false);
    connect(second_, &QCheckBox::toggled, this, [this](bool on) {
        for (QWidget* w : {static_cast<QWidget*>(path2_), static_cast<QWidget*>(from2_),
                           static_cast<QWidget*>(to2_), static_cast<QWidget*>(count2_)})
            w->setEnabled(on && !isRunning());
    });
    secondRow->addWidget(second_);
    secondRow->addWidget(path2_, 1);
    secondRow->addWidget(from2_);
    secondRow->addWidget(new QLabel(tr("to")));
    secondRow->addWidget(to2_);
    secondRow->addWidget(new QLabel(tr("in")));
    secondRow->addWidget(count2_);
    form->addRow(tr("Also vary"), secondRow);

    measure_ = new QComboBox;
    measure_->setObjectName("measure");
    connect(measure_, &QComboBox::currentTextChanged, this, [this] { replot(); });
    form->addRow(tr("Plot"), measure_);
    layout->addLayout(form);

    auto* runRow = new QHBoxLayout;
    run_ = new QPushButton(tr("Run"));
    run_->setObjectName("run");
    cancel_ = new QPushButton(tr("Cancel"));
    cancel_->setObjectName("cancel");
    cancel_->setEnabled(false);
    progress_ = new QProgressBar;
    progress_->setObjectName("progress");
    progress_->setRange(0, 1);
    progress_->setValue(0);
    runRow->addWidget(run_);
    runRow->addWidget(cancel_);
    runRow->addWidget(progress_, 1);
    layout->addLayout(runRow);
    status_ = new QLabel(tr("Each variant runs as its own process, on all cores."));
    status_->setObjectName("status");
    status_->setWordWrap(true);
    where_ = new QLabel;
    where_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    where_->setWordWrap(true);
    layout->addWidget(status_);
    layout->addWidget(where_);

    auto* split = new QSplitter(Qt::Vertical);
    table_ = new QTableWidget;
    table_->setObjectName("summary");
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->setSelectionBehavior(QAbstractItemView::SelectRows);
    table_->setToolTip(tr("Double-click a variant to open it in place of the scene (Edit > Undo brings the scene back)"));
    connect(table_, &QTableWidget::cellDoubleClicked, this, [this](int row, int) { openVariant(row); });
    auto* view = new QChartView(new QChart);
    view->setObjectName("plot");
    view->setRenderHint(QPainter::Antialiasing);
    view->setMinimumHeight(220);
    chart_ = view;
    split->addWidget(table_);
    split->addWidget(view);
    layout->addWidget(split, 1);

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    layout->addWidget(buttons);

    connect(run_, &QPushButton::clicked, this, &SweepDialog::run);
    connect(cancel_, &QPushButton::clicked, this, &SweepDialog::cancel);
    connect(&process_, &QProcess::readyReadStandardError, this, &SweepDialog::readProgress);
    connect(&process_, &QProcess::finished, this, [this](int code, QProcess::ExitStatus) { finished(code); });
    connect(&process_, &QProcess::errorOccurred, this, [this](QProcess::ProcessError e) {
        if (e == QProcess::FailedToStart) {
            status_->setText(tr("Could not start %1: %2").arg(process_.program(), process_.errorString()));
            finished(-1);
        }
    });
    resize(760, 640);
}

SweepDialog::~SweepDialog() {
    if (isRunning()) {
        process_.terminate();  // (tumble sweep stops its variants on SIGTERM)
        process_.waitForFinished(10000);
    }
}

void SweepDialog::setRange(double from, double to, int count) {
    from_->setValue(from);
    to_->setValue(to);
    count_->setValue(count);
}

void SweepDialog::setSecond(const QString& path, double from, double to, int count) {
    second_->setChecked(!path.isEmpty());
    if (path.isEmpty()) return;
    path2_->setCurrentText(path);
    from2_->setValue(from);
    to2_->setValue(to);
    count2_->setValue(count);
}

void SweepDialog::setMeasure(const QString& column) { measure_->setCurrentText(column); }

bool SweepDialog::isRunning() const { return process_.state() != QProcess::NotRunning; }

QString SweepDialog::status() const { return status_->text(); }

void SweepDialog::run() {
    if (isRunning()) return;
    const QString cache = QStandardPaths::writableLocation(QStandardPaths::CacheLocation);
    const QString stem = doc_->filePath().isEmpty() ? QString("untitled") : QFileInfo(doc_->filePath()).completeBaseName();
    folder_ = QDir(cache).filePath("sweeps/" + stem + "-" + QDateTime::currentDateTime().toString("yyyyMMdd-HHmmss-zzz"));
    if (!QDir().mkpath(folder_)) {
        status_->setText(tr("Could not make the folder %1").arg(folder_));
        return;
    }
    // The scene as it is in the editor, saved or not (its mesh files are absolute paths).
    const QString scene = QDir(folder_).filePath("scene.json");
    QFile file(scene);
    if (!file.open(QIODevice::WriteOnly) || file.write(QByteArray::fromStdString(io::sceneToJson(doc_->scene()))) < 0) {
        status_->setText(tr("Could not write %1").arg(scene));
        return;
    }
    file.close();
    QStringList args = {"sweep", scene, "--vary",
                        QString("%1=%2:%3:%4").arg(path_, number(from_->value()), number(to_->value())).arg(count_->value()),
                        "--out", folder_};
    if (second_->isChecked())
        args << "--vary"
             << QString("%1=%2:%3:%4")
                    .arg(path2_->currentText(), number(from2_->value()), number(to2_->value()))
                    .arg(count2_->value());
    const int total = count_->value() * (second_->isChecked() ? count2_->value() : 1);
    progress_->setRange(0, total);
    progress_->setValue(0);
    errors_.clear();
    table_->clear();
    table_->setRowCount(0);
    rows_.clear();
    status_->setText(tr("Running %n variant(s)…", nullptr, total));
    where_->setText(tr("Results in %1").arg(folder_));
    run_->setEnabled(false);
    cancel_->setEnabled(true);
    const QString program = executable().isEmpty() ? QCoreApplication::applicationFilePath() : executable();
    process_.start(program, args);
}

void SweepDialog::cancel() {
    if (!isRunning()) return;
    status_->setText(tr("Stopping…"));
    process_.terminate();
}

void SweepDialog::readProgress() {
    errors_ += process_.readAllStandardError();
    static const QRegularExpression line("sweep: (\\d+) of (\\d+) done, (\\d+) running, (\\d+) failed");
    QRegularExpressionMatch last;
    for (auto it = line.globalMatch(QString::fromUtf8(errors_)); it.hasNext();) last = it.next();
    if (!last.hasMatch()) return;
    progress_->setValue(last.captured(1).toInt());
    status_->setText(tr("%1 of %2 done, %3 running, %4 failed")
                         .arg(last.captured(1), last.captured(2), last.captured(3), last.captured(4)));
}

void SweepDialog::finished(int exitCode) {
    readProgress();
    run_->setEnabled(true);
    cancel_->setEnabled(false);
    loadSummary();
    int ok = 0;
    const int statusColumn = header_.indexOf("status");
    for (const QStringList& r : rows_) ok += r.value(statusColumn) == "ok";
    if (exitCode == 130)
        status_->setText(tr("Cancelled: %1 of %2 variants ran. Run again to start a new sweep.").arg(ok).arg(rows_.size()));
    else if (exitCode == 0 || exitCode == 1)
        status_->setText(tr("%1 variants: %2 ran, %3 failed (their messages are in the table).")
                             .arg(rows_.size())
                             .arg(ok)
                             .arg(rows_.size() - ok));
    else {
        // Bad input: tumble sweep's own message (it names the value and what is wrong).
        const QStringList messages = QString::fromUtf8(errors_).split('\n', Qt::SkipEmptyParts);
        status_->setText(messages.isEmpty() ? tr("The sweep failed.") : messages.last());
    }
    progress_->setValue(progress_->maximum() > 0 && exitCode == 0 ? progress_->maximum() : progress_->value());
    emit sweepFinished(exitCode);
}

void SweepDialog::loadSummary() {
    header_.clear();
    rows_.clear();
    QFile file(QDir(folder_).filePath("summary.csv"));
    if (!file.open(QIODevice::ReadOnly)) return;
    const QStringList lines = QString::fromUtf8(file.readAll()).split('\n', Qt::SkipEmptyParts);
    if (lines.isEmpty()) return;
    header_ = csvCells(lines.first());
    for (int i = 1; i < lines.size(); ++i) rows_ << csvCells(lines[i]);
    table_->setColumnCount(static_cast<int>(header_.size()));
    table_->setHorizontalHeaderLabels(header_);
    table_->setRowCount(static_cast<int>(rows_.size()));
    for (int r = 0; r < rows_.size(); ++r)
        for (int c = 0; c < header_.size(); ++c) table_->setItem(r, c, new QTableWidgetItem(rows_[r].value(c)));
    table_->resizeColumnsToContents();
    // The measures: the columns after wall_s, but the message.
    const QString keep = measure_->currentText();
    QSignalBlocker block(measure_);
    measure_->clear();
    for (int c = static_cast<int>(header_.indexOf("wall_s")) + 1; c < header_.size(); ++c)
        if (header_[c] != "message") measure_->addItem(header_[c]);
    const QString body = path_.section('.', 0, 0);
    const QString preferred = keep.isEmpty() ? body + ".highest" : keep;
    if (measure_->findText(preferred) >= 0) measure_->setCurrentText(preferred);
    replot();
}

void SweepDialog::replot() {
    auto* view = static_cast<QChartView*>(chart_);
    QChart* chart = view->chart();
    chart->removeAllSeries();
    for (QAbstractAxis* a : chart->axes()) {
        chart->removeAxis(a);
        delete a;
    }
    plotted_.clear();
    const int x = static_cast<int>(header_.indexOf(path_)), y = static_cast<int>(header_.indexOf(measure_->currentText()));
    if (x < 0 || y < 0) return;
    const int by = second_->isChecked() ? static_cast<int>(header_.indexOf(path2_->currentText())) : -1;
    QMap<QString, QList<QPointF>> lines;
    QStringList order;
    for (const QStringList& r : rows_) {
        bool okX = false, okY = false;
        const double vx = r.value(x).toDouble(&okX), vy = r.value(y).toDouble(&okY);
        if (!okX || !okY) continue;  // a failed variant, or a measure it has none of (a body still moving)
        const QString key = by >= 0 ? path2_->currentText() + " = " + r.value(by) : measure_->currentText();
        if (!lines.contains(key)) order << key;
        lines[key] << QPointF(vx, vy);
    }
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const QString& key : order) {
        auto* series = new QLineSeries;
        series->setName(key);
        series->setPointsVisible(true);
        for (const QPointF& p : lines[key]) {
            series->append(p);
            x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x()), y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
        }
        chart->addSeries(series);
        plotted_.append({key, lines[key]});
    }
    if (order.isEmpty()) return;
    auto* ax = new QValueAxis;
    auto* ay = new QValueAxis;
    ax->setTitleText(path_);
    ay->setTitleText(measure_->currentText());
    const double padX = x1 > x0 ? 0.02 * (x1 - x0) : 0.5, padY = y1 > y0 ? 0.05 * (y1 - y0) : 0.5;
    ax->setRange(x0 - padX, x1 + padX);
    ay->setRange(y0 - padY, y1 + padY);
    chart->addAxis(ax, Qt::AlignBottom);
    chart->addAxis(ay, Qt::AlignLeft);
    for (QAbstractSeries* s : chart->series()) {
        s->attachAxis(ax);
        s->attachAxis(ay);
    }
    chart->legend()->setVisible(order.size() > 1);
}

void SweepDialog::openVariant(int row) {
    if (row < 0 || row >= rows_.size()) return;
    const QString name = rows_[row].value(0);
    const QString file = QDir(folder_).filePath("variants/" + name + ".json");
    try {
        const SceneDesc scene = io::readSceneFile(file.toStdString());
        QStringList values;
        for (int c = 1; c < header_.indexOf("status"); ++c) values << header_[c] + " = " + rows_[row].value(c);
        doc_->replaceScene(scene, tr("Open sweep variant %1 (%2)").arg(name, values.join(", ")), true);
        status_->setText(tr("Variant %1 is open in the editor (Edit > Undo brings the scene back).").arg(name));
    } catch (const std::exception& e) {
        status_->setText(QString::fromUtf8(e.what()));
    }
}

}  // namespace tumble::ui
