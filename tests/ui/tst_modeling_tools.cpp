// Modeling editor GUI tests under Xvfb (second part), through the real window: hide,
// isolate and show with undo and in the saved file; rotate and scale by Ctrl + drag; the curve
// tool (clicked points interpolated, control-point curves, loft through drawn curves).
#include "editor_test_util.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_construct.h"
#include "render/offscreen_renderer.h"
#include "ui/curvetool.h"
#include "ui/modelingtools.h"

#include <QAction>
#include <QDockWidget>
#include <QFile>
#include <QSettings>
#include <QStatusBar>
#include <QTreeView>
#include <QUndoStack>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

using namespace kw;
using namespace kwtest;

class TestModelingTools : public EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/modeling-tools-config"));
    }

private:
    /// Wide enough for a 3D view of a useful size next to the docks (at 960 px they leave it
    /// its 160 px minimum).
    void openWindow(const char* sample = nullptr) {
        EditorTestBase::openWindow(sample, QSize(1260, 900));
    }
    void key(int k, Qt::KeyboardModifiers mods = Qt::NoModifier) {
        activate();
        QTest::keyClick(m_window.get(), Qt::Key(k), mods);
    }
    /// The clicked pixel on the curve tool's plane (through the camera target, facing the eye).
    glm::dvec3 onPlane(QPoint pixel) const {
        Viewport* vp = m_window->viewport();
        return vp->viewProjection().onViewPlane(QPointF(pixel),
                                                vp->cameraController().camera().target);
    }
    static std::vector<double> chordParameters(const std::vector<glm::dvec3>& q) {
        std::vector<double> t(q.size(), 0.0);
        for (size_t k = 1; k < q.size(); ++k)
            t[k] = t[k - 1] + glm::length(q[k] - q[k - 1]);
        for (double& x : t)
            x /= t.back();
        return t;
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkModelingToolsTest"));
        QSettings().clear();
    }
    void cleanup() { closeWindow(); }

    void hideIsolateShowAllWithUndoAndSaved() {
        // Three surfaces side by side: the bicubic patch, a sphere and a torus made beside it.
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        ModelingTools* tools = m_window->modelingTools();
        const double side = 1.5 * tools->viewScale();
        QVERIFY(tools->createPrimitive(ModelingTools::Primitive::Sphere)->isValid());
        QVERIFY(tools->transformSelected({{side, 0.0, 0.0}, 2, 0.0, 1.0}));
        QVERIFY(tools->createPrimitive(ModelingTools::Primitive::Torus)->isValid());
        QVERIFY(tools->transformSelected({{-side, 0.0, 0.0}, 2, 0.0, 1.0}));
        act("actionFit")->trigger();
        QTest::qWait(50);
        const QRgb background = vp->grabFramebuffer().pixel(2, 2);
        const Scene before = scene();
        QCOMPARE(before.surfaces.size(), size_t(3));
        // The pixels (on a grid) where the renderer's pick sees the patch.
        const SurfaceId id = before.surfaces.front().id;
        std::vector<QPoint> pixels;
        for (int y = 6; y < vp->height() - 6; y += 12)
            for (int x = 6; x < vp->width() - 6; x += 12)
                if (auto h = vp->pickSurface(QPointF(x, y)); h && h->surface == id)
                    pixels.push_back(QPoint(x, y));
        QVERIFY(pixels.size() >= 3);
        const QPoint at = pixels.front();
        m_window->selectSurface(id);
        QCOMPARE(m_window->selection()->selectedSurfaces(), std::vector<SurfaceId>{id});
        // H hides it: one undo step, not drawn, not picked, deselected, the file modified.
        key(Qt::Key_H);
        QVERIFY(m_window->document()->surface(id)->hidden);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Hide surface"));
        QVERIFY(!m_window->undoStack()->isClean());
        QVERIFY(m_window->selection()->selectedSurfaces().empty());
        QTest::qWait(50);
        const QImage hiddenFrame = vp->grabFramebuffer();
        // Where it was: another surface that was behind it, or the background.
        int uncovered = 0;
        for (const QPoint& p : pixels) {
            const auto h = vp->pickSurface(QPointF(p));
            QVERIFY(!h || h->surface != id);
            if (!h) {
                QCOMPARE(hiddenFrame.pixel(p), background);
                ++uncovered;
            }
        }
        QVERIFY(uncovered > 0);
        // Undo: drawn and picked again.
        m_window->undoStack()->undo();
        QVERIFY(!m_window->document()->surface(id)->hidden);
        QCOMPARE(vp->pickSurface(QPointF(at))->surface, id);
        m_window->undoStack()->redo();

        // Shift+H isolates the selection: every other surface hidden, this one shown.
        m_window->selectSurface(id);
        key(Qt::Key_H, Qt::ShiftModifier);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Isolate surface"));
        for (const Surface& s : scene().surfaces)
            QCOMPARE(s.hidden, s.id != id);
        for (int y = 10; y < vp->height(); y += 53)
            for (int x = 10; x < vp->width(); x += 53)
                if (const auto h = vp->pickSurface(QPointF(x, y)))
                    QCOMPARE(h->surface, id);
        QCOMPARE(vp->pickSurface(QPointF(at))->surface, id);

        // Saved hidden and read back so.
        const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/modeling_tools_hidden.knot");
        QFile::remove(path);
        QVERIFY(m_window->saveFile(path));
        QString error;
        const auto saved = readKnotFile(path);
        QVERIFY2(saved, qPrintable(saved.message()));
        QVERIFY(*saved == scene());
        QCOMPARE(int(std::count_if(saved->surfaces.begin(), saved->surfaces.end(),
                                   [](const Surface& s) { return s.hidden; })),
                 int(saved->surfaces.size()) - 1);

        // Ctrl+Alt+H shows everything in one step; undo goes back to the isolation.
        key(Qt::Key_H, Qt::ControlModifier | Qt::AltModifier);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Show 2 surfaces"));
        for (const Surface& s : scene().surfaces)
            QVERIFY(!s.hidden);
        m_window->undoStack()->undo();
        QCOMPARE(int(std::count_if(scene().surfaces.begin(), scene().surfaces.end(),
                                   [](const Surface& s) { return s.hidden; })),
                 int(scene().surfaces.size()) - 1);
        // Undo back to before the first hide: the scene as it was.
        m_window->undoStack()->undo(); // the isolation
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Hide surface"));
        m_window->undoStack()->undo();
        QVERIFY(scene().surfaces == before.surfaces); // (Save also stored the camera)
        // The scene tree's context menu offers the same actions.
        const QList<QAction*> menu = m_window->sceneTree()->actions();
        for (const char* name :
             {"actionHide", "actionIsolate", "actionShowSelected", "actionShowAll"})
            QVERIFY2(menu.contains(act(name)), name);
    }

    void refusedActionsSayWhyInTheStatusBar() {
        openWindow("bicubic");
        ModelingTools* tools = m_window->modelingTools();
        QStatusBar* status = m_window->statusBar();
        const int surfaces = int(scene().surfaces.size());
        tools->selectSurfaces({});
        // Each refusal returns its reason, in the words the status bar shows, and changes
        // nothing.
        const Status moved = tools->transformSelected({{1.0, 0.0, 0.0}, 2, 0.0, 1.0});
        QVERIFY(!moved);
        QCOMPARE(moved.message(), QStringLiteral("Select the surfaces to transform."));
        QCOMPARE(tools->duplicateSelected().message(),
                 QStringLiteral("Select the surfaces to duplicate."));
        const Status knots = tools->removeKnots(Direction::U, 1e-3);
        QVERIFY(knots.message().startsWith(QStringLiteral("Knot removal: ")));
        QVERIFY(knots.message().size() > QStringLiteral("Knot removal: ").size());
        const Expected<SurfaceId> patch = tools->createPatch({3, 3, 3, 4, 1.0, 1.0});
        QVERIFY(!patch);
        QVERIFY2(patch.message().startsWith(
                     QStringLiteral("Cannot create: a patch needs 1 <= degree < control points")),
                 qPrintable(patch.message()));
        const Expected<SurfaceId> loft = tools->createFromCurveList(
            ModelingTools::CurveOperationKind::Loft, ModelingTools::CurveOperation{}, {});
        QCOMPARE(loft.message(),
                 QStringLiteral("Select two or more surfaces whose curves to loft through."));
        QCOMPARE(int(scene().surfaces.size()), surfaces);
        QVERIFY(m_window->undoStack()->count() == 0);

        // The menu actions show the reason in the status bar.
        ModelingTools::Prompts prompts = ModelingTools::Prompts::standard();
        prompts.transform = [](QWidget*) {
            return std::optional<ModelingTools::TransformParams>(
                ModelingTools::TransformParams{{1.0, 0.0, 0.0}, 2, 0.0, 1.0});
        };
        tools->setPrompts(prompts);
        act("actionTransform")->trigger();
        QCOMPARE(status->currentMessage(), QStringLiteral("Select the surfaces to transform."));
        act("actionDuplicate")->trigger();
        QCOMPARE(status->currentMessage(), QStringLiteral("Select the surfaces to duplicate."));
        act("actionDelete")->trigger();
        QCOMPARE(status->currentMessage(), QStringLiteral("Select a surface to delete."));
        QCOMPARE(int(scene().surfaces.size()), surfaces);

        // Done: what was done shows, and the next step is refused no more.
        const Expected<SurfaceId> sphere = tools->createPrimitive(ModelingTools::Primitive::Sphere);
        QVERIFY2(sphere, qPrintable(sphere.message()));
        QCOMPARE(status->currentMessage(), QStringLiteral("Create sphere"));
        act("actionTransform")->trigger();
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Move surface"));
        const Status deleted = tools->deleteSelected();
        QVERIFY2(deleted, qPrintable(deleted.message()));
        QCOMPARE(int(scene().surfaces.size()), surfaces);
    }

    void hideDeselectsTrimPointsOfTheHiddenSurface() {
        // Trim points picked in the UV editor belong to the surface: once it is hidden, a drag
        // or Delete on them would edit what is not seen, so Hide drops them with the rows.
        openWindow("trimmed_plate");
        const Surface& s = scene().surfaces.front();
        QVERIFY(!s.trims.empty());
        m_window->selectSurface(s.id);
        QVERIFY(m_window->selection()->setTrimPoints({TrimPointRef{s.id, s.trims[0].id, 0, 1}}));
        QVERIFY(m_window->selection()->setControlPoints({ControlPointRef{s.id, 0, 0}}));
        key(Qt::Key_H);
        QVERIFY(m_window->document()->surface(s.id)->hidden);
        QVERIFY(m_window->selection()->selectedSurfaces().empty());
        QVERIFY(m_window->selection()->controlPoints().empty());
        QVERIFY(m_window->selection()->trimPoints().empty());
    }

    void hiddenSelectedSurfaceShowsNoNetAndStaysPut() {
        // A hidden surface can be selected again in the tree; it still shows no net (selected
        // or all nets) and a Ctrl + drag leaves it where it is.
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const SurfaceId id = scene().surfaces.front().id;
        vp->setControlNet(true);
        m_window->selectSurface(id);
        QCOMPARE(vp->netSurfaces(), std::vector<SurfaceId>{id});
        key(Qt::Key_H);
        QVERIFY(m_window->document()->surface(id)->hidden);
        m_window->selectSurface(id);
        QCOMPARE(m_window->selection()->selectedSurfaces(), std::vector<SurfaceId>{id});
        QVERIFY(vp->netSurfaces().empty());
        vp->setControlNetForAll(true);
        QVERIFY(vp->netSurfaces().empty());
        vp->setControlNetForAll(false);
        const int steps = m_window->undoStack()->count();
        const QPoint press(vp->width() / 2, vp->height() / 2);
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, press);
        QTest::mouseMove(vp, press + QPoint(40, 10));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::ControlModifier, press + QPoint(40, 10));
        QCOMPARE(m_window->undoStack()->count(), steps);
        m_window->undoStack()->undo(); // the hide
        QCOMPARE(vp->netSurfaces(), std::vector<SurfaceId>{id});
    }

    void rotateAndScaleDragsAreExactAboutThePivot() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        const SurfaceId id = scene().surfaces.front().id;
        m_window->selectSurface(id);
        const NurbsSurface before = scene().surfaces.front().geometry;
        glm::dvec3 lo, hi;
        surfaceControlBounds(before, lo, hi);
        const glm::dvec3 c = 0.5 * (lo + hi);
        const double r = 0.3 * glm::length(hi - lo);

        // R: Ctrl + drag rotates. About z (Z held), from the pivot's +x side to its +y side
        // with Shift (15° snaps): a quarter turn.
        key(Qt::Key_R);
        QCOMPARE(vp->surfaceDrag(), Viewport::SurfaceDrag::Rotate);
        const ViewProjection view = vp->viewProjection();
        const QPoint from = view.project(c + glm::dvec3(r, 0, 0))->toPoint();
        const QPoint to = view.project(c + glm::dvec3(0, r, 0))->toPoint();
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, from);
        QVERIFY(vp->isDragging());
        QTest::keyPress(vp, Qt::Key_Z);
        QTest::mouseMove(vp, to);
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::ControlModifier | Qt::ShiftModifier, to);
        QTest::keyRelease(vp, Qt::Key_Z);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Rotate surface 90° about z"));
        const glm::dmat4 quarter =
            glm::translate(glm::dmat4(1.0), c) *
            glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 0, 1)) *
            glm::translate(glm::dmat4(1.0), -c);
        const NurbsSurface& turned = scene().surfaces.front().geometry;
        double worst = 0.0;
        for (size_t k = 0; k < before.points.size(); ++k) {
            const glm::dvec3 p = before.points[k] - c;
            // Exactly a quarter turn about the vertical through the pivot.
            const glm::dvec3 expected = c + glm::dvec3(-p.y, p.x, p.z);
            worst = std::max(worst, glm::length(turned.points[k] - expected));
            worst = std::max(worst,
                             glm::length(turned.points[k] -
                                         glm::dvec3(quarter * glm::dvec4(before.points[k], 1.0))));
        }
        QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
        QCOMPARE(turned.weights, before.weights);
        QCOMPARE(turned.knotsU, before.knotsU);
        m_window->undoStack()->undo();
        QCOMPARE(scene().surfaces.front().geometry, before);
        QCOMPARE(m_window->undoStack()->count(), 1);

        // Without an axis the rotation is about the view direction, by the cursor's turn.
        const QPoint pc = view.project(c)->toPoint();
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, pc + QPoint(60, 0));
        QTest::mouseMove(vp, pc + QPoint(0, -60));
        double angle = 0.0;
        vp->surfaceDragMatrix(&angle);
        QVERIFY2(std::abs(angle - glm::radians(90.0)) < glm::radians(2.0),
                 qPrintable(QString::number(glm::degrees(angle))));
        // Esc cancels: the points are back, no step.
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(!vp->isDragging());
        QCOMPARE(scene().surfaces.front().geometry, before);
        QCOMPARE(m_window->undoStack()->count(), 1);

        // S: Ctrl + drag scales, from 60 to 120 pixels off the pivot (Shift snaps to 0.1): x2.
        key(Qt::Key_S);
        QCOMPARE(vp->surfaceDrag(), Viewport::SurfaceDrag::Scale);
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, pc + QPoint(60, 0));
        QTest::mouseMove(vp, pc + QPoint(120, 0));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::ControlModifier | Qt::ShiftModifier,
                            pc + QPoint(120, 0));
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Scale surface ×2"));
        const NurbsSurface& scaled = scene().surfaces.front().geometry;
        for (size_t k = 0; k < before.points.size(); ++k)
            QVERIFY(glm::length(scaled.points[k] - (c + 2.0 * (before.points[k] - c))) < 1e-12);
        // With X held, along x only.
        m_window->undoStack()->undo();
        QTest::mousePress(vp, Qt::LeftButton, Qt::ControlModifier, pc + QPoint(60, 0));
        QTest::keyPress(vp, Qt::Key_X);
        QTest::mouseMove(vp, pc + QPoint(90, 0));
        QTest::mouseRelease(vp, Qt::LeftButton, Qt::ControlModifier | Qt::ShiftModifier,
                            pc + QPoint(90, 0));
        QTest::keyRelease(vp, Qt::Key_X);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Scale surface ×1.5 along x"));
        const NurbsSurface& stretched = scene().surfaces.front().geometry;
        for (size_t k = 0; k < before.points.size(); ++k) {
            const glm::dvec3 d = before.points[k] - c;
            QVERIFY(glm::length(stretched.points[k] - (c + glm::dvec3(1.5 * d.x, d.y, d.z))) <
                    1e-12);
        }
        // G: back to moving.
        key(Qt::Key_G);
        QCOMPARE(vp->surfaceDrag(), Viewport::SurfaceDrag::Move);
    }

    void curveToolPreviewFollowsThePointsAndTheMode() {
        // The preview is solved once per change, not per repaint; each change must rebuild it.
        openWindow();
        Viewport* vp = m_window->viewport();
        CurveTool* tool = m_window->modelingTools()->curveTool();
        act("actionViewTop")->trigger();
        act("actionDrawExtrude")->trigger();
        const QPoint c(vp->width() / 2, vp->height() / 2);
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, c + QPoint(-100, 30));
        QVERIFY(tool->preview().points.empty()); // one point: no curve
        for (const QPoint d : {QPoint(0, -40), QPoint(90, 20), QPoint(150, -30)})
            QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, c + d);
        vp->grabFramebuffer(); // paints with the preview
        const NurbsCurve3 four = tool->preview();
        QCOMPARE(four, tool->curveThrough(tool->points()).value());
        QVERIFY(!four.points.empty());
        QTest::keyClick(vp, Qt::Key_Backspace);
        QCOMPARE(tool->preview(), tool->curveThrough(tool->points()).value());
        QVERIFY(!(tool->preview() == four));
        tool->setInterpolating(false);
        QCOMPARE(tool->preview(), controlPointCurve3(tool->points(), 3));
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(tool->preview().points.empty());
    }

    void curveToolInterpolatesTheClickedPoints() {
        openWindow();
        Viewport* vp = m_window->viewport();
        ModelingTools* tools = m_window->modelingTools();
        ModelingTools::Prompts prompts;
        glm::dvec3 extrusion(0.0, 0.0, 0.5);
        int asked = 0;
        bool drawnFlag = true;
        prompts.curveOperation = [&](QWidget*, ModelingTools::CurveOperationKind,
                                     const ModelingTools::CurveOperation& init) {
            ++asked;
            ModelingTools::CurveOperation op = init;
            drawnFlag = drawnFlag && init.drawnCurves; // the dialog is told the curves are drawn
            op.vector = extrusion;
            op.point = glm::dvec3(0.0);
            return std::optional<ModelingTools::CurveOperation>(op);
        };
        tools->setPrompts(prompts);
        act("actionViewTop")->trigger();

        // Extrude: five clicks, Enter. The curve passes through the clicked points.
        act("actionDrawExtrude")->trigger();
        QCOMPARE(vp->tool(), static_cast<Tool*>(tools->curveTool()));
        const QPoint c(vp->width() / 2, vp->height() / 2);
        const QPoint clicks[] = {c + QPoint(-200, 40), c + QPoint(-110, -60), c + QPoint(-10, 10),
                                 c + QPoint(90, -80), c + QPoint(190, 30)};
        std::vector<glm::dvec3> q;
        for (const QPoint& p : clicks) {
            q.push_back(onPlane(p));
            QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, p);
        }
        QCOMPARE(tools->curveTool()->points().size(), size_t(5));
        QVERIFY(scene().surfaces.empty()); // clicks are no edits
        QTest::keyClick(vp, Qt::Key_Return);
        QCOMPARE(asked, 1);
        QVERIFY(drawnFlag);
        QVERIFY(!vp->tool());
        QCOMPARE(scene().surfaces.size(), size_t(1));
        QCOMPARE(m_window->undoStack()->count(), 1);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Create extrusion"));
        const NurbsSurface& ex = scene().surfaces.front().geometry;
        QCOMPARE(ex.degreeU, 3);
        const std::vector<double> t = chordParameters(q);
        double worst = 0.0;
        for (size_t k = 0; k < q.size(); ++k) {
            worst = std::max(worst, glm::length(surfacePoint(ex, t[k], 0.0) - q[k]));
            worst = std::max(worst, glm::length(surfacePoint(ex, t[k], 1.0) - (q[k] + extrusion)));
        }
        qInfo("extrusion through 5 clicked points: worst distance %.3g", worst);
        QVERIFY2(worst < 1e-9, qPrintable(QString::number(worst)));
        m_window->undoStack()->undo();
        QVERIFY(scene().surfaces.empty());

        // Backspace takes back a point; Esc cancels without an edit.
        act("actionDrawRevolve")->trigger();
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, clicks[0]);
        QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, clicks[1]);
        QTest::keyClick(vp, Qt::Key_Backspace);
        QCOMPARE(tools->curveTool()->points().size(), size_t(1));
        QTest::keyClick(vp, Qt::Key_Escape);
        QVERIFY(!vp->tool());
        QCOMPARE(asked, 1);
        QCOMPARE(m_window->undoStack()->count(), 1); // only the undone extrusion

        // Control-point curves: the clicked points are the profile's control polygon.
        act("actionCurveInterpolates")->trigger();
        QVERIFY(!tools->curveTool()->interpolating());
        act("actionDrawRevolve")->trigger();
        std::vector<glm::dvec3> profile;
        for (int k = 0; k < 4; ++k) {
            profile.push_back(onPlane(clicks[k + 1]));
            QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, clicks[k + 1]);
        }
        QTest::keyClick(vp, Qt::Key_Enter);
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Create revolution"));
        const NurbsSurface& rev = scene().surfaces.front().geometry;
        QCOMPARE(rev.countV, 4);
        for (int j = 0; j < 4; ++j)
            QVERIFY(glm::length(rev.points[size_t(rev.index(0, j))] - profile[size_t(j)]) < 1e-12);
        act("actionCurveInterpolates")->trigger();

        // Loft: two curves (Enter after each), Enter again lofts; each curve is a section.
        act("actionDrawLoft")->trigger();
        std::vector<glm::dvec3> a, b;
        for (int k = 0; k < 4; ++k) {
            const QPoint p = clicks[k] + QPoint(0, -150), p2 = clicks[k + 1] + QPoint(0, 120);
            a.push_back(onPlane(p));
            QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, p);
            Q_UNUSED(p2);
        }
        QTest::keyClick(vp, Qt::Key_Return);
        QCOMPARE(tools->curveTool()->curves().size(), size_t(1));
        for (int k = 0; k < 4; ++k) {
            const QPoint p = clicks[k + 1] + QPoint(0, 120);
            b.push_back(onPlane(p));
            QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, p);
        }
        QTest::keyClick(vp, Qt::Key_Return);
        QCOMPARE(scene().surfaces.size(), size_t(1)); // not yet: Enter again lofts
        QTest::keyClick(vp, Qt::Key_Return);
        QCOMPARE(scene().surfaces.size(), size_t(2));
        QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Create loft through 2 curves"));
        const NurbsSurface& loft = scene().surfaces.back().geometry;
        const std::vector<double> ta = chordParameters(a), tb = chordParameters(b);
        worst = 0.0;
        for (size_t k = 0; k < 4; ++k) {
            worst = std::max(worst, glm::length(surfacePoint(loft, ta[k], 0.0) - a[k]));
            worst = std::max(worst, glm::length(surfacePoint(loft, tb[k], 1.0) - b[k]));
        }
        QVERIFY2(worst < 1e-9, qPrintable(QString::number(worst)));
        QCOMPARE(scene().surfaces.back().id, m_window->selection()->currentSurface());
    }

    // View > Adaptive Partitions switches the view, is saved with the project (format 1.1
    // "display") and restored on Open; a project without it follows the preference.
    void partitionModeIsSavedWithTheProject() {
        openWindow("bicubic");
        Viewport* vp = m_window->viewport();
        QAction* adaptive = act("actionAdaptivePartitions");
        QVERIFY(adaptive && adaptive->isCheckable());
        adaptive->setChecked(true);
        QCOMPARE(vp->partitioning(), RenderOptions::Partitioning::Adaptive);
        QTest::qWait(50);
        QVERIFY(vp->lastFrameReport().partitions.worstBoundPixels <= 0.5);
        adaptive->setChecked(false);
        QCOMPARE(vp->partitioning(), RenderOptions::Partitioning::Uniform);
        QVERIFY(m_window->undoStack()->isClean()); // a view setting, not an edit
        const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/display_uniform.knot");
        QVERIFY(m_window->saveFile(path));
        const auto saved = readKnotFile(path);
        QVERIFY2(saved, qPrintable(saved.message()));
        QCOMPARE(saved->display.partitionMode, QStringLiteral("uniform"));
        // The preference says adaptive; the project says uniform and wins on Open.
        adaptive->setChecked(true);
        QVERIFY(m_window->openFile(path));
        QCOMPARE(vp->partitioning(), RenderOptions::Partitioning::Uniform);
        QVERIFY(!adaptive->isChecked());
        // A project without display settings follows the preference (adaptive).
        QVERIFY(m_window->openFile(samplePath("bicubic")));
        QCOMPARE(vp->partitioning(), RenderOptions::Partitioning::Adaptive);
        QVERIFY(adaptive->isChecked());
    }
};

QTEST_MAIN(TestModelingTools)
#include "tst_modeling_tools.moc"
