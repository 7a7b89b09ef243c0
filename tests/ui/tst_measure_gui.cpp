// The editor's Measure menu on the unit sphere sample (label gui, Xvfb): the probe under the
// cursor and held P, distance, angle and radius dimensions against the exact ray hits, and the
// Properties panel's measured face and model.
#include "editor_test_util.h"
#include "model/document/selection.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/offscreen_renderer.h"
#include "ui/measure_properties.h"
#include "ui/probe_tool.h"

#include <QClipboard>
#include <QCursor>
#include <QFrame>
#include <QRegularExpression>
#include <QSignalSpy>
#include <algorithm>
#include <cmath>
#include <numbers>

using namespace kw;

class TestMeasureGui : public kwtest::EditorTestBase {
    Q_OBJECT
public:
    static void initMain() {
        QSurfaceFormat::setDefaultFormat(OffscreenRenderer::requiredFormat());
    }

private Q_SLOTS:
    void cleanup() { closeWindow(); }
    void probe();
    void probeWhileHoldingP();
    void probeCost();
    void measureModeIsTheViewsTool();
    void measureDistance();
    void measureAngle();
    void measureAngleBetweenPlanes();
    void measureRadius();
    void propertiesPanel();

private:
    ProbeTool* tool() const { return m_window->viewport()->findChild<ProbeTool*>(); }
    /// A widget pixel of the sample's unit sphere: the centre's projection moved by `offset`
    /// times the sphere's apparent radius.
    QPoint onSphere(QPointF offset) const {
        const ViewProjection view = m_window->viewport()->viewProjection();
        const QPointF c = *view.project(glm::dvec3(0.0));
        const QPointF edge =
            *view.project(glm::dvec3(0.0) + 0.9 * glm::cross(view.forward(), glm::dvec3(0, 0, 1)));
        const double r = std::hypot(edge.x() - c.x(), edge.y() - c.y());
        return (c + offset * r).toPoint();
    }
    /// The exact hit of the ray through the centre of pixel `at` with the unit sphere.
    glm::dvec3 exactHit(QPoint at) const {
        glm::dvec3 o, d;
        m_window->viewport()->viewProjection().ray(QPointF(at) + QPointF(0.5, 0.5), o, d);
        const double b = glm::dot(o, d), disc = b * b - (glm::dot(o, o) - 1.0);
        return disc >= 0 ? o + (-b - std::sqrt(disc)) * d : glm::dvec3(NAN);
    }
};

// A hover at `at`: the X pointer is put there too, so that the display's own pointer (left
// wherever an earlier window had it) sends no Leave that ends the hover.
static void hover(QWidget* widget, QPoint at) {
    QCursor::setPos(widget->mapToGlobal(at));
    QTest::mouseMove(widget, at);
}

// Probe over the sphere: K = k1 = k2 = 1 within 1e-9, the point on the pixel's ray and on the
// sphere, the panel shown with its text, Copy puts it on the clipboard; over background nothing.
void TestMeasureGui::probe() {
    openWindow("sphere");
    QVERIFY(tool());
    act("actionProbe")->trigger();
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Probe);
    QVERIFY(m_window->viewport()->hasMouseTracking());
    for (QPointF offset : {QPointF(0, 0), QPointF(0.4, -0.3), QPointF(-0.6, 0.5)}) {
        const QPoint at = onSphere(offset);
        hover(m_window->viewport(), at);
        QTRY_VERIFY(tool()->lastProbe().has_value());
        const ProbePoint p = *tool()->lastProbe();
        const glm::dvec3 exact = exactHit(at);
        QVERIFY2(glm::distance(p.point, exact) < 1e-12,
                 qPrintable(QStringLiteral("%1").arg(glm::distance(p.point, exact))));
        QVERIFY2(std::abs(p.gaussian - 1.0) < 1e-9, qPrintable(QString::number(p.gaussian)));
        QVERIFY(std::abs(p.k1 - 1.0) < 1e-9 && std::abs(p.k2 - 1.0) < 1e-9);
        QVERIFY(glm::distance(p.normal, exact) < 1e-9);
        QVERIFY(tool()->panel()->isVisible());
        QVERIFY(tool()->panelText().contains(QStringLiteral("K: 1")));
        QVERIFY(tool()->panelText().contains(QStringLiteral("surface: Unit sphere")));
        // The document's unit (mm unless the file said otherwise) follows every length.
        QVERIFY2(tool()->panelText().contains(
                     QRegularExpression(QStringLiteral("x, y, z: [^\n]* mm\n"))),
                 qPrintable(tool()->panelText()));
        qInfo("probe update %.3f ms (pick and panel), %.4f ms after the pick",
              tool()->lastUpdateMs(), tool()->lastRefineMs());
    }
    // The panel stays where it is, and keeps its values while the cursor goes to its Copy.
    const QPoint panelAt = tool()->panel()->pos();
    const QString shown = tool()->panelText();
    hover(tool()->panel(), tool()->panel()->rect().center());
    QTest::qWait(20);
    QCOMPARE(tool()->panel()->pos(), panelAt);
    QCOMPARE(tool()->panelText(), shown);
    QVERIFY(tool()->panel()->isVisible());
    QVERIFY(tool()->copyProbe());
    QCOMPARE(QApplication::clipboard()->text(), tool()->panelText());
    // Ctrl+C over the view copies it too.
    QApplication::clipboard()->clear();
    activate();
    m_window->viewport()->setFocus();
    QTest::keyClick(m_window->viewport(), Qt::Key_C, Qt::ControlModifier);
    QTRY_COMPARE(QApplication::clipboard()->text(), tool()->panelText());
    // Background: a corner of the view.
    hover(m_window->viewport(), QPoint(3, 3));
    QTRY_VERIFY(!tool()->lastProbe().has_value());
    QVERIFY(!tool()->panel()->isVisible());
    QVERIFY(tool()->panelText().isEmpty());
    QVERIFY(!tool()->copyProbe());
    // Opening a document drops the probe and the dimensions.
    act("actionMeasureRadius")->trigger();
    QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier, onSphere({0, 0}));
    QCOMPARE(tool()->measureTool()->measurements().size(), size_t(1));
    QVERIFY(m_window->openFile(kwtest::samplePath("torus")));
    QVERIFY(tool()->measureTool()->measurements().empty());
    act("actionProbe")->trigger();
    act("actionProbe")->trigger();
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Off);
}

// Holding P probes without the tool; releasing it hides the panel.
void TestMeasureGui::probeWhileHoldingP() {
    openWindow("sphere");
    activate();
    Viewport* vp = m_window->viewport();
    vp->setFocus();
    QCursor::setPos(vp->mapToGlobal(onSphere(QPointF(0.2, 0.1))));
    QTRY_COMPARE(vp->mapFromGlobal(QCursor::pos()), onSphere(QPointF(0.2, 0.1)));
    QTest::keyPress(vp, Qt::Key_P);
    QVERIFY(tool()->probeHeld());
    QVERIFY(tool()->lastProbe().has_value());
    QVERIFY(std::abs(tool()->lastProbe()->k1 - 1.0) < 1e-9);
    QVERIFY(tool()->panel()->isVisible());
    // Hover moves (what the pointer sends with tracking on) update it.
    QVERIFY(vp->hasMouseTracking());
    const auto hover = [vp](QPoint at) {
        QMouseEvent move(QEvent::MouseMove, at, vp->mapToGlobal(at), Qt::NoButton, Qt::NoButton,
                         Qt::NoModifier);
        QCoreApplication::sendEvent(vp, &move);
    };
    hover(QPoint(3, 3));
    QVERIFY(!tool()->lastProbe().has_value());
    QVERIFY(!tool()->panel()->isVisible());
    hover(onSphere(QPointF(-0.2, 0.1)));
    QVERIFY(tool()->lastProbe().has_value());
    QTest::keyRelease(vp, Qt::Key_P);
    QVERIFY(!tool()->probeHeld());
    QVERIFY(!tool()->lastProbe().has_value());
    QVERIFY(!tool()->panel()->isVisible());
}

// A probe update picks one pixel and draws no frame of the view (its panel and marker are
// child widgets); its CPU time is printed (median over the hovers) and the part after the pick
// stays under 1 ms. Run: ctest -R tst_measure_gui -V | grep 'probe cost'.
void TestMeasureGui::probeCost() {
    openWindow("teapot");
    Viewport* vp = m_window->viewport();
    act("actionProbe")->trigger();
    // Let the still frames (progressive samples) finish.
    std::int64_t drawn = -1;
    for (int k = 0; k < 100 && drawn != vp->framesDrawn(); ++k) {
        drawn = vp->framesDrawn();
        QTest::qWait(400);
    }
    std::vector<double> wall, cpu, refine;
    const QRect r = vp->rect();
    // Two walks over the middle of the view (most hovers hit the teapot): the first shows the
    // panel and lets it grow to its values (which may draw a frame), the second is measured.
    for (int walk = 0; walk < 2; ++walk) {
        if (walk == 1) {
            QTest::qWait(400);
            drawn = vp->framesDrawn();
        }
        for (int k = 0; k < 40; ++k) {
            const QPoint at(r.center().x() + (k % 8 - 4) * r.width() / 20,
                            r.center().y() + (k / 8 - 2) * r.height() / 14);
            QMouseEvent move(QEvent::MouseMove, at, vp->mapToGlobal(at), Qt::NoButton, Qt::NoButton,
                             Qt::NoModifier);
            QCoreApplication::sendEvent(vp, &move);
            QCoreApplication::processEvents();
            if (walk == 0 || !tool()->lastProbe())
                continue;
            QVERIFY2(vp->framesDrawn() == drawn, qPrintable(QStringLiteral("hover %1").arg(k)));
            // Every hit pixel answered by the frame on screen, those its forward pass drew too
            // (the teapot's large cells): no render of the pixel.
            QVERIFY2(vp->pickFromFrame(at).known, qPrintable(QStringLiteral("hover %1").arg(k)));
            wall.push_back(tool()->lastUpdateMs());
            cpu.push_back(tool()->lastUpdateCpuMs());
            refine.push_back(tool()->lastRefineMs());
        }
    }
    QCoreApplication::processEvents();
    QCOMPARE(vp->framesDrawn(), drawn); // no hover drew a frame
    QVERIFY(wall.size() >= 20);
    const auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    qInfo("probe cost (teapot, %dx%d, %zu hovers): wall %.3f ms, GUI thread CPU %.3f ms, "
          "after the pick %.4f ms (medians)",
          vp->width(), vp->height(), wall.size(), median(wall), median(cpu), median(refine));
}

// A Measure mode is the view's installed tool (it sees plain clicks first); Off gives the view
// back, and another installed tool (a curve drawing) turns the mode off.
void TestMeasureGui::measureModeIsTheViewsTool() {
    openWindow("sphere");
    Viewport* vp = m_window->viewport();
    QCOMPARE(vp->tool(), nullptr);
    act("actionMeasureDistance")->trigger();
    QCOMPARE(vp->tool(), static_cast<Tool*>(tool()));
    act("actionMeasureDistance")->trigger();
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Off);
    QCOMPARE(vp->tool(), nullptr);
    act("actionMeasureAngle")->trigger();
    act("actionDrawExtrude")->trigger();
    QVERIFY(vp->tool() != nullptr && vp->tool() != static_cast<Tool*>(tool()));
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Off);
    QVERIFY(!act("actionMeasureAngle")->isChecked());
    // The curve tool has the clicks now: no measurement.
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, onSphere({0, 0}));
    QVERIFY(!tool()->measureTool()->hasPending());
}

// Two clicks give a distance equal to the exact hits' within 1e-9 of the model size, with dx,
// dy, dz in its label; the clicks select nothing and push no undo step; the dimension stays
// until cleared; Esc drops a half-made one.
void TestMeasureGui::measureDistance() {
    openWindow("sphere");
    Viewport* vp = m_window->viewport();
    act("actionMeasureDistance")->trigger();
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Distance);
    m_window->selection()->itemSelection()->clear();
    QVERIFY(m_window->selection()->selectedSurfaces().empty());
    const int undoSteps = m_window->undoStack()->count();
    const QPoint a = onSphere(QPointF(-0.5, -0.2)), b = onSphere(QPointF(0.45, 0.35));
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, a);
    QVERIFY(tool()->measureTool()->hasPending());
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, b);
    QCOMPARE(tool()->measureTool()->measurements().size(), size_t(1));
    const Measurement m = tool()->measureTool()->measurements()[0];
    QCOMPARE(m.kind, Measurement::Kind::Distance);
    const double size = 2.0 * std::sqrt(3.0); // the sphere's box diagonal
    const double exact = glm::distance(exactHit(a), exactHit(b));
    QVERIFY2(std::abs(measurementValue(m) - exact) <= 1e-9 * size,
             qPrintable(QStringLiteral("%1 vs %2")
                            .arg(measurementValue(m), 0, 'g', 17)
                            .arg(exact, 0, 'g', 17)));
    const glm::dvec3 d = exactHit(b) - exactHit(a);
    QVERIFY(std::abs((m.b.point - m.a.point).z - d.z) < 1e-9 * size);
    const QString label = tool()->measureTool()->labels().value(0);
    QVERIFY2(label.startsWith(QStringLiteral("distance ")) &&
                 label.contains(QStringLiteral("dx ")) && label.contains(QStringLiteral("dz ")),
             qPrintable(label));
    QVERIFY(m_window->selection()->selectedSurfaces().empty());
    QCOMPARE(m_window->undoStack()->count(), undoSteps);
    QVERIFY(!m_window->isWindowModified());
    // The dimension stays while the view moves and the tool changes.
    vp->setStandardView(StandardView::Top);
    act("actionProbe")->trigger();
    QCOMPARE(tool()->measureTool()->measurements().size(), size_t(1));
    // Esc drops a half-made measurement first, then leaves the mode.
    act("actionMeasureDistance")->trigger();
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, onSphere(QPointF(0, 0)));
    QVERIFY(tool()->measureTool()->hasPending());
    QTest::keyClick(vp, Qt::Key_Escape);
    QVERIFY(!tool()->measureTool()->hasPending());
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Distance);
    QTest::keyClick(vp, Qt::Key_Escape);
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Off);
    // A click on background measures nothing.
    act("actionMeasureDistance")->trigger();
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, QPoint(3, 3));
    QVERIFY(!tool()->measureTool()->hasPending());
    act("actionClearMeasurements")->trigger();
    QVERIFY(tool()->measureTool()->measurements().empty());
}

// The angle between the normals at two clicked points is the angle their exact hits make at
// the sphere's centre.
void TestMeasureGui::measureAngle() {
    openWindow("sphere");
    act("actionMeasureAngle")->trigger();
    QCOMPARE(tool()->mode(), ProbeTool::Mode::Angle);
    const QPoint a = onSphere(QPointF(-0.6, 0.1)), b = onSphere(QPointF(0.5, -0.4));
    QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier, a);
    QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier, b);
    QCOMPARE(tool()->measureTool()->measurements().size(), size_t(1));
    const Measurement m = tool()->measureTool()->measurements()[0];
    QCOMPARE(m.kind, Measurement::Kind::Angle);
    const double expected =
        glm::degrees(std::acos(glm::dot(glm::normalize(exactHit(a)), glm::normalize(exactHit(b)))));
    QVERIFY2(std::abs(measurementValue(m) - expected) < 1e-7,
             qPrintable(QStringLiteral("%1 vs %2").arg(measurementValue(m)).arg(expected)));
    QVERIFY(expected > 20.0);
    QVERIFY(tool()->measureTool()->labels().value(0).contains(QStringLiteral("° between normals")));
}

// Two plane faces meeting at 60 degrees (a roof seen from the front): the angle between their
// normals is the angle between the faces, and the label says so.
void TestMeasureGui::measureAngleBetweenPlanes() {
    openWindow();
    Scene roof;
    const double c = std::cos(std::numbers::pi / 3), s = std::sin(std::numbers::pi / 3);
    for (int k = 0; k < 2; ++k) {
        Surface f;
        f.id = SurfaceId{std::uint32_t(k + 1)};
        f.name = k == 0 ? QStringLiteral("left") : QStringLiteral("right");
        // Both planes leave the ridge line x = 0, z = 1 downwards, one to -x, one to +x.
        const double side = k == 0 ? -1.0 : 1.0;
        f.geometry =
            makePlane(glm::dvec3(0, -1, 1), glm::dvec3(0, 2, 0), glm::dvec3(side * s, 0, -c));
        roof.surfaces.push_back(f);
    }
    roof.nextId = 3;
    QVERIFY(m_window->document()->resetScene(roof));
    m_window->viewport()->resetCamera();
    m_window->viewport()->setStandardView(StandardView::Front);
    QTest::qWait(50);
    const ViewProjection view = m_window->viewport()->viewProjection();
    const QPoint a = view.project(glm::dvec3(-0.5 * s, 0, 1 - 0.5 * c))->toPoint();
    const QPoint b = view.project(glm::dvec3(0.5 * s, 0, 1 - 0.5 * c))->toPoint();
    act("actionMeasureAngle")->trigger();
    QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier, a);
    QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier, b);
    QCOMPARE(tool()->measureTool()->measurements().size(), size_t(1));
    const Measurement m = tool()->measureTool()->measurements()[0];
    QVERIFY(m.a.surface != m.b.surface);
    // Su x Sv is (-cos 60, 0, sin 60) on the left face and (-cos 60, 0, -sin 60) on the right:
    // 120 degrees apart, the faces' angle measured across the ridge's outside.
    const double angle = measurementValue(m);
    QVERIFY2(std::abs(angle - 120.0) < 1e-9, qPrintable(QString::number(angle, 'g', 17)));
    QVERIFY(m.betweenPlanes);
    QVERIFY2(
        tool()->measureTool()->labels().value(0).contains(QStringLiteral("between plane faces")),
        qPrintable(tool()->measureTool()->labels().value(0)));
}

void TestMeasureGui::measureRadius() {
    openWindow("sphere");
    act("actionMeasureRadius")->trigger();
    QTest::mouseClick(m_window->viewport(), Qt::LeftButton, Qt::NoModifier,
                      onSphere(QPointF(0.3, 0.3)));
    QCOMPARE(tool()->measureTool()->measurements().size(), size_t(1));
    QVERIFY(std::abs(measurementValue(tool()->measureTool()->measurements()[0]) - 1.0) < 1e-9);
}

// Properties shows the current face's type, degrees, area and box, and the model's totals.
void TestMeasureGui::propertiesPanel() {
    openWindow("sphere");
    auto* props = m_window->findChild<MeasuredProperties*>();
    QVERIFY(props);
    m_window->selectSurface(scene().surfaces[0].id);
    QTRY_VERIFY(!props->pending());
    QVERIFY2(props->faceText().contains(QStringLiteral("type sphere, degree 2 × 2")),
             qPrintable(props->faceText()));
    QVERIFY2(props->faceText().contains(QStringLiteral(" mm²")), qPrintable(props->faceText()));
    QVERIFY2(props->faceText().contains(QStringLiteral("area 12.56637061")),
             qPrintable(props->faceText()));
    QVERIFY(props->faceText().contains(QStringLiteral("size 2 × 2 × 2")));
    QVERIFY2(props->modelText().contains(QStringLiteral("volume none")),
             qPrintable(props->modelText()));
    QVERIFY(props->modelText().contains(QStringLiteral("area 12.56637061")));
    m_window->selection()->itemSelection()->clear();
    QTRY_VERIFY(!props->pending());
    QVERIFY(props->faceText().contains(QStringLiteral("no surface selected")));
    QCOMPARE(props->facesMeasured(), 1); // the selection changes measured nothing again

    // An edit measures again only the face it changed: the teapot's 32 faces, then one.
    QVERIFY(m_window->openFile(kwtest::samplePath("teapot")));
    QTRY_VERIFY(!props->pending());
    QCOMPARE(props->facesMeasured(), 1 + 32);
    const QString before = props->modelText();
    const Surface& s = scene().surfaces[3];
    const glm::dvec3 moved = s.geometry.points[5] + glm::dvec3(0, 0, 0.25);
    QVERIFY(m_window->document()->setControlPoints(s.id, {5}, {moved}));
    QTRY_VERIFY(!props->pending());
    QCOMPARE(props->facesMeasured(), 1 + 32 + 1);
    QVERIFY2(props->modelText() != before, qPrintable(props->modelText()));
    // The totals are those of the whole edited model measured afresh.
    const ModelProperties fresh = modelProperties(scene());
    QVERIFY2(props->modelText().contains(QStringLiteral("area %1").arg(fresh.area, 0, 'g', 10)),
             qPrintable(props->modelText()));
}

QTEST_MAIN(TestMeasureGui)
#include "tst_measure_gui.moc"
