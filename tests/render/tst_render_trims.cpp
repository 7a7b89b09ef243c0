// GL test: trimmed surfaces by the paper's trim mask. Covered area against the analytic
// trimmed area, every pixel against the CPU classification of model/nurbs/trim.h, nested and
// concave loops, messy input, one mask redrawn per trim edit, and the trim-edge error against mask
// resolution.
#include "expected_test_util.h"
#include "model/analysis/mass_properties.h"
#include "model/nurbs/trim.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"
#include "trim_test_util.h"

#include <QtTest>

using namespace kw;
using namespace kwtest;

namespace {

constexpr int kSide = 1024;

/// Every test here is of the paper's FBO mask (RenderOptions::TrimMode::Mask); the default,
/// exact mode, is tested by tst_render_trims_exact.
RenderOptions maskMode() {
    RenderOptions o;
    o.trimMode = RenderOptions::TrimMode::Mask;
    return o;
}

/// |det d(u, v)/d(pixel)| at (x, y) from differences of the AOV's (u, v): central where both
/// neighbours along an axis show the same surface, one-sided where only one does (at the edge
/// of the base polygon, which spans the trims' (u, v) box), 0 where neither does or at the
/// frame's border.
double uvPerPixelArea(const AovBuffer& aov, int x, int y) {
    if (x < 1 || y < 1 || x + 1 >= aov.width || y + 1 >= aov.height)
        return 0.0;
    const float* c = aov.pixel(x, y);
    auto diff = [&](const float* lo, const float* hi, glm::dvec2& out) {
        const bool a = lo[0] == c[0], b = hi[0] == c[0];
        if (a && b)
            out = glm::dvec2(0.5 * (hi[1] - lo[1]), 0.5 * (hi[2] - lo[2]));
        else if (b)
            out = glm::dvec2(hi[1] - c[1], hi[2] - c[2]);
        else if (a)
            out = glm::dvec2(c[1] - lo[1], c[2] - lo[2]);
        return a || b;
    };
    glm::dvec2 dx, dy;
    if (!diff(aov.pixel(x - 1, y), aov.pixel(x + 1, y), dx) ||
        !diff(aov.pixel(x, y - 1), aov.pixel(x, y + 1), dy))
        return 0.0;
    return std::abs(dx.x * dy.y - dx.y * dy.x);
}

/// Pixels of the AOV showing surface `id` with (u, v) within `radius` of `uv`.
int coveredNear(const AovBuffer& aov, SurfaceId id, glm::dvec2 uv, double radius) {
    int n = 0;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            const float* p = aov.pixel(x, y);
            if (p[0] == float(id.value) && glm::length(glm::dvec2(p[1], p[2]) - uv) < radius)
                ++n;
        }
    return n;
}

Scene messyScene() {
    Scene scene;
    Surface s = makeSurface(1, wavyPatch(3, 3, clampedUniform(3, 6), clampedUniform(3, 6)), 12);
    // A document holds closed loops only (one validation): the open ones are closed
    // as an importer does, by straight segments across the gaps, which is also how
    // makeTrimRegion draws an open loop. Reversed curves, zig-zags across the bridges, a
    // clockwise hole and loops that enclose no area remain.
    s.trims = messyLoops(10);
    for (TrimLoop& loop : s.trims)
        closeTrimLoop(loop, 0.0);
    scene.surfaces.push_back(s);
    scene.nextId = 20;
    return scene;
}

} // namespace

class TestRenderTrims : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    /// Renders `doc` with and without trims; returns the two AOVs.
    bool renderPair(const Document& doc, const RenderOptions& base, AovBuffer& trimmed,
                    AovBuffer& whole) {
        const Camera cam = fitCamera(doc.scene(), 1.0);
        RenderOptions opt = base;
        opt.trims = false;
        if (const Status drawn = m_renderer->render(doc, cam, opt); !drawn) {
            qWarning() << drawn.message();
            return false;
        }
        whole = m_renderer->aov();
        opt.trims = true;
        if (const Status drawn = m_renderer->render(doc, cam, opt); !drawn) {
            qWarning() << drawn.message();
            return false;
        }
        trimmed = m_renderer->aov();
        return true;
    }

    double texelOf(SurfaceId id) const {
        const TrimMask* m = RendererTestHook::scene(m_renderer->renderer()).mask(id);
        if (!m)
            return 1e300; // no mask: every disagreement is "far"... of nothing
        return std::max((m->rect.y - m->rect.x) / m->width, (m->rect.w - m->rect.z) / m->height);
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void coveredAreaMatchesAnalyticArea() {
        QString error;
        const auto scene = loadSample(QStringLiteral("trimmed_plate"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, maskMode(), trimmed, whole));
        const Surface& s = scene->surfaces.front();
        // Each covered pixel contributes |Su x Sv| times its (u, v) footprint, measured on the
        // untrimmed render (its neighbours exist across the trim edges).
        double area = 0.0;
        int covered = 0, unmeasured = 0;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const float* t = trimmed.pixel(x, y);
                if (t[0] != float(s.id.value))
                    continue;
                ++covered;
                const double duv = uvPerPixelArea(whole, x, y);
                if (duv == 0.0) {
                    ++unmeasured;
                    continue;
                }
                const SurfaceDerivatives d = surfaceDerivatives(s.geometry, t[1], t[2]);
                area += glm::length(glm::cross(d.su, d.sv)) * duv;
            }
        const double expected = trimmedSurfaceArea(s.geometry, s.trims);
        qInfo("trimmed plate: %d covered pixels, area from AOV %.5f, analytic %.5f (%.3f%%)",
              covered, area, expected, 100.0 * (area - expected) / expected);
        QVERIFY(covered > 100000);
        QCOMPARE(unmeasured, 0);
        QVERIFY2(std::abs(area - expected) <= 0.005 * expected,
                 qPrintable(QStringLiteral("%1 vs %2").arg(area).arg(expected)));
        // And the trims remove something: the whole plate is clearly larger.
        QVERIFY(trimmedSurfaceArea(s.geometry, {}) > 1.3 * expected);
    }

    void pixelsAgreeWithCpuClassification_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<int>("mode");
        QTest::addColumn<bool>("exactDepth"); // no pre-pass: the exact shader discards itself
        QTest::newRow("trimmed_plate exact") << "trimmed_plate" << int(RenderMode::Exact) << false;
        QTest::newRow("trimmed_plate exact-depth")
            << "trimmed_plate" << int(RenderMode::Exact) << true;
        QTest::newRow("trimmed_plate tessellated")
            << "trimmed_plate" << int(RenderMode::Tessellated) << false;
        QTest::newRow("star_island exact") << "star_island" << int(RenderMode::Exact) << false;
        QTest::newRow("messy exact") << "" << int(RenderMode::Exact) << false;
    }

    void pixelsAgreeWithCpuClassification() {
        QFETCH(QString, sample);
        QFETCH(int, mode);
        QFETCH(bool, exactDepth);
        const auto scene = sample.isEmpty() ? Expected<Scene>(messyScene()) : loadSample(sample);
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        RenderOptions opt = maskMode();
        opt.mode = RenderMode(mode);
        if (exactDepth)
            opt.shading = RenderOptions::Shading::ExactDepth;
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, opt, trimmed, whole));
        const TrimAgreement a =
            compareTrimmedRender(*scene, trimmed, whole, [&](SurfaceId id) { return texelOf(id); });
        qInfo("%s: %ld pixels checked, %.4f%% agree, worst disagreement %.2f texels from a "
              "curve",
              QTest::currentDataTag(), a.checked, 100.0 * a.fraction(), a.worstTexels);
        QVERIFY(a.checked > 100000);
        QVERIFY2(a.fraction() >= 0.999, qPrintable(QString::number(a.fraction())));
        QCOMPARE(a.far, 0L);
        if (sample.isEmpty()) // messy input is reported, once per problem: 2 loops with no area
            QCOMPARE(RendererTestHook::scene(m_renderer->renderer()).maskWarnings().size(), 2);
    }

    void starAndIslandRenderCorrectly() {
        const auto scene = loadSample(QStringLiteral("star_island"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, maskMode(), trimmed, whole));
        const SurfaceId id{1};
        // Island (nesting depth 3) drawn, the hole ring around it not, the plate outside drawn.
        QVERIFY(coveredNear(trimmed, id, {0.7, 0.5}, 0.03) > 50);
        QCOMPARE(coveredNear(trimmed, id, {0.7, 0.5 + 0.21}, 0.015), 0);
        QVERIFY(coveredNear(whole, id, {0.7, 0.5 + 0.21}, 0.015) > 10);
        QVERIFY(coveredNear(trimmed, id, {0.93, 0.9}, 0.03) > 50);
        // Concave star hole: a tip is removed, the notch between two tips is kept.
        const auto at = [](double deg, double r) {
            return glm::dvec2(0.27, 0.5) +
                   r * glm::dvec2(std::cos(glm::radians(deg)), std::sin(glm::radians(deg)));
        };
        QCOMPARE(coveredNear(trimmed, id, at(90.0, 0.15), 0.012), 0);
        QVERIFY(coveredNear(whole, id, at(90.0, 0.15), 0.012) > 10);
        QVERIFY(coveredNear(trimmed, id, at(120.0, 0.15), 0.012) > 10);
        // The mask texels themselves: parity fill against the CPU at every texel centre.
        const TrimMask* m = RendererTestHook::scene(m_renderer->renderer()).mask(id);
        QVERIFY(m);
        const std::vector<unsigned char> texels =
            RendererTestHook::scene(m_renderer->renderer()).readMask(id);
        QCOMPARE(texels.size(), size_t(m->width) * size_t(m->height));
        const TrimRegion region = makeTrimRegion(scene->surfaces[0].trims, 1e-6);
        const double texel = texelOf(id);
        long agree = 0, far = 0;
        for (int y = 0; y < m->height; ++y)
            for (int x = 0; x < m->width; ++x) {
                const glm::dvec2 uv(m->rect.x + (x + 0.5) / m->width * (m->rect.y - m->rect.x),
                                    m->rect.z + (y + 0.5) / m->height * (m->rect.w - m->rect.z));
                const bool kept = texels[size_t(y) * m->width + x] > 127;
                if (kept == trimRegionContains(region, uv))
                    ++agree;
                else if (trimRegionDistance(region, uv) > 0.5 * texel)
                    ++far;
            }
        qInfo("star_island mask %dx%d: %ld of %zu texels agree", m->width, m->height, agree,
              texels.size());
        QVERIFY(double(agree) >= 0.999 * double(texels.size()));
        QCOMPARE(far, 0L);
    }

    void trimEditRedrawsOnlyThatMask() {
        const auto both = plateBesideStar(4.5);
        QVERIFY2(both, qPrintable(both.message()));
        Scene scene = *both;
        Surface untrimmed =
            makeSurface(30, wavyPatch(3, 3, clampedUniform(3, 5), clampedUniform(3, 5)));
        for (glm::dvec3& p : untrimmed.geometry.points)
            p.y += 3.5;
        scene.surfaces.push_back(untrimmed);
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = fitCamera(scene, 1.0);
        RenderOptions opt = maskMode();
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        GpuScene& masks = RendererTestHook::scene(m_renderer->renderer());
        QVERIFY(masks.mask(SurfaceId{1}) && masks.mask(SurfaceId{20}));
        QVERIFY(!masks.mask(SurfaceId{30})); // untrimmed surfaces get no mask
        const std::vector<unsigned char> before = masks.readMask(SurfaceId{20});

        // A frame without changes redraws nothing.
        masks.resetStats();
        QVERIFY(m_renderer->render(doc, cam, opt));
        QCOMPARE(masks.totalMaskStats().redraws, 0);

        // Moving one trim control point of surface 20 redraws exactly its mask.
        const TrimPointRef ref{SurfaceId{20}, TrimLoopId{23}, 0, 1};
        const glm::dvec2 old = doc.surface(SurfaceId{20})->trims[1].curves[0].points[1];
        QVERIFY(doc.setTrimPoint(ref, old + glm::dvec2(0.05, 0.08)));
        QVERIFY(m_renderer->render(doc, cam, opt));
        QCOMPARE(masks.totalMaskStats().redraws, 1);
        QCOMPARE(masks.maskStats(SurfaceId{20}).redraws, 1);
        QCOMPARE(masks.maskStats(SurfaceId{1}).redraws, 0);
        QCOMPARE(masks.totalMaskStats().arrayAllocations, 0);
        QVERIFY(masks.readMask(SurfaceId{20}) != before);
        // Moving a surface control point is not a trim change (the mask size holds).
        masks.resetStats();
        const Surface* s1 = doc.surface(SurfaceId{1});
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {4},
                                     {s1->geometry.points[4] + glm::dvec3(0, 0, 0.01)}));
        QVERIFY(m_renderer->render(doc, cam, opt));
        QCOMPARE(masks.totalMaskStats().redraws, 0);
        // Removing the trimmed surface frees its mask.
        QVERIFY(doc.removeSurface(SurfaceId{20}));
        QVERIFY(m_renderer->render(doc, cam, opt));
        QVERIFY(!masks.mask(SurfaceId{20}));
        QVERIFY(masks.mask(SurfaceId{1}));
    }

    void manySurfacesShareOneArray() {
        // 256 trimmed surfaces (a 16 x 16 grid, each kept inside a disc of (u, v)): one mask
        // array allocated once, one layer each, one redraw each, and every pixel as the CPU says.
        Scene scene;
        std::uint32_t next = 1;
        for (int k = 0; k < 256; ++k) {
            Surface s =
                makeSurface(next++, wavyPatch(2, 2, clampedUniform(2, 4), clampedUniform(2, 4)), 4);
            for (glm::dvec3& p : s.geometry.points)
                p += glm::dvec3(5.0 * (k % 16), 4.0 * (k / 16), 0.0);
            s.trims.push_back(discLoop(next++, 0.1 * k));
            scene.surfaces.push_back(s);
        }
        scene.nextId = next;
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        GpuScene& masks = RendererTestHook::scene(m_renderer->renderer());
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, maskMode(), trimmed, whole));
        const TrimMaskStats st = masks.totalMaskStats();
        QCOMPARE(st.redraws, 256);
        QCOMPARE(st.arrayAllocations, 1);
        QVERIFY(masks.trimMasks().layerCount() >= 256);
        qInfo("256 trimmed surfaces: mask array %d x %d x %d", masks.trimMasks().layerSize(),
              masks.trimMasks().layerSize(), masks.trimMasks().layerCount());
        const TrimAgreement a =
            compareTrimmedRender(scene, trimmed, whole, [&](SurfaceId id) { return texelOf(id); });
        qInfo("%ld pixels checked, %.4f%% agree, worst disagreement %.2f texels", a.checked,
              100.0 * a.fraction(), a.worstTexels);
        QVERIFY(a.checked > 50000);
        // The discs are ~40 pixels wide, so about a tenth of their pixels lie on an edge (the
        // samples' share is under 1%): the 99.9% bar of the samples does not apply, the
        // one-texel bound does.
        QVERIFY2(a.fraction() >= 0.99, qPrintable(QString::number(a.fraction())));
        QCOMPARE(a.far, 0L);
    }

    void maskResolutionFollowsScreenWithinCap() {
        QString error;
        const auto scene = loadSample(QStringLiteral("trimmed_plate"));
        QVERIFY(scene);
        const Surface& s = scene->surfaces.front();
        FrameCamera fc = frameCamera(fitCamera(*scene, 1.0), *scene, 1.0);
        fc.viewport = {kSide, kSide};
        const glm::ivec2 big = TrimMaskPass::maskResolution(s, fc, 1024);
        fc.viewport = {64, 64}; // 16 times smaller on screen: at most a quarter of the side
        const glm::ivec2 small = TrimMaskPass::maskResolution(s, fc, 1024);
        QVERIFY(big.x >= 512 && big.y >= 512);
        QVERIFY(small.x <= 256 && small.y <= 256 && small.x >= kMinTrimMaskSize);
        QCOMPARE(TrimMaskPass::maskResolution(s, fc, 8), glm::ivec2(kMinTrimMaskSize));
        fc.viewport = {kSide, kSide};
        QCOMPARE(TrimMaskPass::maskResolution(s, fc, 300), glm::ivec2(300));
    }

    /// The numbers of docs/PERFORMANCE.md (## Trims): trim-edge error in screen pixels at
    /// 1024^2 against the mask cap, from the AOV against the CPU classification.
    void edgeErrorAgainstMaskResolution() {
        const auto scene = loadSample(QStringLiteral("trimmed_plate"));
        QVERIFY(scene);
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        const Surface& s = scene->surfaces.front();
        const TrimRegion region = makeTrimRegion(s.trims, 1e-6);
        double worst64 = 0.0, worst1024 = 0.0;
        for (int cap : {32, 64, 128, 256, 512, 1024, 2048}) {
            RenderOptions opt = maskMode();
            opt.trimMaskCap = cap;
            AovBuffer trimmed, whole;
            QVERIFY(renderPair(doc, opt, trimmed, whole));
            const TrimMask* m = RendererTestHook::scene(m_renderer->renderer()).mask(s.id);
            QVERIFY(m);
            // A wrongly classified pixel is off by its distance to the curve, in pixels:
            // the (u, v) distance over the pixel's (u, v) size sqrt|det J|.
            double worst = 0.0, sum = 0.0;
            long wrong = 0, checked = 0;
            for (int y = 0; y < kSide; ++y)
                for (int x = 0; x < kSide; ++x) {
                    const float* w = whole.pixel(x, y);
                    if (w[0] != float(s.id.value))
                        continue;
                    ++checked;
                    const glm::dvec2 uv(w[1], w[2]);
                    const bool shown = trimmed.pixel(x, y)[0] == w[0];
                    if (shown == trimRegionContains(region, uv))
                        continue;
                    const double duv = uvPerPixelArea(whole, x, y);
                    if (duv == 0.0)
                        continue;
                    const double px = trimRegionDistance(region, uv) / std::sqrt(duv);
                    worst = std::max(worst, px);
                    sum += px;
                    ++wrong;
                }
            qInfo("cap %4d: mask %4dx%-4d  wrong pixels %5ld of %ld  edge error mean %.3f px, "
                  "max %.3f px",
                  cap, m->width, m->height, wrong, checked, wrong ? sum / wrong : 0.0, worst);
            if (cap == 64)
                worst64 = worst;
            if (cap == 1024)
                worst1024 = worst;
        }
        QVERIFY(worst64 > 2.0 * worst1024);
        QVERIFY(worst1024 <= 1.0);
    }
};

QTEST_MAIN(TestRenderTrims)
#include "tst_render_trims.moc"
