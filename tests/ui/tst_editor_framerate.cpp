// GUI test: the editor's frames while the view moves and after it stops, in the main window
// at its first-start size (most of the 1280 x 1024 test screen, as a user's first start).
//
// - stillFrameIsTheFullImage: on a software rasteriser an orbit's frames are previews
//   (Viewport::previewWhileMoving: fewer pixels, aliased, magnified) and the still frame after
//   the last move is the full anti-aliased image, the same bytes as the image of that view
//   drawn with previews off (the editor before previews existed); a drag's frames are previews
//   too, partial frames (the dragged face's rectangle redrawn), and its still frame is the
//   full image again.
// - probeReadsTheFrame: a probe hover over the still frame reads the pixel's surface and
//   (u, v) back from the frame (Renderer::pickInLastFrame) and draws nothing; the refined
//   point is on the pixel's ray.
// - profile (a measurement, printed, nothing timed is asserted): orbit and drag frames of
//   each model, per pass medians (Renderer::setPassProfiling: each pass ended by glFinish,
//   wall and process CPU), the paint, QPainter overlays and swap, and the frames per second
//   the status bar shows, with previews on (the editor) and off (the full frame, as before),
//   the drag with partial frames (the editor's) and with every frame whole (before).
//   Models: KW_FRAMERATE_FILES (paths, comma separated), else tests/data/hammer.iges;
//   KW_FRAMERATE_FRAMES frames per gesture (default 3: the suite's short run).
#include "cad_test_util.h"
#include "editor_test_util.h"
#include "model/nurbs/nurbs.h"
#include "render/frame_report.h"
#include "render/offscreen_renderer.h"
#include "render/pass_clock.h"
#include "ui/controlpointpicker.h"
#include "ui/probe_tool.h"

#include <QElapsedTimer>
#include <QFileInfo>
#include <QLabel>
#include <QSettings>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <algorithm>
#include <cstdlib>
#include <fstream>

using namespace kw;

namespace {

double median(std::vector<double> v) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

QString loadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return QString::fromStdString(a + " " + b + " " + c);
}

} // namespace

class TestEditorFramerate : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    }

private:
    /// A window at the first start's size (MainWindow::sizeFirstStart) showing `scene`.
    void openScene(Scene scene) {
        m_window = std::make_unique<MainWindow>();
        kwtest::scriptDialogs(*m_window, m_script);
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        QVERIFY(m_window->document()->resetScene(std::move(scene)));
        QVERIFY2(m_window->viewport()->glError(),
                 qPrintable(m_window->viewport()->glError().message()));
        waitStill();
    }
    /// Processes events until the view has drawn a frame after `before` frames.
    bool nextFrame(std::int64_t before) {
        QElapsedTimer t;
        t.start();
        while (m_window->viewport()->framesDrawn() == before && t.elapsed() < 10000)
            QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents, 5);
        // The frame's composition and swap (frameSwapped) come in the same repaint.
        QCoreApplication::processEvents();
        return m_window->viewport()->framesDrawn() > before;
    }
    void move(QPoint at, Qt::MouseButtons buttons) {
        Viewport* vp = m_window->viewport();
        QMouseEvent e(QEvent::MouseMove, at, vp->mapToGlobal(at), Qt::NoButton, buttons,
                      Qt::NoModifier);
        QCoreApplication::sendEvent(vp, &e);
    }
    /// The largest face (most control points) with a pickable control point away from the
    /// view's border, selected, and that point with its pixel; invalid when none has one.
    std::pair<ControlPointRef, QPoint> dragPoint() {
        const Scene& s = m_window->document()->scene();
        std::vector<const Surface*> faces;
        for (const Surface& f : s.surfaces)
            faces.push_back(&f);
        std::stable_sort(faces.begin(), faces.end(), [](const Surface* a, const Surface* b) {
            return a->geometry.points.size() > b->geometry.points.size();
        });
        for (const Surface* face : faces)
            if (const auto found = dragPointOf(face); found.first.surface.isValid())
                return found;
        return {};
    }
    std::pair<ControlPointRef, QPoint> dragPointOf(const Surface* face) {
        Viewport* vp = m_window->viewport();
        vp->selectClickedSurface(face->id, false);
        QCoreApplication::processEvents();
        ControlPointPicker picker;
        const std::vector<SurfaceId> only{face->id};
        picker.update(*m_window->document(), vp->viewProjection(), &only);
        const NurbsSurface& g = face->geometry;
        std::vector<std::pair<int, int>> order;
        for (int j = 0; j < g.countV; ++j)
            for (int i = 0; i < g.countU; ++i)
                order.emplace_back(i, j);
        // The middle of the net first.
        std::sort(order.begin(), order.end(), [&](auto a, auto b) {
            const auto d = [&](std::pair<int, int> p) {
                return std::abs(2 * p.first - g.countU) + std::abs(2 * p.second - g.countV);
            };
            return d(a) < d(b);
        });
        for (auto [i, j] : order) {
            const ControlPointRef ref{face->id, i, j};
            const std::optional<QPointF> px = picker.pixelOf(ref);
            if (!px || !vp->rect().adjusted(40, 40, -40, -40).contains(px->toPoint()))
                continue;
            if (vp->controlPointAt(px->toPoint()) == ref)
                return {ref, px->toPoint()};
        }
        return {};
    }

    struct Run {
        std::vector<double> passWall[PassTimes::kCount], passCpu[PassTimes::kCount];
        std::vector<double> paint, painter, swap, render, frameWall, frameCpu, fps;
        std::vector<double> scale;
        int frames = 0;
        int partial = 0;      ///< frames drawn partial (FrameReport::partial)
        double seconds = 0.0; ///< from the first measured frame's move to the last frame
    };
    /// `frames` frames of an orbit (middle drag) or of a control-point drag, measured.
    void gesture(bool drag, int frames, Run& run) {
        Viewport* vp = m_window->viewport();
        QPoint at = vp->rect().center();
        Qt::MouseButton button = Qt::MiddleButton;
        if (drag) {
            const auto [ref, press] = dragPoint();
            QVERIFY2(ref.surface.isValid(), "no control point to drag");
            waitStill();
            at = press;
            button = Qt::LeftButton;
        }
        QMetaObject::Connection fps =
            connect(vp, &Viewport::framesPerSecond, this,
                    [&run](double f, const FrameReport&) { run.fps.push_back(f); });
        QTest::mousePress(vp, button, Qt::NoModifier, at);
        QCoreApplication::processEvents();
        QElapsedTimer wall, whole;
        for (int k = 0; k < frames + 2; ++k) {
            if (k == 2)
                whole.start();
            const std::int64_t before = vp->framesDrawn();
            wall.start();
            const double cpu0 = processCpuMs();
            at += drag ? QPoint(k % 2 ? 2 : -1, 1) : QPoint(6, k % 2 ? 2 : -2);
            move(at, button);
            QVERIFY(nextFrame(before));
            if (k < 2)
                continue; // the press's frame and the first step's uploads
            const FrameReport& r = vp->lastFrameReport();
            const Viewport::FrameTiming& t = vp->lastFrameTiming();
            for (int p = 0; p < PassTimes::kCount; ++p) {
                run.passWall[p].push_back(r.passes.wallMs[p]);
                run.passCpu[p].push_back(r.passes.cpuMs[p]);
            }
            run.render.push_back(t.renderMs);
            run.painter.push_back(t.painterMs);
            run.swap.push_back(t.swapMs);
            run.frameWall.push_back(double(wall.nsecsElapsed()) * 1e-6);
            run.frameCpu.push_back(processCpuMs() - cpu0);
            run.scale.push_back(double(r.drawnSize.width()) / vp->width() /
                                vp->devicePixelRatioF());
            run.partial += r.partial;
            ++run.frames;
        }
        run.seconds = double(whole.nsecsElapsed()) * 1e-9;
        QTest::mouseRelease(vp, button, Qt::NoModifier, at);
        disconnect(fps);
    }
    void print(const QString& model, const char* what, const Run& run) {
        Viewport* vp = m_window->viewport();
        // The status bar's rate once a second; the first also counts the rest before the press.
        const std::vector<double> fps(run.fps.size() > 1 ? run.fps.begin() + 1 : run.fps.begin(),
                                      run.fps.end());
        QString passes;
        for (int p = 0; p < PassTimes::kCount; ++p) {
            const double w = median(run.passWall[p]);
            if (w < 0.05)
                continue;
            passes += QStringLiteral(" %1 %2 (%3)")
                          .arg(QLatin1String(PassTimes::name(p)))
                          .arg(w, 0, 'f', 1)
                          .arg(median(run.passCpu[p]), 0, 'f', 1);
        }
        qInfo("FRAMERATE %s %s view %dx%d drawn %.2f: %.1f FPS (%d frames in %.2f s, %d "
              "partial), status bar %.1f FPS, frame %.1f ms (process CPU %.1f): render %.1f, "
              "painter %.1f, swap %.1f;%s%s; load %s",
              qPrintable(model), what, vp->width(), vp->height(), median(run.scale),
              run.frames / std::max(1e-6, run.seconds), run.frames, run.seconds, run.partial,
              median(fps), median(run.frameWall), median(run.frameCpu), median(run.render),
              median(run.painter), median(run.swap),
              passes.isEmpty() ? "" : " passes wall (process CPU) ms:", qPrintable(passes),
              qPrintable(loadAverage()));
    }

private Q_SLOTS:
    void initTestCase() {
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/framerate-config"));
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkFramerateTest"));
        QSettings().clear();
    }
    void cleanup() { closeWindow(); }

    void stillFrameIsTheFullImage() {
        const std::optional<Scene> hammer = kwtest::importedPart(QStringLiteral("hammer.iges"));
        QVERIFY(hammer);
        openScene(*hammer);
        Viewport* vp = m_window->viewport();
        QVERIFY2(vp->previewWhileMoving(), "the test screen's OpenGL is not llvmpipe");
        // An orbit: its frames are previews.
        const QPoint c = vp->rect().center();
        QTest::mousePress(vp, Qt::MiddleButton, Qt::NoModifier, c);
        for (int k = 1; k <= 4; ++k) {
            const std::int64_t before = vp->framesDrawn();
            move(c + QPoint(9 * k, 4 * k), Qt::MiddleButton);
            QVERIFY(nextFrame(before));
            const FrameReport& r = vp->lastFrameReport();
            QVERIFY(vp->lastFrameTiming().moving);
            QCOMPARE(r.samplesInImage, 1);
            QVERIFY2(
                r.drawnSize.width() * 3 < vp->width() * 2,
                qPrintable(QStringLiteral("%1 of %2").arg(r.drawnSize.width()).arg(vp->width())));
        }
        QTest::mouseRelease(vp, Qt::MiddleButton, Qt::NoModifier, c + QPoint(36, 16));
        waitStill();
        // The still frame: the full image with all its samples.
        const FrameReport& still = vp->lastFrameReport();
        QVERIFY(!vp->lastFrameTiming().moving);
        QCOMPARE(still.samplesInImage, vp->samples());
        QVERIFY(still.samplesInImage > 1);
        QCOMPARE(still.drawnSize, QSize(vp->width(), vp->height()) * vp->devicePixelRatioF());
        const QImage afterMotion = vp->grabFramebuffer();
        // The same view drawn afresh with previews off, as the editor drew it before them.
        const Camera camera = vp->cameraController().camera();
        closeWindow();
        openScene(*hammer);
        vp = m_window->viewport();
        vp->setPreviewScale(1.0);
        vp->setCamera(camera);
        waitStill();
        QCOMPARE(vp->lastFrameReport().samplesInImage, vp->samples());
        const QImage fresh = vp->grabFramebuffer();
        QCOMPARE(afterMotion.size(), fresh.size());
        QVERIFY2(afterMotion == fresh,
                 "the still frame after an orbit differs from the view's image");

        // A drag: previews while the point moves, the full image once it rests.
        openScene(*hammer);
        vp = m_window->viewport();
        Run run;
        gesture(true, 3, run);
        QCOMPARE(run.frames, 3);
        QVERIFY(*std::max_element(run.scale.begin(), run.scale.end()) < 0.6);
        // Each step after the first redraws the dragged face's rectangle only.
        QCOMPARE(run.partial, 3);
        waitStill();
        QCOMPARE(vp->lastFrameReport().samplesInImage, vp->samples());
        QCOMPARE(vp->lastFrameReport().drawnSize,
                 QSize(vp->width(), vp->height()) * vp->devicePixelRatioF());
    }

    void probeReadsTheFrame() {
        const std::optional<Scene> hammer = kwtest::importedPart(QStringLiteral("hammer.iges"));
        QVERIFY(hammer);
        openScene(*hammer);
        Viewport* vp = m_window->viewport();
        act("actionProbe")->trigger();
        waitStill();
        ProbeTool* probe = vp->findChild<ProbeTool*>();
        QVERIFY(probe);
        const std::int64_t drawn = vp->framesDrawn();
        const QRect r = vp->rect();
        int read = 0, hits = 0;
        std::vector<double> cpu;
        for (int k = 0; k < 400; ++k) {
            const QPoint at(r.left() + (k % 20) * r.width() / 20 + 7,
                            r.top() + (k / 20) * r.height() / 20 + 5);
            const Renderer::FramePick shown = vp->pickFromFrame(at);
            move(at, Qt::NoButton);
            if (!probe->lastProbe())
                continue;
            ++hits;
            cpu.push_back(probe->lastUpdateCpuMs());
            if (!shown.known)
                continue;
            ++read;
            // The frame's surface, refined onto the pixel's ray: what the GL pick finds.
            const std::optional<PickHit> drawnPick = vp->pickByDrawing(at);
            QVERIFY(drawnPick);
            QVERIFY(shown.hit);
            QCOMPARE(shown.hit->surface, drawnPick->surface);
            QCOMPARE(probe->lastProbe()->surface, drawnPick->surface);
            QVERIFY2(probe->lastProbe()->rayDistance < 1e-9,
                     qPrintable(QString::number(probe->lastProbe()->rayDistance)));
        }
        QCOMPARE(vp->framesDrawn(), drawn); // no hover drew a frame
        QVERIFY2(hits >= 20, qPrintable(QString::number(hits)));
        QVERIFY2(read * 10 >= hits * 9, qPrintable(QStringLiteral("%1 of %2").arg(read).arg(hits)));
        qInfo("probe update from the frame: median %.3f ms thread CPU over %d hovers (%d read "
              "from the frame), load %s",
              median(cpu), hits, read, qPrintable(loadAverage()));
    }

    void profile_data() {
        QTest::addColumn<QString>("path");
        QStringList files =
            qEnvironmentVariable("KW_FRAMERATE_FILES").split(QLatin1Char(','), Qt::SkipEmptyParts);
        if (files.isEmpty()) // in the suite: a short run, so that the measurement keeps working
            files << QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges");
        for (const QString& f : files)
            QTest::newRow(qPrintable(QFileInfo(f).fileName())) << f;
    }
    void profile() {
        QFETCH(QString, path);
        Expected<ImportResult> imported = importFile(path);
        QVERIFY2(imported, qPrintable(imported.message()));
        const int n = std::max(3, qEnvironmentVariableIntValue("KW_FRAMERATE_FRAMES"));
        const QString model = QStringLiteral("%1 (%2 faces)")
                                  .arg(QFileInfo(path).fileName())
                                  .arg(imported->scene.surfaces.size());
        for (double scale : {1.0, Viewport::kPreviewScale}) {
            openScene(imported->scene);
            Viewport* vp = m_window->viewport();
            vp->setPreviewScale(scale);
            // First as the editor runs, then each pass ended by glFinish (slower: no overlap).
            // A drag twice: with partial frames (the editor's) and every frame whole (before).
            for (bool profiled : {false, true}) {
                vp->setPassProfiling(profiled);
                for (int gestureKind : {0, 1, 2}) {
                    const bool drag = gestureKind > 0;
                    vp->setPartialFrames(gestureKind != 2);
                    Run run;
                    gesture(drag, n, run);
                    const QString what = QStringLiteral("%1 %2%3%4")
                                             .arg(drag ? "drag" : "orbit")
                                             .arg(scale < 1.0 ? "preview" : "full")
                                             .arg(gestureKind == 2 ? " whole frames" : "")
                                             .arg(profiled ? " profiled" : "");
                    print(model, qPrintable(what), run);
                    waitStill();
                }
                vp->setPartialFrames(true);
            }
            closeWindow();
        }
    }
};

QTEST_MAIN(TestEditorFramerate)
#include "tst_editor_framerate.moc"
