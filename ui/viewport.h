// The 3D view of the document: every body drawn and lit, a ground grid and axes, an orbit
// camera (mouse and keyboard), click to select. Qt3D stays behind the pimpl: this header is
// included by the main window and must stay light.
#pragma once

#include <QPoint>
#include <QVector3D>
#include <QWidget>

#include <memory>

class QWindow;

namespace tumble::ui {

class Document;

class Viewport : public QWidget {
    Q_OBJECT
public:
    explicit Viewport(Document* document, QWidget* parent = nullptr);
    ~Viewport() override;

    /// The body under a widget point: the nearest hit of the ray from the camera through that
    /// pixel against the bodies' exact shapes, or -1.
    int bodyAt(const QPoint& widgetPos) const;
    /// Selects the body under the point (Ctrl: toggles it in the selection); empty space
    /// clears the selection (Ctrl: leaves it). What a left click does.
    void clickAt(const QPoint& widgetPos, Qt::KeyboardModifiers modifiers = Qt::NoModifier);

    /// Body entities in the 3D scene (one per body of the document).
    int entityCount() const;
    /// Where a world point appears, in widget pixels (z: depth, in [-1, 1] when visible).
    QVector3D projectToWidget(const QVector3D& world) const;

    // ---- The camera (an orbit about a target).
    QVector3D cameraPosition() const;
    QVector3D cameraTarget() const;
    float cameraDistance() const;
    void setCamera(const QVector3D& target, float distance, float yawDegrees, float pitchDegrees);

    /// The Qt3D window inside the container (it receives the mouse and keys).
    QWindow* renderWindow() const;

public slots:
    /// Looks at the selected bodies (all of them when nothing is selected).
    void frameSelection();
    /// Looks at every body (planes excluded: they are infinite).
    void frameAll();

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;

private:
    bool handleKey(QKeyEvent* event);
    void frameBodies(const QList<int>& indices);
    void syncCamera();

    struct Impl;
    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
