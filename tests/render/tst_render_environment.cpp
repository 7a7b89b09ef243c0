// GL test of the environment analysis mode with environment files read through OpenImageIO
// (render/image_reader.h): an EXR written with float values above 1, a hand-written Radiance
// HDR and a PNG of the same two-hemisphere sky must load with their values and render a sphere
// whose reflections pick the expected hemisphere's colour; corrupt files fail naming the file.
#include "expected_test_util.h"
#include "render/analysis_gl.h"
#include "render/image_writer.h"
#include "render/oiio/image_module.h"
#include "render/oiio_loader.h"
#include "render_test_util.h"

#include <QFile>
#include <glm/glm.hpp>

using namespace kw;

namespace {

constexpr int kSide = 256;
constexpr int kEnvW = 64, kEnvH = 32;
// Upper hemisphere (latitude > 0, image rows 0..15) and lower; the upper red is above 1 (HDR).
// Every value is exact in float and in RGBE (shared exponent): 4 = 128 * 2^-5, 0.5 = 16 * 2^-5,
// 0.25 = 8 * 2^-5; 0.5 = 128 * 2^-8, 0.25 = 64 * 2^-8, 0.125 = 32 * 2^-8.
constexpr float kUpper[3] = {4.0f, 0.5f, 0.25f};
constexpr float kLower[3] = {0.125f, 0.25f, 0.5f};

const float* skyAt(int row) {
    return row < kEnvH / 2 ? kUpper : kLower;
}

/// The sky as an EXR through the module's write entry (float, values above 1 kept).
Status writeExr(const QString& path) {
    std::vector<float> rgb;
    for (int y = 0; y < kEnvH; ++y)
        for (int x = 0; x < kEnvW; ++x)
            rgb.insert(rgb.end(), skyAt(y), skyAt(y) + 3);
    const Expected<void*> symbol = oiioModuleSymbol(KW_IMAGE_WRITE_SYMBOL);
    if (!symbol)
        return symbol.error();
    const auto write = reinterpret_cast<KwImageWriteFn>(*symbol);
    const QByteArray file = path.toLocal8Bit();
    const KwImageWrite image{file.constData(), kEnvW, kEnvH, 3, 1, rgb.data(), nullptr, 0, nullptr};
    char message[512] = {0};
    if (!write(&image, message, sizeof message))
        return Error(QString::fromLocal8Bit(message), path);
    return ok();
}

/// The sky as a flat (not run-length encoded) Radiance RGBE file, written byte by byte so the
/// reader is checked against the format, not against OpenImageIO's own writer.
bool writeHdr(const QString& path) {
    QByteArray data("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32 +X 64\n");
    for (int y = 0; y < kEnvH; ++y)
        for (int x = 0; x < kEnvW; ++x) {
            const float* c = skyAt(y);
            const float top = std::max({c[0], c[1], c[2]});
            int e = 0;
            std::frexp(top, &e); // top = f 2^e, f in [0.5, 1): mantissas m = c 2^(8 - e)
            for (int k = 0; k < 3; ++k)
                data.append(char(int(std::ldexp(c[k], 8 - e))));
            data.append(char(e + 128));
        }
    QFile f(path);
    return f.open(QIODevice::WriteOnly) && f.write(data) == data.size() && f.flush();
}

/// The sky as an 8-bit PNG (clamped to 1).
Status writePng(const QString& path) {
    QImage img(kEnvW, kEnvH, QImage::Format_RGB888);
    for (int y = 0; y < kEnvH; ++y)
        for (int x = 0; x < kEnvW; ++x) {
            const float* c = skyAt(y);
            const auto b = [](float v) {
                return int(std::lround(std::min(v, 1.0f) * 255.0f));
            };
            img.setPixel(x, y, qRgb(b(c[0]), b(c[1]), b(c[2])));
        }
    return writeColorImage(img, path);
}

} // namespace

class TestRenderEnvironment : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;
    Scene m_scene;

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
        m_scene.surfaces.push_back(kwtest::makeSurface(1, makeSphere(glm::dvec3(0.0), 1.0), 12));
        m_scene.camera.eye = glm::dvec3(0.0, -6.0, 0.0);
        m_scene.camera.target = glm::dvec3(0.0);
        m_scene.camera.up = glm::dvec3(0.0, 0.0, 1.0);
        m_scene.camera.fovYDegrees = 30.0;
        m_scene.camera.authored = true;
        const QDir out = kwtest::outputDir();
        KW_VERIFY_OK(writeExr(out.filePath("env_sky.exr")));
        QVERIFY(writeHdr(out.filePath("env_sky.hdr")));
        KW_VERIFY_OK(writePng(out.filePath("env_sky.png")));
    }

    void filesLoadWithTheirValues_data();
    void filesLoadWithTheirValues();
    void sphereReflectsTheExpectedHemisphere_data();
    void sphereReflectsTheExpectedHemisphere();
    void corruptFilesAreReported();

    void cleanupTestCase() { m_renderer.reset(); }
};

void TestRenderEnvironment::filesLoadWithTheirValues_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<bool>("hdr");
    QTest::newRow("exr") << "env_sky.exr" << true;
    QTest::newRow("hdr") << "env_sky.hdr" << true;
    QTest::newRow("png") << "env_sky.png" << false;
}

void TestRenderEnvironment::filesLoadWithTheirValues() {
    QFETCH(QString, file);
    QFETCH(bool, hdr);
    const Expected<EnvironmentImage> loaded =
        loadEnvironmentImage(kwtest::outputDir().filePath(file));
    QVERIFY2(loaded, qPrintable(loaded.message()));
    const EnvironmentImage& img = *loaded;
    QCOMPARE(img.width, kEnvW);
    QCOMPARE(img.height, kEnvH);
    for (int y : {0, kEnvH / 2 - 1, kEnvH / 2, kEnvH - 1})
        for (int x : {0, kEnvW / 3, kEnvW - 1})
            for (int c = 0; c < 3; ++c) {
                const float want =
                    hdr ? skyAt(y)[c] : std::round(std::min(skyAt(y)[c], 1.0f) * 255.0f) / 255.0f;
                const float got = img.rgb[(size_t(y) * kEnvW + size_t(x)) * 3 + size_t(c)];
                QVERIFY2(std::abs(got - want) <= 1e-6f,
                         qPrintable(QStringLiteral("%1 pixel (%2, %3) channel %4: %5, expected %6")
                                        .arg(file)
                                        .arg(x)
                                        .arg(y)
                                        .arg(c)
                                        .arg(got)
                                        .arg(want)));
            }
}

void TestRenderEnvironment::sphereReflectsTheExpectedHemisphere_data() {
    QTest::addColumn<QString>("file");
    QTest::newRow("exr") << "env_sky.exr";
    QTest::newRow("hdr") << "env_sky.hdr";
    QTest::newRow("png") << "env_sky.png";
}

// Every covered pixel whose reflected view ray (from the AOV's exact point and normal) points
// clearly up or down shows that hemisphere's colour, clamped to 1 by the 8-bit image.
void TestRenderEnvironment::sphereReflectsTheExpectedHemisphere() {
    QFETCH(QString, file);
    RenderOptions opt;
    opt.analysis.mode = AnalysisMode::Environment;
    opt.analysis.environmentMap = kwtest::outputDir().filePath(file);
    Document doc;
    QString error;
    KW_VERIFY_OK(doc.resetScene(m_scene));
    KW_VERIFY_OK(m_renderer->render(doc, m_scene.camera, opt));
    const QImage img = m_renderer->colorImage();
    const AovBuffer aov = m_renderer->aov();
    KW_VERIFY_OK(
        writeColorImage(img, kwtest::outputDir().filePath("environment_" + file + ".png")));
    int up = 0, down = 0;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            const float* px = aov.pixel(x, y);
            if (px[0] < 0.0f)
                continue;
            const glm::dvec3 p(px[3], px[4], px[5]), n(px[6], px[7], px[8]);
            const glm::dvec3 v = glm::normalize(m_scene.camera.eye - p);
            const glm::dvec3 r = 2.0 * glm::dot(n, v) * n - v;
            if (std::abs(r.z) < 0.15) // the band that filters the two hemispheres' rows
                continue;
            const float* want = r.z > 0.0 ? kUpper : kLower;
            (r.z > 0.0 ? up : down)++;
            const QRgb got = img.pixel(x, y);
            const int rgb[3] = {qRed(got), qGreen(got), qBlue(got)};
            for (int c = 0; c < 3; ++c) {
                const int expect = int(std::lround(std::min(want[c], 1.0f) * 255.0f));
                QVERIFY2(std::abs(rgb[c] - expect) <= 2,
                         qPrintable(QStringLiteral("%1: pixel (%2, %3) reflecting z %4: channel "
                                                   "%5 is %6, expected %7")
                                        .arg(file)
                                        .arg(x)
                                        .arg(y)
                                        .arg(r.z)
                                        .arg(c)
                                        .arg(rgb[c])
                                        .arg(expect)));
            }
        }
    qInfo("%s: %d pixels reflect the upper hemisphere, %d the lower", qPrintable(file), up, down);
    QVERIFY(up > 1000 && down > 1000);
}

void TestRenderEnvironment::corruptFilesAreReported() {
    const QDir out = kwtest::outputDir();
    // An EXR and an HDR whose headers are garbage, and a PNG cut short after its header.
    QFile png(out.filePath("env_sky.png"));
    QVERIFY(png.open(QIODevice::ReadOnly));
    const QByteArray start = png.read(60);
    const struct {
        const char* name;
        QByteArray bytes;
    } cases[] = {{"corrupt_env.exr", QByteArray(64, '\x55')},
                 {"corrupt_env.hdr",
                  QByteArray("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 99999999 +X 99999999\n")},
                 {"truncated_env.png", start}};
    for (const auto& c : cases) {
        const QString path = out.filePath(QString::fromLatin1(c.name));
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly) && f.write(c.bytes) == c.bytes.size());
        f.close();
        const Expected<EnvironmentImage> loaded = loadEnvironmentImage(path);
        QVERIFY2(!loaded, c.name);
        QVERIFY2(loaded.message().contains(path), qPrintable(loaded.message()));
        qInfo("%s", qPrintable(loaded.message()));
        // The frame fails with the same message (naming the file) instead of drawing.
        RenderOptions opt;
        opt.analysis.mode = AnalysisMode::Environment;
        opt.analysis.environmentMap = path;
        Document doc;
        QVERIFY(doc.resetScene(m_scene));
        const auto result = m_renderer->render(doc, m_scene.camera, opt);
        QVERIFY(!result);
        QVERIFY2(result.message().contains(path), qPrintable(result.message()));
    }
}

QTEST_MAIN(TestRenderEnvironment)
#include "tst_render_environment.moc"
