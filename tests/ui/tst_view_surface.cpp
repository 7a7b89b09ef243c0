// The 3D view's frames in a native OpenGL window (ui/view_surface.h) on the unit sphere sample
// (label gui, Xvfb): a frame repaints no widget, the screen shows what grabFramebuffer reads, the
// probe's panel shows over the window, measurements and the rubber band are painted over the frame,
// a drag step's partial frame is copied where it changed and the overlays were (measured only when
// so copied), input that reaches the native window itself is the view's (a control-point drag edits
// the document), and the QOpenGLWidget fallback draws the same pixels; on a context too old for the
// renderer (tests/ui/view_frames.cmake) the view shows why instead of a frame.
#include "editor_test_util.h"
#include "render/offscreen_renderer.h"
#include "ui/controlpointpicker.h"
#include "ui/probe_tool.h"

#include <QCursor>
#include <QFrame>
#include <QPainter>
#include <QScreen>
#include <QSignalSpy>
#include <QUndoStack>
#include <QWindow>

using namespace kw;

namespace {

/// Counts paint events of the widgets inside the view.
class PaintCounter : public QObject {
public:
    int paints = 0;

protected:
    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() == QEvent::Paint && watched->isWidgetType())
            ++paints;
        return false;
    }
};

/// Pixels within `tolerance` of `colour` in each channel.
int pixelsNear(const QImage& image, QColor colour, int tolerance = 24) {
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const QRgb p = image.pixel(x, y);
            n += std::abs(qRed(p) - colour.red()) <= tolerance &&
                 std::abs(qGreen(p) - colour.green()) <= tolerance &&
                 std::abs(qBlue(p) - colour.blue()) <= tolerance;
        }
    return n;
}

} // namespace

class TestViewSurface : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    }

private Q_SLOTS:
    void cleanup() {
        closeWindow();
        qunsetenv("KNOTWORK_VIEW");
    }

    void framesGoToTheNativeWindow() {
        openWindow("sphere");
        Viewport* vp = m_window->viewport();
        QVERIFY(vp->isNativeWindow());
        QVERIFY(vp->findChild<QWidget*>(QStringLiteral("viewWindowContainer")));
        waitStill(300);
        // Frames are drawn and swapped by the window alone: no widget in the view repaints
        // (a QOpenGLWidget is repainted, and its window composed again, at every frame).
        PaintCounter counter;
        vp->installEventFilter(&counter);
        for (QWidget* w : vp->findChildren<QWidget*>())
            w->installEventFilter(&counter);
        for (int k = 0; k < 4; ++k)
            QVERIFY(nextFrame());
        QCOMPARE(counter.paints, 0);
        // What is on screen is the frame.
        waitStill(300);
        const QImage frame = vp->grabFramebuffer();
        QCoreApplication::processEvents(); // the grabbed frame shown
        QTest::qWait(50);
        QCOMPARE(differingPixels(frame, onScreen(vp, vp->rect())), 0);
    }

    void probePanelShowsOverTheView() {
        openWindow("sphere");
        Viewport* vp = m_window->viewport();
        waitStill(300);
        auto* probe = vp->findChild<ProbeTool*>();
        QVERIFY(probe);
        act("actionProbe")->trigger();
        const QPoint at = vp->rect().center();
        QCursor::setPos(vp->mapToGlobal(at));
        QMouseEvent move(QEvent::MouseMove, at, vp->mapToGlobal(at), Qt::NoButton, Qt::NoButton,
                         Qt::NoModifier);
        QCoreApplication::sendEvent(vp, &move);
        QTRY_VERIFY(probe->lastProbe().has_value());
        auto* panel = vp->findChild<QFrame*>(QStringLiteral("probePanel"));
        QVERIFY(panel && panel->isVisible());
        QTest::qWait(100);
        // The panel as it paints itself is what the screen shows there, not the frame under it.
        const QImage drawn = panel->grab().toImage();
        const QImage shown = onScreen(panel, panel->rect());
        QVERIFY2(differingPixels(drawn, shown) < drawn.width() * drawn.height() / 50,
                 qPrintable(QString::number(differingPixels(drawn, shown))));
    }

    void measurementsAndRubberBandArePaintedOverTheFrame() {
        openWindow("sphere");
        Viewport* vp = m_window->viewport();
        waitStill(300);
        const QColor dimension(255, 200, 40);
        const QImage bare = vp->grabFramebuffer();
        const int before = pixelsNear(bare, dimension);
        act("actionMeasureDistance")->trigger();
        const QPoint c = vp->rect().center();
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, c + QPoint(-40, -10));
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, c + QPoint(40, 20));
        auto* probe = vp->findChild<ProbeTool*>();
        QCOMPARE(probe->measureTool()->measurements().size(), size_t(1));
        const QImage measured = vp->grabFramebuffer();
        QVERIFY2(pixelsNear(measured, dimension) > before + 40,
                 qPrintable(
                     QStringLiteral("%1 -> %2").arg(before).arg(pixelsNear(measured, dimension))));
        // Drawn over the frame on screen too, after the view came to rest.
        waitStill(300);
        QTest::qWait(50);
        QVERIFY(pixelsNear(onScreen(vp, vp->rect()), dimension) > before + 40);
        act("actionClearMeasurements")->trigger();
        act("actionMeasureDistance")->trigger(); // off: plain clicks select again

        // A rubber band from empty space (top right) is painted over the last frame while it
        // is dragged: no new frame, the band on screen, nothing else changed; gone on release.
        waitStill(300);
        const QPoint from(vp->width() - 150, 30), to(vp->width() - 40, 110);
        const QRect band = QRect(from, to).normalized();
        const QRect below(0, 150, vp->width(), 100);
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, from);
        const QImage still = vp->grabFramebuffer(); // the press's frame: no band yet
        QTest::qWait(50);
        const std::int64_t drawn = vp->framesDrawn();
        QTest::mouseMove(vp, to - QPoint(30, 30));
        QTest::mouseMove(vp, to);
        QTest::qWait(100);
        QCOMPARE(vp->framesDrawn(), drawn);
        QVERIFY(differingPixels(onScreen(vp, band), still.copy(band)) > band.width() * 2);
        QCOMPARE(differingPixels(onScreen(vp, below), still.copy(below)), 0);
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, to);
        waitStill(300);
        QCOMPARE(differingPixels(onScreen(vp, band), vp->grabFramebuffer().copy(band)), 0);
    }

    void inputOnTheNativeWindowIsTheViews() {
        // Where a platform hands the native window input despite WindowTransparentForInput,
        // the window's own events must drive the view: a control-point drag sent to the
        // window edits the document live and is one undo step.
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        QWindow* window = nativeWindow();
        QVERIFY(window);
        QCOMPARE(window->geometry().size(), vp->size());
        waitStill(300);
        const ControlPointRef ref = pointRef();
        const std::optional<QPointF> pixel = pickablePixel(ref);
        QVERIFY(pixel);
        const QPoint press = pixel->toPoint();
        const glm::dvec3 p0 = point(ref);

        QTest::mouseMove(window, press);
        QTest::mousePress(window, Qt::LeftButton, Qt::NoModifier, press);
        QVERIFY(vp->isDragging());
        QTest::mouseMove(window, press + QPoint(12, -8));
        QVERIFY(point(ref) != p0); // the step reached the document
        QCOMPARE(m_window->undoStack()->count(), 0);
        QTest::mouseMove(window, press + QPoint(30, -20));
        QTest::mouseRelease(window, Qt::LeftButton, Qt::NoModifier, press + QPoint(30, -20));
        QVERIFY(!vp->isDragging());
        QCOMPARE(m_window->undoStack()->count(), 1);
        const glm::dvec3 p1 = point(ref);
        QVERIFY(p1 != p0);
        // The point's pixel moved as far as the mouse did.
        const auto moved = vp->viewProjection().project(p1);
        QVERIFY(moved);
        QVERIFY2(std::hypot(moved->x() - (pixel->x() + 30), moved->y() - (pixel->y() - 20)) < 1e-3,
                 qPrintable(QStringLiteral("%1,%2").arg(moved->x()).arg(moved->y())));
        m_window->undoStack()->undo();
        QCOMPARE(point(ref), p0);
    }

    void dragStepsCopyWhatChanged() {
        // A drag step's partial frame is copied into the window's framebuffer where it redrew
        // and where the overlays were (the selected point's square moves with the drag, and a
        // mark at the top): the
        // rest is the last frame's already. What the view holds is still the whole frame.
        // Aliased full-size frames (a software rasteriser's previews while moving are
        // magnified into the whole framebuffer).
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        QVERIFY(vp->isNativeWindow() && vp->partialFrames());
        vp->setPreviewScale(1.0);
        vp->setSamples(1);
        // The surface and its net small in the view, as one face of a part.
        Camera camera = vp->cameraController().camera();
        camera.eye = camera.target + (camera.eye - camera.target) * 3.0;
        vp->setCamera(camera);
        // And a mark at the top edge in the dragged point's column: an overlay off the
        // rectangles, which only its bounds (the right way up) bring into the copy; no axis
        // indicator, whose corner would stretch the overlays' rectangle over most of the view.
        vp->setAxisIndicator(false);
        const ControlPointRef ref = pointRef();
        QObject owner;
        vp->addOverlay(&owner, [this, vp, ref](QPainter& p) {
            if (const auto at = vp->viewProjection().project(point(ref)))
                p.fillRect(QRectF(at->x() - 3, 6, 6, 6), Qt::yellow);
        });
        waitStill(300);
        const std::optional<QPointF> pixel = pickablePixel(ref);
        QVERIFY(pixel);
        const QPoint press = pixel->toPoint();
        QTest::mouseMove(vp, press);
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QVERIFY(vp->isDragging());
        const std::int64_t whole = std::int64_t(vp->lastFrameReport().drawnSize.width()) *
                                   vp->lastFrameReport().drawnSize.height();
        int copiedLess = 0;
        for (int k = 1; k <= 4; ++k) {
            const std::int64_t before = vp->framesDrawn();
            QTest::mouseMove(vp, press + QPoint(9 * k, -6 * k));
            QVERIFY(QTest::qWaitFor([&] { return vp->framesDrawn() > before; }, 5000));
            const FrameReport& r = vp->lastFrameReport();
            copiedLess += r.partial && r.presentedPixels > 0 && r.presentedPixels < whole / 2;
        }
        QVERIFY2(copiedLess >= 3, qPrintable(QString::number(copiedLess)));
        const QImage partial = vp->grabFramebuffer();
        QVERIFY(vp->lastFrameReport().partial);
        vp->setPartialFrames(false);
        const QImage straight = vp->grabFramebuffer();
        QVERIFY(!vp->lastFrameReport().partial);
        vp->setPartialFrames(true);
        QCOMPARE(differingPixels(partial, straight), 0);
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(36, -24));
    }

    void overlaysAreMeasuredOnlyForPartialCopies() {
        // The overlays are painted a second time, on a device that measures them, only where
        // the next frame may copy what changed alone: a frame drawn straight into the
        // framebuffer (the software rasteriser's progressive still frames) paints them once.
        openWindow("sphere");
        Viewport* vp = m_window->viewport();
        struct CountingTool : Tool {
            int paints = 0;
            bool press(QMouseEvent*) override { return false; }
            void paint(QPainter&) override { ++paints; }
        } tool;
        vp->setTool(&tool);
        waitStill(300);
        const auto paintsPerFrame = [&] {
            tool.paints = 0;
            const std::int64_t before = vp->framesDrawn();
            for (int k = 0; k < 3; ++k)
                if (!nextFrame())
                    return -1.0;
            return double(tool.paints) / double(vp->framesDrawn() - before);
        };
        QVERIFY(!vp->lastFrameReport().keptInHost);
        QCOMPARE(paintsPerFrame(), 1.0);
        // Aliased frames are kept and copied: measured, then painted.
        vp->setSamples(1);
        waitStill(300);
        QVERIFY(vp->lastFrameReport().keptInHost);
        QCOMPARE(paintsPerFrame(), 2.0);
        vp->setTool(nullptr);
    }

    void widgetFallbackDrawsTheSameFrame() {
        openWindow("sphere");
        QVERIFY(m_window->viewport()->isNativeWindow());
        waitStill(300);
        const QImage native = m_window->viewport()->grabFramebuffer();
        closeWindow();
        // Where the platform has no native child windows (or KNOTWORK_VIEW=widget).
        qputenv("KNOTWORK_VIEW", "widget");
        openWindow("sphere");
        Viewport* vp = m_window->viewport();
        QVERIFY(!vp->isNativeWindow());
        QVERIFY(!vp->findChild<QWidget*>(QStringLiteral("viewWindowContainer")));
        waitStill(300);
        QCOMPARE(differingPixels(vp->grabFramebuffer(), native), 0);
    }

    void unavailableRendererIsShownInTheView() {
        // CTest runs this alone on a context the renderer cannot use (MESA_GL_VERSION_OVERRIDE
        // =3.3, tests/ui/view_frames.cmake); the suite's own run has a 4.5 context.
        if (qEnvironmentVariableIsEmpty("MESA_GL_VERSION_OVERRIDE"))
            QSKIP("needs a context older than OpenGL 4.5 (MESA_GL_VERSION_OVERRIDE=3.3)");
        m_window = std::make_unique<MainWindow>();
        Viewport* vp = m_window->viewport();
        QSignalSpy errors(vp, &Viewport::renderError);
        m_window->resize(960, 640);
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        QTRY_VERIFY(!vp->glError());
        const QString why = vp->glError().message();
        QVERIFY2(why.startsWith(QStringLiteral("OpenGL 4.5 core is required, got ")),
                 qPrintable(why));
        QTRY_COMPARE(errors.size(), 1);
        QCOMPARE(errors.at(0).at(0).toString(), QStringLiteral("Renderer unavailable: ") + why);
        // The view says so where the frame would be, and draws no frame.
        const QImage shown = vp->grabFramebuffer();
        QCOMPARE(shown.pixelColor(4, 4), QColor(46, 48, 54));
        QCOMPARE(vp->framesDrawn(), std::int64_t(0));
    }

private:
    /// The view's native window (the one that shows its frames and asks for no input).
    QWindow* nativeWindow() const {
        for (QWindow* w : QGuiApplication::allWindows()) {
            if (w->surfaceType() != QSurface::OpenGLSurface ||
                !(w->flags() & Qt::WindowTransparentForInput))
                continue;
            for (QWindow* up = w->parent(); up; up = up->parent())
                if (up == m_window->windowHandle())
                    return w;
        }
        return nullptr;
    }
    /// The first surface's control point (1, 1).
    ControlPointRef pointRef() const {
        return {m_window->document()->scene().surfaces.front().id, 1, 1};
    }
    /// Where the view shows `ref`, when inside it and the nearest point there.
    std::optional<QPointF> pickablePixel(const ControlPointRef& ref) const {
        Viewport* vp = m_window->viewport();
        ControlPointPicker picker;
        picker.update(*m_window->document(), vp->viewProjection());
        const std::optional<QPointF> pixel = picker.pixelOf(ref);
        if (!pixel || !vp->rect().contains(pixel->toPoint()) ||
            !(picker.nearest(pixel->toPoint()) == ref))
            return std::nullopt;
        return pixel;
    }
    glm::dvec3 point(const ControlPointRef& ref) const {
        const Surface& s = m_window->document()->scene().surfaces.front();
        return s.geometry.points[size_t(s.geometry.index(ref.i, ref.j))];
    }
    /// Draws one frame and waits for it.
    bool nextFrame() {
        Viewport* vp = m_window->viewport();
        const std::int64_t before = vp->framesDrawn();
        vp->update();
        return QTest::qWaitFor([&] { return vp->framesDrawn() > before; }, 5000);
    }
    /// The screen's pixels of `rect` of `widget` (the X server's image, child windows in).
    QImage onScreen(QWidget* widget, QRect rect) const {
        const QPoint at = widget->mapTo(m_window.get(), rect.topLeft());
        return m_window->screen()
            ->grabWindow(m_window->winId(), at.x(), at.y(), rect.width(), rect.height())
            .toImage();
    }
    static int differingPixels(const QImage& a, const QImage& b) {
        return kwtest::differingPixels(a.convertToFormat(QImage::Format_RGB32),
                                       b.convertToFormat(QImage::Format_RGB32));
    }
};

QTEST_MAIN(TestViewSurface)
#include "tst_view_surface.moc"
