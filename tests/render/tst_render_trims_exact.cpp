// GL test: exact trim edges. Every pixel of the exact trim mode against the CPU
// classification from 1x to 512x zoom on an edge, hammer.iges's faces, trim memory that scales
// with each surface's need, one trim edit rebuilding one surface, and the memory budget.
#include "expected_test_util.h"
#include "model/cad/cadimport.h"
#include "model/nurbs/trim.h"
#include "model/nurbs/trim_arcs.h"
#include "model/nurbs/visible_bounds.h"
#include "render/renderer_test_hook.h"
#include "render/trim_grid_store.h"
#include "render_test_util.h"
#include "trim_test_util.h"

#include <QtTest>

using namespace kw;
using namespace kwtest;

namespace {

constexpr int kSide = 1024;

/// Per-pixel check of a trimmed render against trimArcsContain (model/nurbs/trim_arcs.h, which
/// tst_trim_exact holds to model/nurbs/trim.h). A disagreement counts as "near" when the CPU
/// classification changes within half a pixel of the pixel's centre (its (u, v) moved by half
/// a pixel along x, y and the diagonals, through the AOV's (u, v) derivatives), else "far".
struct PixelAgreement {
    long checked = 0, disagree = 0, far = 0;
    long lone = 0; ///< disagreements at pixels with no neighbour of their surface (not far)
    long kept = 0; ///< checked pixels the CPU keeps (the rest it cuts)
    int farX = -1, farY = -1; ///< the last far disagreement, for the failure message
    glm::dvec2 farUv{0.0}, farJx{0.0}, farJy{0.0};
};

PixelAgreement comparePixels(const Scene& scene, const AovBuffer& trimmed, const AovBuffer& whole) {
    std::map<float, TrimArcs> arcs;
    for (const Surface& s : scene.surfaces)
        if (!s.trims.empty())
            arcs[float(s.id.value)] = makeTrimArcs(s.trims, trimTolerance(s.geometry));
    auto uvAt = [](const AovBuffer& a, int x, int y) {
        return glm::dvec2(a.pixel(x, y)[1], a.pixel(x, y)[2]);
    };
    // d(u, v)/dx and /dy at a pixel of `a` from its neighbours showing the same surface.
    auto derivative = [&](const AovBuffer& a, int x, int y, int dx, int dy) {
        const float id = a.pixel(x, y)[0];
        const int x0 = std::max(x - dx, 0), y0 = std::max(y - dy, 0);
        const int x1 = std::min(x + dx, a.width - 1), y1 = std::min(y + dy, a.height - 1);
        const bool lo = a.pixel(x0, y0)[0] == id, hi = a.pixel(x1, y1)[0] == id;
        if (lo && hi && (x1 != x0 || y1 != y0))
            return (uvAt(a, x1, y1) - uvAt(a, x0, y0)) / double(std::max(x1 - x0, y1 - y0));
        if (hi && (x1 != x || y1 != y))
            return uvAt(a, x1, y1) - uvAt(a, x, y);
        if (lo && (x0 != x || y0 != y))
            return uvAt(a, x, y) - uvAt(a, x0, y0);
        return glm::dvec2(0.0);
    };
    PixelAgreement r;
    auto check = [&](const AovBuffer& a, int x, int y, bool shown) {
        const float id = a.pixel(x, y)[0];
        const TrimArcs& arc = arcs[id];
        const glm::dvec2 uv = uvAt(a, x, y);
        const bool inside = trimArcsContain(arc, uv);
        ++r.checked;
        r.kept += inside;
        if (inside == shown)
            return;
        ++r.disagree;
        const glm::dvec2 jx = derivative(a, x, y, 1, 0), jy = derivative(a, x, y, 0, 1);
        if (jx == glm::dvec2(0.0) && jy == glm::dvec2(0.0)) {
            // No neighbour shows the surface: the face is thinner than a pixel here (a sliver
            // seen edge-on), so its trims' curves are within the pixel; the footprint is unknown.
            ++r.lone;
            return;
        }
        for (int sx = -1; sx <= 1; ++sx)
            for (int sy = -1; sy <= 1; ++sy)
                if (trimArcsContain(arc, uv + 0.5 * (double(sx) * jx + double(sy) * jy)) != inside)
                    return;
        ++r.far;
        r.farX = x, r.farY = y, r.farUv = uv, r.farJx = jx, r.farJy = jy;
    };
    // A trimmed surface shown in the trimmed render must be kept at its own (u, v) there; one
    // shown in the untrimmed render but not at that place in the trimmed one must be cut. (The
    // two renders' (u, v) at a pixel may differ by rounding where the pixel centre lies on a
    // base polygon edge, so "that place" allows a hundredth of a pixel's footprint.)
    for (int y = 0; y < whole.height; ++y)
        for (int x = 0; x < whole.width; ++x) {
            const float* w = whole.pixel(x, y);
            const float* t = trimmed.pixel(x, y);
            if (arcs.count(t[0]))
                check(trimmed, x, y, true);
            if (!arcs.count(w[0]))
                continue;
            const glm::dvec2 step =
                glm::abs(derivative(whole, x, y, 1, 0)) + glm::abs(derivative(whole, x, y, 0, 1));
            const glm::dvec2 d = glm::abs(uvAt(whole, x, y) - uvAt(trimmed, x, y));
            if (t[0] != w[0] || d.x > 0.01 * step.x + 1e-7 || d.y > 0.01 * step.y + 1e-7)
                check(whole, x, y, false);
        }
    return r;
}

/// The middle of the trim curve of `s` that lies furthest inside its trims' (u, v) box: where
/// a zoom onto a trim edge keeps the surface around the edge in view.
glm::dvec2 innermostCurveMiddle(const Surface& s) {
    const ParameterBox box = trimParameterBox(s);
    glm::dvec2 target{0.0};
    double inside = -1.0;
    for (const TrimLoop& l : s.trims)
        for (const NurbsCurve2& c : l.curves) {
            const Interval d = curveDomain(c);
            const glm::dvec2 m = curvePoint(c, 0.5 * (d.first + d.last));
            const double margin = std::min({(m.x - box.u.first) / (box.u.last - box.u.first),
                                            (box.u.last - m.x) / (box.u.last - box.u.first),
                                            (m.y - box.v.first) / (box.v.last - box.v.first),
                                            (box.v.last - m.y) / (box.v.last - box.v.first)});
            if (margin > inside)
                inside = margin, target = m;
        }
    return target;
}

} // namespace

class TestRenderTrimsExact : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    bool renderPair(const Document& doc, const Camera& cam, const RenderOptions& base,
                    AovBuffer& trimmed, AovBuffer& whole) {
        RenderOptions opt = base;
        opt.trims = false;
        if (const Status drawn = m_renderer->render(doc, cam, opt); !drawn)
            return qWarning() << drawn.message(), false;
        whole = m_renderer->aov();
        opt.trims = true;
        if (const Status drawn = m_renderer->render(doc, cam, opt); !drawn)
            return qWarning() << drawn.message(), false;
        trimmed = m_renderer->aov();
        return true;
    }

    GpuScene& gpu() { return RendererTestHook::scene(m_renderer->renderer()); }
    const TrimMaskPass& masks() { return gpu().trimMasks(); }
    /// Trimmed surfaces holding a grid block, and the words they hold.
    int blockCount() {
        int n = 0;
        for (const SurfaceRecord* r : gpu().records())
            n += r->mask.grid.words > 0;
        return n;
    }

private Q_SLOTS:
    void initTestCase() {
        m_renderer = std::make_unique<OffscreenRenderer>();
        KW_VERIFY_OK(m_renderer->create());
        KW_VERIFY_OK(m_renderer->setSize(QSize(kSide, kSide), true));
    }

    void pixelsAgreeAtEveryZoom_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<double>("zoom");
        QTest::addColumn<int>("budgetKiB"); // 0: the default budget
        QTest::addColumn<int>("loop");      // the loop zoomed on
        QTest::addColumn<double>("along");  // where on the curve, as a part of its domain
        for (double zoom : {1.0, 8.0, 64.0}) {
            // The plate's rounded outline (rational quarter circles) and the concave star hole.
            QTest::addRow("trimmed_plate %gx", zoom) << "trimmed_plate" << zoom << 0 << 0 << 0.5;
            QTest::addRow("star_island %gx", zoom) << "star_island" << zoom << 0 << 1 << 0.5;
        }
        // A budget far below the need: coarse grids, the same exact picture.
        QTest::addRow("trimmed_plate 64x, 8 KiB budget")
            << "trimmed_plate" << 64.0 << 8 << 0 << 0.5;
        // Near either end of a quarter circle, where it turns into a straight edge: one of its
        // coordinates nears its extremum, so the GPU's root find on the piece
        // (shaders/trim_exact.glsl) works where the arc's slope along the solved axis nears
        // zero, its least well-conditioned place. (Right at the ends the view holds too little
        // cut away.)
        for (double along : {0.1, 0.9})
            QTest::addRow("trimmed_plate arc at %g, 512x", along)
                << "trimmed_plate" << 512.0 << 0 << 0 << along;
    }

    void pixelsAgreeAtEveryZoom() {
        QFETCH(QString, sample);
        QFETCH(double, zoom);
        QFETCH(int, budgetKiB);
        QFETCH(int, loop);
        QFETCH(double, along);
        const auto scene = loadSample(sample);
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        const Surface& s = scene->surfaces.front();
        QVERIFY(!s.trims.empty());
        // Zoom on the loop's second curve (a rational arc on the plate), or its only one.
        const std::vector<NurbsCurve2>& curves = s.trims.at(size_t(loop)).curves;
        const NurbsCurve2& c = curves.size() > 1 ? curves[1] : curves[0];
        if (sample == "trimmed_plate") // a quarter circle: degree 2, weights not all equal
            QVERIFY(c.degree == 2 && std::any_of(c.weights.begin(), c.weights.end(),
                                                 [&](double w) { return w != c.weights.front(); }));
        const Interval d = curveDomain(c);
        const Camera cam = zoomedOn(fitCamera(*scene, 1.0), s,
                                    curvePoint(c, d.first + along * (d.last - d.first)), zoom);
        RenderOptions opt;
        if (budgetKiB)
            opt.trimBudgetBytes = std::int64_t(budgetKiB) << 10;
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, cam, opt, trimmed, whole));
        const TrimMask* m = gpu().mask(s.id);
        QVERIFY(m && m->grid.words > 0 && m->layer < 0);
        const PixelAgreement a = comparePixels(*scene, trimmed, whole);
        qInfo("%s at %gx (grid %dx%d, %lld bytes): %ld pixels (%ld kept), %ld disagree within "
              "half a pixel of a curve, %ld further",
              qPrintable(sample), zoom, m->width, m->height, (long long)masks().residentBytes(),
              a.checked, a.kept, a.disagree - a.far, a.far);
        if (a.far)
            qInfo("far: pixel (%d, %d) at (%.9g, %.9g), d/dx (%.3g, %.3g), d/dy (%.3g, %.3g)",
                  a.farX, a.farY, a.farUv.x, a.farUv.y, a.farJx.x, a.farJx.y, a.farJy.x, a.farJy.y);
        QVERIFY(a.checked > kSide * kSide / 16);
        QVERIFY(a.kept > a.checked / 20 && a.kept < a.checked * 19 / 20); // an edge in view
        // At 64x the plate and the star each have a pixel whose float u equals a piece end's u
        // to the last bit (the star at a vertex): the GPU's root find once took that end's zero
        // for the wrong side of the bracket and misclassified it far from any curve.
        QCOMPARE(a.far, 0L);
        if (budgetKiB) {
            // The budget is at least kMinTrimBudgetBytes.
            const std::int64_t budget =
                std::max(std::int64_t(budgetKiB) << 10, kMinTrimBudgetBytes);
            QVERIFY(!masks().budgetWarning().isEmpty());
            QVERIFY(gpu().maskWarnings().contains(masks().budgetWarning()));
            QVERIFY(masks().gridBytesUsed() <= budget);
            QVERIFY(masks().residentBytes() <= budget);
        } else {
            QVERIFY(masks().budgetWarning().isEmpty());
        }
    }

    void hammerFacesAgree_data() {
        QTest::addColumn<double>("zoom");
        for (double zoom : {1.0, 8.0, 64.0})
            QTest::addRow("%gx", zoom) << zoom;
    }

    /// Every trimmed face of hammer.iges in the fitted view; closer up, the face whose trims
    /// cut the most from their (u, v) box, alone (nothing in front of its cut-away parts),
    /// zoomed on the middle of its trim curve furthest inside that box.
    void hammerFacesAgree() {
#ifndef KW_HAVE_OCCT
        QSKIP("built without OpenCASCADE (KW_HAVE_OCCT): hammer.iges cannot be imported");
#else
        QFETCH(double, zoom);
        const auto imported = importFile(QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges"));
        QVERIFY2(imported, qPrintable(imported.message()));
        Scene scene = imported->scene;
        Camera cam = fitCamera(scene, 1.0);
        if (zoom > 1.0) {
            const Surface* best = nullptr;
            double bestCut = 0.0;
            for (const Surface& s : scene.surfaces) {
                if (s.trims.empty())
                    continue;
                const ParameterBox box = trimParameterBox(s);
                const TrimRegion region = makeTrimRegion(s.trims, trimTolerance(s.geometry));
                int cut = 0;
                for (int i = 0; i < 32; ++i)
                    for (int j = 0; j < 32; ++j)
                        cut += !trimRegionContains(
                            region, {box.u.first + (i + 0.5) / 32 * (box.u.last - box.u.first),
                                     box.v.first + (j + 0.5) / 32 * (box.v.last - box.v.first)});
                if (cut / 1024.0 > bestCut)
                    bestCut = cut / 1024.0, best = &s;
            }
            QVERIFY(best && bestCut > 0.05);
            const glm::dvec2 target = innermostCurveMiddle(*best);
            const Surface face = *best;
            scene.surfaces = {face};
            cam = zoomedOn(fitCamera(scene, 1.0), face, target, zoom);
        }
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, cam, RenderOptions{}, trimmed, whole));
        const PixelAgreement a = comparePixels(scene, trimmed, whole);
        qInfo("hammer.iges at %gx: %ld pixels (%ld kept), %ld disagree within half a pixel of a "
              "curve, %ld further; %d trimmed faces use %lld bytes of grids (%lld per face)",
              zoom, a.checked, a.kept, a.disagree - a.far, a.far, blockCount(),
              (long long)masks().gridBytesUsed(),
              (long long)(masks().gridBytesUsed() / std::max(blockCount(), 1)));
        if (a.far)
            qInfo("far: pixel (%d, %d) at (%.9g, %.9g)", a.farX, a.farY, a.farUv.x, a.farUv.y);
        QVERIFY(a.checked > 10000);
        if (zoom > 1.0)
            QVERIFY(a.kept > a.checked / 20 && a.kept < a.checked * 19 / 20); // an edge in view
        QCOMPARE(a.far, 0L);
#endif
    }

    // Every trimmed face of hammer.iges, drawn alone and zoomed 8x and 64x onto the middle of
    // the trim curve that lies furthest inside its (u, v) box: no pixel disagrees with the CPU
    // further than half a pixel from a curve. At 512^2 to keep the suite short (the 1024^2
    // rows above check the face its trims cut most).
    void everyHammerFaceAgreesZoomed() {
#ifndef KW_HAVE_OCCT
        QSKIP("built without OpenCASCADE (KW_HAVE_OCCT): hammer.iges cannot be imported");
#else
        const auto imported = importFile(QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges"));
        QVERIFY2(imported, qPrintable(imported.message()));
        QVERIFY(m_renderer->setSize(QSize(512, 512), true));
        int faces = 0;
        long checked = 0, near = 0, lone = 0;
        QStringList failures;
        for (const Surface& face : imported->scene.surfaces) {
            if (face.trims.empty())
                continue;
            ++faces;
            const glm::dvec2 target = innermostCurveMiddle(face);
            Scene scene = imported->scene;
            scene.surfaces = {face};
            Document doc;
            KW_VERIFY_OK(doc.resetScene(scene));
            for (double zoom : {8.0, 64.0}) {
                const Camera cam = zoomedOn(fitCamera(scene, 1.0), face, target, zoom);
                AovBuffer trimmed, whole;
                QVERIFY(renderPair(doc, cam, RenderOptions{}, trimmed, whole));
                const PixelAgreement a = comparePixels(scene, trimmed, whole);
                checked += a.checked;
                near += a.disagree - a.far - a.lone;
                lone += a.lone;
                if (a.far) {
                    failures << QStringLiteral("face %1 at %2x: %3 of %4 pixels far off, e.g. "
                                               "(%5, %6) at (u, v) (%7, %8)")
                                    .arg(face.id.value)
                                    .arg(zoom)
                                    .arg(a.far)
                                    .arg(a.checked)
                                    .arg(a.farX)
                                    .arg(a.farY)
                                    .arg(a.farUv.x, 0, 'g', 9)
                                    .arg(a.farUv.y, 0, 'g', 9);
                }
            }
        }
        qInfo("hammer.iges: %d trimmed faces at 8x and 64x, %ld pixels, %ld disagree within half "
              "a pixel of a curve, %ld at lone pixels of faces thinner than a pixel, %lld further",
              faces, checked, near, lone, (long long)failures.size());
        QVERIFY(faces >= 40);
        QVERIFY2(failures.isEmpty(), qPrintable(failures.join(QStringLiteral("; "))));
        QVERIFY2(lone <= checked / 100000, qPrintable(QString::number(lone))); // a few slivers
        QVERIFY(m_renderer->setSize(QSize(kSide, kSide), true));
#endif
    }

    void splitByTrimsKeepsEveryPixel_data() {
        QTest::addColumn<QString>("model");
        QTest::addColumn<double>("zoom");
        QTest::addColumn<bool>("adaptive");
        for (const char* m : {"star_island", "trimmed_plate", "hammer"}) {
            QTest::addRow("%s fitted uniform", m) << QString(m) << 1.0 << false;
            QTest::addRow("%s fitted adaptive", m) << QString(m) << 1.0 << true;
            QTest::addRow("%s 6x adaptive", m) << QString(m) << 6.0 << true;
        }
    }

    /// The pre-pass split by the trims (RenderOptions::splitCellsByTrims, kw::splitByTrims)
    /// shows exactly the pixels and AOVs of the pre-pass over whole ranges, while it tests the
    /// trims on fewer cells and leaves out cells the trims remove.
    void splitByTrimsKeepsEveryPixel() {
        QFETCH(QString, model);
        QFETCH(double, zoom);
        QFETCH(bool, adaptive);
        Scene scene;
        if (model == QLatin1String("hammer")) {
#ifndef KW_HAVE_OCCT
            QSKIP("built without OpenCASCADE (KW_HAVE_OCCT): hammer.iges cannot be imported");
#else
            const auto imported = importFile(QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges"));
            QVERIFY2(imported, qPrintable(imported.message()));
            scene = imported->scene;
#endif
        } else {
            const auto sample = loadSample(model);
            QVERIFY2(sample, qPrintable(sample.message()));
            scene = *sample;
        }
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        Camera cam = fitCamera(doc.scene(), 1.0);
        if (zoom > 1.0) {
            // Into the middle of the first trimmed surface's trim box (cut away on the star).
            const auto it = std::find_if(doc.scene().surfaces.begin(), doc.scene().surfaces.end(),
                                         [](const Surface& s) { return !s.trims.empty(); });
            QVERIFY(it != doc.scene().surfaces.end());
            const ParameterBox box = trimParameterBox(*it);
            cam = zoomedOn(cam, *it,
                           {0.5 * (box.u.first + box.u.last), 0.5 * (box.v.first + box.v.last)},
                           zoom);
        }
        RenderOptions opt;
        opt.partitioning =
            adaptive ? RenderOptions::Partitioning::Adaptive : RenderOptions::Partitioning::Uniform;
        QImage colour[2];
        AovBuffer aov[2];
        FrameReport report[2];
        for (int k = 0; k < 2; ++k) {
            opt.splitCellsByTrims = k == 1;
            KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
            colour[k] = m_renderer->colorImage();
            aov[k] = m_renderer->aov();
            report[k] = m_renderer->lastReport();
        }
        const FrameReport::Partitions& off = report[0].partitions;
        const FrameReport::Partitions& on = report[1].partitions;
        qInfo("%s: %lld cells; trims tested on %lld cells, split: %lld (%lld left out)",
              qPrintable(QTest::currentDataTag()), (long long)off.cells,
              (long long)off.trimTestedCells, (long long)on.trimTestedCells,
              (long long)on.trimmedAwayCells);
        QCOMPARE(off.trimmedAwayCells, std::int64_t(0));
        QVERIFY(off.trimTestedCells > 0);
        QVERIFY(on.trimTestedCells < off.trimTestedCells);
        if (!adaptive) {
            QCOMPARE(colour[1], colour[0]);
            QVERIFY(aov[1].data == aov[0].data);
            return;
        }
        // Finer cells fit between the curves and the box: some lie wholly outside the trims
        // (the coarse 10 x 10 star keeps a texel's margin in every cell).
        QVERIFY(on.trimmedAwayCells > 0);
        // Adaptive frames test the trims at the point under the pixel, which lies up to the
        // pixel tolerance from the polygon's (u, v): a cell the split calls wholly inside or
        // trimmed away (its texels and their neighbours) can have a pixel whose point crosses
        // a curve where the grid's texels are finer than that on screen, so the split keeps or
        // leaves out a pixel the whole ranges do not (within the tolerance of the edge):
        // measured 0 on the samples, 3 and 2 pixels on hammer.iges. Testing those cells too
        // would cost a close-up through a hole 11x (docs/PERFORMANCE.md ## Edges).
        int differ = 0;
        const size_t channels = size_t(AovBuffer::kChannels);
        for (int y = 0; y < colour[0].height(); ++y)
            for (int x = 0; x < colour[0].width(); ++x) {
                const size_t at = (size_t(y) * size_t(aov[0].width) + size_t(x)) * channels;
                differ += colour[0].pixel(x, y) != colour[1].pixel(x, y) ||
                          !std::equal(aov[0].data.begin() + std::ptrdiff_t(at),
                                      aov[0].data.begin() + std::ptrdiff_t(at + channels),
                                      aov[1].data.begin() + std::ptrdiff_t(at));
            }
        qInfo("pixels the split changes: %d", differ);
        QVERIFY(aov[0].width == colour[0].width() && aov[1].data.size() == aov[0].data.size());
        QVERIFY(differ <= 6);
    }

    void memoryFollowsEachSurfacesNeed() {
        // 256 trimmed surfaces, scaled from tiny to large on screen: the grids depend on the
        // trims alone, so the words in use are the sum of each surface's own packed grid, and
        // the buffer holds at most a quarter more (it grows by a quarter).
        const auto plate = loadSample(QStringLiteral("trimmed_plate"));
        const auto star = loadSample(QStringLiteral("star_island"));
        QVERIFY(plate && star);
        Scene scene;
        std::int64_t need = 0;
        for (int k = 0; k < 256; ++k) {
            Surface s = (k % 2 ? *star : *plate).surfaces.front();
            s.id = SurfaceId{std::uint32_t(k + 1)};
            const double scale = std::pow(2.0, (k % 8) - 4.0); // 1/16 .. 8
            for (glm::dvec3& p : s.geometry.points)
                p = p * scale + glm::dvec3(6.0 * (k % 16), 6.0 * (k / 16), 0.0);
            for (TrimLoop& l : s.trims)
                l.id = TrimLoopId{std::uint32_t(1000 + 10 * k + (l.id.value % 10))};
            const TrimArcs arcs = makeTrimArcs(s.trims, trimTolerance(s.geometry));
            need +=
                4 * std::int64_t(
                        packTrimGrid(makeTrimGrid(arcs, trimGridResolution(arcs)), arcs).size());
            scene.surfaces.push_back(s);
        }
        scene.nextId = 5000;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        RenderOptions opt;
        KW_VERIFY_OK(m_renderer->render(doc, fitCamera(scene, 1.0), opt));
        QCOMPARE(blockCount(), 256);
        QCOMPARE(masks().gridBytesUsed(), need);
        const std::int64_t exact = masks().residentBytes();
        QVERIFY(exact >= need && exact <= need + need / 4 + 4096); // the growth step's slack
        const FrameReport report = m_renderer->lastReport();
        QCOMPARE(report.gpuBytes.trimMasks, exact);
        // The paper's mask array for the same scene, and back: exact mode's memory is freed
        // while masks are in use, and the other way round.
        opt.trimMode = RenderOptions::TrimMode::Mask;
        KW_VERIFY_OK(m_renderer->render(doc, fitCamera(scene, 1.0), opt));
        const std::int64_t mask = masks().residentBytes();
        QCOMPARE(masks().gridBytesUsed(), 0);
        qInfo("256 surfaces: exact grids need %lld bytes (buffer %lld); the mask array holds "
              "%lld bytes",
              (long long)need, (long long)exact, (long long)mask);
        QVERIFY(exact < mask);
        opt.trimMode = RenderOptions::TrimMode::Exact;
        KW_VERIFY_OK(m_renderer->render(doc, fitCamera(scene, 1.0), opt));
        QCOMPARE(masks().residentBytes(), exact);
        // Removing every surface frees every grid.
        QVERIFY(doc.resetScene(Scene{}));
        KW_VERIFY_OK(m_renderer->render(doc, fitCamera(scene, 1.0), opt));
        QCOMPARE(masks().residentBytes(), 0);
    }

    void blocksStartOnWholeQuads() {
        // The shader reads pieces and points 4 words at a time through an RGBA32UI view of the
        // array (shaders/trim_exact.glsl, kwTrimQuad): blocks, pieces and points must start on
        // a multiple of 4 words, whatever the sizes before them.
        TrimGridStore store;
        std::vector<TrimGridBlock> blocks(6);
        bool grew = false;
        for (size_t k = 0; k < blocks.size(); ++k) {
            const auto scene = loadSample(k % 2 ? "star_island" : "trimmed_plate");
            QVERIFY2(scene, qPrintable(scene.message()));
            const Surface& s = scene->surfaces.front();
            const TrimArcs arcs = makeTrimArcs(s.trims, trimTolerance(s.geometry));
            // Resolutions whose texel lists leave the entries at every length modulo 4.
            const int side = 16 + int(k);
            std::vector<std::uint32_t> words = packTrimGrid(makeTrimGrid(arcs, {side, side}), arcs);
            QCOMPARE(words.size() % 4, size_t(0));
            QCOMPARE(words[1] % 4, 0u); // pieces
            QCOMPARE(words[3] % 4, 0u); // points
            if (k == 3)
                words.resize(words.size() - 3); // a size not of whole quads still places on one
            QVERIFY(store.place(blocks[k], words, &grew));
            QCOMPARE(blocks[k].offset % 4, 0u);
            QCOMPARE(blocks[k].words % 4, 0u);
            if (k == 2)
                store.release(blocks[1]); // a hole for the next blocks to fill
        }
    }

    void arenaGrowsByAQuarter() {
        // The GPU buffer is the whole array: growth is memory held unused. Doubling put 2^20 +
        // 64 words in an array of 2^21 (Motor-c's 8.04 MiB of grids in a 16 MiB buffer).
        TrimWordArena arena;
        QCOMPARE(arena.allocate(1u << 20), 0u);
        QCOMPARE(arena.capacity(), 1u << 20);
        QCOMPARE(arena.allocate(64), 1u << 20);
        QCOMPARE(arena.used(), (1u << 20) + 64);
        QCOMPARE(arena.capacity(), (1u << 20) + (1u << 18));
        // Blocks one after another: the array stays within a quarter (or 1024 words) of them,
        // and every range starts on a multiple of 4 words.
        TrimWordArena blocks;
        std::uint32_t used = 0;
        for (std::uint32_t k = 0; k < 2000; ++k) {
            const std::uint32_t words = 4 * (1 + (k * 37) % 500);
            QCOMPARE(blocks.allocate(words) % 4, 0u);
            used += words;
            QVERIFY2(blocks.capacity() <= used + std::max(used / 4, 1024u) + 2000,
                     qPrintable(QStringLiteral("%1 words in %2").arg(used).arg(blocks.capacity())));
        }
    }

    void arenaStopsAtWhatTheShaderAddresses() {
        // Bookkeeping only (no words are stored): offsets are the shader's 32-bit words.
        TrimWordArena arena;
        QCOMPARE(arena.allocate(100), 0u);
        const std::uint32_t half = 0x80000000u;
        const std::uint32_t second = arena.allocate(half);
        QVERIFY(second != TrimWordArena::kNoRoom);
        QCOMPARE(arena.allocate(half), TrimWordArena::kNoRoom); // would need 2^32 words
        QCOMPARE(arena.used(), 100u + half);
        arena.release(second, half);
        QVERIFY(arena.allocate(half) != TrimWordArena::kNoRoom); // the freed range again
    }

    void oneTrimEditRebuildsOneSurface() {
        const auto both = plateBesideStar(5.0);
        QVERIFY2(both, qPrintable(both.message()));
        const Scene& scene = *both;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = fitCamera(scene, 1.0);
        KW_VERIFY_OK(m_renderer->render(doc, cam, RenderOptions{}));
        gpu().resetStats();
        KW_VERIFY_OK(m_renderer->render(doc, cam, RenderOptions{}));
        QCOMPARE(gpu().totalMaskStats().redraws, 0); // nothing changed, nothing rebuilt
        const Surface& s = doc.scene().surfaces.back();
        const TrimPointRef ref{s.id, s.trims.front().id, 0, 1};
        const glm::dvec2 old = s.trims.front().curves.front().points[1];
        QVERIFY(doc.setTrimPoint(ref, old + glm::dvec2(0.01, 0.02)));
        KW_VERIFY_OK(m_renderer->render(doc, cam, RenderOptions{}));
        QCOMPARE(gpu().totalMaskStats().redraws, 1);
        QCOMPARE(gpu().maskStats(s.id).redraws, 1);
        QCOMPARE(gpu().maskStats(doc.scene().surfaces.front().id).redraws, 0);
        qInfo("one trim point moved: %.3f ms CPU to rebuild its surface's grid",
              gpu().maskStats(s.id).cpuNanoseconds / 1e6);
        // And the picture follows the edit exactly.
        AovBuffer trimmed, whole;
        QVERIFY(renderPair(doc, cam, RenderOptions{}, trimmed, whole));
        QCOMPARE(comparePixels(doc.scene(), trimmed, whole).far, 0L);
    }
};

QTEST_MAIN(TestRenderTrimsExact)
#include "tst_render_trims_exact.moc"
