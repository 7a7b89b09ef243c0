// The editor's continuity tools (gui): the Edge Continuity overlay follows edits of a point
// across the G0 tolerance live, the tolerances change its classes, Keep Seams Closed keeps a
// dragged corner's seam shut as one undo step.
#include "editor_test_util.h"
#include "expected_test_util.h"
#include "model/analysis/continuity.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_construct.h"
#include "render/offscreen_renderer.h"
#include "render/render_types.h"
#include "ui/edgecontinuity.h"
#include "ui/edit/commands.h"

#include <QAction>
#include <QHelpEvent>
#include <QSettings>
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
        Scene scene;
        for (double x : {0.0, 2.0}) {
            Surface s;
            s.id = SurfaceId{scene.nextId++};
            s.name = QStringLiteral("Patch %1").arg(s.id.value);
            s.geometry = makePatch({x, 0, 0}, 3, 3, 5, 5, 2, 2);
            scene.surfaces.push_back(s);
        }
        m_path = m_dir.filePath(QStringLiteral("patches.knot"));
        QString error;
        KW_VERIFY_OK(writeKnotFile(m_path, scene));
        openWindow();
        QVERIFY(m_window->openFile(m_path));
        act("actionEdgeContinuity")->setChecked(true);
    }
    void cleanup() { closeWindow(); }
    void keepSeamsClosedIsOnByDefault();
    void overlayFollowsAPointAcrossTheTolerance();
    void tolerancesChangeTheClasses();
    void keepSeamsClosedIsOneUndoStep();
    void hoveringAnEdgeShowsItsValues();

private:
    QTemporaryDir m_dir;
    QString m_path;
};

void TestEditorContinuity::keepSeamsClosedIsOnByDefault() {
    QVERIFY(act("actionKeepSeamsClosed")->isChecked());
    QVERIFY(!act("actionKeepTangency")->isChecked());
    QCOMPARE(m_window->document()->seamLink(), Document::SeamLink::Position);
}

// Point moves as a drag applies them (Document::setControlPoints per step): the band turns red
// past the G0 tolerance and the status bar says what opened; back, it is G2 again.
void TestEditorContinuity::overlayFollowsAPointAcrossTheTolerance() {
    act("actionKeepSeamsClosed")->setChecked(false);
    EdgeContinuityOverlay* overlay = m_window->edgeContinuity();
    QVERIFY(overlay->enabled());
    QCOMPARE(int(overlay->report().edges.size()), 1);
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::G2);
    QVERIFY(hasColour(*overlay->bands(), continuityColor(ContinuityClass::G2)));
    QVERIFY(hasColour(*overlay->bands(), freeEdgeColor()));
    Document* doc = m_window->document();
    const glm::dvec3 corner = doc->scene().surfaces[1].geometry.points[0];
    for (double d : {0.0002, 0.0006, 0.002, 0.004}) {
        QVERIFY(doc->setControlPoints(SurfaceId{2}, {0}, {corner + glm::dvec3(0, 0, d)}));
        const ContinuityClass c = overlay->report().edges[0].continuity;
        // Within G0 the lifted corner tilts and bends the seam (G1 or G0), past it it opens.
        if (d > 0.001)
            QCOMPARE(c, ContinuityClass::Open);
        else
            QVERIFY(c == ContinuityClass::G1 || c == ContinuityClass::G0);
        QVERIFY(hasColour(*overlay->bands(), continuityColor(c)));
        QVERIFY(!hasColour(*overlay->bands(), continuityColor(ContinuityClass::G2)));
    }
    QVERIFY2(m_window->statusBar()->currentMessage().contains(
                 QStringLiteral("opens 1 seam, max gap 0.004")),
             qPrintable(m_window->statusBar()->currentMessage()));
    QVERIFY(doc->setControlPoints(SurfaceId{2}, {0}, {corner}));
    QCOMPARE(overlay->report().edges[0].continuity, ContinuityClass::G2);
    QVERIFY(overlay->lastUpdateMs() >= 0.0);
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

QTEST_MAIN(TestEditorContinuity)
#include "tst_editor_continuity.moc"
