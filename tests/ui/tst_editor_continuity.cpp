// The editor's continuity tools (gui): the Edge Continuity overlay follows a control point
// dragged with the mouse across the G0 tolerance live, the status bar says what a drag opens
// with the overlay on or off, the tolerances (set in Preferences) change its classes, Keep Seams
// Closed keeps a dragged corner's seam shut as one undo step.
#include "editor_test_util.h"
#include "expected_test_util.h"
#include "model/analysis/continuity.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_construct.h"
#include "render/offscreen_renderer.h"
#include "render/render_types.h"
#include "ui/desktopactions.h"
#include "ui/edgecontinuity.h"
#include "ui/edit/commands.h"
#include "ui/preferences.h"

#include <QAction>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QHelpEvent>
#include <QSettings>
#include <QSignalSpy>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QToolTip>

using namespace kw;

namespace {

bool hasColour(const EdgeBands& bands, const glm::vec4& c) {
    return std::any_of(bands.vertices.begin(), bands.vertices.end(),
                       [&](const EdgeBandVertex& v) { return v.color == c; });
}

/// Two flat bicubic patches, 2 x 2, side by side along x (the shared edge at x = 1), and with
/// `far` two more far away along y sharing an edge of their own.
Scene patches(bool far) {
    Scene scene;
    for (double y : far ? std::vector<double>{0.0, 20.0} : std::vector<double>{0.0})
        for (double x : {0.0, 2.0}) {
            Surface s;
            s.id = SurfaceId{scene.nextId++};
            s.name = QStringLiteral("Patch %1").arg(s.id.value);
            s.geometry = makePatch({x, y, 0}, 3, 3, 5, 5, 2, 2);
            scene.surfaces.push_back(s);
        }
    return scene;
}

/// `n` x `n` flat bicubic patches, 2 x 2, edge to edge: more faces than the overlay measures at
/// once, so turning it on measures in the background.
Scene grid(int n) {
    Scene scene;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Surface s;
            s.id = SurfaceId{scene.nextId++};
            s.name = QStringLiteral("Patch %1").arg(s.id.value);
            s.geometry = makePatch({2.0 * i, 2.0 * j, 0}, 3, 3, 4, 4, 2, 2);
            scene.surfaces.push_back(s);
        }
    return scene;
}

/// Patch 2's control point (0, 2), on the shared edge's middle.
constexpr int kEdgePoint = 10;

} // namespace

class TestEditorContinuity : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        // Before QApplication: GL 4.5 core for every context, settings in the build tree.
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
        qputenv("XDG_CONFIG_HOME", QByteArrayLiteral(KW_TEST_OUTPUT_DIR "/continuity-config"));
    }

private Q_SLOTS:
    void initTestCase() {
        QCoreApplication::setOrganizationName(QStringLiteral("KnotworkContinuityTest"));
        QSettings().clear();
    }
    void init() {
        m_path = m_dir.filePath(QStringLiteral("patches.knot"));
        QString error;
        KW_VERIFY_OK(writeKnotFile(m_path, patches(false)));
        openWindow();
        QVERIFY(m_window->openFile(m_path));
        act("actionEdgeContinuity")->setChecked(true);
    }
    void cleanup() { closeWindow(); }
    void keepSeamsClosedIsOnByDefault();
    void overlayFollowsAMouseDragAcrossTheTolerance();
    void statusBarSaysWhatADragOpensWithTheOverlayOff();
    void tolerancesChangeTheClasses();
    void preferencesChangeTheClasses();
    void keepSeamsClosedIsOneUndoStep();
    void hoveringAnEdgeShowsItsValues();
    void aLargeModelIsMeasuredInTheBackground();
    void turningOffCancelsTheBackgroundMeasure();

private:
    /// Opens a grid(kGrid) with the overlay off (it pairs in the background).
    void openGrid();
    static constexpr int kGrid = 24;
    /// The view's pixel of model point `p`.
    QPoint pixelOf(const glm::dvec3& p) const;
    /// Model length of one pixel at `p` in the plane facing the camera (where a drag moves a
    /// point).
    double pixelSize(const glm::dvec3& p) const;
    /// Presses on patch 2's edge point (its net alone shown, so no twin can be picked).
    QPoint pressOnEdgePoint();

    QTemporaryDir m_dir;
    QString m_path;
};

QPoint TestEditorContinuity::pixelOf(const glm::dvec3& p) const {
    Viewport* vp = m_window->viewport();
    const CameraMatrices m = cameraMatrices(vp->cameraController().camera(), scene(),
                                            double(vp->width()) / vp->height());
    const glm::dvec4 c = m.projection * m.view * glm::dvec4(p, 1.0);
    return QPoint(int(std::lround((c.x / c.w * 0.5 + 0.5) * vp->width())),
                  int(std::lround((0.5 - c.y / c.w * 0.5) * vp->height())));
}

double TestEditorContinuity::pixelSize(const glm::dvec3& p) const {
    Viewport* vp = m_window->viewport();
    const Camera& c = vp->cameraController().camera();
    const double depth = glm::dot(p - c.eye, glm::normalize(c.target - c.eye));
    return 2.0 * depth * std::tan(glm::radians(c.fovYDegrees) * 0.5) / vp->height();
}

QPoint TestEditorContinuity::pressOnEdgePoint() {
    act("actionKeepSeamsClosed")->setChecked(false);
    act("actionControlNet")->setChecked(true);
    m_window->selectSurface(SurfaceId{2});
    Viewport* vp = m_window->viewport();
    const glm::dvec3 home =
        m_window->document()->surface(SurfaceId{2})->geometry.points[kEdgePoint];
    const QPoint press = pixelOf(home);
    const std::optional<ControlPointRef> picked = vp->controlPointAt(press);
    if (!picked || picked->surface != SurfaceId{2} || picked->i != 0 || picked->j != 2)
        return {};
    QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, press);
    return vp->isDragging() ? press : QPoint();
}

void TestEditorContinuity::keepSeamsClosedIsOnByDefault() {
    QVERIFY(act("actionKeepSeamsClosed")->isChecked());
    QVERIFY(!act("actionKeepTangency")->isChecked());
    QCOMPARE(m_window->document()->seamLink(), Document::SeamLink::Position);
}

// A control point on the shared edge dragged with the mouse: within the G0 tolerance (a few
// pixels) the band keeps a closed class, past it it turns red and the status bar says what
// opened; dragged back to where it was pressed it is G2 again, and the drag is one undo step.
void TestEditorContinuity::overlayFollowsAMouseDragAcrossTheTolerance() {
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    Document* doc = m_window->document();
    QVERIFY(overlay->enabled());
    QCOMPARE(int(overlay->report().edges.size()), 1);
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::G2);
    QVERIFY(hasColour(*overlay->bands(), continuityColor(ContinuityClass::G2)));
    QVERIFY(hasColour(*overlay->bands(), freeEdgeColor()));
    // G0 tolerance: six pixels' worth at the point, so a 2-pixel step stays within and a
    // 40-pixel one (the boundary moves by more than half the point's move) does not.
    const glm::dvec3 home = doc->surface(SurfaceId{2})->geometry.points[kEdgePoint];
    ContinuityTolerances t = doc->scene().continuity;
    t.g0 = 6.0 * pixelSize(home);
    t.match = std::max(t.match, t.g0);
    QVERIFY(doc->setContinuityTolerances(t));
    const QPoint press = pressOnEdgePoint();
    QVERIFY(!press.isNull());
    Viewport* vp = m_window->viewport();
    QTest::mouseMove(vp, press + QPoint(1, -1));
    QTest::mouseMove(vp, press + QPoint(2, -2));
    QVERIFY(doc->surface(SurfaceId{2})->geometry.points[kEdgePoint] != home);
    const EdgeContinuity& near = overlay->report().edges[0];
    QVERIFY2(near.continuity != ContinuityClass::Open && near.g0 > 0.0,
             qPrintable(QStringLiteral("gap %1 tolerance %2").arg(near.g0).arg(t.g0)));
    QVERIFY(hasColour(*overlay->bands(), continuityColor(near.continuity)));
    QVERIFY(!hasColour(*overlay->bands(), continuityColor(ContinuityClass::Open)));
    QTest::mouseMove(vp, press + QPoint(20, -20));
    QTest::mouseMove(vp, press + QPoint(40, -40));
    const EdgeContinuity& far = overlay->report().edges[0];
    QVERIFY2(far.continuity == ContinuityClass::Open,
             qPrintable(QStringLiteral("gap %1 tolerance %2").arg(far.g0).arg(t.g0)));
    QVERIFY(hasColour(*overlay->bands(), continuityColor(ContinuityClass::Open)));
    QVERIFY(!hasColour(*overlay->bands(), continuityColor(ContinuityClass::G2)));
    const QString message = m_window->statusBar()->currentMessage();
    QVERIFY2(message.contains(QStringLiteral("opens 1 seam, max gap ")) &&
                 message.endsWith(QLatin1Char(' ') + lengthUnitKey(doc->scene().unit)),
             qPrintable(message));
    QTest::mouseMove(vp, press);
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::G2);
    QTest::mouseMove(vp, press + QPoint(40, -40));
    QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(40, -40));
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::Open);
    QCOMPARE(m_window->undoStack()->count(), 1);
    m_window->undoStack()->undo();
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::G2);
    QVERIFY(hasColour(*overlay->bands(), continuityColor(ContinuityClass::G2)));
}

// With the overlay off the drag still says what it opens, measuring the dragged face's edges
// only: the far pair's edge is never measured, and no bands are made.
void TestEditorContinuity::statusBarSaysWhatADragOpensWithTheOverlayOff() {
    const QString path = m_dir.filePath(QStringLiteral("four.knot"));
    KW_VERIFY_OK(writeKnotFile(path, patches(true)));
    QVERIFY(m_window->openFile(path));
    act("actionEdgeContinuity")->setChecked(false);
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    QVERIFY(!overlay->enabled());
    // Paired once the event loop turns after the change, before any drag; none measured.
    QTRY_COMPARE(int(overlay->report().topology.edges.size()), 2);
    for (const EdgeContinuity& e : overlay->report().edges)
        QCOMPARE(e.samples, 0);
    m_window->statusBar()->clearMessage();
    const QPoint press = pressOnEdgePoint();
    QVERIFY(!press.isNull());
    Viewport* vp = m_window->viewport();
    QTest::mouseMove(vp, press + QPoint(20, -20));
    QTest::mouseMove(vp, press + QPoint(40, -40));
    const QString message = m_window->statusBar()->currentMessage();
    QVERIFY2(message.startsWith(QStringLiteral("This edit opens 1 seam, max gap ")),
             qPrintable(message));
    QVERIFY(!overlay->bands());
    const ContinuityReport& r = overlay->report();
    QCOMPARE(int(r.edges.size()), 2);
    int measured = 0;
    for (const EdgeContinuity& e : r.edges) {
        const bool dragged =
            e.edge.sides[0].surface == SurfaceId{2} || e.edge.sides[1].surface == SurfaceId{2};
        QCOMPARE(e.samples > 0, dragged);
        QCOMPARE(e.continuity == ContinuityClass::Open, dragged);
        measured += e.samples > 0;
    }
    QCOMPARE(measured, 1);
    QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, press + QPoint(40, -40));
    QCOMPARE(m_window->undoStack()->count(), 1);
}

// The tolerances saved with the project re-classify the edges.
void TestEditorContinuity::tolerancesChangeTheClasses() {
    act("actionKeepSeamsClosed")->setChecked(false);
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    Document* doc = m_window->document();
    const glm::dvec3 corner = doc->scene().surfaces[1].geometry.points[0];
    QVERIFY(doc->setControlPoints(SurfaceId{2}, {0}, {corner + glm::dvec3(0, 0, 0.004)}));
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::Open);
    ContinuityTolerances loose;
    loose.g0 = 0.005;
    loose.g1Degrees = 1.0;
    QVERIFY(doc->setContinuityTolerances(loose));
    QVERIFY(overlay->report().edges[0].continuity != ContinuityClass::Open);
    QVERIFY(!hasColour(*overlay->bands(), continuityColor(ContinuityClass::Open)));
    QCOMPARE(doc->scene().continuity, loose);
}

// Edit > Preferences edits the open project's tolerances (one undo step, saved with it) and the
// defaults for new projects (QSettings): loosening the project's G0 turns the open edge closed.
void TestEditorContinuity::preferencesChangeTheClasses() {
    act("actionKeepSeamsClosed")->setChecked(false);
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    Document* doc = m_window->document();
    const glm::dvec3 corner = doc->scene().surfaces[1].geometry.points[0];
    QVERIFY(doc->setControlPoints(SurfaceId{2}, {0}, {corner + glm::dvec3(0, 0, 0.004)}));
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::Open);
    const ContinuityTolerances before = doc->scene().continuity;
    bool focused = false;
    DesktopActions::Prompts prompts = DesktopActions::Prompts::standard();
    prompts.preferences = [&](QWidget*, const PreferencesEdit& current, bool focusContinuity) {
        // The real dialog, shown the project's tolerances and the defaults, edited as a user
        // would type into it.
        PreferencesDialog d(current);
        focused = focusContinuity;
        auto* g0 = d.findChild<QDoubleSpinBox*>(QStringLiteral("prefProjectG0"));
        auto* g1 = d.findChild<QDoubleSpinBox*>(QStringLiteral("prefProjectG1"));
        auto* defaultG0 = d.findChild<QDoubleSpinBox*>(QStringLiteral("prefDefaultG0"));
        if (!g0 || !g1 || !defaultG0 || g0->value() != current.project->g0)
            return std::optional<PreferencesEdit>();
        g0->setValue(0.005);
        g1->setValue(1.0);
        defaultG0->setValue(0.002);
        return std::optional(d.edit());
    };
    m_window->desktopActions()->setPrompts(prompts);
    // View > Analysis > Continuity Tolerances opens the same dialog, on the project's values.
    act("actionContinuityTolerances")->trigger();
    QVERIFY(focused);
    QCOMPARE(doc->scene().continuity.g0, 0.005);
    const ContinuityClass loose = overlay->report().edges[0].continuity;
    QVERIFY(loose != ContinuityClass::Open);
    QVERIFY(!hasColour(*overlay->bands(), continuityColor(ContinuityClass::Open)));
    QVERIFY(hasColour(*overlay->bands(), continuityColor(loose)));
    QCOMPARE(Preferences::load().continuity.g0, 0.002);
    QCOMPARE(m_window->undoStack()->undoText(), QStringLiteral("Set continuity tolerances"));
    m_window->undoStack()->undo();
    QCOMPARE(doc->scene().continuity, before);
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::Open);
    // The defaults are for new projects; the open one keeps its own.
    act("actionNew")->trigger();
    QCOMPARE(doc->scene().continuity.g0, 0.002);
    QSettings().remove(QStringLiteral("continuity"));
}

// With Keep Seams Closed (the default, the first test's window shows), the neighbour's coincident
// corner moves with the dragged one: the seam stays closed, and one undo restores both patches.
void TestEditorContinuity::keepSeamsClosedIsOneUndoStep() {
    act("actionKeepSeamsClosed")->setChecked(true);
    Document* doc = m_window->document();
    QCOMPARE(doc->seamLink(), Document::SeamLink::Position);
    const Scene before = doc->scene();
    const glm::dvec3 corner = before.surfaces[1].geometry.points[0];
    const glm::dvec3 to = corner + glm::dvec3(0.1, 0.05, 0.3);
    for (int k = 1; k <= 4; ++k)
        QVERIFY(doc->setControlPoints(SurfaceId{2}, {0}, {corner + (to - corner) * (k / 4.0)}));
    QVERIFY(pushCommand(m_window->undoStack(),
                        MoveControlPoints::create(doc, SurfaceId{2}, {0}, {corner}, {to})));
    const EdgeContinuity& e = m_window->edgeContinuity()->report().edges[0];
    QVERIFY2(e.g0 <= 1e-9, qPrintable(QString::number(e.g0)));
    QCOMPARE(m_window->undoStack()->count(), 1);
    m_window->undoStack()->undo();
    QVERIFY(doc->scene().surfaces == before.surfaces);
}

// The shared edge's midpoint, hovered: its class and three values in a tool tip.
void TestEditorContinuity::hoveringAnEdgeShowsItsValues() {
    Viewport* vp = m_window->viewport();
    const CameraMatrices m = cameraMatrices(vp->cameraController().camera(), scene(),
                                            double(vp->width()) / vp->height());
    const glm::dvec4 c = m.projection * m.view * glm::dvec4(1.0, 0.0, 0.0, 1.0);
    const QPoint at(int((c.x / c.w * 0.5 + 0.5) * vp->width()),
                    int((0.5 - c.y / c.w * 0.5) * vp->height()));
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    QCOMPARE(overlay->edgeAt(at), std::optional<size_t>(0));
    QVERIFY(!overlay->edgeAt(QPoint(2, 2)));
    QHelpEvent help(QEvent::ToolTip, at, vp->mapToGlobal(at));
    QApplication::sendEvent(vp, &help);
    QTRY_VERIFY(QToolTip::text().contains(QStringLiteral("G2 edge between surfaces 1 and 2")));
    QVERIFY(QToolTip::text().contains(QStringLiteral("G0 gap")));
    QVERIFY(QToolTip::text().contains(QStringLiteral("G1 angle")));
    QVERIFY(QToolTip::text().contains(QStringLiteral("G2 curvature jump")));
}

void TestEditorContinuity::openGrid() {
    act("actionKeepSeamsClosed")->setChecked(false);
    const QString path = m_dir.filePath(QStringLiteral("grid.knot"));
    KW_VERIFY_OK(writeKnotFile(path, grid(kGrid)));
    act("actionEdgeContinuity")->setChecked(false);
    QVERIFY(m_window->openFile(path));
    QVERIFY(int(scene().surfaces.size()) > EdgeContinuityOverlay::kForegroundFaces);
}

// Turning the overlay on for a model of hundreds of faces returns to the event loop at once,
// with the progress in the status bar; the bands appear once every edge is measured, and a face
// edited meanwhile (its revision newer than the copy measured) is measured as it is now.
void TestEditorContinuity::aLargeModelIsMeasuredInTheBackground() {
    openGrid();
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    QSignalSpy status(overlay, &EdgeContinuityOverlay::measureStatus);
    QElapsedTimer clock;
    clock.start();
    act("actionEdgeContinuity")->setChecked(true);
    const qint64 toggleMs = clock.elapsed();
    QVERIFY(overlay->measuring());
    QVERIFY(!overlay->bands());
    QVERIFY2(m_window->statusBar()->currentMessage().startsWith(
                 QStringLiteral("Measuring edge continuity…")),
             qPrintable(m_window->statusBar()->currentMessage()));
    // An edit before the measure is in: patch 1's far corner (shared by patches 2, 25 and 26,
    // whose corners stay: seams are not kept closed) lifted, so its edges with 2 and 25 open.
    Document* doc = m_window->document();
    const glm::dvec3 corner = doc->surface(SurfaceId{1})->geometry.points[15];
    QVERIFY(doc->setControlPoints(SurfaceId{1}, {15}, {corner + glm::dvec3(0, 0, 0.5)}));
    QVERIFY(!overlay->bands());
    QTRY_VERIFY_WITH_TIMEOUT(overlay->bands() != nullptr, 120000);
    const qint64 doneMs = clock.elapsed();
    qInfo("%d faces: the toggle returned in %lld ms, the bands came in %lld ms", kGrid * kGrid,
          toggleMs, doneMs);
    QVERIFY2(
        toggleMs * 4 < doneMs,
        qPrintable(QStringLiteral("toggle %1 ms, bands after %2 ms").arg(toggleMs).arg(doneMs)));
    QVERIFY(!overlay->measuring());
    const ContinuityReport& r = overlay->report();
    QCOMPARE(int(r.edges.size()), 2 * kGrid * (kGrid - 1));
    QCOMPARE(int(r.topology.freeSides.size()), 4 * kGrid);
    int open = 0;
    for (const EdgeContinuity& e : r.edges) {
        QVERIFY(e.samples > 0);
        const bool lifted =
            e.edge.sides[0].surface == SurfaceId{1} || e.edge.sides[1].surface == SurfaceId{1};
        QVERIFY2((e.continuity == ContinuityClass::Open) == lifted,
                 qPrintable(QStringLiteral("edge %1-%2 gap %3")
                                .arg(e.edge.sides[0].surface.value)
                                .arg(e.edge.sides[1].surface.value)
                                .arg(e.g0)));
        open += e.continuity == ContinuityClass::Open;
    }
    QCOMPARE(open, 2);
    QVERIFY(hasColour(*overlay->bands(), continuityColor(ContinuityClass::Open)));
    QCOMPARE(overlay->bands()->ranges.size(), r.edges.size() + r.topology.freeSides.size());
    // Progress was shown in edges, and the status bar no longer says it is measuring.
    const QString total = QStringLiteral(" of %1 edges").arg(r.edges.size());
    QVERIFY(std::any_of(status.begin(), status.end(), [&](const QList<QVariant>& args) {
        return args.at(0).toString().endsWith(total);
    }));
    QVERIFY(status.last().at(0).toString().isEmpty());
    QVERIFY(!m_window->statusBar()->currentMessage().startsWith(
        QStringLiteral("Measuring edge continuity…")));
}

// A second toggle while the measure runs drops it (nothing shows while off), and turning the
// overlay on again measures the document as it is then.
void TestEditorContinuity::turningOffCancelsTheBackgroundMeasure() {
    openGrid();
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    act("actionEdgeContinuity")->setChecked(true);
    QVERIFY(overlay->measuring());
    act("actionEdgeContinuity")->setChecked(false);
    QVERIFY(!overlay->measuring());
    QVERIFY(m_window->statusBar()->currentMessage().isEmpty());
    // Off, the status bar's pairing comes in; no band and no measured edge ever does.
    QTRY_COMPARE_WITH_TIMEOUT(int(overlay->report().topology.edges.size()), 2 * kGrid * (kGrid - 1),
                              60000);
    QTest::qWait(200);
    QVERIFY(!overlay->bands());
    for (const EdgeContinuity& e : overlay->report().edges)
        QCOMPARE(e.samples, 0);
    act("actionEdgeContinuity")->setChecked(true);
    QVERIFY(overlay->measuring());
    QTRY_VERIFY_WITH_TIMEOUT(overlay->bands() != nullptr, 120000);
    QCOMPARE(overlay->report().count(ContinuityClass::G2), 2 * kGrid * (kGrid - 1));
}

QTEST_MAIN(TestEditorContinuity)
#include "tst_editor_continuity.moc"
