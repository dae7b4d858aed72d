// The editor's main window. For now it opens a scene and lists its bodies; the docks,
// the viewport and undo come with the editor issue.
#pragma once

#include <tumble/scene.h>

#include <QMainWindow>
#include <QString>

class QTreeWidget;
class QLabel;

namespace tumble::ui {

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);

    /// Loads a scene file (or a ":/scenes/..." resource). On failure returns false,
    /// keeps the current scene and puts the message in `error`.
    bool openScene(const QString& path, QString* error);

    const SceneDesc& scene() const { return scene_; }
    const QString& scenePath() const { return path_; }

    /// The sample scene opened when no scene is given.
    static QString defaultScenePath();

private:
    void showScene();
    void chooseScene();

    SceneDesc scene_;
    QString path_;
    QTreeWidget* bodies_ = nullptr;
    QLabel* summary_ = nullptr;
};

}  // namespace tumble::ui
