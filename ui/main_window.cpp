#include "main_window.h"
#include "editor_main.h"

#include <tumble/io/scene_file.h>
#include <tumble/model.h>

#include <QApplication>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QHeaderView>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace tumble::ui {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
    auto* central = new QWidget(this);
    auto* layout = new QVBoxLayout(central);
    summary_ = new QLabel(central);
    bodies_ = new QTreeWidget(central);
    bodies_->setHeaderLabels({tr("Body"), tr("Motion"), tr("Shape"), tr("Mass (kg)")});
    bodies_->setRootIsDecorated(false);
    bodies_->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
    layout->addWidget(summary_);
    layout->addWidget(bodies_);
    setCentralWidget(central);

    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&Open..."), QKeySequence::Open, this, &MainWindow::chooseScene);
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, qApp, &QApplication::closeAllWindows);
    resize(720, 480);
}

QString MainWindow::defaultScenePath() { return QStringLiteral(":/scenes/tumbling-box.json"); }

bool MainWindow::openScene(const QString& path, QString* error) {
    QFile file(path);
    const QString name = path.startsWith(":/") ? QFileInfo(path).fileName() : path;
    if (!file.open(QIODevice::ReadOnly)) {
        if (error) *error = tr("%1: cannot be read (%2)").arg(name, file.errorString());
        return false;
    }
    try {
        const QByteArray text = file.readAll();
        scene_ = io::parseScene(std::string_view(text.constData(), size_t(text.size())), name.toStdString());
    } catch (const io::InputError& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    path_ = path;
    showScene();
    return true;
}

void MainWindow::showScene() {
    setWindowTitle(tr("%1 - Tumble").arg(QFileInfo(path_).fileName()));
    bodies_->clear();
    Model model;
    try {
        model = compile(scene_);
    } catch (const std::exception& e) {
        statusBar()->showMessage(QString::fromStdString(e.what()));
    }
    for (size_t i = 0; i < scene_.bodies.size(); ++i) {
        const BodyDesc& b = scene_.bodies[i];
        const QString mass = i < model.bodies.size() && b.motion == Motion::Dynamic
                                 ? QString::number(model.bodies[i].mass, 'g', 6)
                                 : QStringLiteral("-");
        new QTreeWidgetItem(bodies_, {QString::fromStdString(b.name), toString(b.motion), toString(b.shape.type), mass});
    }
    const Settings& s = scene_.settings;
    const int n = int(scene_.bodies.size());
    summary_->setText((n == 1 ? tr("1 body") : tr("%1 bodies").arg(n)) +
                      tr("; %1 s at a step of %2 s, %3 frames per second")
                          .arg(s.duration)
                          .arg(s.dt)
                          .arg(s.frameRate));
}

void MainWindow::chooseScene() {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open scene"), QString(), tr("Tumble scenes (*.json)"));
    if (path.isEmpty()) return;
    QString error;
    if (!openScene(path, &error)) QMessageBox::warning(this, tr("Open scene"), error);
}

int runEditor(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setApplicationName("Tumble");
    QApplication::setOrganizationName("Tumble");
    MainWindow window;
    const QStringList args = QApplication::arguments();
    QString error;
    const QString path = args.size() > 1 ? args[1] : MainWindow::defaultScenePath();
    if (!window.openScene(path, &error)) {
        QMessageBox::critical(nullptr, QObject::tr("Tumble"), error);
        if (!window.openScene(MainWindow::defaultScenePath(), &error)) return 1;
    }
    window.show();
    return app.exec();
}

}  // namespace tumble::ui
