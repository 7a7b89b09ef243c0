// GL test of the default light rig: every visible face of a default-material part is lit. The
// samples and the CAD parts of tests/data (imported as the editor imports them), with every
// surface given the default material and the scene's own lights, from the seven standard
// views and a few random ones, exact and tessellated, headlight on and off: no covered pixel
// (the AOV's id) is darker than 15 % grey. Lights authored for one side left the other black
// (a connecting rod's lower faces); the viewer's fill (kw::kViewerFill) is what keeps them
// readable, for faces of either B-rep orientation.
#include "cad_test_util.h"
#include "render/image_writer.h"
#include "render_test_util.h"

#include <random>

using namespace kw;

namespace {

constexpr int kSide = 192;
constexpr double kDarkest = 0.15;

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
    for (int k = 0; k < 5; ++k) {
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
        m_renderer = kwtest::offscreenRenderer(QSize(kSide, kSide), true, &error);
        QVERIFY2(m_renderer, qPrintable(error));
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
        QString error;
        std::optional<Scene> scene = source.contains(QLatin1Char('.'))
                                         ? kwtest::importedPart(source)
                                         : kwtest::loadSample(source, &error);
        QVERIFY2(scene, qPrintable(error.isEmpty() ? source : error));
        for (Surface& s : scene->surfaces)
            s.material = Material{};
        Document doc;
        QVERIFY2(doc.resetScene(*scene, &error), qPrintable(error));
        double darkest = 1.0;
        QString where;
        int views = 0;
        for (const auto& [name, cam] : ::views(*scene))
            for (RenderMode mode : {RenderMode::Exact, RenderMode::Tessellated}) {
                RenderOptions opt;
                opt.mode = mode;
                opt.partitioning = RenderOptions::Partitioning::Adaptive;
                opt.headlight = (views++ % 2) == 0; // both rigs, on alternate views
                QVERIFY2(m_renderer->render(doc, cam, opt, &error), qPrintable(error));
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
                    QVERIFY2(writeColorImage(img, kwtest::outputDir().filePath(file), &error),
                             qPrintable(error));
                }
            }
        qInfo("%d frames, darkest covered pixel %.3f (%s)", views, darkest, qPrintable(where));
        QVERIFY2(darkest >= kDarkest,
                 qPrintable(QStringLiteral("a covered pixel at luminance %1 < %2: %3")
                                .arg(darkest)
                                .arg(kDarkest)
                                .arg(where)));
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderLighting)
#include "tst_render_lighting.moc"
