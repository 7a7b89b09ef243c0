// Editor GUI tests under Xvfb: open, drag control points in the viewport (view plane and axis),
// undo, partition slider, trim-point drag in the UV panel, File actions, errors, responsiveness.
#include "editor_test_util.h"
#include "model/io/knotfile.h"
#include "render/gpu_layout.h"
#include "render/offscreen_renderer.h"
#include "ui/edit/commands.h"
#include "ui/lightspanel.h"
#include "ui/propertypanel.h"
#include "ui/uvpanel.h"

#include <QAction>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QMenu>
#include <QMimeData>
#include <QPushButton>
#include <QSettings>
#include <QSlider>
#include <QSpinBox>
#include <QUndoStack>
#include <QWheelEvent>
#include <algorithm>

using namespace kw;
using namespace kwtest;

class TestEditor : public EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        // Before QApplication: GL 4.5 core for every context, settings in the build tree.
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/editor-config"));
    }

private:
    const NurbsSurface& geometry(int surfaceIndex = 0) const {
        return m_window->document()->scene().surfaces[size_t(surfaceIndex)].geometry;
    }
    /// A control point of the first surface whose projection the picker finds at its own
    /// rounded pixel (not hidden by a neighbour), and that pixel.
    std::pair<ControlPointRef, QPoint> pickablePoint() const {
        Viewport* vp = m_window->viewport();
        const ViewProjection view = vp->viewProjection();
        ControlPointPicker picker;
        picker.update(*m_window->document(), view);
        const Surface& s = m_window->document()->scene().surfaces.front();
        for (int j = 1; j + 1 < s.geometry.countV; ++j)
            for (int i = 1; i + 1 < s.geometry.countU; ++i) {
                const ControlPointRef ref{s.id, i, j};
                const auto px = picker.pixelOf(ref);
                if (!px || !vp->rect().adjusted(60, 60, -60, -60).contains(px->toPoint()))
                    continue;
                const QPoint at = px->toPoint();
                if (picker.nearest(at) == ref)
                    return {ref, at};
            }
        return {};
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkTest"));
        QSettings().clear();
    }
    void cleanup() { closeWindow(); }

    void opensSampleAndShowsIt() {
        openWindow("bicubic");
        QCOMPARE(m_window->document()->scene().surfaces.size(), size_t(1));
        QCOMPARE(m_window->selection()->currentSurface(), SurfaceId{1});
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("bicubic.knot")));
        QVERIFY(!m_window->isWindowModified());
        QCOMPARE(m_window->recentFiles().value(0), samplePath("bicubic"));
        // The exact surface is drawn: the frame is not just the background.
        const QImage frame = m_window->viewport()->grabFramebuffer();
        const QRgb background = frame.pixel(2, 2);
        int covered = 0;
        for (int y = 0; y < frame.height(); y += 4)
            for (int x = 0; x < frame.width(); x += 4)
                covered += frame.pixel(x, y) != background;
        QVERIFY2(covered > 200, qPrintable(QString::number(covered)));
        // Picked control points are marked in the view.
        auto marked = [](const QImage& img) {
            int n = 0;
            for (int y = 0; y < img.height(); ++y)
                for (int x = 0; x < img.width(); ++x) {
                    const QRgb c = img.pixel(x, y);
                    n += qRed(c) > 200 && qGreen(c) < 120 && qBlue(c) < 90;
                }
            return n;
        };
        QCOMPARE(marked(frame), 0);
        m_window->action(QStringLiteral("actionSelectAll"))->trigger();
        QCOMPARE(m_window->selection()->controlPoints().size(), size_t(30));
        const int n = marked(m_window->viewport()->grabFramebuffer());
        QVERIFY2(n > 30 * 8, qPrintable(QString::number(n)));
    }

    void dragMovesPointInViewPlaneAndUndoRestores() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const auto [ref, press] = pickablePoint();
        QVERIFY(ref.surface.isValid());
        const NurbsSurface before = geometry();
        const int index = before.index(ref.i, ref.j);
        const glm::dvec3 p0 = before.points[size_t(index)];
        const ViewProjection view = vp->viewProjection();
        const QImage frameBefore = vp->grabFramebuffer();

        const QPoint move(37, -23);
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QVERIFY(vp->isDragging());
        QTest::mouseMove(vp, press + QPoint(12, -8));
        // The surface follows live: the document already holds a moved point.
        QVERIFY(geometry().points[size_t(index)] != p0);
        QCOMPARE(m_window->undoStack()->count(), 0);
        QTest::mouseMove(vp, press + move);
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + move);
        QVERIFY(!vp->isDragging());

        // Moved in the view plane: same depth, and its projection moved with the mouse.
        const glm::dvec3 p1 = geometry().points[size_t(index)];
        const double scale = glm::length(p0 - view.eye());
        QVERIFY2(std::abs(view.depth(p1) - view.depth(p0)) < 1e-9 * scale,
                 qPrintable(QString::number(view.depth(p1) - view.depth(p0))));
        const QPointF expected = *view.project(p0) + QPointF(move);
        const QPointF got = *view.project(p1);
        QVERIFY2(std::hypot(got.x() - expected.x(), got.y() - expected.y()) < 1e-6,
                 qPrintable(QStringLiteral("%1,%2 vs %3,%4")
                                .arg(got.x())
                                .arg(got.y())
                                .arg(expected.x())
                                .arg(expected.y())));
        QVERIFY(glm::length(p1 - p0) > 1e-3 * scale);
        // Only that point moved.
        for (size_t k = 0; k < before.points.size(); ++k)
            if (int(k) != index)
                QCOMPARE(geometry().points[k], before.points[k]);
        // The rendered frame changed.
        QTest::qWait(30);
        const int changed = differingPixels(frameBefore, vp->grabFramebuffer());
        QVERIFY2(changed > 100, qPrintable(QString::number(changed)));

        // One drag, one undo step; undo restores exactly, redo re-applies.
        QUndoStack* stack = m_window->undoStack();
        QCOMPARE(stack->count(), 1);
        QCOMPARE(stack->undoText(), QStringLiteral("Move control point"));
        QVERIFY(m_window->action(QStringLiteral("actionUndo"))
                    ->text()
                    .contains(QStringLiteral("Move control point")));
        QVERIFY(m_window->isWindowModified());
        stack->undo();
        QVERIFY(geometry() == before);
        QVERIFY(!m_window->isWindowModified());
        stack->redo();
        QCOMPARE(geometry().points[size_t(index)], p1);
    }

    void axisKeyConstrainsDrag() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const auto [ref, press] = pickablePoint();
        QVERIFY(ref.surface.isValid());
        const int index = geometry().index(ref.i, ref.j);
        const glm::dvec3 p0 = geometry().points[size_t(index)];
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QTest::keyPress(vp, Qt::Key_X);
        QCOMPARE(vp->axisConstraint(), 0);
        QTest::mouseMove(vp, press + QPoint(40, 15));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(40, 15));
        QTest::keyRelease(vp, Qt::Key_X);
        QCOMPARE(vp->axisConstraint(), -1);
        const glm::dvec3 p1 = geometry().points[size_t(index)];
        QVERIFY(std::abs(p1.x - p0.x) > 1e-3);
        QCOMPARE(p1.y, p0.y);
        QCOMPARE(p1.z, p0.z);
        QCOMPARE(m_window->undoStack()->count(), 1);
    }

    void shiftClickAddsAndRubberBandSelects() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        ControlPointPicker picker;
        picker.update(*m_window->document(), vp->viewProjection());
        const auto [first, at] = pickablePoint();
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, at);
        QCOMPARE(m_window->selection()->controlPoints(), std::vector<ControlPointRef>{first});
        // Shift-click on another pickable point adds it.
        std::optional<ControlPointRef> second;
        QPoint at2;
        for (const auto& p : picker.projected())
            if (p.ref != first && vp->rect().contains(p.pixel.toPoint()) &&
                picker.nearest(p.pixel.toPoint()) == p.ref) {
                second = p.ref;
                at2 = p.pixel.toPoint();
                break;
            }
        QVERIFY(second);
        QTest::mouseClick(vp, Qt::LeftButton, Qt::ShiftModifier, at2);
        QCOMPARE(m_window->selection()->controlPoints().size(), size_t(2));
        // A rubber band over the whole view selects every visible point.
        const QPoint a(2, 2), b(vp->width() - 3, vp->height() - 3);
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, a);
        QTest::mouseMove(vp, b);
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, b);
        QCOMPARE(m_window->selection()->controlPoints(), picker.inRect(QRectF(a, b)));
        QVERIFY(m_window->selection()->controlPoints().size() > 2);
        QCOMPARE(m_window->undoStack()->count(), 0);
    }

    void escapeCancelsDrag() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const auto [ref, press] = pickablePoint();
        const NurbsSurface before = geometry();
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QTest::mouseMove(vp, press + QPoint(25, 25));
        QVERIFY(!(geometry() == before));
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(!vp->isDragging());
        QVERIFY(geometry() == before);
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(25, 25));
        QVERIFY(geometry() == before);
        QCOMPARE(m_window->undoStack()->count(), 0);
    }

    void cameraGesturesAndViews() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        auto distance = [vp] {
            const Camera& c = vp->cameraController().camera();
            return glm::length(c.eye - c.target);
        };
        const Camera start = vp->cameraController().camera();
        const double d0 = distance();
        // Middle drag orbits about the target (distance kept), the document is untouched.
        const QPoint c = vp->rect().center();
        QTest::mousePress(vp, Qt::MiddleButton, Qt::NoModifier, c);
        QTest::mouseMove(vp, c + QPoint(50, 10));
        QTest::mouseRelease(vp, Qt::MiddleButton, Qt::NoModifier, c + QPoint(50, 10));
        QVERIFY(glm::length(vp->cameraController().camera().eye - start.eye) > 1e-3);
        QVERIFY(std::abs(distance() - d0) < 1e-9 * d0);
        QCOMPARE(vp->cameraController().camera().target, start.target);
        // Right drag pans: eye and target move together.
        QTest::mousePress(vp, Qt::RightButton, Qt::NoModifier, c);
        QTest::mouseMove(vp, c + QPoint(-30, 20));
        QTest::mouseRelease(vp, Qt::RightButton, Qt::NoModifier, c + QPoint(-30, 20));
        QVERIFY(glm::length(vp->cameraController().camera().target - start.target) > 1e-6);
        QVERIFY(std::abs(distance() - d0) < 1e-9 * d0);
        // The wheel zooms in.
        QWheelEvent wheel(QPointF(c), vp->mapToGlobal(QPointF(c)), QPoint(), QPoint(0, 120),
                          Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
        QCoreApplication::sendEvent(vp, &wheel);
        QVERIFY(std::abs(distance() - d0 * CameraController::kZoomPerStep) < 1e-9 * d0);
        // Standard views and fit.
        m_window->action(QStringLiteral("actionViewTop"))->trigger();
        const Camera top = vp->cameraController().camera();
        QVERIFY(glm::length(glm::normalize(top.target - top.eye) - glm::dvec3(0, 0, -1)) < 1e-12);
        m_window->action(QStringLiteral("actionFit"))->trigger();
        ControlPointPicker picker;
        picker.update(*m_window->document(), vp->viewProjection());
        QCOMPARE(picker.inRect(vp->rect()).size(), size_t(30)); // every point in view
        QCOMPARE(m_window->undoStack()->count(), 0);
    }

    void knotActionsAndPointFields() {
        openWindow("bicubic");
        PropertyPanel* panel = m_window->propertyPanel();
        const NurbsSurface before = geometry();
        auto* value = panel->findChild<QDoubleSpinBox*>(QStringLiteral("knotValue"));
        QVERIFY(value);
        value->setValue(0.6);
        QTest::mouseClick(panel->findChild<QPushButton*>(QStringLiteral("insertKnot")),
                          Qt::LeftButton);
        QCOMPARE(geometry().countU, before.countU + 1);
        QVERIFY(std::count(geometry().knotsU.begin(), geometry().knotsU.end(), 0.6) == 1);
        QTest::mouseClick(panel->findChild<QPushButton*>(QStringLiteral("elevateDegree")),
                          Qt::LeftButton);
        QCOMPARE(geometry().degreeU, before.degreeU + 1);
        QCOMPARE(m_window->undoStack()->count(), 2);
        QCOMPARE(m_window->undoStack()->undoText(),
                 QStringLiteral("Elevate degree u to %1").arg(before.degreeU + 1));
        m_window->undoStack()->undo();
        m_window->undoStack()->undo();
        QVERIFY(geometry() == before);

        // The picked point's fields edit it; consecutive edits merge into one step.
        const auto [ref, at] = pickablePoint();
        QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier, at);
        auto* x = panel->findChild<QDoubleSpinBox*>(QStringLiteral("pointX"));
        auto* w = panel->findChild<QDoubleSpinBox*>(QStringLiteral("pointWeight"));
        const int index = before.index(ref.i, ref.j);
        QCOMPARE(x->value(), std::round(before.points[size_t(index)].x * 1e4) / 1e4);
        x->setValue(0.125);
        x->setValue(0.25);
        QCOMPARE(geometry().points[size_t(index)].x, 0.25);
        QCOMPARE(m_window->undoStack()->count(), 1);
        w->setValue(2.5);
        QCOMPARE(geometry().weights[size_t(index)], 2.5);
        QCOMPARE(m_window->undoStack()->count(), 2);
        m_window->undoStack()->undo();
        m_window->undoStack()->undo();
        QVERIFY(geometry() == before);
    }

    // An imported face's domain can be narrow and far from zero (a Pump_Nut face has v in
    // [4.6166286, 4.6188022]): the knot field resolves it, and the knot goes in where the field
    // says. With four fixed decimals a typed value moved by up to 2% of such a domain.
    void knotFieldResolvesNarrowDomains() {
        openWindow("bicubic");
        PropertyPanel* panel = m_window->propertyPanel();
        const SurfaceId id = m_window->document()->scene().surfaces.front().id;
        const NurbsSurface before = geometry();
        const Interval d0 = surfaceDomainU(before);
        const double a = 4.6166285687407065, width = 0.0021735827027216;
        std::vector<double> knots = before.knotsU;
        for (double& k : knots)
            k = a + (k - d0.first) / (d0.last - d0.first) * width;
        QVERIFY(pushCommand(m_window->undoStack(),
                            SetKnotVector::create(m_window->document(), id, Direction::U, knots)));
        auto* value = panel->findChild<QDoubleSpinBox*>(QStringLiteral("knotValue"));
        QVERIFY(value);
        const double x = a + 0.3717 * width;
        value->setValue(x);
        QVERIFY2(std::abs(value->value() - x) <= 1e-4 * width, qPrintable(value->text()));
        const double shown = value->value();
        QTest::mouseClick(panel->findChild<QPushButton*>(QStringLiteral("insertKnot")),
                          Qt::LeftButton);
        QCOMPARE(geometry().countU, before.countU + 1);
        QCOMPARE(std::count(geometry().knotsU.begin(), geometry().knotsU.end(), shown), 1);
        m_window->undoStack()->undo();
        m_window->undoStack()->undo();
        QVERIFY(geometry() == before);
    }

    void lightsPanelEditsLights() {
        openWindow("bicubic");
        LightsPanel* panel = m_window->lightsPanel();
        const std::vector<Light> before = m_window->document()->scene().lights;
        panel->countBox()->setValue(int(before.size()) + 1);
        QCOMPARE(m_window->document()->scene().lights.size(), before.size() + 1);
        QCOMPARE(m_window->undoStack()->count(), 1);
        m_window->undoStack()->undo();
        QVERIFY(m_window->document()->scene().lights == before);
        QCOMPARE(panel->countBox()->value(), int(before.size()));
    }

    void partitionSliderIsOneUndoStep() {
        openWindow("bicubic");
        QSlider* slider = m_window->propertyPanel()->partitionSliderU();
        const int before = m_window->document()->scene().surfaces[0].partitionsU;
        QCOMPARE(slider->value(), before);
        const QImage frameBefore = m_window->viewport()->grabFramebuffer();
        slider->setFocus();
        for (int k = 0; k < 5; ++k)
            QTest::keyClick(slider, Qt::Key_Right);
        QCOMPARE(m_window->document()->scene().surfaces[0].partitionsU, before + 5);
        QCOMPARE(m_window->undoStack()->count(), 1);
        // The tessellated baseline shows the partitions: its frame changes with them.
        m_window->action(QStringLiteral("actionShadeTessellated"))->trigger();
        const QImage finer = m_window->viewport()->grabFramebuffer();
        m_window->undoStack()->undo();
        QCOMPARE(m_window->document()->scene().surfaces[0].partitionsU, before);
        QCOMPARE(slider->value(), before);
        QVERIFY(differingPixels(finer, m_window->viewport()->grabFramebuffer()) > 0);
        Q_UNUSED(frameBefore);
    }

    void trimDragChangesTrimAndMask() {
        openWindow("trimmed_plate");
        UvPanel* uv = m_window->uvPanel();
        const Surface& s = m_window->document()->scene().surfaces[0];
        QCOMPARE(uv->surface(), s.id);
        // The star: one closed degree-1 curve; its first point is also its last.
        const TrimLoop star = s.trims.back();
        QCOMPARE(star.curves.size(), size_t(1));
        const std::vector<TrimLoop> trimsBefore = s.trims;
        const std::vector<glm::dvec2>& pts = star.curves[0].points;
        QCOMPARE(pts.front(), pts.back());
        const QImage maskBefore = uv->mask();
        const double keptBefore = keptFraction(maskBefore);

        const QPoint press = uv->toWidget(pts.front()).toPoint();
        const TrimPointRef first{s.id, star.id, 0, 0};
        QCOMPARE(uv->trimPointAt(press), std::optional<TrimPointRef>(first));
        const QPoint release = press + QPoint(-30, 20);
        QTest::mousePress(uv, Qt::LeftButton, Qt::NoModifier, press);
        const std::int64_t frames = m_window->viewport()->framesDrawn();
        QTest::mouseMove(uv, press + QPoint(-10, 5));
        // Live: the document and the mask change while dragging, and the 3D view redraws.
        QVERIFY(m_window->document()->scene().surfaces[0].trims != trimsBefore);
        QVERIFY(differingPixels(maskBefore, uv->mask()) > 0);
        QTRY_VERIFY(m_window->viewport()->framesDrawn() > frames);
        QTest::mouseMove(uv, release);
        QTest::mouseRelease(uv, Qt::LeftButton, Qt::NoModifier, release);

        const auto& moved = m_window->document()->scene().surfaces[0].trims.back().curves[0].points;
        const glm::dvec2 expected = pts.front() + (uv->toUv(release) - uv->toUv(press));
        QVERIFY(glm::length(moved.front() - expected) < 1e-12);
        QCOMPARE(moved.back(), moved.front()); // the loop stays closed
        const QImage maskAfter = uv->mask();
        QVERIFY(differingPixels(maskBefore, maskAfter) > 50);
        QVERIFY(keptFraction(maskAfter) != keptBefore);
        QCOMPARE(m_window->undoStack()->count(), 1);
        m_window->undoStack()->undo();
        QVERIFY(m_window->document()->scene().surfaces[0].trims == trimsBefore);
        QCOMPARE(differingPixels(maskBefore, uv->mask()), 0);
    }

    void saveAndReopenRoundTrips() {
        openWindow("trimmed_plate");
        const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/editor_roundtrip.knot");
        QFile::remove(path);
        // An edit, then Save As through the File action.
        QVERIFY(pushCommand(m_window->undoStack(),
                            SetPartitions::create(m_window->document(), SurfaceId{1}, 7, 9)));
        QVERIFY(m_window->isWindowModified());
        const Scene saved = m_window->document()->scene();
        m_script.savePath = path;
        m_window->action(QStringLiteral("actionSaveAs"))->trigger();
        QVERIFY(QFile::exists(path));
        QVERIFY(!m_window->isWindowModified());
        QCOMPARE(m_window->filePath(), path);
        QVERIFY(m_window->windowTitle().startsWith(QStringLiteral("editor_roundtrip.knot")));

        m_window->action(QStringLiteral("actionNew"))->trigger();
        QVERIFY(m_window->document()->scene().surfaces.empty());
        QCOMPARE(m_script.asks, 0); // nothing unsaved

        m_script.openPath = path;
        m_window->action(QStringLiteral("actionOpen"))->trigger();
        QCOMPARE(m_script.opens, 1);
        const Scene& reopened = m_window->document()->scene();
        QVERIFY(reopened.surfaces == saved.surfaces);
        QVERIFY(reopened.lights == saved.lights);
        QCOMPARE(reopened.surfaces[0].partitionsU, 7);
        QCOMPARE(m_window->recentFiles().value(0), path);
        QVERIFY(m_script.errors.isEmpty());

        // Export Image writes the viewport's frame.
        const QString png = QStringLiteral(KW_TEST_OUTPUT_DIR "/editor_export.png");
        QFile::remove(png);
        m_script.savePath = png;
        m_window->action(QStringLiteral("actionExportImage"))->trigger();
        const QImage exported(png);
        QCOMPARE(exported.size(), m_window->viewport()->size());
        QVERIFY(m_script.errors.isEmpty());
    }

    void droppingKnotFileOpensIt() {
        openWindow("bicubic");
        QMimeData mime;
        mime.setUrls({QUrl::fromLocalFile(samplePath("torus"))});
        QDragEnterEvent enter(QPoint(50, 50), Qt::CopyAction, &mime, Qt::LeftButton,
                              Qt::NoModifier);
        QCoreApplication::sendEvent(m_window.get(), &enter);
        QVERIFY(enter.isAccepted());
        QDropEvent drop(QPointF(50, 50), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
        QCoreApplication::sendEvent(m_window.get(), &drop);
        QCOMPARE(m_window->filePath(), samplePath("torus"));
        // Other files are refused.
        QMimeData other;
        other.setUrls({QUrl::fromLocalFile(QStringLiteral(KW_SOURCE_DIR "/README.md"))});
        QDragEnterEvent refused(QPoint(50, 50), Qt::CopyAction, &other, Qt::LeftButton,
                                Qt::NoModifier);
        refused.setAccepted(false);
        QCoreApplication::sendEvent(m_window.get(), &refused);
        QVERIFY(!refused.isAccepted());
    }

    void badFileKeepsDocumentAndShowsLoaderMessage() {
        openWindow("bicubic");
        const Scene before = m_window->document()->scene();
        const QString bad = QStringLiteral(KW_TEST_DATA_DIR "/broken/decreasing_knot.knot");
        QString loaderMessage;
        const auto result = readKnotFile(bad);
        QVERIFY(!result);
        m_script.openPath = bad;
        m_window->action(QStringLiteral("actionOpen"))->trigger();
        QCOMPARE(m_script.errors, QStringList{result.message()});
        QVERIFY(m_window->document()->scene() == before);
        QCOMPARE(m_window->filePath(), samplePath("bicubic"));
    }

    void unsavedChangesAreAsked() {
        openWindow("bicubic");
        QVERIFY(pushCommand(m_window->undoStack(),
                            SetPartitions::create(m_window->document(), SurfaceId{1}, 3, 3)));
        const Scene edited = m_window->document()->scene();
        m_script.openPath = samplePath("sphere");
        m_script.askAnswer = QMessageBox::Cancel;
        m_window->action(QStringLiteral("actionOpen"))->trigger();
        QCOMPARE(m_script.asks, 1);
        QCOMPARE(m_script.opens, 0);
        QVERIFY(m_window->document()->scene() == edited);
        // Closing asks too; Cancel keeps the window open.
        QVERIFY(!m_window->close());
        QCOMPARE(m_script.asks, 2);
        QVERIFY(m_window->isVisible());
        m_script.askAnswer = QMessageBox::Discard;
        m_window->action(QStringLiteral("actionOpen"))->trigger();
        QCOMPARE(m_script.opens, 1);
        QCOMPARE(m_window->document()->scene().surfaces.front().name,
                 readKnotFile(samplePath("sphere"))->surfaces.front().name);
    }

    void layoutAndRecentFilesPersist() {
        openWindow("sphere");
        QDockWidget* uvDock = m_window->findChild<QDockWidget*>(QStringLiteral("dockUv"));
        QVERIFY(uvDock && uvDock->isVisible());
        uvDock->hide();
        QVERIFY(m_window->close()); // unmodified: no question; saves the layout
        m_window = std::make_unique<MainWindow>();
        scriptDialogs(*m_window, m_script);
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        QVERIFY(!m_window->findChild<QDockWidget*>(QStringLiteral("dockUv"))->isVisible());
        // File > Open Recent lists the file first and opens it.
        QMenu* recent = m_window->findChild<QMenu*>(QStringLiteral("menuRecent"));
        QVERIFY(recent && !recent->actions().isEmpty());
        QAction* first = recent->actions().first();
        QCOMPARE(first->data().toString(), samplePath("sphere"));
        first->trigger();
        QCOMPARE(m_window->filePath(), samplePath("sphere"));
        m_window->findChild<QDockWidget*>(QStringLiteral("dockUv"))->show();
    }

    void dragResponsiveness_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<bool>("adaptive");
        QTest::newRow("teapot") << QStringLiteral("teapot") << false;
        QTest::newRow("bicubic") << QStringLiteral("bicubic") << false;
        QTest::newRow("bicubic adaptive") << QStringLiteral("bicubic") << true;
    }
    void dragResponsiveness() {
        // Mouse-move -> next draw call during a drag, and bytes uploaded per step.
        QFETCH(QString, sample);
        QFETCH(bool, adaptive);
        openWindow(qPrintable(sample));
        Viewport* vp = m_window->viewport();
        // The paper's uniform grid: the partial uploads below are measured against it. The
        // editor's default, adaptive, is dragged too (the last row).
        vp->setPartitioning(adaptive ? RenderOptions::Partitioning::Adaptive
                                     : RenderOptions::Partitioning::Uniform,
                            0.5);
        QTest::qWait(30);
        const auto [ref, press] = pickablePoint();
        QVERIFY(ref.surface.isValid());
        QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
        QTest::qWait(30);
        vp->resetDragMetrics();
        const int steps = 40;
        for (int k = 1; k <= steps; ++k) {
            QTest::mouseMove(vp, press + QPoint(k, k / 2));
            QTRY_COMPARE_WITH_TIMEOUT(vp->dragMetrics().moveToDrawMs.size(), size_t(k), 5000);
        }
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(steps, steps / 2));
        QCOMPARE(m_window->undoStack()->count(), 1);
        Viewport::DragMetrics m = vp->dragMetrics();
        auto median = [](auto v) {
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        std::vector<double> paintMs;
        std::vector<std::int64_t> stepBytes;
        for (const FrameReport& f : m.frames) {
            paintMs.push_back(f.cpuMs.total);
            // The exact data of the surface; the control-net overlay, which is rebuilt
            // whole when points move, is counted apart (netBuilds).
            stepBytes.push_back(f.uploads.texels * std::int64_t(sizeof(glm::vec4)) +
                                f.uploads.vertexBytes);
        }
        const double moveToDraw = median(m.moveToDrawMs), paint = median(paintMs);
        const auto bytes = median(stepBytes);
        const auto maxBytes = *std::max_element(stepBytes.begin(), stepBytes.end());
        const QString report =
            QStringLiteral("drag on %9, %1 steps, viewport %2x%3: move->draw median %4 ms "
                           "(max %5; mouse-move handler %10 ms), paintGL median %6 ms, "
                           "bytes per step median %7 (max %8)")
                .arg(steps)
                .arg(vp->width())
                .arg(vp->height())
                .arg(moveToDraw, 0, 'f', 3)
                .arg(*std::max_element(m.moveToDrawMs.begin(), m.moveToDrawMs.end()), 0, 'f', 3)
                .arg(paint, 0, 'f', 2)
                .arg(bytes)
                .arg(maxBytes)
                .arg(sample)
                .arg(median(m.handlerMs), 0, 'f', 3);
        qInfo().noquote() << report;
        QFile out(QStringLiteral(KW_TEST_OUTPUT_DIR "/drag_metrics_%1%2.txt")
                      .arg(sample, adaptive ? QStringLiteral("_adaptive") : QString()));
        QVERIFY(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
        out.write(report.toUtf8() + '\n');
        if (adaptive) {
            // Each step uploads one control texel and evaluates one surface's partitions again
            // (the view is still); the polygon is updated in place, or rebuilt when the
            // required density changed.
            for (const FrameReport& f : m.frames) {
                QCOMPARE(f.uploads.fullUploads, 0);
                QCOMPARE(f.uploads.texels, 1);
                QCOMPARE(f.partitions.choicesEvaluated, 1);
                QVERIFY(f.uploads.basePolygonBuilds <= 1);
                QVERIFY(f.partitions.worstBoundPixels <= 0.5);
            }
            return;
        }
        // Each step re-uploads one control texel as a sub-image and a range of base polygon
        // vertices, never the whole surface.
        const Surface* surface = m_window->document()->surface(ref.surface);
        QVERIFY(surface);
        const BasePolygon polygon =
            buildBasePolygon(surface->geometry, surface->partitionsU, surface->partitionsV);
        const std::int64_t fullBytes = std::int64_t(
            size_t(surface->geometry.countU * surface->geometry.countV) * sizeof(glm::vec4) +
            polygon.vertices.size() * sizeof(BaseVertex));
        QVERIFY(std::all_of(stepBytes.begin(), stepBytes.end(), [](auto b) { return b > 0; }));
        QVERIFY2(maxBytes < fullBytes,
                 qPrintable(QStringLiteral("%1 >= %2").arg(maxBytes).arg(fullBytes)));
        UploadStats st;
        for (const FrameReport& f : m.frames) {
            QCOMPARE(f.uploads.fullUploads, 0);
            QCOMPARE(f.uploads.subImageUploads, 1);
            QCOMPARE(f.uploads.texels, 1);
            st += f.uploads;
        }
        qInfo().noquote() << QStringLiteral("per step: %1 control texel bytes, %2 vertex bytes "
                                            "(a full upload of this patch: %3 bytes)")
                                 .arg(sizeof(glm::vec4))
                                 .arg(double(st.vertexBytes) / st.vertexUpdates, 0, 'f', 0)
                                 .arg(fullBytes);
    }
};

QTEST_MAIN(TestEditor)
#include "tst_editor.moc"
