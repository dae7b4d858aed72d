// "Sweep this value…" (issue 22, docs/sweeps.md): one value of the scene from one number
// to another in a count of steps, and optionally a second one, run in the background as
// `tumble sweep` (the same command a user types: each variant its own process, on all
// cores) with its progress and a Cancel; then the summary as a table and a plot of a chosen
// measure against the value (one line per value of the second). Double-clicking a row
// opens that variant in place of the scene, one undo step (Edit > Undo brings the scene
// back).
#pragma once

#include <QDialog>
#include <QPointF>
#include <QProcess>
#include <QStringList>

class QComboBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QCheckBox;
class QWidget;

namespace tumble::ui {

class Document;
class PropertySpinBox;

class SweepDialog : public QDialog {
    Q_OBJECT
public:
    /// `path` is the value swept first (e.g. "ball.restitution"), now at `value`.
    SweepDialog(Document* doc, const QString& path, double value, QWidget* parent = nullptr);
    ~SweepDialog() override;

    /// The program run as `PROGRAM sweep ...`: the editor itself by default (it is tumble);
    /// tests give the built tumble.
    static void setExecutable(const QString& program);

    /// The values a sweep of this scene can vary: settings and each body's numbers, as
    /// tumble sweep names them (orientation and inertia left out: a quaternion's or a
    /// matrix's entries alone are not what a user turns).
    static QStringList sweepablePaths(const Document& doc);

    // What the controls hold, for tests and for the panel that opens it.
    void setRange(double from, double to, int count);
    void setSecond(const QString& path, double from, double to, int count);  ///< empty path: none
    void setMeasure(const QString& column);

    void run();
    void cancel();
    bool isRunning() const;
    /// The folder the sweep writes (made when it runs).
    QString folder() const { return folder_; }
    QTableWidget* table() const { return table_; }
    /// The plotted lines, each (its label, its points).
    QList<std::pair<QString, QList<QPointF>>> plotted() const { return plotted_; }
    QString status() const;

signals:
    /// The sweep ended (exit status of tumble sweep: 0, 1 some failed, 130 cancelled).
    void sweepFinished(int exitCode);

private:
    void readProgress();
    void finished(int exitCode);
    void loadSummary();
    void replot();
    void openVariant(int row);

    Document* doc_ = nullptr;
    QString path_;
    QString folder_;
    QProcess process_;
    QByteArray errors_;
    PropertySpinBox *from_ = nullptr, *to_ = nullptr, *from2_ = nullptr, *to2_ = nullptr;
    QSpinBox *count_ = nullptr, *count2_ = nullptr;
    QCheckBox* second_ = nullptr;
    QComboBox *path2_ = nullptr, *measure_ = nullptr;
    QPushButton *run_ = nullptr, *cancel_ = nullptr;
    QProgressBar* progress_ = nullptr;
    QLabel *status_ = nullptr, *where_ = nullptr;
    QTableWidget* table_ = nullptr;
    QWidget* chart_ = nullptr;  // a QChartView (Qt Charts stays inside the .cpp)
    QStringList header_;
    QList<QStringList> rows_;
    QList<std::pair<QString, QList<QPointF>>> plotted_;
};

}  // namespace tumble::ui
