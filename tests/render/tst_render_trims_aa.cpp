// GL test: anti-aliased trim edges and silhouettes. A straight trim edge's
// pixels are covered within 1/8 of the box filter's analytic coverage, at several angles, in
// exact and mask trim mode; two faces sharing a trim edge show no seam (their coverages sum,
// nothing of the background shows through); MSAA softens a silhouette; --samples 1 stays
// aliased; AOV frames and picks are never anti-aliased.
#include "expected_test_util.h"
#include "model/nurbs/trim_arcs.h"
#include "model/nurbs/visible_bounds.h"
#include "render/accumulate_target.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"
#include "trim_test_util.h"

#include <QtTest>

using namespace kw;
using namespace kwtest;

namespace {

constexpr int kSide = 256;
constexpr double kHalf = 4.0; // the plane spans [-4, 4]^2, wider than the view

/// The plane z = 0 over [-kHalf, kHalf]^2, u along x and v along y, white.
Surface plane(std::uint32_t id) {
    NurbsSurface g;
    g.degreeU = g.degreeV = 1;
    g.countU = g.countV = 2;
    g.knotsU = g.knotsV = {0.0, 0.0, 1.0, 1.0};
    g.points = {
        {-kHalf, -kHalf, 0.0}, {kHalf, -kHalf, 0.0}, {-kHalf, kHalf, 0.0}, {kHalf, kHalf, 0.0}};
    g.weights.assign(4, 1.0);
    Surface s = makeSurface(id, g, 4);
    s.material.color = glm::dvec3(1.0);
    return s;
}

glm::dvec3 worldOf(glm::dvec2 uv) {
    return glm::dvec3(-kHalf + 2.0 * kHalf * uv.x, -kHalf + 2.0 * kHalf * uv.y, 0.0);
}

/// The polygon `poly` clipped to the half-plane dot(n, x - c) >= 0 (Sutherland-Hodgman).
std::vector<glm::dvec2> clipHalfPlane(const std::vector<glm::dvec2>& poly, glm::dvec2 c,
                                      glm::dvec2 n) {
    std::vector<glm::dvec2> out;
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
        const double da = glm::dot(n, a - c), db = glm::dot(n, b - c);
        if (da >= 0.0)
            out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0))
            out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

double area(const std::vector<glm::dvec2>& poly) {
    double a = 0.0;
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec2 p = poly[k], q = poly[(k + 1) % poly.size()];
        a += p.x * q.y - q.x * p.y;
    }
    return 0.5 * std::abs(a);
}

/// The domain's part on the left of the line through `c` along `dir` (in (u, v)), as a loop.
TrimLoop halfLoop(std::uint32_t id, glm::dvec2 c, glm::dvec2 dir, bool left) {
    const glm::dvec2 n = (left ? 1.0 : -1.0) * glm::dvec2(-dir.y, dir.x);
    std::vector<glm::dvec2> poly = clipHalfPlane({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, c, n);
    poly.push_back(poly.front());
    return loopOf(id, {polylineCurve(poly)});
}

/// A 24-gon of radius 0.08 about the middle of the domain (1.3 model units across: a third
/// of the view), its corners off the axes.
TrimLoop smallDisc(std::uint32_t id) {
    std::vector<glm::dvec2> disc;
    for (int i = 0; i <= 24; ++i) {
        const double a = 2.0 * M_PI * (i % 24) / 24.0 + 0.1;
        disc.emplace_back(0.5 + 0.08 * std::cos(a), 0.5 + 0.08 * std::sin(a));
    }
    return loopOf(id, {polylineCurve(disc)});
}

/// The trims of the whole domain with smallDisc cut out: loops `id` and `id + 1`.
std::vector<TrimLoop> domainWithHole(std::uint32_t id) {
    return {loopOf(id, {polylineCurve({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}})}),
            smallDisc(id + 1)};
}

/// One straight trim edge on screen: pixel coverages of an anti-aliased frame against the
/// analytic ones.
struct EdgeCoverage {
    int edgePixels = 0;       ///< pixels the edge crosses (analytic coverage in (0.01, 0.99))
    int checked = 0;          ///< pixels compared (all where the untrimmed plane is drawn)
    double maxError = 0.0;    ///< largest |coverage - analytic|
    double meanEdgeError = 0; ///< mean over the edge pixels
    int worstX = -1, worstY = -1;
    double worstGot = 0, worstWant = 0;
};

} // namespace

class TestRenderTrimsAa : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    Camera topCamera() const {
        Camera c;
        c.eye = {0.0, 0.0, 3.0};
        c.target = {0.0, 0.0, 0.0};
        c.up = {0.0, 1.0, 0.0};
        c.authored = true;
        return c;
    }

    static RenderOptions
    aaOptions(int samples, RenderOptions::TrimMode mode,
              RenderOptions::Antialiasing method = RenderOptions::Antialiasing::Coverage) {
        RenderOptions o;
        o.samples = samples;
        o.antialiasing = method;
        o.trimMode = mode;
        o.background = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        o.lightCount = 1;
        o.headlight = true;
        o.polygonOverTrims = false; // the same base polygon trimmed or not: the whole domain
        return o;
    }

    bool renderImage(const Document& doc, const RenderOptions& o, QImage& image) {
        if (const Status drawn = m_renderer->render(doc, topCamera(), o); !drawn)
            return qWarning() << drawn.message(), false;
        image = m_renderer->colorImage();
        return true;
    }

    /// The plane trimmed to the left of the line through `c` along `dir`, drawn with `o`:
    /// each pixel's coverage is its colour over the untrimmed plane's (black background),
    /// compared with the area of the pixel square left of the line's projection.
    EdgeCoverage measure(glm::dvec2 c, glm::dvec2 dir, const RenderOptions& o) {
        EdgeCoverage r;
        Scene scene;
        scene.surfaces.push_back(plane(1));
        scene.surfaces[0].trims = {halfLoop(10, c, dir, true)};
        Document doc;
        if (const Status reset = doc.resetScene(scene); !reset)
            return qWarning() << reset.message(), r;
        RenderOptions whole = o;
        whole.trims = false;
        QImage trimmed, full;
        if (!renderImage(doc, o, trimmed) || !renderImage(doc, whole, full))
            return r;
        // The line on screen (window pixels, y up): the plane is flat, so the projection of
        // the (u, v) line is a straight line.
        const CameraMatrices m = cameraMatrices(topCamera(), scene, 1.0);
        const auto window = [&](glm::dvec2 uv) {
            return kwtest::windowPixels(m.projection * m.view, worldOf(uv), glm::dvec2(kSide));
        };
        const glm::dvec2 a = window(c), b = window(c + 0.1 * dir);
        const glm::dvec2 side = window(c + 0.1 * glm::dvec2(-dir.y, dir.x)); // kept side
        glm::dvec2 n(-(b - a).y, (b - a).x);
        if (glm::dot(n, side - a) < 0.0)
            n = -n;
        double sum = 0.0;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const QColor w = full.pixelColor(x, y), t = trimmed.pixelColor(x, y);
                const glm::dvec3 wv(w.redF(), w.greenF(), w.blueF()),
                    tv(t.redF(), t.greenF(), t.blueF());
                if (glm::dot(wv, wv) < 0.05)
                    continue; // not on the plane
                const double got = glm::dot(tv, wv) / glm::dot(wv, wv);
                const double wy = kSide - 1 - y; // window row of image row y
                const double want = area(clipHalfPlane(
                    {{x, wy}, {x + 1.0, wy}, {x + 1.0, wy + 1.0}, {x, wy + 1.0}}, a, n));
                const double error = std::abs(got - want);
                ++r.checked;
                if (want > 0.01 && want < 0.99) {
                    ++r.edgePixels;
                    sum += error;
                }
                if (error > r.maxError) {
                    r.maxError = error;
                    r.worstX = x, r.worstY = y, r.worstGot = got, r.worstWant = want;
                }
            }
        r.meanEdgeError = r.edgePixels > 0 ? sum / r.edgePixels : 0.0;
        return r;
    }

private Q_SLOTS:
    void initTestCase() {
        m_renderer = std::make_unique<OffscreenRenderer>();
        QString error;
        KW_VERIFY_OK(m_renderer->create());
        KW_VERIFY_OK(m_renderer->setSize(QSize(kSide, kSide), false));
    }

    void straightEdgeCoverage_data() {
        QTest::addColumn<double>("degrees");
        QTest::addColumn<bool>("mask");
        QTest::addColumn<int>("accumulated"); // samples of Antialiasing::Accumulate, 0: coverage
        for (double deg : {0.0, 7.0, 30.0, 45.0, 62.0, 90.0, 121.0})
            QTest::addRow("exact %g deg", deg) << deg << false << 0;
        // The paper's mask (--trim-mode mask) is anti-aliased from its bilinear value's
        // gradient, but its edge is only as accurate as its texels (about a pixel here), so
        // only its print-out is kept (docs/PERFORMANCE.md ## Trims).
        QTest::addRow("mask 30 deg") << 30.0 << true << 0;
        // Accumulated frames: each sample is the aliased frame's exact classification, so the
        // coverage is the fraction of the 16 sample offsets inside the line.
        for (double deg : {7.0, 30.0, 62.0, 121.0})
            QTest::addRow("accumulated 16 %g deg", deg) << deg << false << 16;
    }

    // The test: within 1/8 of the analytic coverage for a straight trim edge.
    void straightEdgeCoverage() {
        QFETCH(double, degrees);
        QFETCH(bool, mask);
        QFETCH(int, accumulated);
        const double a = glm::radians(degrees);
        const glm::dvec2 dir(std::cos(a), std::sin(a));
        // Off the pixel grid's symmetry: the line misses pixel centres and corners.
        const glm::dvec2 c(0.5 + 0.0123, 0.5 - 0.0071);
        const EdgeCoverage r =
            measure(c, dir,
                    aaOptions(accumulated > 0 ? accumulated : 4,
                              mask ? RenderOptions::TrimMode::Mask : RenderOptions::TrimMode::Exact,
                              accumulated > 0 ? RenderOptions::Antialiasing::Accumulate
                                              : RenderOptions::Antialiasing::Coverage));
        qInfo("%s %g deg: %d edge pixels, mean error %.4f, max %.4f at (%d, %d): %.3f for %.3f",
              mask ? "mask" : (accumulated > 0 ? "accumulated" : "exact"), degrees, r.edgePixels,
              r.meanEdgeError, r.maxError, r.worstX, r.worstY, r.worstGot, r.worstWant);
        QVERIFY(r.checked > kSide * kSide / 2);
        QVERIFY2(r.edgePixels >= kSide / 2, qPrintable(QString::number(r.edgePixels)));
        if (mask)
            return;
        QVERIFY2(r.maxError <= 0.125, qPrintable(QStringLiteral("coverage %1 for %2 at (%3, %4)")
                                                     .arg(r.worstGot)
                                                     .arg(r.worstWant)
                                                     .arg(r.worstX)
                                                     .arg(r.worstY)));
    }

    void curvedEdgeCoverage_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<double>("zoom");
        QTest::addColumn<int>("loop");
        for (double zoom : {1.0, 8.0, 64.0}) {
            // The plate's rounded outline (rational quarter circles) and the concave star hole.
            QTest::addRow("trimmed_plate %gx", zoom) << "trimmed_plate" << zoom << 0;
            QTest::addRow("star_island %gx", zoom) << "star_island" << zoom << 1;
        }
    }

    // Curved trim edges (rational arcs, a star's corners) at 1x, 8x and 64x zoom on an edge:
    // each pixel's coverage against the CPU's, the fraction of 16 x 16 points spread over the
    // pixel (through the (u, v) derivatives of an AOV frame) that trimArcsContain keeps.
    void curvedEdgeCoverage() {
        QFETCH(QString, sample);
        QFETCH(double, zoom);
        QFETCH(int, loop);
        // The fitted view at 1024^2, as a user sees it: at 256^2 the grids' texels are smaller
        // than the pixels, which keep their centre's classification (trim_exact.glsl).
        const int side = zoom == 1.0 ? 1024 : kSide;
        QString error;
        const auto scene = loadSample(sample);
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        const Surface& s = scene->surfaces.front();
        const std::vector<NurbsCurve2>& curves = s.trims.at(size_t(loop)).curves;
        const NurbsCurve2& c = curves.size() > 1 ? curves[1] : curves[0];
        const Interval d = curveDomain(c);
        const Camera cam =
            zoomedOn(fitCamera(*scene, 1.0), s, curvePoint(c, 0.5 * (d.first + d.last)), zoom);
        RenderOptions o = aaOptions(4, RenderOptions::TrimMode::Exact);
        o.trims = false;
        QVERIFY(m_renderer->setSize(QSize(side, side), true));
        KW_VERIFY_OK(m_renderer->render(doc, cam, o));
        const AovBuffer aov = m_renderer->aov();
        QVERIFY(m_renderer->setSize(QSize(side, side), false));
        QImage whole, cut;
        KW_VERIFY_OK(m_renderer->render(doc, cam, o));
        whole = m_renderer->colorImage();
        o.trims = true;
        KW_VERIFY_OK(m_renderer->render(doc, cam, o));
        cut = m_renderer->colorImage();
        cut.save(outputDir().filePath(QStringLiteral("trims_aa_%1_%2x.png").arg(sample).arg(zoom)));

        const TrimArcs arcs = makeTrimArcs(s.trims, trimTolerance(s.geometry));
        const float id = float(s.id.value);
        auto uvAt = [&](int x, int y) {
            return glm::dvec2(aov.pixel(x, y)[1], aov.pixel(x, y)[2]);
        };
        int edge = 0, compared = 0, worstX = -1, worstY = -1;
        double worst = 0.0, sum = 0.0, worstGot = 0.0, worstWant = 0.0;
        for (int y = 1; y + 1 < side; ++y)
            for (int x = 1; x + 1 < side; ++x) {
                // Inside the surface's image, away from its silhouette (MSAA's business).
                bool interior = true;
                for (int k = -1; k <= 1 && interior; ++k)
                    interior = aov.pixel(x + k, y)[0] == id && aov.pixel(x, y + k)[0] == id;
                if (!interior)
                    continue;
                const glm::dvec2 jx = 0.5 * (uvAt(x + 1, y) - uvAt(x - 1, y));
                const glm::dvec2 jy = 0.5 * (uvAt(x, y + 1) - uvAt(x, y - 1));
                const glm::dvec2 uv = uvAt(x, y);
                const QColor w = whole.pixelColor(x, y), t = cut.pixelColor(x, y);
                const glm::dvec3 wv(w.redF(), w.greenF(), w.blueF());
                const glm::dvec3 tv(t.redF(), t.greenF(), t.blueF());
                if (glm::dot(wv, wv) < 0.01)
                    continue;
                const double got = glm::dot(tv, wv) / glm::dot(wv, wv);
                const auto count = [&](int n) {
                    int in = 0;
                    for (int sy = 0; sy < n; ++sy)
                        for (int sx = 0; sx < n; ++sx)
                            in += trimArcsContain(arcs, uv + ((sx + 0.5) / n - 0.5) * jx +
                                                            ((sy + 0.5) / n - 0.5) * jy);
                    return double(in) / (n * n);
                };
                // 5 x 5 points first; 16 x 16 where they disagree or the GPU covers partly.
                double want = count(5);
                if ((want > 0.0 && want < 1.0) || std::abs(got - want) > 0.02)
                    want = count(16);
                const double error = std::abs(got - want);
                ++compared;
                if (want > 0.0 && want < 1.0)
                    ++edge, sum += error;
                if (error > worst)
                    worst = error, worstX = x, worstY = y, worstGot = got, worstWant = want;
            }
        qInfo("%s at %gx: %d pixels, %d on an edge, mean error there %.4f, max %.4f at (%d, %d): "
              "%.3f for %.3f",
              qPrintable(sample), zoom, compared, edge, edge ? sum / edge : 0.0, worst, worstX,
              worstY, worstGot, worstWant);
        QVERIFY(compared > side * side / 8);
        QVERIFY2(edge >= side / 4, qPrintable(QString::number(edge)));
        // The reference counts 256 points; the GPU takes the nearest curve as straight across
        // the pixel, which a star's corner is not.
        QVERIFY2(worst <= 0.125, qPrintable(QStringLiteral("coverage %1 for %2 at (%3, %4)")
                                                .arg(worstGot)
                                                .arg(worstWant)
                                                .arg(worstX)
                                                .arg(worstY)));
    }

    // Without anti-aliasing every pixel is wholly in or out: the same edge is stair-stepped.
    void oneSampleIsAliased() {
        const glm::dvec2 dir(std::cos(0.5), std::sin(0.5));
        const EdgeCoverage r =
            measure({0.5123, 0.4929}, dir, aaOptions(1, RenderOptions::TrimMode::Exact));
        QVERIFY(r.edgePixels >= kSide / 2);
        // Aliased pixels are 0 or 1, so a pixel cut near half is off by about half.
        QVERIFY2(r.maxError > 0.4, qPrintable(QString::number(r.maxError)));
    }

    // Two faces meeting along a curve (a disc and the plate it was cut from) show no seam:
    // every pixel along the shared edge has the colour of the faces, as the untrimmed plane
    // does. Blending each partly covered fragment over the last would let a quarter of the
    // background through at pixels each face covers by half.
    // (The paper's masks of the two faces are two rasters, of different rectangles: their
    // edges do not meet exactly, anti-aliased or not, so mask mode is not held to this.)
    void sharedEdgeHasNoSeam() {
        const bool mask = false;
        Scene scene;
        scene.surfaces = {plane(1), plane(2)};
        scene.surfaces[0].trims = {smallDisc(10)};
        scene.surfaces[1].trims = domainWithHole(11);
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        RenderOptions o =
            aaOptions(4, mask ? RenderOptions::TrimMode::Mask : RenderOptions::TrimMode::Exact);
        QImage both, whole;
        QVERIFY(renderImage(doc, o, both));
        o.trims = false;
        QVERIFY(renderImage(doc, o, whole));
        int worst = 0, differing = 0, worstX = -1, worstY = -1;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const QColor a = both.pixelColor(x, y), b = whole.pixelColor(x, y);
                const int d =
                    std::max({std::abs(a.red() - b.red()), std::abs(a.green() - b.green()),
                              std::abs(a.blue() - b.blue())});
                differing += d > 2;
                if (d > worst)
                    worst = d, worstX = x, worstY = y;
            }
        both.save(outputDir().filePath(QStringLiteral("trims_aa_seam.png")));
        qInfo("%s: largest difference %d/255 at (%d, %d), %d pixels over 2/255",
              mask ? "mask" : "exact", worst, worstX, worstY, differing);
        // 8-bit rounding of the two summed parts: a level or two.
        QVERIFY2(
            worst <= 3,
            qPrintable(QStringLiteral("%1/255 at (%2, %3)").arg(worst).arg(worstX).arg(worstY)));
    }

    // MSAA: a silhouette (the plane's own border, not a trim) gets partly covered pixels with
    // samples > 1 and none with 1; shading stays once per pixel, so the inside is unchanged.
    void silhouetteIsMultisampled_data() {
        QTest::addColumn<int>("method");
        QTest::addRow("coverage") << int(RenderOptions::Antialiasing::Coverage);
        QTest::addRow("accumulate") << int(RenderOptions::Antialiasing::Accumulate);
    }
    void silhouetteIsMultisampled() {
        QFETCH(int, method);
        const auto antialiasing = RenderOptions::Antialiasing(method);
        Scene scene;
        Surface s = plane(1);
        for (glm::dvec3& p : s.geometry.points)
            p = glm::dvec3(p.x * 0.15, p.y * 0.1, 0.0) + glm::dvec3(0.0123, -0.0071, 0.0);
        // Turned 20 degrees so the border is not along the pixel grid.
        const double t = glm::radians(20.0);
        for (glm::dvec3& p : s.geometry.points)
            p = glm::dvec3(p.x * std::cos(t) - p.y * std::sin(t),
                           p.x * std::sin(t) + p.y * std::cos(t), 0.0);
        scene.surfaces.push_back(s);
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        auto partial = [&](int samples, QImage& image) {
            if (!renderImage(doc, aaOptions(samples, RenderOptions::TrimMode::Exact, antialiasing),
                             image))
                return -1;
            int n = 0;
            for (int y = 0; y < kSide; ++y)
                for (int x = 0; x < kSide; ++x) {
                    const int g = image.pixelColor(x, y).green();
                    const int inside = image.pixelColor(kSide / 2, kSide / 2).green();
                    n += g > 8 && g < inside - 40;
                }
            return n;
        };
        QImage aliased, smooth;
        const int none = partial(1, aliased), some = partial(4, smooth);
        qInfo("partly covered border pixels: %d with 1 sample, %d with 4", none, some);
        QCOMPARE(none, 0);
        QVERIFY2(some > 100, qPrintable(QString::number(some)));
        QCOMPARE(smooth.pixelColor(kSide / 2, kSide / 2), aliased.pixelColor(kSide / 2, kSide / 2));
        const FrameReport& report = m_renderer->lastReport();
        // MSAA: 4 samples of colour, sum and depth; accumulated: one sample's colour and depth
        // and the float sum.
        QVERIFY(report.gpuBytes.frameTargets >=
                std::int64_t(kSide) * kSide *
                    (antialiasing == RenderOptions::Antialiasing::Coverage ? 4 * 16 : 24));
    }

    // Past the GPU's limit the frame is drawn with its most samples, with a warning; turning
    // anti-aliasing off frees the frame's attachments.
    void samplesBeyondTheGpuWarn() {
        Scene scene;
        scene.surfaces.push_back(plane(1));
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        GLint most = 1;
        m_renderer->makeCurrent();
        RendererTestHook::gl(m_renderer->renderer())->glGetIntegerv(GL_MAX_SAMPLES, &most);
        QImage image;
        QVERIFY(renderImage(doc, aaOptions(kMaxSamples, RenderOptions::TrimMode::Exact), image));
        const FrameReport r = m_renderer->lastReport();
        if (most < kMaxSamples) {
            QVERIFY(!r.warnings.isEmpty());
            QVERIFY2(r.warnings.join(' ').contains(QStringLiteral("the GPU allows %1").arg(most)),
                     qPrintable(r.warnings.join(' ')));
        }
        QVERIFY(r.gpuBytes.frameTargets > 0);
        QVERIFY(renderImage(doc, aaOptions(1, RenderOptions::TrimMode::Exact), image));
        QCOMPARE(m_renderer->lastReport().gpuBytes.frameTargets, std::int64_t(0));
        // Accumulated frames are whole frames: any count up to kMaxSamples, with no warning.
        QVERIFY(renderImage(doc,
                            aaOptions(kMaxSamples, RenderOptions::TrimMode::Exact,
                                      RenderOptions::Antialiasing::Accumulate),
                            image));
        QVERIFY2(m_renderer->lastReport().warnings.isEmpty(),
                 qPrintable(m_renderer->lastReport().warnings.join(' ')));
        QVERIFY(m_renderer->lastReport().gpuBytes.frameTargets > 0);
        QVERIFY(renderImage(doc, aaOptions(1, RenderOptions::TrimMode::Exact), image));
        QCOMPARE(m_renderer->lastReport().gpuBytes.frameTargets, std::int64_t(0));
    }

    // Progressive accumulation (the editor on software OpenGL): a sample per call, added to the
    // sum while nothing drawn changes, ends on the very image of all samples drawn in one call;
    // once complete, a call draws no surface; any change (document, camera, options, a frame
    // drawn otherwise in between) starts the image again. Without the restart a dragged point
    // or a moved view would leave its old samples mixed into the new image.
    void progressiveFramesAddUpToTheWholeImage() {
        Scene scene;
        scene.surfaces = {plane(1), plane(2)};
        // A small square turned 20 degrees over the plate's corner, and the plate with a hole.
        const double t = glm::radians(20.0);
        for (glm::dvec3& p : scene.surfaces[0].geometry.points)
            p = glm::dvec3(p.x * 0.1 * std::cos(t) - p.y * 0.1 * std::sin(t) - 0.4,
                           p.x * 0.1 * std::sin(t) + p.y * 0.1 * std::cos(t) - 0.4, 0.05);
        scene.surfaces[1].trims = domainWithHole(11);
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        RenderOptions o =
            aaOptions(4, RenderOptions::TrimMode::Exact, RenderOptions::Antialiasing::Accumulate);
        QImage whole;
        QVERIFY(renderImage(doc, o, whole));
        QCOMPARE(m_renderer->lastReport().samplesInImage, 4);
        QVERIFY(!m_renderer->lastReport().refining);
        const auto differing = [](const QImage& a, const QImage& b) {
            int n = 0;
            for (int y = 0; y < a.height(); ++y)
                for (int x = 0; x < a.width(); ++x)
                    n += a.pixel(x, y) != b.pixel(x, y);
            return n;
        };
        o.progressive = true;
        QImage image;
        for (int i = 1; i <= 4; ++i) {
            QVERIFY(renderImage(doc, o, image));
            const FrameReport& r = m_renderer->lastReport();
            QCOMPARE(r.samplesInImage, i);
            QCOMPARE(r.refining, i < 4);
            QVERIFY(r.drawCalls > 0);
            const int off = differing(image, whole);
            qInfo("progressive sample %d: %d pixels differ from the 4-sample image", i, off);
            if (i == 1)
                QVERIFY(off > 100); // the hole's edge and the square's: aliased
            if (i == 4)
                QCOMPARE(off, 0);
        }
        // Complete: resolved again, nothing drawn.
        QVERIFY(renderImage(doc, o, image));
        QCOMPARE(m_renderer->lastReport().samplesInImage, 4);
        QVERIFY(!m_renderer->lastReport().refining);
        QCOMPARE(m_renderer->lastReport().drawCalls, 0);
        QCOMPARE(differing(image, whole), 0);
        // The overlays are drawn over a complete image (no surface drawn) as over one drawn in
        // a single call: a square under the plate's hole, wider than it, with its control net.
        Scene under = scene;
        for (glm::dvec3& p : under.surfaces[0].geometry.points)
            p = glm::dvec3(p.x * 1.5 + 0.6, p.y * 1.5 + 0.6, -0.05); // centred on the hole
        Document underDoc;
        KW_VERIFY_OK(underDoc.resetScene(under));
        RenderOptions net = o;
        net.controlNet = true;
        net.progressive = false;
        QImage netWhole, noNet;
        QVERIFY(renderImage(underDoc, net, netWhole));
        net.controlNet = false;
        QVERIFY(renderImage(underDoc, net, noNet));
        net.controlNet = true;
        net.progressive = true;
        for (int i = 0; i < 5; ++i)
            QVERIFY(renderImage(underDoc, net, image));
        QCOMPARE(m_renderer->lastReport().samplesInImage, 4);
        QCOMPARE(m_renderer->lastReport().drawCalls > 0, true); // the net's, no surface's
        QVERIFY(differing(netWhole, noNet) > 50);               // the net shows in the hole
        QCOMPARE(differing(image, netWhole), 0);
        const auto restarts = [&](const char* what) {
            QImage restarted;
            if (!renderImage(doc, o, restarted))
                return false;
            const FrameReport& r = m_renderer->lastReport();
            if (r.samplesInImage != 1 || !r.refining || r.drawCalls == 0)
                return qWarning("%s: %d samples, refining %d, %d draws", what, r.samplesInImage,
                                int(r.refining), r.drawCalls),
                       false;
            for (int i = 2; i <= 4; ++i)
                if (!renderImage(doc, o, restarted))
                    return false;
            return m_renderer->lastReport().samplesInImage == 4;
        };
        // A control point moved (and moved back: a new revision all the same).
        const glm::dvec3 p = doc.surface(SurfaceId{1})->geometry.points[0];
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p + glm::dvec3(0.0, 0.0, 0.01)}));
        QVERIFY(restarts("a moved point"));
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p}));
        QVERIFY(restarts("the point moved back"));
        QVERIFY(renderImage(doc, o, image));
        QCOMPARE(differing(image, whole), 0);
        // Another option, the camera, a surface removed, a frame drawn in between.
        o.background = glm::vec4(0.1f, 0.0f, 0.0f, 1.0f);
        QVERIFY(restarts("another background"));
        Camera nearer = topCamera();
        nearer.eye.z = 2.5;
        QVERIFY(m_renderer->render(doc, nearer, o));
        QCOMPARE(m_renderer->lastReport().samplesInImage, 1);
        QVERIFY(restarts("the camera back"));
        RenderOptions once = o;
        once.progressive = false;
        once.samples = 2;
        QVERIFY(renderImage(doc, once, image));
        QVERIFY(restarts("a whole frame in between"));
        QVERIFY(doc.removeSurface(SurfaceId{2}));
        QVERIFY(restarts("a surface removed"));
    }

    // The accumulated samples' offsets: inside the pixel, on distinct rows and columns for the
    // standard counts (an edge near the pixel grid still gets every level), centred.
    void accumulationOffsetsAreSpread() {
        for (int n = 1; n <= kMaxSamples; ++n) {
            const std::vector<glm::vec2> o = accumulationOffsets(n);
            QCOMPARE(int(o.size()), n);
            glm::vec2 mean(0.0f);
            for (const glm::vec2& p : o) {
                QVERIFY(std::abs(p.x) <= 0.5f && std::abs(p.y) <= 0.5f);
                mean += p / float(n);
            }
            QVERIFY2(glm::length(mean) <= 1.0f / 16.0f + 1e-6f, qPrintable(QString::number(n)));
            if (n == 2 || n == 4 || n == 8 || n == 16) {
                for (size_t i = 0; i < o.size(); ++i)
                    for (size_t j = i + 1; j < o.size(); ++j)
                        QVERIFY(o[i].x != o[j].x && o[i].y != o[j].y);
            }
        }
    }
};

QTEST_MAIN(TestRenderTrimsAa)
#include "tst_render_trims_aa.moc"
