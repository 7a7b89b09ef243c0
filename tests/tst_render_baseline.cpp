// GL test: one baseline image per sample, compared with OpenImageIO under a stated tolerance.
// A missing baseline fails; KW_UPDATE_BASELINES=1 writes the baselines instead of comparing.
// On a mismatch <name>.actual.png and <name>.diff.png are written to KW_TEST_OUTPUT_DIR.
#include "render/image_writer.h"
#include "render_test_util.h"

#include <OpenImageIO/imagebufalgo.h>

using namespace kw;

namespace {

// Tolerance: a pixel fails when any channel differs by more than kFailThreshold (0..1 scale,
// about 13 of 255 levels); the image fails when more than kMaxFailedFraction of its pixels do
// or the mean error exceeds kMaxMeanError. Rasteriser or compiler differences move silhouette
// pixels and last bits; a wrong normal, light or camera moves far more.
constexpr float kFailThreshold = 0.05f;
constexpr double kMaxFailedFraction = 0.002;
constexpr double kMaxMeanError = 0.004;
constexpr int kSide = 256;

QString baselinePath(const QString& name) {
    return QStringLiteral(KW_SOURCE_DIR "/tests/baselines/") + name + QStringLiteral(".png");
}

} // namespace

class TestRenderBaseline : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        m_renderer = std::make_unique<OffscreenRenderer>();
        QString error;
        QVERIFY2(m_renderer->create(&error), qPrintable(error));
        QVERIFY2(m_renderer->setSize(QSize(kSide, kSide), false, &error), qPrintable(error));
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
        const std::optional<Scene> scene = kwtest::loadSample(sample, &error);
        QVERIFY2(scene, qPrintable(error));
        Document doc;
        QVERIFY2(doc.resetScene(*scene, &error), qPrintable(error));
        RenderOptions opt;
        opt.mode = RenderMode(mode);
        if (opt.mode == RenderMode::Tessellated)
            opt.partitionsU = opt.partitionsV = 8; // coarse, so Gouraud facets show
        if (overlays) {
            opt.partitionsU = opt.partitionsV = 6;
            opt.wireframe = opt.controlNet = true;
        }
        const Camera cam = scene->camera.authored ? scene->camera : fitCamera(*scene, 1.0);
        QVERIFY2(m_renderer->render(doc, cam, opt, &error), qPrintable(error));
        const QImage img = m_renderer->colorImage();
        const QString expected = baselinePath(name);

        if (qEnvironmentVariableIntValue("KW_UPDATE_BASELINES") == 1) {
            QDir().mkpath(QFileInfo(expected).absolutePath());
            QVERIFY2(writeColorImage(img, expected, &error), qPrintable(error));
            qInfo("wrote %s", qPrintable(expected));
            return;
        }
        QVERIFY2(
            QFileInfo::exists(expected),
            qPrintable(QStringLiteral("missing baseline %1 (generate with KW_UPDATE_BASELINES=1)")
                           .arg(expected)));
        const QString actualPath =
            kwtest::outputDir().filePath(name + QStringLiteral(".actual.png"));
        const QString diffPath = kwtest::outputDir().filePath(name + QStringLiteral(".diff.png"));
        QVERIFY2(writeColorImage(img, actualPath, &error), qPrintable(error));
        OIIO::ImageBuf actual(actualPath.toStdString()), base(expected.toStdString());
        QVERIFY2(actual.read() && base.read(), "could not read the images back");
        QCOMPARE(actual.spec().width, base.spec().width);
        QCOMPARE(actual.spec().height, base.spec().height);
        const OIIO::ImageBufAlgo::CompareResults r =
            OIIO::ImageBufAlgo::compare(actual, base, kFailThreshold, kFailThreshold * 0.5f);
        const double failed = double(r.nfail) / double(kSide * kSide);
        qInfo("%s: mean error %.5f, max %.4f, %lld pixel(s) over %.2f (%.3f%%)", qPrintable(name),
              r.meanerror, r.maxerror, (long long)r.nfail, kFailThreshold, 100.0 * failed);
        const bool ok = failed <= kMaxFailedFraction && r.meanerror <= kMaxMeanError;
        if (ok) {
            QFile::remove(actualPath);
        } else {
            OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, base);
            diff = OIIO::ImageBufAlgo::mul(diff, 8.0f);
            diff.write(diffPath.toStdString());
        }
        QVERIFY2(ok, qPrintable(QStringLiteral("%1 differs from %2; see %3 and %4")
                                    .arg(name, expected, actualPath, diffPath)));
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderBaseline)
#include "tst_render_baseline.moc"
