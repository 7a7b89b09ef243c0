// The Edge Continuity overlay on the GPU (render/edge_bands.h, EdgeBandsPass): the band drawn
// over each shared edge of a known G2 / G1 / G0 / open configuration has the colour of the
// class the continuity kernel gives it.
#include "expected_test_util.h"
#include "model/analysis/continuity.h"
#include "model/nurbs/nurbs_construct.h"
#include "render/edge_bands.h"
#include "render/offscreen_renderer.h"
#include "render_test_util.h"

#include <QTest>

using namespace kw;

namespace {

constexpr int kSide = 320;

/// A bicubic patch over [x0, x0 + 1] x [0, 1] with height z(x).
Surface patch(std::uint32_t id, double x0, const std::function<double(double)>& z) {
    NurbsSurface g;
    g.degreeU = g.degreeV = 3;
    g.countU = g.countV = 4;
    g.knotsU = g.knotsV = {0, 0, 0, 0, 1, 1, 1, 1};
    // z is at most quadratic in x, so control heights from its Bezier form: z at 0 and 1, and
    // the interior points of the cubic's degree-elevated quadratic.
    const double z0 = z(x0), zh = z(x0 + 0.5), z1 = z(x0 + 1.0);
    const double c = 2.0 * zh - 0.5 * (z0 + z1); // quadratic Bezier middle point
    const double heights[4] = {z0, (z0 + 2.0 * c) / 3.0, (2.0 * c + z1) / 3.0, z1};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            g.points.push_back({x0 + i / 3.0, j / 3.0, heights[i]});
    g.weights.assign(16, 1.0);
    Surface s;
    s.id = SurfaceId{id};
    s.name = QStringLiteral("Patch %1").arg(id);
    s.geometry = g;
    return s;
}

/// Four pairs side by side along x, each meeting along x = x0 + 1: flat-flat (G2), flat-
/// tangent parabola (G1), a 26.6 degree crease (G0), and flat-flat 0.004 apart (open).
Scene configuration() {
    Scene scene;
    const auto flat = [](double) {
        return 0.0;
    };
    std::uint32_t id = 1;
    for (int k = 0; k < 4; ++k) {
        const double x0 = 3.0 * k;
        scene.surfaces.push_back(patch(id++, x0, flat));
        std::function<double(double)> right = flat;
        if (k == 1)
            right = [x0](double x) {
                return 0.3 * (x - x0 - 1.0) * (x - x0 - 1.0);
            };
        else if (k == 2)
            right = [x0](double x) {
                return 0.5 * (x - x0 - 1.0);
            };
        else if (k == 3)
            right = [](double) {
                return 0.004;
            };
        scene.surfaces.push_back(patch(id++, x0 + 1.0, right));
    }
    scene.nextId = id;
    return scene;
}

Camera topCamera() {
    Camera c;
    c.eye = {5.5, 0.5, 30.0};
    c.target = {5.5, 0.5, 0.0};
    c.up = {0.0, 1.0, 0.0};
    c.fovYDegrees = 25.0;
    c.authored = true;
    return c;
}

double colourDistance(QRgb a, const glm::vec4& b) {
    return std::max({std::abs(qRed(a) / 255.0 - b.r), std::abs(qGreen(a) / 255.0 - b.g),
                     std::abs(qBlue(a) / 255.0 - b.b)});
}

} // namespace

class TestRenderEdgeBands : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), false);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }
    void bandColoursAreTheKernelsClasses();
    void bandsOffScreenAreLeftOut();
    void aDragStepRewritesOnlyTheDraggedFacesBands();

private:
    std::unique_ptr<OffscreenRenderer> m_renderer;
};

void TestRenderEdgeBands::bandColoursAreTheKernelsClasses() {
    const Scene scene = configuration();
    const ContinuityReport report = continuityReport(scene, {});
    QCOMPARE(int(report.edges.size()), 4);
    const ContinuityClass expected[4] = {ContinuityClass::G2, ContinuityClass::G1,
                                         ContinuityClass::G0, ContinuityClass::Open};
    Document doc;
    QString error;
    KW_VERIFY_OK(doc.resetScene(scene));
    RenderOptions options;
    auto bands = std::make_shared<EdgeBands>(makeEdgeBands(scene, report, 1));
    bands->widthPixels = 5.0f;
    options.edgeBands = bands;
    KW_VERIFY_OK(m_renderer->render(doc, topCamera(), options));
    const QImage image = m_renderer->colorImage();
    image.save(kwtest::outputDir().filePath(QStringLiteral("edge_bands.png")));
    const CameraMatrices m = cameraMatrices(topCamera(), scene, 1.0);
    for (const EdgeContinuity& e : report.edges) {
        const int pair = int(e.edge.sides[0].surface.value - 1) / 2;
        QCOMPARE(e.continuity, expected[pair]);
        // The edge's midpoint on screen (window y up, image rows down).
        const glm::dvec2 w = kwtest::windowPixels(m.projection * m.view,
                                                  {3.0 * pair + 1.0, 0.5, 0.0}, glm::dvec2(kSide));
        const QRgb pixel = image.pixel(int(w.x), kSide - 1 - int(w.y));
        const glm::vec4 want = continuityColor(e.continuity);
        QVERIFY2(colourDistance(pixel, want) < 0.08,
                 qPrintable(QStringLiteral("pair %1 (%2): pixel %3 at (%4, %5)")
                                .arg(pair)
                                .arg(continuityClassName(e.continuity))
                                .arg(QColor(pixel).name())
                                .arg(w.x)
                                .arg(w.y)));
        // And it is no other class's colour (the colours are told apart).
        for (ContinuityClass other : expected)
            if (other != e.continuity)
                QVERIFY(colourDistance(pixel, continuityColor(other)) > 0.2);
    }
    // Without the overlay, no band: the same pixel shows the surface.
    options.edgeBands.reset();
    KW_VERIFY_OK(m_renderer->render(doc, topCamera(), options));
    const QImage plain = m_renderer->colorImage();
    const glm::dvec2 w =
        kwtest::windowPixels(m.projection * m.view, {1.0, 0.5, 0.0}, glm::dvec2(kSide));
    QVERIFY(colourDistance(plain.pixel(int(w.x), kSide - 1 - int(w.y)),
                           continuityColor(ContinuityClass::G2)) > 0.2);
}

QTEST_MAIN(TestRenderEdgeBands)
// The culling of the band pass (CPU): a band beside the view is left out, one in it or just past
// its edge (within the band's margin) is kept, adjacent kept bands are one run.
void TestRenderEdgeBands::bandsOffScreenAreLeftOut() {
    Camera c;
    c.eye = {0.0, 0.0, 10.0};
    c.target = {0.0, 0.0, 0.0};
    c.up = {0.0, 1.0, 0.0};
    c.authored = true;
    Scene empty;
    const CameraMatrices m = cameraMatrices(c, empty, 1.0);
    const glm::mat4 vp = glm::mat4(m.projection * m.view);
    // The view's half-width at depth 10, from the projection.
    const double half = 10.0 / m.projection[0][0];
    EdgeBands bands;
    bands.vertices.resize(8);
    const auto range = [&](std::uint32_t first, glm::vec3 lo, glm::vec3 hi) {
        bands.ranges.push_back({first, 2, lo, hi});
    };
    range(0, {-1, -1, 0}, {1, -1, 0});                                  // in view
    range(2, {-1, 1, 0}, {1, 1, 0});                                    // in view, adjacent
    range(4, {float(3 * half), 0, 0}, {float(4 * half), 0, 0});         // far right: out
    range(6, {float(half * 1.001), 0, 0}, {float(half * 1.001), 1, 0}); // just past: margin
    EdgeBandRuns runs = visibleEdgeBands(bands, vp, 0.01f);
    QCOMPARE(runs.first, (std::vector<std::int32_t>{0, 6}));
    QCOMPARE(runs.count, (std::vector<std::int32_t>{4, 2}));
    runs = visibleEdgeBands(bands, vp, 0.0f);
    QCOMPARE(runs.first, (std::vector<std::int32_t>{0}));
    // Without ranges every vertex is one run.
    bands.ranges.clear();
    runs = visibleEdgeBands(bands, vp, 0.0f);
    QCOMPARE(runs.first, (std::vector<std::int32_t>{0}));
    QCOMPARE(runs.count, (std::vector<std::int32_t>{8}));
}

// A drag step through the cache: the bands are the same object updated in place (no other
// vertex copied, the layout kept), only the dragged face's ranges are stamped new, the vertices
// equal a full rebuild's, and the pass's sub-range upload reaches the GPU (the band drawn changes
// colour).
void TestRenderEdgeBands::aDragStepRewritesOnlyTheDraggedFacesBands() {
    Scene scene = configuration();
    ContinuityReport report = continuityReport(scene, {});
    Document doc;
    KW_VERIFY_OK(doc.resetScene(scene));
    EdgeBandCache cache;
    const std::shared_ptr<const EdgeBands> before = cache.update(scene, report);
    const std::uint64_t revision = before->revision, layout = before->layoutRevision;
    QCOMPARE(layout, revision);
    RenderOptions options;
    options.edgeBands = before;
    KW_VERIFY_OK(m_renderer->render(doc, topCamera(), options));
    const CameraMatrices m = cameraMatrices(topCamera(), scene, 1.0);
    const glm::dvec2 w =
        kwtest::windowPixels(m.projection * m.view, {3.0 * 3 + 1.0, 0.5, 0.0}, glm::dvec2(kSide));
    const auto pixel = [&] {
        return m_renderer->colorImage().pixel(int(w.x), kSide - 1 - int(w.y));
    };
    QVERIFY(colourDistance(pixel(), continuityColor(ContinuityClass::Open)) < 0.08);
    // Patch 8 (the open pair's right side, 0.004 up) dragged down onto its neighbour.
    const SurfaceId dragged{8};
    std::vector<int> indices;
    std::vector<glm::dvec3> points;
    for (int k = 0; k < 16; ++k) {
        indices.push_back(k);
        points.push_back(doc.surface(dragged)->geometry.points[size_t(k)] * glm::dvec3(1, 1, 0));
    }
    QVERIFY(doc.setControlPoints(dragged, indices, points));
    scene = doc.scene();
    QCOMPARE(updateContinuity(report, scene, {dragged}), 1);
    QCOMPARE(report.edges[3].continuity, ContinuityClass::G2);
    const std::shared_ptr<const EdgeBands> after = cache.update(scene, report, {dragged});
    QCOMPARE(after.get(), before.get());
    QVERIFY(after->revision > revision);
    QCOMPARE(after->layoutRevision, layout);
    // Patch 8's shared edge (drawn along patch 7's side, which covers it) and its three free
    // sides are re-made; every other range keeps the first revision.
    int stamped = 0;
    for (const EdgeBandRange& r : after->ranges) {
        QVERIFY(r.revision == revision || r.revision == after->revision);
        stamped += r.revision == after->revision;
    }
    QCOMPARE(stamped, 4);
    const EdgeBands full = makeEdgeBands(scene, report, 0);
    QCOMPARE(after->vertices.size(), full.vertices.size());
    for (size_t k = 0; k < full.vertices.size(); ++k) {
        QCOMPARE(after->vertices[k].position, full.vertices[k].position);
        QCOMPARE(after->vertices[k].color, full.vertices[k].color);
    }
    KW_VERIFY_OK(m_renderer->render(doc, topCamera(), options));
    QVERIFY2(colourDistance(pixel(), continuityColor(ContinuityClass::G2)) < 0.08,
             qPrintable(QColor(pixel()).name()));
    // Hiding the face empties its free sides' lines (its shared edge is drawn along patch 7,
    // which covers it): a new layout, the pass uploads it whole.
    QVERIFY(doc.setHidden(dragged, true));
    scene = doc.scene();
    const std::shared_ptr<const EdgeBands> hidden = cache.update(scene, report, {dragged});
    QVERIFY(hidden.get() != before.get());
    QCOMPARE(hidden->layoutRevision, hidden->revision);
    QCOMPARE(hidden->ranges.size(), before->ranges.size() - 3);
}

#include "tst_render_edge_bands.moc"
