// The ground grid (issue 52 item 6): a line lying on the ground plane is drawn whole far from
// the eye (the ground's depth no longer fights the line's and breaks it into dashes), and the
// grid fades out with distance, sooner the lower the eye, and towards its edge, instead of
// ending hard. Pixels of the real view under Xvfb.
#include "document/document.h"
#include "viewport/viewport.h"
#include "viewport/viewport_grid.h"
#include "viewport_test_util.h"

#include <QImage>
#include <QScreen>
#include <QWindow>
#include <QtTest>

#include <QtMath>

#include <algorithm>
#include <memory>
#include <cmath>

using namespace tumble;
using namespace tumble::ui;
using tumble::test::projected;

namespace {

// The brightest grey in the 3 x 3 pixels around `at` (a one-pixel line may fall beside the
// rounded projection of a point on it).
int brightestAround(const QImage& image, QPoint at) {
    int best = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const QPoint p = at + QPoint(dx, dy);
            if (!image.rect().contains(p)) continue;
            const QColor c = image.pixelColor(p);
            best = std::max(best, (c.red() + c.green() + c.blue()) / 3);
        }
    return best;
}

int greyAt(const QImage& image, QPoint at) {
    const QColor c = image.pixelColor(at);
    return (c.red() + c.green() + c.blue()) / 3;
}

// The view's pixels once two grabs a little apart agree (the frame for the camera is drawn)
// and `ready` finds in them what the test looks at (else the last grab after 10 s). Qt3D may
// draw the scene a few frames before a pass it adds (the grid, blended after the scene): under
// load two grabs without the grid once agreed, and a test found no line drawn at all.
template <class Ready>
QImage settled(Viewport& view, Ready&& ready) {
    QImage last;
    for (int tries = 0; tries < 100; ++tries) {
        QTest::qWait(100);
        QImage shot = view.screen()->grabWindow(view.winId()).toImage();
        if (!last.isNull() && shot == last && ready(shot)) return shot;
        last = shot;
    }
    return last;
}

// A view of `doc`, 640 x 480, on screen, looking at the origin from `distance` m at `pitch`
// degrees down, along -z.
std::unique_ptr<Viewport> shown(Document& doc, float distance, float pitch) {
    auto view = std::make_unique<Viewport>(&doc);
    view->resize(640, 480);
    view->show();
    if (!QTest::qWaitForWindowExposed(view.get())) qWarning("the view was not exposed");
    view->setCamera(QVector3D(0, 0, 0), distance, 0.0f, pitch);
    return view;
}

}  // namespace

class TestViewportGrid : public QObject {
    Q_OBJECT
private slots:
    void theFadeItsShaderDraws() {
        const float half = 20.0f;
        QCOMPARE(gridOpacity(1.0f, 5.0f, 0.0f, half), 1.0f);  // near: whole
        QCOMPARE(gridOpacity(100.0f, 5.0f, 0.0f, half), 0.0f);
        QCOMPARE(gridOpacity(3.0f, 5.0f, half, half), 0.0f);  // at the edge: gone
        // Lower eyes fade sooner (lines crowd together on screen sooner).
        QVERIFY(gridOpacity(10.0f, 0.5f, 0.0f, half) < gridOpacity(10.0f, 5.0f, 0.0f, half));
        // No step anywhere: opacity changes smoothly along a line walked away from the eye.
        float last = 1.0f;
        for (float d = 0.0f; d < 60.0f; d += 0.05f) {
            const float a = gridOpacity(d, 3.0f, 0.0f, half);
            QVERIFY(a <= last + 1e-6f && last - a < 0.01f);
            last = a;
        }
    }

    // The line x = -5 (every fifth line is brighter) running away from the eye, 4.1 m up: where
    // the fade leaves it at least 60 % opaque (out to about 14 m), every point of it is drawn.
    // Before the ground was drawn a little behind by its depth slope it broke into dashes
    // from 8 m on.
    void aLineOnTheGroundIsWholeAway() {
        Document doc;  // the ground alone
        const float distance = 12.0f, pitch = 20.0f;
        const auto shownView = shown(doc, distance, pitch);
        Viewport& view = *shownView;
        const QVector3D eye(0.0f, distance * std::sin(qDegreesToRadians(pitch)),
                            distance * std::cos(qDegreesToRadians(pitch)));
        // (Ready: the line is drawn near the eye.)
        const QImage shot = settled(view, [&](const QImage& image) {
            return brightestAround(image, projected(view, Vec3(-5, 0, 2.5))) >
                   greyAt(image, projected(view, Vec3(-4.5, 0, 2.5))) + 12;
        });
        int samples = 0, gaps = 0;
        QString where;
        for (double z = 3.0; z >= -12.0; z -= 0.02) {
            const QVector3D p(-5.0f, 0.0f, float(z));
            if (gridOpacity(p.distanceToPoint(eye), eye.y(), 5.0f, 20.0f) < 0.6f) break;
            const QPoint at = projected(view, Vec3(-5, 0, z));
            const int ground = greyAt(shot, projected(view, Vec3(-4.5, 0, std::floor(z) + 0.5)));  // inside a cell
            if (!shot.rect().contains(at) || std::abs(z) < 0.06) continue;  // (the x axis crosses, dark red)
            ++samples;
            if (brightestAround(shot, at) <= ground + 12) {
                ++gaps;
                if (where.size() < 200) where += QString(" %1").arg(z, 0, 'f', 2);
            }
        }
        QVERIFY2(samples > 300, qPrintable(QString::number(samples)));
        QVERIFY2(gaps == 0, qPrintable(QString("%1 of %2 points of the line show the ground, at z:%3")
                                           .arg(gaps)
                                           .arg(samples)
                                           .arg(where)));
    }

    // The lines stay behind a body standing on them (the ground's offset moves the ground
    // alone): the front face of a box on the line x = -5, from 2.5 cm above the ground up, is
    // the box's colour (the orange of a dynamic body) at every pixel over the line.
    void aBodyOnTheGridHidesIt() {
        Document doc;
        doc.addBody(test::body("crate", ShapeType::Box, Vec3(-5, 0.5, -2)));  // 1 m cube
        const auto shownView = shown(doc, 12.0f, 20.0f);
        Viewport& view = *shownView;
        auto boxColoured = [&](const QImage& image, double y) {
            const QColor c = image.pixelColor(projected(view, Vec3(-5, y, -1.5)));
            return c.red() > c.blue() + 60;
        };
        // (Ready: the box and the grid are drawn.)
        const QImage shot = settled(view, [&](const QImage& image) {
            return boxColoured(image, 0.5) && brightestAround(image, projected(view, Vec3(-5, 0, 2.5))) >
                                                  greyAt(image, projected(view, Vec3(-4.5, 0, 2.5))) + 12;
        });
        for (double y = 0.025; y < 1.0; y += 0.025) {
            const QPoint at = projected(view, Vec3(-5, y, -1.5));
            const QColor c = shot.pixelColor(at);
            QVERIFY2(c.red() > c.blue() + 60, qPrintable(QString("at y = %1 m: rgb(%2, %3, %4)")
                                                            .arg(y)
                                                            .arg(c.red())
                                                            .arg(c.green())
                                                            .arg(c.blue())));
        }
    }

    // A line walked away from the eye: clear near it, less clear farther, gone before the
    // grid ends (no hard end where the lines stop).
    void theGridFadesAwayFromTheEye() {
        Document doc;
        const auto shownView = shown(doc, 10.0f, 12.0f);
        Viewport& view = *shownView;
        auto contrastIn = [&](const QImage& image, double z) {
            const QPoint at = projected(view, Vec3(-1, 0, z));
            const QPoint cell = projected(view, Vec3(-1.5, 0, z));
            return brightestAround(image, at) - greyAt(image, cell);
        };
        // (Ready: the grid is drawn near the eye.)
        const QImage shot = settled(view, [&](const QImage& image) { return contrastIn(image, 3.5) > 12; });
        auto contrast = [&](double z) { return contrastIn(shot, z); };
        // The eye 2.1 m up; cells' middles (z half way between lines) about 6 to 19 m away.
        int last = 255;
        QString profile;
        bool fading = true;
        for (double z = 3.5; z >= -9.5; z -= 1.0) {
            const int c = contrast(z);
            profile += QString(" %1").arg(c);
            fading = fading && c <= last + 2;  // never brighter farther away (2: rounding)
            last = c;
        }
        const int near = contrast(3.5), middle = contrast(-2.5), far = contrast(-9.5);
        QVERIFY2(fading && near > 25 && near > middle + 5 && middle > far + 10 && far < 5,
                 qPrintable("contrast from near to far:" + profile));
    }
};

QTEST_MAIN(TestViewportGrid)
#include "tst_viewport_grid.moc"
