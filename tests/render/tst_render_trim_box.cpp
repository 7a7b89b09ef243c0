// GL test: a trimmed surface's base polygon spans its trim loops' (u, v) box,
// so a small face on a large domain gets the partitions, not the part of the domain it leaves
// out. Measured against the CPU reference (render/reference_render.h): the screen normal error
// of a small disc on a sphere at 4 x 4 partitions. The polygon is rebuilt when a trim edit moves
// the box, and only then.
#include "expected_test_util.h"
#include "model/nurbs/nurbs_shapes.h"
#include "model/nurbs/visible_bounds.h"
#include "render/edge_metrics.h"
#include "render/gpu_layout.h"
#include "render/reference_render.h"
#include "render_test_util.h"

#include <QGuiApplication>

using namespace kw;

namespace {

/// A sphere whose trims keep a disc of radius 0.06 around (0.3, 0.55) of its unit domain.
Scene discOnSphere(int partitions) {
    Scene scene;
    Surface s = kwtest::makeSurface(1, makeSphere(glm::dvec3(0.0), 2.0), partitions);
    TrimLoop loop;
    loop.id = TrimLoopId{2};
    loop.curves.push_back(makeCircle2(glm::dvec2(0.3, 0.55), 0.06));
    s.trims.push_back(loop);
    scene.surfaces.push_back(s);
    return scene;
}

} // namespace

class TestRenderTrimBox : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(256, 256), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void polygonSpansTheTrimBox() {
        const Scene scene = discOnSphere(4);
        const Surface& s = scene.surfaces.front();
        const ParameterBox box = trimParameterBox(s);
        const BasePolygon poly = buildBasePolygon(s.geometry, box, 4, 4);
        QCOMPARE(poly.breaksU.front(), box.u.first);
        QCOMPARE(poly.breaksU.back(), box.u.last);
        QCOMPARE(poly.breaksV.front(), box.v.first);
        QCOMPARE(poly.breaksV.back(), box.v.last);
        // Interior knots inside the box still cut cells (the sphere's u knots are at quarters,
        // v's at 1/2: u = 1/4 and v = 1/2 lie in the box), and no break lies outside it.
        for (double k : s.geometry.knotsU)
            if (k > box.u.first && k < box.u.last)
                QVERIFY(std::find(poly.breaksU.begin(), poly.breaksU.end(), k) !=
                        poly.breaksU.end());
        for (double b : poly.breaksU)
            QVERIFY(b >= box.u.first && b <= box.u.last);
        QVERIFY(poly.cellsU() >= 4 && poly.cellsV() >= 4);
    }

    void smallFaceGetsThePartitions() {
        // At 4 x 4 over the whole domain the disc would lie in one or two flat cells; over the
        // trim box it gets 4 x 4 of its own. Screen normal error against the reference outside
        // the one-pixel edge band (render/edge_metrics.h).
        const Scene scene = discOnSphere(4);
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = fitCamera(scene, 1.0);
        KW_VERIFY_OK(m_renderer->render(doc, cam, RenderOptions{}));
        const AovBuffer frame = m_renderer->aov();
        const AovBuffer reference = renderReference(scene, cam, frame.width, frame.height);
        EdgeMetrics m;
        KW_VERIFY_OK(compareWithReference(frame, reference, 1e-3, m));
        qInfo("disc on a sphere at 4 x 4: %lld covered, normal error mean %.4f p99 %.4f max %.4f "
              "deg over %lld pixels; silhouette max %.2f px",
              m.covered, m.normalMeanDegrees, m.normalP99Degrees, m.normalMaxDegrees,
              m.normalPixels, m.silhouetteMaxPixels);
        QVERIFY(m.normalPixels > 10000);
        QVERIFY(m.normalP99Degrees < 0.5);
        QVERIFY(m.silhouetteMaxPixels <= 1.5);
    }

    void rebuiltOnlyWhenTheBoxMoves() {
        const Scene scene = discOnSphere(4);
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = fitCamera(scene, 1.0);
        const RenderOptions opt;
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        QCOMPARE(m_renderer->lastReport().uploads.basePolygonBuilds, 1);
        // Moving an interior control point of the circle outward grows the box: one rebuild.
        const SurfaceId sid{1};
        const TrimLoopId lid{2};
        QVERIFY(doc.setTrimPoint(TrimPointRef{sid, lid, 0, 2}, glm::dvec2(0.2, 0.75)));
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        QCOMPARE(m_renderer->lastReport().uploads.basePolygonBuilds, 1);
        // A move inside the box leaves it: no rebuild.
        const glm::dvec2 inside = doc.surface(sid)->trims.front().curves.front().points[4];
        QVERIFY(doc.setTrimPoint(TrimPointRef{sid, lid, 0, 4}, inside + glm::dvec2(0.01, 0.0)));
        QCOMPARE(trimParameterBox(*doc.surface(sid)), trimParameterBox([&] {
                     Surface before = *doc.surface(sid);
                     before.trims.front().curves.front().points[4] = inside;
                     return before;
                 }()));
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        QCOMPARE(m_renderer->lastReport().uploads.basePolygonBuilds, 0);
        // With trims off (and the polygon over the domain, as knotwork render --no-trims) the
        // whole surface shows: one rebuild, and far more of the view is covered.
        auto coveredPixels = [&] {
            const AovBuffer aov = m_renderer->aov();
            long n = 0;
            for (int y = 0; y < aov.height; ++y)
                for (int x = 0; x < aov.width; ++x)
                    n += aov.pixel(x, y)[0] >= 0.0f;
            return n;
        };
        const long trimmedCover = coveredPixels();
        RenderOptions untrimmed;
        untrimmed.trims = false;
        untrimmed.polygonOverTrims = false;
        KW_VERIFY_OK(m_renderer->render(doc, cam, untrimmed));
        QCOMPARE(m_renderer->lastReport().uploads.basePolygonBuilds, 1);
        QVERIFY(coveredPixels() > 2 * trimmedCover);
    }
};

QTEST_MAIN(TestRenderTrimBox)
#include "tst_render_trim_box.moc"
