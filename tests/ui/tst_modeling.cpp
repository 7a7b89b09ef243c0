// Modeling editor GUI tests under Xvfb, through the real window: create, trim in the
// UV panel, place, view camera in the file, shortcuts, preferences, desktop basics.
#include "editor_test_util.h"
#include "model/document/naming.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_construct.h"
#include "render/offscreen_renderer.h"
#include "ui/desktopactions.h"
#include "ui/modelingtools.h"
#include "ui/propertypanel.h"
#include "ui/uvpanel.h"

#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QProgressDialog>
#include <QSettings>
#include <QTreeView>
#include <QUndoStack>
#include <QWheelEvent>
#include <algorithm>

using namespace kw;
using namespace kwtest;

class TestModeling : public EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/modeling-config"));
    }

private:
    /// Pixel of the 3D frame at a surface point (the grab's size equals the widget's here).
    QRgb pixelAt(const QImage& frame, const glm::dvec3& p) const {
        const auto px = m_window->viewport()->viewProjection().project(p);
        return px ? frame.pixel(px->toPoint()) : 0;
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkModelingTest"));
        QSettings().clear();
    }
    void cleanup() { closeWindow(); }

    void createEachPrimitiveThenUndoAndRedo() {
        openWindow();
        ModelingTools* tools = m_window->modelingTools();
        ModelingTools::Prompts prompts;
        prompts.patch = [](QWidget*, const ModelingTools::PatchParams&) {
            return std::optional(ModelingTools::PatchParams{3, 2, 6, 4, 2.0, 1.0});
        };
        prompts.curveOperation = [](QWidget*, ModelingTools::CurveOperationKind kind,
                                    const ModelingTools::CurveOperation& init) {
            ModelingTools::CurveOperation op = init;
            op.curve.edge = ModelingTools::CurveEdge::VStart;
            op.point = glm::dvec3(0.0);
            op.vector = kind == ModelingTools::CurveOperationKind::Extrude
                            ? glm::dvec3(0.0, 0.0, 0.5)
                            : glm::dvec3(0.0, 1.0, 0.0);
            return std::optional(op);
        };
        prompts.transform = [](QWidget*) {
            return std::optional(ModelingTools::TransformParams{{0.0, 0.0, 1.0}, 2, 0.0, 1.0});
        };
        tools->setPrompts(prompts);
        const glm::dvec3 target = m_window->viewport()->cameraController().camera().target;
        const struct {
            const char* action;
            const char* text;
        } steps[] = {
            {"actionCreatePlane", "Create plane"},       {"actionCreateSphere", "Create sphere"},
            {"actionCreateCylinder", "Create cylinder"}, {"actionCreateCone", "Create cone"},
            {"actionCreateTorus", "Create torus"},       {"actionCreatePatch", "Create patch"}};
        QUndoStack* stack = m_window->undoStack();
        for (const auto& step : steps) {
            const size_t before = scene().surfaces.size();
            act(step.action)->trigger();
            QCOMPARE(scene().surfaces.size(), before + 1);
            QCOMPARE(stack->undoText(), QLatin1String(step.text));
            const Surface& made = scene().surfaces.back();
            // Selected; the first one placed at the view's target, the next beside it (the
            // plane's and the sphere's centres are their nets' centres).
            QCOMPARE(m_window->selection()->selectedSurfaces(), std::vector<SurfaceId>{made.id});
            QCOMPARE(m_window->selection()->currentSurface(), made.id);
            glm::dvec3 lo, hi;
            surfaceControlBounds(made.geometry, lo, hi);
            if (before == 0)
                QVERIFY(glm::length(0.5 * (lo + hi) - target) < 1e-9);
            else if (QLatin1String(step.action) == QLatin1String("actionCreateSphere"))
                QVERIFY(glm::length(0.5 * (lo + hi) - target) > 0.5 * glm::length(hi - lo));
        }
        const NurbsSurface& patch = scene().surfaces.back().geometry;
        QCOMPARE(patch.degreeU, 3);
        QCOMPARE(patch.countV, 4);
        QCOMPARE(patch.knotsU, clampedUniformKnots(3, 6));

        // Revolve and extrude the patch's v = start boundary; a second patch, moved up, makes
        // a loft through two curves.
        act("actionRevolve")->trigger();
        QCOMPARE(stack->undoText(), QStringLiteral("Create revolution"));
        const SurfaceId patchId = scene().surfaces[5].id;
        tools->selectSurfaces({patchId});
        act("actionExtrude")->trigger();
        QCOMPARE(stack->undoText(), QStringLiteral("Create extrusion"));
        const NurbsSurface& ex = scene().surfaces.back().geometry;
        QVERIFY(glm::length(surfacePoint(ex, 0.3, 1.0) - surfacePoint(ex, 0.3, 0.0) -
                            glm::dvec3(0, 0, 0.5)) < 1e-12);
        act("actionDuplicate")->trigger(); // the extrusion, copied and selected
        const SurfaceId copy = scene().surfaces.back().id;
        act("actionTransform")->trigger(); // moved up by 1
        tools->selectSurfaces({patchId, copy});
        act("actionLoft")->trigger();
        QCOMPARE(stack->undoText(), QStringLiteral("Create loft through 2 curves"));
        QCOMPARE(m_window->selection()->currentSurface(), scene().surfaces.back().id);

        const Scene full = scene();
        const int steps_ = stack->count();
        for (int k = 0; k < steps_; ++k)
            stack->undo();
        QVERIFY(scene().surfaces.empty());
        for (int k = 0; k < steps_; ++k)
            stack->redo();
        QVERIFY(scene().surfaces == full.surfaces);
    }

    void circularHoleInUvPanelShowsIn3D() {
        openWindow("bicubic");
        UvPanel* uv = m_window->uvPanel();
        const Surface& s = scene().surfaces.front();
        QVERIFY(s.trims.empty());
        const glm::dvec2 centre(
            0.5 * (surfaceDomainU(s.geometry).first + surfaceDomainU(s.geometry).last),
            0.5 * (surfaceDomainV(s.geometry).first + surfaceDomainV(s.geometry).last));
        const glm::dvec3 at = surfacePoint(s.geometry, centre.x, centre.y);
        QImage frame = m_window->viewport()->grabFramebuffer();
        const QRgb background = frame.pixel(2, 2);
        QVERIFY(pixelAt(frame, at) != background);

        act("uvToolCircle")->trigger();
        QCOMPARE(uv->tool(), UvTool::Circle);
        const QPoint press = uv->toWidget(centre).toPoint();
        QTest::mousePress(uv, Qt::LeftButton, Qt::NoModifier, press);
        QTest::mouseMove(uv, press + QPoint(30, 0));
        QTest::mouseRelease(uv, Qt::LeftButton, Qt::NoModifier, press + QPoint(30, 0));
        // One step: the domain boundary (outer loop) and the exact rational circle.
        const Surface& cut = scene().surfaces.front();
        QCOMPARE(cut.trims.size(), size_t(2));
        QCOMPARE(cut.trims[1].curves.front().degree, 2);
        QCOMPARE(cut.trims[1].curves.front().weights[1], std::sqrt(0.5));
        QCOMPARE(m_window->undoStack()->count(), 1);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Add circular hole"));
        QVERIFY(uv->crossingWarning().isEmpty());
        QTest::qWait(50);
        frame = m_window->viewport()->grabFramebuffer();
        QCOMPARE(pixelAt(frame, at), background); // the hole shows the background
        // The rest of the surface is still drawn.
        QVERIFY(pixelAt(frame, surfacePoint(cut.geometry, 0.15, 0.5)) != background);
        m_window->undoStack()->undo();
        QVERIFY(scene().surfaces.front().trims.empty());

        // A second loop across the first one is kept, with a warning.
        m_window->undoStack()->redo();
        act("uvToolRectangle")->trigger();
        QTest::mousePress(uv, Qt::LeftButton, Qt::NoModifier, press + QPoint(10, -10));
        QTest::mouseRelease(uv, Qt::LeftButton, Qt::NoModifier, press + QPoint(80, 40));
        QCOMPARE(scene().surfaces.front().trims.size(), size_t(3));
        QVERIFY(!uv->crossingWarning().isEmpty());
    }

    void polygonToolZoomAndTrimPointEdits() {
        openWindow("bicubic");
        UvPanel* uv = m_window->uvPanel();
        uv->setDrawHoles(false); // an outer boundary
        act("uvToolPolygon")->trigger();
        const QPoint a = uv->toWidget({0.2, 0.2}).toPoint(),
                     b = uv->toWidget({0.8, 0.25}).toPoint(),
                     c = uv->toWidget({0.5, 0.8}).toPoint();
        QTest::mouseClick(uv, Qt::LeftButton, Qt::NoModifier, a);
        QTest::mouseClick(uv, Qt::LeftButton, Qt::NoModifier, b);
        QTest::mouseClick(uv, Qt::LeftButton, Qt::NoModifier, c);
        QTest::keyClick(uv, Qt::Key_Return);
        const auto& trims = scene().surfaces.front().trims;
        QCOMPARE(trims.size(), size_t(1));
        QCOMPARE(trims[0].curves[0].points.size(), size_t(4)); // closed: first repeated
        // Zoom about the cursor keeps the point under it.
        const glm::dvec2 under = uv->toUv(QPointF(b));
        QWheelEvent wheel(QPointF(b), uv->mapToGlobal(QPointF(b)), QPoint(), QPoint(0, 240),
                          Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(uv, &wheel);
        QVERIFY(uv->zoom() > 1.4);
        QVERIFY(glm::length(uv->toUv(QPointF(b)) - under) < 0.01);
        // Pick the polygon's second point, type exact (u, v), insert and delete a point.
        act("uvToolSelect")->trigger();
        const QPoint second = uv->toWidget(trims[0].curves[0].points[1]).toPoint();
        QTest::mouseClick(uv, Qt::LeftButton, Qt::NoModifier, second);
        QCOMPARE(m_window->selection()->trimPoints().size(), size_t(1));
        auto* fu = m_window->findChild<QDoubleSpinBox*>(QStringLiteral("uvPointU"));
        auto* fv = m_window->findChild<QDoubleSpinBox*>(QStringLiteral("uvPointV"));
        QVERIFY(fu && fv && fu->isEnabled());
        fv->setValue(0.25);
        fu->setValue(0.875);
        QCOMPARE(scene().surfaces.front().trims[0].curves[0].points[1], glm::dvec2(0.875, 0.25));
        QCOMPARE(m_window->undoStack()->undoText(),
                 QStringLiteral("Set trim point to (0.875, 0.25)"));
        QVERIFY(uv->insertTrimPoint());
        QCOMPARE(scene().surfaces.front().trims[0].curves[0].points.size(), size_t(5));
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Insert trim control point"));
        m_window->selection()->setTrimPoints({TrimPointRef{
            scene().surfaces.front().id, scene().surfaces.front().trims[0].id, 0, 2}});
        QVERIFY(uv->deleteTrimPoint());
        QCOMPARE(scene().surfaces.front().trims[0].curves[0].points.size(), size_t(4));
        // Nothing picked: the fields are disabled and blank.
        m_window->selection()->setTrimPoints({});
        QVERIFY(!fu->isEnabled());
        QCOMPARE(fu->text().trimmed(), QString());
    }

    void deleteKeyOnTrimLoopKeepsSurface() {
        openWindow("trimmed_plate");
        UvPanel* uv = m_window->uvPanel();
        const Surface& s = scene().surfaces.front();
        const size_t loops = s.trims.size();
        QVERIFY(loops >= 2);
        const TrimLoop star = s.trims.back();
        QTest::mouseClick(uv, Qt::LeftButton, Qt::NoModifier,
                          uv->toWidget(star.curves[0].points[1]).toPoint());
        QVERIFY(!m_window->selection()->trimPoints().empty());
        activate();
        uv->setFocus();
        QTRY_VERIFY(uv->hasFocus());
        QTest::keyClick(uv, Qt::Key_Delete);
        QCOMPARE(scene().surfaces.size(), size_t(1)); // the surface remains
        QCOMPARE(scene().surfaces.front().trims.size(), loops - 1);
        for (const TrimLoop& l : scene().surfaces.front().trims)
            QVERIFY(l.id != star.id);
        m_window->undoStack()->undo();
        QCOMPARE(scene().surfaces.front().trims.back(), star);
    }

    void moveByTypedOffsetMovesEveryPointExactly() {
        openWindow("teapot");
        ModelingTools* tools = m_window->modelingTools();
        const glm::dvec3 offset(0.25, -1.5, 3.125);
        ModelingTools::Prompts prompts = ModelingTools::Prompts::standard();
        prompts.transform = [&](QWidget*) {
            return std::optional(ModelingTools::TransformParams{offset, 2, 0.0, 1.0});
        };
        tools->setPrompts(prompts);
        const Scene before = scene();
        tools->selectSurfaces({before.surfaces[1].id, before.surfaces[3].id});
        act("actionTransform")->trigger();
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Move 2 surfaces"));
        for (size_t k = 0; k < before.surfaces.size(); ++k) {
            const auto& p0 = before.surfaces[k].geometry.points;
            const auto& p1 = scene().surfaces[k].geometry.points;
            const bool moved = k == 1 || k == 3;
            for (size_t i = 0; i < p0.size(); ++i)
                QCOMPARE(p1[i], moved ? p0[i] + offset : p0[i]);
            QCOMPARE(scene().surfaces[k].geometry.weights, before.surfaces[k].geometry.weights);
        }
        m_window->undoStack()->undo();
        QVERIFY(scene().surfaces == before.surfaces);
    }

    void clickSelectsSurfaceIn3D() {
        openWindow("teapot");
        Viewport* vp = m_window->viewport();
        // A pixel of some surface that is not the current one: the renderer's pick says which.
        const SurfaceId current = m_window->selection()->currentSurface();
        const std::vector<SurfaceId> nets = vp->netSurfaces();
        ControlPointPicker picker; // the nets shown: a click near one of their points picks it
        picker.update(*m_window->document(), vp->viewProjection(), &nets);
        std::optional<PickHit> hit;
        QPoint at;
        for (int y = 40; y < vp->height() - 40 && !hit; y += 17)
            for (int x = 40; x < vp->width() - 40 && !hit; x += 17)
                if (auto h = vp->pickSurface(QPointF(x, y));
                    h && h->surface != current && !picker.nearest(QPointF(x, y), 10.0)) {
                    hit = h;
                    at = QPoint(x, y);
                }
        QVERIFY(hit.has_value());
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, at);
        QVERIFY(m_window->selection()->controlPoints().empty());
        QCOMPARE(m_window->selection()->currentSurface(), hit->surface);
        QCOMPARE(m_window->selection()->selectedSurfaces(), std::vector<SurfaceId>{hit->surface});
        // The hit is where the kernel puts that surface's (u, v).
        const Surface* s = m_window->document()->surface(hit->surface);
        QVERIFY(glm::length(surfacePoint(s->geometry, hit->uv.x, hit->uv.y) - hit->point) < 1e-9);
        // Shift + click adds another surface; the tree shows both.
        std::optional<PickHit> other;
        QPoint at2;
        const std::vector<SurfaceId> nets2 = vp->netSurfaces();
        picker.update(*m_window->document(), vp->viewProjection(), &nets2);
        for (int y = 40; y < vp->height() - 40 && !other; y += 13)
            for (int x = 40; x < vp->width() - 40 && !other; x += 13)
                if (auto h = vp->pickSurface(QPointF(x, y));
                    h && h->surface != hit->surface && !picker.nearest(QPointF(x, y), 10.0)) {
                    other = h;
                    at2 = QPoint(x, y);
                }
        QVERIFY(other.has_value());
        QTest::mouseClick(vp, Qt::LeftButton, Qt::ShiftModifier, at2);
        std::vector<SurfaceId> both{hit->surface, other->surface};
        std::sort(both.begin(), both.end(), [&](SurfaceId a, SurfaceId b) {
            return m_window->document()->indexOf(a) < m_window->document()->indexOf(b);
        });
        QCOMPARE(m_window->selection()->selectedSurfaces(), both);
        QCOMPARE(m_window->sceneTree()->selectionModel()->selectedRows().size(), 2);
    }

    void ctrlDragMovesSurfacesAndCtrlShiftDragSetsWeight() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const NurbsSurface before = scene().surfaces.front().geometry;
        // Ctrl + drag with X held: every control point moves by one x offset.
        const QPoint press(vp->width() / 2, vp->height() / 2);
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, press);
        QVERIFY(vp->isDragging());
        QTest::keyPress(vp, Qt::Key_X);
        QTest::mouseMove(vp, press + QPoint(40, 10));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::ControlModifier, press + QPoint(40, 10));
        QTest::keyRelease(vp, Qt::Key_X);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Move surface"));
        const NurbsSurface& moved = scene().surfaces.front().geometry;
        const glm::dvec3 d = moved.points[0] - before.points[0];
        QVERIFY(std::abs(d.x) > 1e-3);
        for (size_t k = 0; k < before.points.size(); ++k) {
            const glm::dvec3 dk = moved.points[k] - before.points[k];
            QVERIFY(glm::length(dk - d) < 1e-12);
            QCOMPARE(dk.y, 0.0);
            QCOMPARE(dk.z, 0.0);
        }
        // Ctrl + Shift + drag up on a control point doubles its weight per 100 px.
        const SurfaceId id = scene().surfaces.front().id;
        const ControlPointRef ref{id, 2, 2};
        const QPoint at =
            vp->viewProjection().project(moved.points[size_t(moved.index(2, 2))])->toPoint();
        const double w0 = moved.weights[size_t(moved.index(2, 2))];
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier | Qt::ShiftModifier, at);
        QTest::mouseMove(vp, at + QPoint(0, -100));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::ControlModifier | Qt::ShiftModifier,
                            at + QPoint(0, -100));
        QCOMPARE(m_window->selection()->controlPoints(), std::vector<ControlPointRef>{ref});
        const double w1 = scene().surfaces.front().geometry.weights[size_t(moved.index(2, 2))];
        QVERIFY2(std::abs(w1 - 2.0 * w0) < 1e-9, qPrintable(QString::number(w1)));
        QVERIFY(m_window->undoStack()->undoText().startsWith(QStringLiteral("Set weight")));
        m_window->undoStack()->undo();
        QCOMPARE(scene().surfaces.front().geometry.weights[size_t(moved.index(2, 2))], w0);
    }

    void knotRemovalActionUndoesInsertion() {
        openWindow("bicubic");
        const SurfaceId id = scene().surfaces.front().id;
        const NurbsSurface original = scene().surfaces.front().geometry;
        QVERIFY(pushCommand(m_window->undoStack(),
                            InsertKnot::create(m_window->document(), id, Direction::U, 0.37)));
        ModelingTools::Prompts prompts = ModelingTools::Prompts::standard();
        prompts.knotRemoval = [](QWidget*, double) {
            return std::optional(std::pair(0, 1e-9));
        };
        m_window->modelingTools()->setPrompts(prompts);
        act("actionRemoveKnots")->trigger();
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Remove 1 knot in u"));
        QCOMPARE(scene().surfaces.front().geometry.knotsU, original.knotsU);
        // Nothing more to remove at that tolerance: refused, no step.
        const int steps = m_window->undoStack()->count();
        act("actionRemoveKnots")->trigger();
        QCOMPARE(m_window->undoStack()->count(), steps);
    }

    void cameraIsSavedWithoutModifyingAndRestored() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        QTest::mousePress(vp, Qt::MiddleButton, Qt::NoModifier, QPoint(300, 300));
        QTest::mouseMove(vp, QPoint(360, 320));
        QTest::mouseRelease(vp, Qt::MiddleButton, Qt::NoModifier, QPoint(360, 320));
        QWheelEvent wheel(QPointF(200, 150), vp->mapToGlobal(QPointF(200, 150)), QPoint(),
                          QPoint(0, 120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(vp, &wheel);
        QVERIFY(!m_window->isWindowModified()); // a view change is not an edit
        QCOMPARE(m_window->undoStack()->count(), 0);
        const Camera seen = vp->cameraController().camera();
        const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/modeling_camera.knot");
        QFile::remove(path);
        QVERIFY(m_window->saveFile(path));
        m_window->close();
        m_window.reset();
        openWindow();
        QVERIFY(m_window->openFile(path));
        const Camera back = m_window->viewport()->cameraController().camera();
        QVERIFY(back.authored);
        QVERIFY(glm::length(back.eye - seen.eye) < 1e-12);
        QVERIFY(glm::length(back.target - seen.target) < 1e-12);
        QVERIFY(glm::length(back.up - seen.up) < 1e-12);
        QCOMPARE(back.fovYDegrees, seen.fovYDegrees);
    }

    void zoomMovesTowardTheCursor() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const QPointF cursor(150, 120);
        const Camera c0 = vp->cameraController().camera();
        const glm::dvec3 under = vp->viewProjection().onViewPlane(cursor, c0.target);
        QWheelEvent wheel(cursor, vp->mapToGlobal(cursor), QPoint(), QPoint(0, 240), Qt::NoButton,
                          Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(vp, &wheel);
        const Camera c1 = vp->cameraController().camera();
        QVERIFY(glm::length(c1.eye - c1.target) < glm::length(c0.eye - c0.target));
        // The point under the cursor stays under it.
        const auto px = vp->viewProjection().project(under);
        QVERIFY(px && std::hypot(px->x() - cursor.x(), px->y() - cursor.y()) < 1e-6);
    }

    void ctrlYAndCtrlShiftSReachTheirActions() {
        openWindow("bicubic");
        QVERIFY(act("actionRedo")->shortcuts().contains(QKeySequence(Qt::CTRL | Qt::Key_Y)));
        QCOMPARE(act("actionSaveAs")->shortcut(), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S));
        QVERIFY(pushCommand(m_window->undoStack(),
                            SetPartitions::create(m_window->document(), SurfaceId{1}, 5, 6)));
        m_window->undoStack()->undo();
        activate();
        QTest::keyClick(m_window.get(), Qt::Key_Y, Qt::ControlModifier);
        QCOMPARE(scene().surfaces.front().partitionsU, 5); // redone
        const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/modeling_saveas.knot");
        QFile::remove(path);
        m_script.savePath = path;
        QTest::keyClick(m_window.get(), Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);
        QVERIFY(QFile::exists(path));
        QCOMPARE(m_window->filePath(), path);
        // The shortcuts page lists them (it is made from the actions themselves).
        const QString page = m_window->desktopActions()->shortcutsHtml();
        QVERIFY(
            page.contains(QKeySequence(Qt::CTRL | Qt::Key_Y).toString(QKeySequence::NativeText)));
        QVERIFY(page.contains(QStringLiteral("Save As")));
    }

    // Anti-aliasing is on by default: automatic draws 4 samples; on software OpenGL (llvmpipe
    // here and in CI), where they cost several times the frame, frames drawn while the view
    // moves are aliased previews (half the pixels, Viewport::previewWhileMoving). With
    // accumulation (the default method) every still frame draws one sample,
    // the still view is drawn again until all 4 are in (RenderOptions::progressive), so no
    // frame costs more than an aliased one; with MSAA the still frame after draws all at once.
    // An explicit choice is drawn as it is, moving or not.
    void antiAliasingIsOnByDefault() {
        QSettings().clear();
        openWindow("trimmed_plate");
        Viewport* vp = m_window->viewport();
        QCOMPARE(Preferences::load().samples, Viewport::kAutoSamples);
        QCOMPARE(vp->samples(), Viewport::kAutoSamplesCount);
        QTRY_VERIFY(vp->framesDrawn() > 0);
        std::vector<int> samplesDrawn; // FrameReport::samplesInImage of each full frame
        int previews = 0;              // frames of the moving view drawn as previews (fewer pixels)
        connect(vp, &Viewport::frameDrawn, this, [&](const FrameReport& r) {
            if (r.drawnSize.width() < vp->width() * vp->devicePixelRatioF())
                ++previews;
            else
                samplesDrawn.push_back(r.samplesInImage);
        });
        auto settled = [&] {
            return QTest::qWaitFor(
                [&] {
                    const FrameReport& r = vp->lastFrameReport();
                    return !r.refining && r.samplesInImage == vp->samples();
                },
                5000);
        };
        auto nextFrame = [&] {
            const std::int64_t before = vp->framesDrawn();
            vp->update();
            return QTest::qWaitFor([&] { return vp->framesDrawn() > before; }, 5000);
        };
        QVERIFY(nextFrame());
        QVERIFY(settled());
        QVERIFY(vp->lastFrameReport().gpuBytes.frameTargets > 0);
        vp->makeCurrent();
        const QString gl = QString::fromLatin1(reinterpret_cast<const char*>(
            QOpenGLContext::currentContext()->functions()->glGetString(GL_RENDERER)));
        vp->doneCurrent();
        const bool software = gl.contains(QStringLiteral("llvmpipe"), Qt::CaseInsensitive) ||
                              gl.contains(QStringLiteral("softpipe"), Qt::CaseInsensitive);
        QCOMPARE(vp->aliasedWhileMoving(), software);
        // A wheel zoom: the frame it draws, then the still one.
        const QPoint middle(vp->width() / 2, vp->height() / 2);
        auto zoom = [&] {
            samplesDrawn.clear();
            previews = 0;
            const std::int64_t before = vp->framesDrawn();
            QWheelEvent wheel(middle, vp->mapToGlobal(middle), QPoint(), QPoint(0, 120),
                              Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
            QCoreApplication::sendEvent(vp, &wheel);
            // On software OpenGL the zoom's frame is a preview, the first full one comes
            // Viewport::kStillMs later.
            return QTest::qWaitFor([&] { return vp->framesDrawn() > before; }, 5000) &&
                   QTest::qWaitFor([&] { return !samplesDrawn.empty(); }, 5000);
        };
        QVERIFY(zoom());
        QCOMPARE(samplesDrawn.front(), software ? 1 : 4);
        QCOMPARE(previews > 0, software);
        QVERIFY(settled());
        qInfo("GL_RENDERER %s: samples of the frames after a zoom: %s", qPrintable(gl),
              qPrintable([&] {
                  QStringList l;
                  for (int n : samplesDrawn)
                      l << QString::number(n);
                  return l.join(' ');
              }()));
        if (software) { // a sample per frame, in order, until all are in
            QVERIFY(samplesDrawn.size() >= 4);
            for (size_t i = 0; i < 4; ++i)
                QCOMPARE(samplesDrawn[i], int(i) + 1);
        }
        // Edits with the view still, one per frame (a slider held): each starts the image
        // again, and it is still completed once they stop.
        Document* doc = m_window->document();
        const SurfaceId first = doc->scene().surfaces.front().id;
        for (int k = 0; k < 4; ++k) {
            QVERIFY(doc->setPartitions(first, 4 + k % 2, 4));
            QVERIFY(nextFrame());
        }
        QVERIFY(settled());
        // MSAA: aliased while moving on software OpenGL, then all samples in one frame.
        vp->setAntialiasing(RenderOptions::Antialiasing::Coverage);
        QVERIFY(nextFrame());
        QVERIFY(settled());
        QVERIFY(zoom());
        QCOMPARE(samplesDrawn.front(), 4); // the still frame, after the previews
        QCOMPARE(previews > 0, software);
        QVERIFY(settled());
        QVERIFY(std::none_of(samplesDrawn.begin(), samplesDrawn.end(),
                             [](int n) { return n > 1 && n < 4; }));
        vp->setAntialiasing(RenderOptions::Antialiasing::Accumulate);
        // Explicit choices.
        vp->setSamples(1);
        QVERIFY(nextFrame());
        QCOMPARE(vp->lastFrameReport().gpuBytes.frameTargets, std::int64_t(0));
        QCOMPARE(vp->lastFrameReport().samplesInImage, 1);
        vp->setSamples(2);
        QVERIFY(!vp->aliasedWhileMoving());
        QVERIFY(nextFrame());
        QVERIFY(vp->lastFrameReport().gpuBytes.frameTargets > 0);
        QCOMPARE(vp->lastFrameReport().samplesInImage, 2);
        QVERIFY(!vp->lastFrameReport().refining);
        disconnect(vp, &Viewport::frameDrawn, this, nullptr);
    }

    void preferencesPersistAcrossRestart() {
        openWindow();
        Preferences wanted;
        wanted.autosaveSeconds = 0;
        wanted.keepBackup = false;
        wanted.partitionMode = QStringLiteral("adaptive");
        wanted.pixelTolerance = 1.25;
        wanted.trimMaskCap = 256;
        wanted.trimMode = QStringLiteral("mask");
        wanted.trimBudgetMiB = 64;
        wanted.samples = 2;
        wanted.aaMethod = QStringLiteral("coverage");
        wanted.headlight = false;
        wanted.background = QColor(10, 20, 30);
        QVERIFY(!(Preferences::load() == wanted));
        DesktopActions::Prompts prompts = DesktopActions::Prompts::standard();
        prompts.preferences = [&](QWidget*, const PreferencesEdit& current, bool) {
            // The dialog shows the current values and returns what it shows.
            PreferencesDialog d(current);
            return std::optional(d.edit() == current ? PreferencesEdit{wanted, current.project}
                                                     : PreferencesEdit{});
        };
        m_window->desktopActions()->setPrompts(prompts);
        act("actionPreferences")->trigger();
        QVERIFY(!m_window->viewport()->renderOptions().headlight);
        m_window->close();
        m_window.reset(); // restart
        openWindow();
        QVERIFY(Preferences::load() == wanted);
        QCOMPARE(PreferencesDialog(Preferences::load()).value(), wanted);
        {
            // A partition mode this build does not draw is kept but not offered as a choice.
            const PreferencesDialog d(Preferences::load());
            const auto* mode = d.findChild<QComboBox*>(QStringLiteral("prefPartitionMode"));
            const auto* tolerance =
                d.findChild<QDoubleSpinBox*>(QStringLiteral("prefPixelTolerance"));
            QVERIFY(mode && tolerance);
            const bool adaptive =
                Preferences::availablePartitionModes().contains(QStringLiteral("adaptive"));
            QCOMPARE(tolerance->isEnabled(), adaptive);
            QCOMPARE(mode->isEnabled(), Preferences::availablePartitionModes().size() > 1);
        }
        const RenderOptions& o = m_window->viewport()->renderOptions();
        QVERIFY(!o.headlight);
        QCOMPARE(o.trimMaskCap, 256);
        QVERIFY(o.trimMode == RenderOptions::TrimMode::Mask);
        QCOMPARE(o.trimBudgetBytes, std::int64_t(64) << 20);
        QCOMPARE(m_window->viewport()->samples(), 2);
        QVERIFY(o.antialiasing == RenderOptions::Antialiasing::Coverage);
        QCOMPARE(o.background.r, float(10 / 255.0));
        QCOMPARE(QSettings().value(QStringLiteral("autosave/intervalSeconds")).toInt(), 0);
        QCOMPARE(QSettings().value(QStringLiteral("save/keepBackup")).toBool(), false);
        QSettings().clear();
    }

    // A stored anti-aliasing method this build does not know (a hand-edited or newer settings
    // file) loads as the default, accumulation, and the viewport draws with it.
    void unknownAntialiasingMethodLoadsTheDefault() {
        QSettings().setValue(QStringLiteral("view/aaMethod"), QStringLiteral("msaa8x"));
        QCOMPARE(Preferences::load().aaMethod, QStringLiteral("accumulate"));
        openWindow();
        QVERIFY(m_window->viewport()->renderOptions().antialiasing ==
                RenderOptions::Antialiasing::Accumulate);
        QSettings().clear();
    }

    void disabledFieldsAreClearedWithoutSelection() {
        openWindow("bicubic");
        m_window->selection()->setControlPoints({ControlPointRef{SurfaceId{1}, 1, 1}});
        auto spins = m_window->propertyPanel()->findChildren<QAbstractSpinBox*>();
        QVERIFY(spins.size() > 6);
        m_window->selection()->clear();
        for (QAbstractSpinBox* box : spins) {
            QVERIFY(!box->isEnabled() || !box->parentWidget()->isEnabled() ||
                    !box->isEnabledTo(m_window->propertyPanel()));
            QVERIFY2(box->text().trimmed().isEmpty(), qPrintable(box->text()));
        }
    }

    void exportImageAtChosenSizeWithAovs() {
        openWindow("torus");
        const QString png = QStringLiteral(KW_TEST_OUTPUT_DIR "/modeling_export.png");
        const QString exr = QStringLiteral(KW_TEST_OUTPUT_DIR "/modeling_export_aov.exr");
        QFile::remove(png);
        QFile::remove(exr);
        MainWindow::Dialogs d;
        d.saveFile = [&](QWidget*, const QString&, const QString& filter, const QString&) {
            return filter.contains(QStringLiteral("*.exr")) ? png : QString();
        };
        d.error = [](QWidget*, const QString&, const QString& text) {
            QFAIL(qPrintable(text));
        };
        QSize offered;
        d.exportOptions = [&](QWidget*, const MainWindow::Dialogs::ExportOptions& init) {
            offered = init.size;
            return std::optional(MainWindow::Dialogs::ExportOptions{QSize(320, 200), true});
        };
        m_window->setDialogs(d);
        act("actionExportImage")->trigger();
        QCOMPARE(offered, m_window->viewport()->size()); // the view's size is offered first
        const QImage image(png);
        QCOMPARE(image.size(), QSize(320, 200));
        int covered = 0; // the torus, not only background
        for (int y = 0; y < image.height(); y += 2)
            for (int x = 0; x < image.width(); x += 2)
                covered += image.pixel(x, y) != image.pixel(1, 1);
        QVERIFY2(covered > 50, qPrintable(QString::number(covered)));
        QVERIFY(QFileInfo(exr).size() > 1000); // compressed float channels
        // The picture is anti-aliased as the view is (automatic: 4 samples), AOVs or not: the
        // same pixels with and without them, others than with anti-aliasing off.
        d.exportOptions = [&](QWidget*, const MainWindow::Dialogs::ExportOptions&) {
            return std::optional(MainWindow::Dialogs::ExportOptions{QSize(320, 200), false});
        };
        m_window->setDialogs(d);
        act("actionExportImage")->trigger();
        const QImage withoutAov(png);
        QVERIFY(withoutAov.convertToFormat(QImage::Format_RGB32) ==
                image.convertToFormat(QImage::Format_RGB32));
        m_window->viewport()->setSamples(1);
        act("actionExportImage")->trigger();
        const QImage aliased(png);
        m_window->viewport()->setSamples(Viewport::kAutoSamples);
        QCOMPARE(aliased.size(), image.size());
        int differing = 0; // the torus's outline
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                differing += aliased.pixel(x, y) != image.pixel(x, y);
        QVERIFY2(differing > 100, qPrintable(QString::number(differing)));
    }

    void recentFilesTellSameNamesApart() {
        const QStringList labels =
            recentLabels({QStringLiteral("/a/x/model.knot"), QStringLiteral("/b/x/model.knot"),
                          QStringLiteral("/c/other.knot")});
        QCOMPARE(labels[2], QStringLiteral("other.knot"));
        QVERIFY(labels[0] != labels[1]);
        QVERIFY(labels[0].contains(QStringLiteral("a/x")));
    }

    void importedRepeatedNamesBecomeDistinct() {
        Scene s;
        for (const char* n : {"Face", "Face", "Lid", "", "Face"}) {
            Surface x;
            x.name = QLatin1String(n);
            s.surfaces.push_back(x);
        }
        QCOMPARE(makeSurfaceNamesDistinct(s, QStringLiteral("hammer")), 4);
        QCOMPARE(s.surfaces[0].name, QStringLiteral("Face 1"));
        QCOMPARE(s.surfaces[1].name, QStringLiteral("Face 2"));
        QCOMPARE(s.surfaces[2].name, QStringLiteral("Lid"));
        QCOMPARE(s.surfaces[3].name, QStringLiteral("hammer 1"));
        QCOMPARE(s.surfaces[4].name, QStringLiteral("Face 3"));
    }

    void failedImportProgressNeverCoversTheError() {
        openWindow();
        const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/modeling_bad.obj");
        {
            QFile f(path);
            QVERIFY(f.open(QIODevice::WriteOnly));
            f.write("v 0 0 0\ncstype bspline\ndeg 3 3\nsurf 0 1 0 1 1 2\nend\n");
        }
        int visibleProgress = -1;
        MainWindow::Dialogs d;
        d.error = [&](QWidget*, const QString&, const QString&) {
            // The user reads the message for a while: no progress box may appear meanwhile.
            QTest::qWait(700);
            visibleProgress = 0;
            for (QWidget* w : QApplication::topLevelWidgets())
                visibleProgress += qobject_cast<QProgressDialog*>(w) && w->isVisible();
            for (QProgressDialog* p : m_window->findChildren<QProgressDialog*>())
                visibleProgress += p->isVisible();
        };
        d.askSave = [](QWidget*, const QString&) {
            return QMessageBox::Discard;
        };
        m_window->setDialogs(d);
        QVERIFY(!m_window->importFile(path));
        QCOMPARE(visibleProgress, 0);
        QTest::qWait(500);
        for (QProgressDialog* p : m_window->findChildren<QProgressDialog*>())
            QVERIFY(!p->isVisible());
    }
};

QTEST_MAIN(TestModeling)
#include "tst_modeling.moc"
