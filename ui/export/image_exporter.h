// Export of the recording as images: one PNG per selected frame, rendered by a viewport of
// exactly the chosen size, and an MP4 of them when ffmpeg is installed (found on PATH at
// run time; never needed to build).
//
// How a frame is taken: the exporter makes a second Viewport of the document, a frameless
// top-level window of the chosen size drawing the same timeline with the user's camera,
// overlays and collision shapes (not the selection: no highlight, no handles), and puts a
// Qt3D render capture at the root of its frame graph. For each frame it seeks the timeline
// and requests captures until two in a row agree (a reply completes only with a frame
// drawn after the request, but Qt3D can draw the bodies' instance transforms a frame
// late), saves the image and goes on to the next frame from the event loop: the UI never
// blocks. A window of its own, rather than an offscreen render target in the user's
// viewport, leaves the user's view untouched and works the same on a GPU and under Xvfb
// (llvmpipe), where the tests run, also larger than the screen.
//
// Writes are atomic: the PNGs go to a hidden temporary folder inside the target folder
// and are moved into place only when every frame was saved; the MP4 is written by ffmpeg
// to a temporary name beside the target and renamed when ffmpeg succeeds. Cancel or a
// failed frame leaves neither images nor video (and removes the target folder if the
// export created it). When the video alone fails (ffmpeg absent or in error) the images,
// all of them good, are kept and finished(false, ...) says why there is no MP4.
#pragma once

#include <QObject>
#include <QSize>
#include <QString>

#include <memory>

namespace tumble::ui {

class Timeline;
class Viewport;

struct ImageExportOptions {
    /// The PNGs go here as <prefix>0000.png, <prefix>0001.png, ...: numbered 0 to count - 1
    /// in the order of the frames (image i is frame firstFrame + i * frameStep), with 4
    /// digits or as many as the count needs. Created when missing; files of the same names
    /// are replaced.
    QString folder;
    QString prefix = QStringLiteral("frame_");
    /// Pixels of every image.
    QSize size{1280, 720};
    /// Recorded frames firstFrame, firstFrame + frameStep, ... up to lastFrame (-1: the last
    /// recorded frame).
    int firstFrame = 0;
    int lastFrame = -1;
    int frameStep = 1;
    /// Also an MP4 (H.264 when ffmpeg has libx264, else MPEG-4 part 2) at
    /// frameRate / frameStep frames per second.
    bool video = false;
    /// The .mp4 path.
    QString videoFile;
};

class ImageExporter : public QObject {
    Q_OBJECT
public:
    /// `viewport`: the user's view, whose camera, overlays and collision-shape toggle are
    /// copied; `timeline`: the recording (its playhead is moved during the export and put
    /// back at the end).
    ImageExporter(Viewport* viewport, Timeline* timeline, QObject* parent = nullptr);
    ~ImageExporter() override;

    /// ffmpeg's path on PATH (QStandardPaths::findExecutable), empty when absent.
    static QString ffmpegPath();
    /// The file name of image `index` of an export of `count` images.
    static QString imageFileName(const QString& prefix, int index, int count);

    /// Starts an export; returns at once. progress() follows each saved image, finished()
    /// comes once, always after start() has returned (also when the options are refused).
    /// Ignored while an export runs.
    void start(const ImageExportOptions& options);
    /// Stops the export in progress: nothing it wrote is left; finished(false,
    /// "Export cancelled") is emitted before this returns.
    void cancel();
    bool isRunning() const;

signals:
    void progress(int done, int total);
    void finished(bool ok, const QString& message);

private:
    struct Impl;
    void fail(const QString& message);
    void finish(bool ok, const QString& message);
    void deleteView();
    void waitForView();
    void beginFrame();
    void requestCapture();
    void onCaptured();
    void framesDone();
    void probeEncoders();
    void encode(const QString& codec);
    void onEncoded();
    /// Moves the images from the temporary folder into the target; an error message or empty.
    QString moveImagesIntoPlace();

    std::unique_ptr<Impl> d_;
};

}  // namespace tumble::ui
