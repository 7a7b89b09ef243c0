// GL test of the default light rig: every visible face of a default-material part is lit. The
// samples and the CAD parts of tests/data (imported as the editor imports them), with every
// surface given the default material and the scene's own lights, from the seven standard
// views and 20 random ones, exact and tessellated, headlight on and off: no covered pixel
// (the AOV's id) is darker than 15 % grey. Lights authored for one side left the other black
// (a connecting rod's lower faces); the viewer's fill (kw::kViewerFill) is what keeps them
// readable, for faces of either B-rep orientation.
#include "cad_test_util.h"
#include "expected_test_util.h"
#include "render/image_writer.h"
#include "render_test_util.h"

#include <random>

using namespace kw;

namespace {

constexpr int kSide = 192;
constexpr double kDarkest = 0.15;
/// Random views besides the seven standard ones (the count).
constexpr int kRandomViews = 20;

double luminance(QRgb c) {
    return (0.2126 * qRed(c) + 0.7152 * qGreen(c) + 0.0722 * qBlue(c)) / 255.0;
}

/// The editor's standard views (CameraController::setStandardView): front, back, left, right,
/// top, bottom, iso, each looking at the fitted target from its fitted distance.
Camera viewFrom(const Scene& scene, glm::dvec3 dir, glm::dvec3 up) {
    const Camera fitted = fitCamera(scene, 1.0);
    Camera c = fitted;
    c.up = up;
    c.eye = fitted.target + glm::normalize(dir) * glm::length(fitted.eye - fitted.target);
    c.authored = true;
    return c;
}

std::vector<std::pair<QString, Camera>> views(const Scene& scene) {
    const glm::dvec3 z(0, 0, 1), y(0, 1, 0);
    std::vector<std::pair<QString, Camera>> out = {
        {QStringLiteral("front"), viewFrom(scene, {0, -1, 0}, z)},
        {QStringLiteral("back"), viewFrom(scene, {0, 1, 0}, z)},
        {QStringLiteral("left"), viewFrom(scene, {-1, 0, 0}, z)},
        {QStringLiteral("right"), viewFrom(scene, {1, 0, 0}, z)},
        {QStringLiteral("top"), viewFrom(scene, {0, 0, 1}, y)},
        {QStringLiteral("bottom"), viewFrom(scene, {0, 0, -1}, y)},
        {QStringLiteral("iso"), viewFrom(scene, {0.55, -1.0, 0.65}, z)},
    };
    std::mt19937 rng(43);
    std::normal_distribution<double> g;
    for (int k = 0; k < kRandomViews; ++k) {
        glm::dvec3 d(g(rng), g(rng), g(rng));
        glm::dvec3 up = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
        if (glm::length(glm::cross(glm::normalize(d), up)) < 0.2)
            up = glm::dvec3(1, 0, 0);
        out.push_back({QStringLiteral("random %1").arg(k), viewFrom(scene, d, up)});
    }
    return out;
}

} // namespace

class TestRenderLighting : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void everyVisibleFaceIsLit_data() {
        QTest::addColumn<QString>("source");
        for (const char* name :
             {"teapot", "sphere", "torus", "bicubic", "trimmed_plate", "star_island"})
            QTest::newRow(name) << QString::fromLatin1(name);
        for (const char* file :
             {"Pump_Nut.brep", "Axis_of_bearing.brep", "screw.step", "hammer.iges", "teapot.igs"})
            QTest::newRow(file) << QString::fromLatin1(file);
    }

    void everyVisibleFaceIsLit() {
        QFETCH(QString, source);
        // A CAD part (its import's reason is logged) or a sample.
        Expected<Scene> scene = Error(source);
        if (!source.contains(QLatin1Char('.')))
            scene = kwtest::loadSample(source);
        else if (std::optional<Scene> part = kwtest::importedPart(source))
            scene = std::move(*part);
        QVERIFY2(scene, qPrintable(scene.message().isEmpty() ? source : scene.message()));
        for (Surface& s : scene->surfaces)
            s.material = Material{};
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        double darkest = 1.0;
        QString where;
        int views = 0;
        for (const auto& [name, cam] : ::views(*scene))
            for (RenderMode mode : {RenderMode::Exact, RenderMode::Tessellated}) {
                RenderOptions opt;
                opt.mode = mode;
                opt.partitioning = RenderOptions::Partitioning::Adaptive;
                opt.headlight = (views++ % 2) == 0; // both rigs, on alternate views
                KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
                const QImage img = m_renderer->colorImage();
                const AovBuffer aov = m_renderer->aov();
                int covered = 0;
                double low = 1.0;
                QPoint at;
                for (int y = 0; y < kSide; ++y)
                    for (int x = 0; x < kSide; ++x) {
                        if (aov.pixel(x, y)[0] < 0.0f)
                            continue;
                        ++covered;
                        const double l = luminance(img.pixel(x, y));
                        if (l < low)
                            low = l, at = QPoint(x, y);
                    }
                QVERIFY2(covered > 200, qPrintable(QStringLiteral("%1: nothing drawn").arg(name)));
                if (low < darkest) {
                    darkest = low;
                    where = QStringLiteral("%1 view, %2, headlight %3, pixel (%4, %5)")
                                .arg(name,
                                     mode == RenderMode::Exact ? QStringLiteral("exact")
                                                               : QStringLiteral("tessellated"),
                                     opt.headlight ? QStringLiteral("on") : QStringLiteral("off"))
                                .arg(at.x())
                                .arg(at.y());
                    QString file = QStringLiteral("lighting_darkest_%1.png").arg(source);
                    KW_VERIFY_OK(writeColorImage(img, kwtest::outputDir().filePath(file)));
                }
            }
        qInfo("%d frames, darkest covered pixel %.3f (%s)", views, darkest, qPrintable(where));
        QVERIFY2(darkest >= kDarkest,
                 qPrintable(QStringLiteral("a covered pixel at luminance %1 < %2: %3")
                                .arg(darkest)
                                .arg(kDarkest)
                                .arg(where)));
    }

    /// The light background: a vertical gradient from the bottom colour to the top one behind
    /// the part, in aliased, accumulated and coverage-AA frames; the part's pixels and the
    /// AOVs are those of the dark background's frame (the AOVs still say "no surface").
    void lightBackgroundGradient_data() {
        QTest::addColumn<int>("samples");
        QTest::addColumn<bool>("coverage");
        QTest::newRow("aliased") << 1 << false;
        QTest::newRow("accumulated") << 4 << false;
        QTest::newRow("coverage") << 4 << true;
    }

    void lightBackgroundGradient() {
        QFETCH(int, samples);
        QFETCH(bool, coverage);
        QString error;
        const auto scene = kwtest::loadSample(QStringLiteral("sphere"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const Camera cam = fitCamera(*scene, 1.0);
        RenderOptions opt;
        opt.samples = samples;
        opt.antialiasing = coverage ? RenderOptions::Antialiasing::Coverage
                                    : RenderOptions::Antialiasing::Accumulate;
        QVERIFY(backgroundNamed(QStringLiteral("dark"), opt));
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const QImage dark = m_renderer->colorImage();
        RenderOptions light = opt;
        QVERIFY(backgroundNamed(QStringLiteral("light"), light));
        QVERIFY(light.backgroundTop && !opt.backgroundTop);
        QVERIFY(!backgroundNamed(QStringLiteral("purple"), light));
        KW_VERIFY_OK(m_renderer->render(doc, cam, light));
        const QImage img = m_renderer->colorImage();
        KW_VERIFY_OK(writeColorImage(
            img,
            kwtest::outputDir().filePath(QStringLiteral("background_light_%1.png")
                                             .arg(QString::fromLatin1(QTest::currentDataTag())))));
        // The corner columns hold no part: bottom colour at the bottom row, top at the top,
        // brightening monotonically (row 0 of the image is the top).
        const auto channel = [](QRgb c) {
            return qGreen(c) / 255.0;
        };
        const double top = channel(img.pixel(0, 0)), bottom = channel(img.pixel(0, kSide - 1));
        const double halfPixel = 0.5 / kSide;
        QVERIFY2(std::abs(top - (light.backgroundTop->g -
                                 halfPixel * (light.backgroundTop->g - light.background.g))) <
                     1.5 / 255.0,
                 qPrintable(QStringLiteral("top %1").arg(top)));
        QVERIFY2(std::abs(bottom - (light.background.g +
                                    halfPixel * (light.backgroundTop->g - light.background.g))) <
                     1.5 / 255.0,
                 qPrintable(QStringLiteral("bottom %1").arg(bottom)));
        for (int y = 1; y < kSide; ++y)
            QVERIFY(channel(img.pixel(0, y)) <= channel(img.pixel(0, y - 1)));
        // The part is drawn as on the dark background wherever the dark frame shows no
        // background (edge pixels of anti-aliased frames mix the two).
        const QRgb darkBg = dark.pixel(0, 0);
        int part = 0, differing = 0;
        for (int y = 1; y + 1 < kSide; ++y)
            for (int x = 1; x + 1 < kSide; ++x) {
                bool inside = true;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        inside = inside && dark.pixel(x + dx, y + dy) != darkBg;
                if (!inside)
                    continue;
                ++part;
                differing += dark.pixel(x, y) != img.pixel(x, y);
            }
        QVERIFY(part > 1000);
        QCOMPARE(differing, 0);
        if (samples == 1) {
            // AOV frames: the background is still "no surface".
            RenderOptions aovLight = light;
            KW_VERIFY_OK(m_renderer->render(doc, cam, aovLight));
            const AovBuffer aov = m_renderer->aov();
            QCOMPARE(aov.pixel(0, 0)[0], -1.0f);
            QCOMPARE(aov.pixel(0, kSide - 1)[0], -1.0f);
        }
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderLighting)
#include "tst_render_lighting.moc"
