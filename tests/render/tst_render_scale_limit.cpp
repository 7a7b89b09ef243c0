// Forty strips whose control points together need about ten times the GPU's buffer limit
// (lowered to 1 MiB for the test): the frame reports them in one short line with the totals,
// not a line per surface, and draws the surfaces that fit.
#include "expected_test_util.h"
#include "render/gpu_scene.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"

#include <QRegularExpression>
#include <QScopeGuard>

using namespace kw;

class TestRenderScaleLimit : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void manySurfacesPastTheLimitGiveOneShortLine() {
        auto made = kwtest::offscreenRenderer(QSize(64, 64), true);
        QVERIFY2(made, qPrintable(made.message()));
        std::unique_ptr<OffscreenRenderer> renderer = std::move(made).value();
        GpuScene::setBufferLimitForTests(1048576);
        const auto restore = qScopeGuard([] { GpuScene::setBufferLimitForTests(0); });
        // 8192 x 2 control points: 256 KiB of control texels per strip, so about four fit.
        constexpr int kStrips = 40;
        Scene scene;
        for (int k = 0; k < kStrips; ++k) {
            NurbsSurface g;
            g.countU = 8192;
            g.countV = 2;
            g.knotsU = kwtest::clampedUniform(1, g.countU);
            g.knotsV = {0, 0, 1, 1};
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < g.countU; ++i) {
                    g.points.emplace_back(double(i) / g.countU, double(j) + 1.5 * k, 0.0);
                    g.weights.push_back(1.0);
                }
            scene.surfaces.push_back(kwtest::makeSurface(std::uint32_t(k + 1), g, 1));
        }
        scene.nextId = kStrips + 1;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        const auto result = renderer->render(doc, fitCamera(scene, 1.0), RenderOptions{});
        QVERIFY(!result);
        QVERIFY2(!result.message().contains(QLatin1Char('\n')) && result.message().size() < 300,
                 qPrintable(result.message()));
        const QRegularExpressionMatch m =
            QRegularExpression(QStringLiteral("^(\\d+) of 40 surfaces do not fit the GPU's "
                                              "buffer limit of 1048576 bytes"))
                .match(result.message());
        QVERIFY2(m.hasMatch(), qPrintable(result.message()));
        const int refused = m.captured(1).toInt();
        QVERIFY2(refused > 20 && refused < kStrips, qPrintable(result.message()));
        // The ones that fit are on the GPU; the count of those left out is the error's.
        int drawn = 0;
        for (const Surface& s : doc.scene().surfaces)
            drawn += RendererTestHook::scene(renderer->renderer()).surfaceGpu(s.id) != nullptr;
        QCOMPARE(drawn, kStrips - refused);
        QCOMPARE(renderer->lastReport().warnings.count(result.message()), 1);
    }
};

QTEST_MAIN(TestRenderScaleLimit)
#include "tst_render_scale_limit.moc"
