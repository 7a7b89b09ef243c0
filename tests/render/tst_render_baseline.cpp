// GL test: one baseline image per sample, compared with OpenImageIO under a stated tolerance.
// A missing baseline fails; KW_UPDATE_BASELINES=1 writes the baselines instead of comparing.
// On a mismatch <name>.actual.png and <name>.diff.png are written to KW_TEST_OUTPUT_DIR.
#include "baseline_compare.h"
#include "expected_test_util.h"

using namespace kw;

namespace {

// Tolerance (kwtest::BaselineTolerance): a pixel fails when any channel differs by more than
// 0.05 (about 13 of 255 levels); the image fails when more than 0.2% of its pixels do or the
// mean error exceeds 0.004. Rasteriser or compiler differences move silhouette pixels and last
// bits; a wrong normal, light or camera moves far more.
constexpr kwtest::BaselineTolerance kTolerance{0.05f, 0.002, 0.004};
constexpr int kSide = 256;

} // namespace

class TestRenderBaseline : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), false);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void matchesBaseline_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<int>("mode");
        QTest::addColumn<bool>("overlays");
        for (const char* s :
             {"bicubic", "sphere", "torus", "trimmed_plate", "star_island", "teapot"})
            QTest::newRow(s) << QString::fromLatin1(s) << int(RenderMode::Exact) << false;
        QTest::newRow("teapot_tessellated")
            << QStringLiteral("teapot") << int(RenderMode::Tessellated) << false;
        QTest::newRow("torus_overlays")
            << QStringLiteral("torus") << int(RenderMode::Exact) << true;
    }

    void matchesBaseline() {
        QFETCH(QString, sample);
        QFETCH(int, mode);
        QFETCH(bool, overlays);
        const QString name = QString::fromLatin1(QTest::currentDataTag());
        QString error;
        const auto scene = kwtest::loadSample(sample);
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        RenderOptions opt;
        opt.mode = RenderMode(mode);
        if (opt.mode == RenderMode::Tessellated)
            opt.partitionsU = opt.partitionsV = 8; // coarse, so Gouraud facets show
        if (overlays) {
            opt.partitionsU = opt.partitionsV = 6;
            opt.wireframe = opt.controlNet = true;
        }
        const Camera cam = scene->camera.authored ? scene->camera : fitCamera(*scene, 1.0);
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const QImage img = m_renderer->colorImage();
        kwtest::checkBaseline(img, name, kTolerance);
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderBaseline)
#include "tst_render_baseline.moc"
