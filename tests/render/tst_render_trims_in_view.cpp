// GL test: exact trim grids are held only for the trimmed surfaces in view. A close-up on one
// patch of a grid of trimmed patches holds a fraction of the fitted view's grid bytes, draws the
// same bytes (colour and AOV) as with every grid held (culling off), and a view back out builds
// the dropped grids again: the same frame as a fresh renderer's. Trim warnings stay.
#include "expected_test_util.h"
#include "render/offscreen_renderer.h"
#include "render_test_util.h"

using namespace kw;

namespace {

constexpr QSize kSize(256, 192);

using Frame = kwtest::DrawnFrame;

int trimmedPixels(const Frame& f, const Scene& scene) {
    // Pixels of trimmed surfaces (odd ids' surfaces carry the discs) in the AOV.
    int n = 0;
    for (int y = 0; y < f.aov.height; ++y)
        for (int x = 0; x < f.aov.width; ++x) {
            const float id = f.aov.pixel(x, y)[0];
            if (id < 0.0f)
                continue;
            for (const Surface& s : scene.surfaces)
                if (s.id.value == std::uint32_t(id) && !s.trims.empty())
                    ++n;
        }
    return n;
}

} // namespace

class TestRenderTrimsInView : public QObject {
    Q_OBJECT

private Q_SLOTS:
    void closeUpHoldsTheGridsInView() {
        auto made = kwtest::offscreenRenderer(kSize, true);
        QVERIFY2(made, qPrintable(made.message()));
        OffscreenRenderer& r = **made;
        Document doc;
        Scene scene = kwtest::variantGrid(40, true);
        KW_VERIFY_OK(doc.resetScene(scene));
        RenderOptions opt;
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        opt.trimMode = RenderOptions::TrimMode::Exact;
        const double aspect = double(kSize.width()) / kSize.height();
        const Camera fit = fitCamera(doc.scene(), aspect);
        auto fitted = kwtest::drawFrame(r, doc, fit, opt);
        QVERIFY2(fitted, qPrintable(fitted.message()));
        QVERIFY(trimmedPixels(*fitted, doc.scene()) > 100);
        // A close-up on a trimmed patch (the second): its disc and its neighbours fill the view.
        const Surface& patch = doc.scene().surfaces[1];
        QVERIFY(!patch.trims.empty());
        const Camera near = kwtest::zoomedOn(fit, patch, {0.5, 0.5}, 6.0);
        auto close = kwtest::drawFrame(r, doc, near, opt);
        QVERIFY2(close, qPrintable(close.message()));
        opt.cullOutsideView = false;
        auto every = kwtest::drawFrame(r, doc, near, opt);
        QVERIFY2(every, qPrintable(every.message()));
        opt.cullOutsideView = true;
        qInfo("trim grid bytes: fitted %lld, close-up %lld, close-up holding every grid %lld",
              (long long)fitted->report.gpuBytes.trimMasks,
              (long long)close->report.gpuBytes.trimMasks,
              (long long)every->report.gpuBytes.trimMasks);
        QVERIFY(trimmedPixels(*close, doc.scene()) > 300);
        QCOMPARE(kwtest::differingPixels(*close, *every), 0);
        QVERIFY(4 * close->report.gpuBytes.trimMasks < every->report.gpuBytes.trimMasks);
        QVERIFY(4 * close->report.gpuBytes.trimMasks < fitted->report.gpuBytes.trimMasks);
        // Back out: the dropped grids are built again, the frame is the fitted one.
        auto back = kwtest::drawFrame(r, doc, fit, opt);
        QVERIFY2(back, qPrintable(back.message()));
        QCOMPARE(kwtest::differingPixels(*back, *fitted), 0);
        // Every grid held again (the array's capacity may differ with the order of placement).
        QVERIFY(back->report.gpuBytes.trimMasks > 4 * close->report.gpuBytes.trimMasks);
        QCOMPARE(back->report.warnings, fitted->report.warnings);
    }
};

QTEST_MAIN(TestRenderTrimsInView)
#include "tst_render_trims_in_view.moc"
