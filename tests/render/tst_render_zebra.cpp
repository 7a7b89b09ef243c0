// GL test of the zebra map against its definition: every covered pixel of a tilted plane and a
// sphere, fitted and from an oblique eye, shows the band of the analytic stripe function at the
// AOV's exact point and normal (analysis.glsl: the reflected view ray's angle about the stripe
// axis, from the direction back to the viewer), except within one pixel of a band edge, where
// the shader's filter mixes the two. A false line (a grey or flipped streak across the image,
// as llvmpipe's helper invocations drew along the view's diagonal) fails it.
#include "expected_test_util.h"
#include "render/image_writer.h"
#include "render_test_util.h"

#include <glm/gtc/matrix_transform.hpp>
#include <limits>

using namespace kw;

namespace {

constexpr int kSide = 384;

double luminance(QRgb c) {
    return (0.2126 * qRed(c) + 0.7152 * qGreen(c) + 0.0722 * qBlue(c)) / 255.0;
}

/// The stripe function: the phase at point p with unit normal n (a band per 0.5, white first)
/// from setAnalysisUniforms's stripe axis and analysis.glsl's angle, in double.
struct Stripes {
    glm::dvec3 eye, back, axisB;
    double count;
    double phase(const glm::dvec3& p, glm::dvec3 n) const {
        const glm::dvec3 v = glm::normalize(eye - p);
        if (glm::dot(n, v) < 0.0)
            n = -n;
        const glm::dvec3 r = 2.0 * glm::dot(n, v) * n - v;
        return std::atan2(glm::dot(r, axisB), glm::dot(r, back)) / M_PI * count;
    }
    /// Which half-period: a band edge lies between two points whose indices differ (also
    /// where the bands come back to the same colour within a pixel, at grazing angles).
    static long long halfBand(double phase) { return (long long)std::floor(2.0 * phase); }
};

Stripes stripesFor(const Camera& camera, const Scene& scene, const AnalysisOptions& o) {
    const CameraMatrices m = cameraMatrices(camera, scene, 1.0);
    const glm::dmat3 rot = glm::transpose(glm::dmat3(m.view)); // view -> world
    const double a = glm::radians(o.stripeAngleDegrees);
    const glm::dvec3 axis = glm::normalize(std::cos(a) * rot[0] + std::sin(a) * rot[1]);
    const glm::dvec3 back = -m.forward;
    return {m.eye, back, glm::normalize(glm::cross(axis, back)),
            std::max(0.5, std::round(2.0 * o.stripeCount) / 2.0)};
}

} // namespace

class TestRenderZebra : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void matchesStripeFunction_data() {
        QTest::addColumn<Scene>("scene");
        QTest::addColumn<double>("angle");
        QTest::addColumn<bool>("adaptive"); // adaptive partitions: the deferred pass
        Scene sphere;
        sphere.surfaces.push_back(kwtest::makeSurface(1, makeSphere(glm::dvec3(0.0), 1.0), 12));
        QTest::newRow("sphere fitted") << sphere << 90.0 << true;
        QTest::newRow("sphere fitted, uniform partitions") << sphere << 90.0 << false;
        Scene oblique = sphere;
        oblique.camera.eye = glm::dvec3(1.9, -2.3, 1.4);
        oblique.camera.target = glm::dvec3(0.1, 0.0, -0.1);
        oblique.camera.up = glm::dvec3(0.0, 0.0, 1.0);
        oblique.camera.authored = true;
        QTest::newRow("sphere oblique, stripes at 30 degrees") << oblique << 30.0 << true;
        // A plane seen at a slant through a wide lens: the reflected rays fan out, so the
        // plane shows several stripes.
        Scene plane;
        plane.surfaces.push_back(
            kwtest::makeSurface(1,
                                makePlane(glm::dvec3(-2.0, -2.0, 0.0), glm::dvec3(4.0, 0.0, 0.0),
                                          glm::dvec3(0.0, 4.0, 0.0)),
                                4));
        plane.camera.eye = glm::dvec3(0.3, -3.2, 1.6);
        plane.camera.target = glm::dvec3(0.0, 0.0, 0.0);
        plane.camera.up = glm::dvec3(0.0, 0.0, 1.0);
        plane.camera.fovYDegrees = 70.0;
        plane.camera.authored = true;
        QTest::newRow("plane") << plane << 90.0 << true;
        QTest::newRow("plane, stripes at 45 degrees") << plane << 45.0 << true;
    }

    void matchesStripeFunction() {
        QFETCH(Scene, scene);
        QFETCH(double, angle);
        QFETCH(bool, adaptive);
        RenderOptions opt;
        opt.partitioning =
            adaptive ? RenderOptions::Partitioning::Adaptive : RenderOptions::Partitioning::Uniform;
        opt.analysis.mode = AnalysisMode::Zebra;
        opt.analysis.stripeCount = 8.0;
        opt.analysis.stripeAngleDegrees = angle;
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = scene.camera.authored ? scene.camera : fitCamera(scene, 1.0);
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const QImage img = m_renderer->colorImage();
        const AovBuffer aov = m_renderer->aov();
        const Stripes stripes = stripesFor(cam, scene, opt.analysis);

        // The half-band index of every covered pixel; none where uncovered.
        constexpr long long kNone = std::numeric_limits<long long>::min();
        std::vector<long long> half(size_t(kSide) * kSide, kNone);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const float* px = aov.pixel(x, y);
                if (px[0] < 0.0f)
                    continue;
                const double ph =
                    stripes.phase(glm::dvec3(px[3], px[4], px[5]), glm::dvec3(px[6], px[7], px[8]));
                half[size_t(y) * kSide + x] = Stripes::halfBand(ph);
            }
        int compared = 0, wrong = 0, edge = 0;
        QString first;
        for (int y = 1; y + 1 < kSide; ++y)
            for (int x = 1; x + 1 < kSide; ++x) {
                const long long h = half[size_t(y) * kSide + x];
                if (h == kNone)
                    continue;
                // Within one pixel of a band edge or of the outline: the filter's business.
                bool near = false;
                for (int dy = -1; dy <= 1 && !near; ++dy)
                    for (int dx = -1; dx <= 1 && !near; ++dx)
                        near = half[size_t(y + dy) * kSide + x + dx] != h;
                if (near) {
                    ++edge;
                    continue;
                }
                ++compared;
                const int b =
                    h % 2 == 0 ? 1 : 0; // white where fract(phase) < 0.5, as analysis.glsl
                const double l = luminance(img.pixel(x, y));
                if (std::abs(l - b) > 0.25) {
                    if (++wrong == 1)
                        first = QStringLiteral("(%1, %2): luminance %3, band %4")
                                    .arg(x)
                                    .arg(y)
                                    .arg(l)
                                    .arg(b);
                }
            }
        KW_VERIFY_OK(writeColorImage(
            img,
            kwtest::outputDir().filePath(QStringLiteral("zebra_%1.png")
                                             .arg(QString::fromLatin1(QTest::currentDataTag())
                                                      .replace(QLatin1Char(' '), QLatin1Char('_'))
                                                      .remove(QLatin1Char(','))))));
        qInfo("%d pixels compared, %d within a pixel of a band edge, %d wrong", compared, edge,
              wrong);
        QVERIFY2(compared > kSide * kSide / 20, "too little of the surface to compare");
        QVERIFY2(edge > 200, "too few band edges: the stripes were not exercised");
        QVERIFY2(wrong == 0,
                 qPrintable(QStringLiteral("%1 pixels off the stripe function, first %2")
                                .arg(wrong)
                                .arg(first)));
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderZebra)
#include "tst_render_zebra.moc"
