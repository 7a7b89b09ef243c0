// GL test: base polygons keep only the cells that may reach the view (kw::cutInView,
// RenderOptions::polygonsInView). Every cell of the whole cut that shows a point on screen is
// kept (checked on the CPU), and close-up frames are the same bytes, colour and AOV, as with
// every cell, while holding fewer cells and fewer polygon bytes. A close-up with nothing for the
// deferred pass gives its per-pixel input back.
#include "expected_test_util.h"
#include "model/nurbs/nurbs.h"
#include "model/nurbs/visible_bounds.h"
#include "render/adaptive_partitions.h"
#include "render/gpu_layout.h"
#include "render/offscreen_renderer.h"
#include "render_test_util.h"

#include <array>
#include <cstring>

using namespace kw;

namespace {

constexpr QSize kSize(256, 192);

FrameCamera frameOf(const Scene& scene, const Camera& camera) {
    FrameCamera fc = frameCamera(camera, scene, double(kSize.width()) / kSize.height());
    fc.viewport = glm::ivec2(kSize.width(), kSize.height());
    return fc;
}

/// The close-ups: the teapot's patches and a sphere, 8x and 64x closer on points of their
/// outline and inside, so surfaces reach off screen on every side.
struct View {
    const char* name;
    Camera camera;
};

std::vector<View> closeUps(const Scene& scene) {
    const double aspect = double(kSize.width()) / kSize.height();
    const Camera fit = fitCamera(scene, aspect);
    std::vector<View> out;
    out.push_back({"fitted", fit});
    for (const double zoom : {8.0, 64.0})
        for (const glm::dvec2 at : {glm::dvec2(0.5, 0.5), glm::dvec2(0.3, 0.62)}) {
            out.push_back({zoom < 10.0 ? "8x" : "64x", zoomedCamera(fit, zoom, at, aspect)});
        }
    // Closer along the line of sight: the eye among the patches, some of them behind it.
    Camera inside = fit;
    inside.eye = fit.target + (fit.eye - fit.target) * 0.3;
    out.push_back({"eye close", inside});
    return out;
}

/// True when some point of the cell's two triangles (5 x 5 barycentric samples and its
/// corners) projects inside the viewport in front of the eye.
bool cellShows(const NurbsSurface& g, const BasePolygon& poly, int i, int j,
               const FrameCamera& fc) {
    const auto node = [&](int a, int b) {
        return surfacePoint(g, poly.breaksU[size_t(i + a)], poly.breaksV[size_t(j + b)]);
    };
    const glm::dvec3 c00 = node(0, 0), c10 = node(1, 0), c11 = node(1, 1), c01 = node(0, 1);
    const glm::dmat4 vp(fc.viewProjection);
    for (const auto& tri : {std::array{c00, c10, c11}, std::array{c00, c11, c01}})
        for (int a = 0; a <= 4; ++a)
            for (int b = 0; a + b <= 4; ++b) {
                const double l1 = a / 4.0, l2 = b / 4.0, l0 = 1.0 - l1 - l2;
                const glm::dvec4 c = vp * glm::dvec4(l0 * tri[0] + l1 * tri[1] + l2 * tri[2], 1.0);
                if (c.w > 0.0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w)
                    return true;
            }
    return false;
}

} // namespace

class TestRenderInView : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        auto made = kwtest::offscreenRenderer(kSize, true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    // Every cell of the whole cut with a point on screen lies in the block cutInView keeps,
    // and a close-up leaves most cells out.
    void keepsEveryCellOnScreen() {
        const auto teapot = kwtest::loadSample(QStringLiteral("teapot"));
        QVERIFY2(teapot, qPrintable(teapot.message()));
        std::int64_t whole = 0, kept = 0, shown = 0;
        for (const View& view : closeUps(*teapot)) {
            const FrameCamera fc = frameOf(*teapot, view.camera);
            const ScreenScale scale = frameScreenScale(fc);
            for (const Surface& s : teapot->surfaces) {
                AdaptivePartitions all, inView;
                const ParameterBox box = trimParameterBox(s);
                all.choose(s, Revisions{}, box, scale, 1, 0.5, s.partitionsU, s.partitionsV,
                           nullptr, false);
                inView.choose(s, Revisions{}, box, scale, 1, 0.5, s.partitionsU, s.partitionsV,
                              nullptr, true);
                QCOMPARE(inView.choiceCells(), all.choiceCells());
                const BasePolygon full = buildBasePolygon(s.geometry, box, all.cut());
                const PolygonCut& cut = inView.cut();
                // The kept cells are a block of the whole cut's rows and columns.
                const auto at = [](const std::vector<double>& in, double t) {
                    return int(std::find(in.begin(), in.end(), t) - in.begin());
                };
                const int iu0 = at(full.breaksU, cut.breaksU.front());
                const int iv0 = at(full.breaksV, cut.breaksV.front());
                const int cu = int(cut.breaksU.size()) - 1, cv = int(cut.breaksV.size()) - 1;
                QVERIFY(iu0 + cu <= full.cellsU() && iv0 + cv <= full.cellsV());
                QVERIFY(std::equal(cut.breaksU.begin(), cut.breaksU.end(),
                                   full.breaksU.begin() + iu0));
                QVERIFY(std::equal(cut.breaksV.begin(), cut.breaksV.end(),
                                   full.breaksV.begin() + iv0));
                whole += full.cellCount();
                kept += std::int64_t(cu) * cv;
                for (int j = 0; j < full.cellsV(); ++j)
                    for (int i = 0; i < full.cellsU(); ++i) {
                        if (!cellShows(s.geometry, full, i, j, fc))
                            continue;
                        ++shown;
                        QVERIFY2(i >= iu0 && i < iu0 + cu && j >= iv0 && j < iv0 + cv,
                                 qPrintable(QStringLiteral("%1: %2, cell (%3, %4) on screen "
                                                           "but not kept")
                                                .arg(QLatin1String(view.name), s.name)
                                                .arg(i)
                                                .arg(j)));
                    }
            }
        }
        qInfo("%lld cells of the whole cuts, %lld kept, %lld with a point on screen",
              (long long)whole, (long long)kept, (long long)shown);
        QVERIFY(shown > 0);
        QVERIFY(2 * kept < whole);
    }

    void sameFrameWithFewerCells_data() {
        QTest::addColumn<QString>("sample");
        QTest::newRow("teapot") << QStringLiteral("teapot");
        QTest::newRow("sphere") << QStringLiteral("sphere");
        // Trimmed faces: the cells near a curve and those trimmed away are split.
        QTest::newRow("plate beside star") << QStringLiteral("plate+star");
    }
    // The frames with only the cells in view are the frames with every cell, byte for byte.
    void sameFrameWithFewerCells() {
        QFETCH(QString, sample);
        Scene sphere;
        sphere.surfaces.push_back(kwtest::makeSurface(1, makeSphere({0, 0, 0}, 1.0), 1));
        sphere.nextId = 2;
        auto s = sample == QLatin1String("plate+star") ? kwtest::plateBesideStar(2.4)
                 : sample == QLatin1String("sphere") ? Expected<Scene>(sphere)
                                                     : kwtest::loadSample(sample);
        QVERIFY2(s, qPrintable(s.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*s));
        RenderOptions opt;
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        std::int64_t cellsAll = 0, cellsInView = 0, hostAll = 0, hostInView = 0;
        for (const View& view : closeUps(doc.scene())) {
            opt.polygonsInView = false;
            KW_VERIFY_OK(m_renderer->render(doc, view.camera, opt));
            const FrameReport all = m_renderer->lastReport();
            const QImage colour = m_renderer->colorImage();
            const AovBuffer aov = m_renderer->aov();
            opt.polygonsInView = true;
            KW_VERIFY_OK(m_renderer->render(doc, view.camera, opt));
            const FrameReport in = m_renderer->lastReport();
            const QImage inColour = m_renderer->colorImage();
            const AovBuffer inAov = m_renderer->aov();
            int covered = 0, otherColour = 0, otherAov = 0;
            for (int y = 0; y < aov.height; ++y)
                for (int x = 0; x < aov.width; ++x) {
                    covered += aov.pixel(x, y)[0] >= 0.0f;
                    otherColour += colour.pixel(x, y) != inColour.pixel(x, y);
                    otherAov += std::memcmp(aov.pixel(x, y), inAov.pixel(x, y),
                                            sizeof(float) * size_t(AovBuffer::kChannels)) != 0;
                }
            qInfo("%s: %lld cells with every cell, %lld in view; %d covered pixels, %d of "
                  "another colour, %d another AOV",
                  view.name, (long long)all.partitions.cells, (long long)in.partitions.cells,
                  covered, otherColour, otherAov);
            QVERIFY2(covered > 1000, view.name);
            QCOMPARE(otherColour, 0);
            QCOMPARE(otherAov, 0);
            QVERIFY(in.partitions.cells <= all.partitions.cells);
            // The same choice: the partition bound and the surfaces drawn do not change.
            QCOMPARE(in.partitions.worstBoundPixels, all.partitions.worstBoundPixels);
            QCOMPARE(in.partitions.deferredSurfaces, all.partitions.deferredSurfaces);
            // The host copies (control texels, polygon vertices, span bounds, fins) follow.
            QVERIFY(in.hostCopyBytes > 0);
            QVERIFY(in.hostCopyBytes <= all.hostCopyBytes);
            cellsAll += all.partitions.cells;
            cellsInView += in.partitions.cells;
            hostAll += all.hostCopyBytes;
            hostInView += in.hostCopyBytes;
        }
        // A sphere's far side lies in the view's frustum too, behind its near side: the block
        // of rows and columns holding both keeps most of its cells.
        QVERIFY(cellsInView < cellsAll);
        QVERIFY(hostInView < hostAll);
        if (sample != QLatin1String("sphere"))
            QVERIFY(2 * cellsInView < cellsAll);
    }

    // The deferred pass's input (16 bytes a pixel) is held while frames defer, and given back
    // by a close-up whose surfaces all have cells large enough for the forward way.
    void closeUpGivesTheDeferredInputBack() {
        const auto teapot = kwtest::loadSample(QStringLiteral("teapot"));
        QVERIFY2(teapot, qPrintable(teapot.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*teapot));
        RenderOptions opt;
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        const double aspect = double(kSize.width()) / kSize.height();
        const Camera fit = fitCamera(doc.scene(), aspect);
        const std::int64_t input = std::int64_t(kSize.width()) * kSize.height() * 16;
        KW_VERIFY_OK(m_renderer->render(doc, fit, opt));
        const FrameReport fitted = m_renderer->lastReport();
        QVERIFY(fitted.partitions.deferredSurfaces > 0);
        QVERIFY(fitted.gpuBytes.perSurface >= input);
        const Camera near = zoomedCamera(fit, 64.0, glm::dvec2(0.5, 0.5), aspect);
        KW_VERIFY_OK(m_renderer->render(doc, near, opt));
        const FrameReport close = m_renderer->lastReport();
        QCOMPARE(close.partitions.deferredSurfaces, 0);
        QVERIFY(close.gpuBytes.perSurface < input);
        // And made again when a frame defers.
        KW_VERIFY_OK(m_renderer->render(doc, fit, opt));
        QCOMPARE(m_renderer->lastReport().partitions.deferredSurfaces,
                 fitted.partitions.deferredSurfaces);
        QCOMPARE(m_renderer->lastReport().gpuBytes.perSurface, fitted.gpuBytes.perSurface);
    }
};

QTEST_MAIN(TestRenderInView)
#include "tst_render_in_view.moc"
