// File > Export: the format (trajectory CSV or JSON, glTF, glb, a PNG image sequence, an
// MP4 video when ffmpeg is installed), where to, which frames (range and step, so a lower
// frame rate), which bodies (trajectories), the joints' reactions (trajectories of a scene
// with joints) and the image size (images, video). The last choices are remembered
// (QSettings).
#pragma once

#include <tumble/io/trajectory_writer.h>

#include <QDialog>
#include <QSize>
#include <QStringList>

class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QSpinBox;
class QDialogButtonBox;

namespace tumble::ui {

class ExportDialog : public QDialog {
    Q_OBJECT
public:
    enum class Kind { Csv, Json, Gltf, Glb, Images, Video };
    Q_ENUM(Kind)

    /// `bodyNames` in scene order; `frames` and `frameRate` of the recording; `sceneName`
    /// the scene's name, or its file's path (the export then starts beside it).
    ExportDialog(const QStringList& bodyNames, int frames, double frameRate, const QString& sceneName,
                 QWidget* parent = nullptr);

    Kind kind() const;
    void setKind(Kind kind);
    /// A file for the trajectory formats and video, a folder for images.
    QString target() const;
    void setTarget(const QString& path);
    io::ExportOptions options() const;
    void setFrameRange(int first, int last, int step);
    void setBodiesChecked(const QList<int>& bodies);
    /// Whether the scene has joints: then a CSV or JSON export can add their reactions
    /// (ExportOptions::jointForces; a CSV's go in FILE-joints.csv beside it).
    void setHasJoints(bool has);
    void setJointForces(bool on);
    QSize imageSize() const;
    /// What is wrong with the choices, or empty (the OK button is enabled only then).
    QString problem() const;

    void accept() override;  // remembers the choices

    /// The folder the target starts in (see the definition): `remembered` the last
    /// export's, `scene` the scene's name or its file's path.
    static QString startFolder(const QString& remembered, const QString& scene);

private:
    void browse();
    void update();
    void restore(const QString& sceneName);

    int frames_;
    double frameRate_;
    QComboBox* kind_;
    QLineEdit* target_;
    QSpinBox* first_;
    QSpinBox* last_;
    QSpinBox* step_;
    QLabel* rate_;
    QListWidget* bodies_;
    QCheckBox* jointForces_;
    QWidget* jointsLabel_ = nullptr;
    QSpinBox* width_;
    QSpinBox* height_;
    QLabel* problem_;
    QDialogButtonBox* buttons_;
    QWidget* bodiesRow_;
    QWidget* sizeRow_;
};

/// The extension of a kind ("csv", ...; "" for images).
QString exportExtension(ExportDialog::Kind kind);

}  // namespace tumble::ui
