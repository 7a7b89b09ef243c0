// Section planes (RenderOptions::sections): every covered pixel's exact point lies on the kept
// side of every plane, in exact mode (uniform and adaptive partitions, every shading) and the
// tessellated mode; a closed solid cut through its middle shows its cap with no background
// pixel inside the cap's outline at 1x and 64x zoom; caps carry id kSectionCapId, P on the
// plane and N the plane's normal; bad planes are refused and a plane that hides everything
// draws an empty view; `knotwork render --section` and its errors.
#include "knotwork_process.h"
#include "model/document/document.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/exact_contract.h"
#include "render/offscreen_renderer.h"
#include "render_test_util.h"

#include <QFile>
#include <QtTest>
#include <cmath>
#include <memory>

using namespace kw;

namespace {

constexpr int kSide = 256;

/// The teapot sample with a closed sphere (one solid, outside along S_u x S_v) beside it.
Scene teapotAndSphere() {
    QString error;
    auto teapot = kwtest::loadSample(QStringLiteral("teapot"));
    if (!teapot)
        qFatal("%s", qPrintable(teapot.message()));
    Scene scene = *teapot;
    glm::dvec3 lo, hi;
    sceneBounds(scene, lo, hi);
    Surface sphere =
        kwtest::makeSurface(scene.nextId++, makeSphere(glm::dvec3(hi.x + 1.2, 0.0, 0.8), 1.0));
    sphere.solid = 0;
    sphere.outsideAlongNormal = true;
    scene.surfaces.push_back(sphere);
    return scene;
}

/// A lone closed sphere of radius 1 about the origin.
Scene sphereSolid() {
    Scene scene;
    Surface s = kwtest::makeSurface(1, makeSphere(glm::dvec3(0.0), 1.0), 12);
    // The side S_u x S_v points to, as the importer's mark says it: out of the sphere.
    const SurfaceDerivatives d = surfaceDerivatives(s.geometry, 0.3, 0.4);
    s.solid = 0;
    s.outsideAlongNormal = glm::dot(glm::cross(d.su, d.sv), d.s) > 0.0;
    scene.surfaces.push_back(s);
    scene.nextId = 2;
    return scene;
}

double diagonal(const Scene& scene) {
    glm::dvec3 lo, hi;
    sceneBounds(scene, lo, hi);
    return glm::length(hi - lo);
}

/// The unit direction of the ray through the centre of pixel (x, y) (row 0 at the top).
glm::dvec3 pixelRay(const Camera& c, int x, int y, int width, int height) {
    const glm::dvec3 f = glm::normalize(c.target - c.eye);
    const glm::dvec3 r = glm::normalize(glm::cross(f, c.up));
    const glm::dvec3 u = glm::cross(r, f);
    const double t = std::tan(glm::radians(c.fovYDegrees) * 0.5);
    const double nx = (x + 0.5) / width * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / height * 2.0;
    return glm::normalize(f + r * (nx * t * width / height) + u * (ny * t));
}

struct Counts {
    int surface = 0, caps = 0, background = 0;
};

} // namespace

class TestRenderSections : public QObject {
    Q_OBJECT

    std::unique_ptr<OffscreenRenderer> m_gl;

    AovBuffer render(const Scene& scene, const Camera& camera, const RenderOptions& options,
                     QString* error = nullptr) {
        Document doc;
        if (const Status reset = doc.resetScene(scene); !reset)
            qFatal("%s", qPrintable(reset.message()));
        if (const Status drawn = m_gl->render(doc, camera, options); !drawn) {
            if (error)
                *error = drawn.message();
            else
                qWarning("%s", qPrintable(drawn.message()));
            return {};
        }
        return m_gl->aov();
    }

    /// Checks every pixel: surfaces kept by every plane, caps on a plane with its normal.
    /// Returns the counts; a failure is reported through QTest and `ok`.
    static Counts checkKept(const AovBuffer& aov, const std::vector<SectionPlane>& planes,
                            double tolerance, bool& ok) {
        Counts c;
        ok = false;
        for (int y = 0; y < aov.height; ++y)
            for (int x = 0; x < aov.width; ++x) {
                const float* px = aov.pixel(x, y);
                if (px[0] == -1.0f) {
                    ++c.background;
                    continue;
                }
                const glm::dvec3 p(px[3], px[4], px[5]), n(px[6], px[7], px[8]);
                for (const SectionPlane& s : planes) {
                    const double beyond = glm::dot(p - s.position, s.removedSide());
                    if (!(beyond <= tolerance)) {
                        qWarning("pixel (%d, %d) id %g: %g beyond a plane", x, y, double(px[0]),
                                 beyond);
                        return c;
                    }
                }
                if (px[0] > 0.0f) {
                    ++c.surface;
                    continue;
                }
                if (px[0] != float(kSectionCapId)) {
                    qWarning("pixel (%d, %d): id %g", x, y, double(px[0]));
                    return c;
                }
                ++c.caps;
                bool onOne = false;
                for (const SectionPlane& s : planes)
                    onOne = onOne ||
                            (std::abs(glm::dot(p - s.position, s.removedSide())) <= tolerance &&
                             glm::length(n - s.removedSide()) < 1e-5);
                if (!onOne) {
                    qWarning("cap pixel (%d, %d) is on no plane with its normal", x, y);
                    return c;
                }
            }
        ok = true;
        return c;
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_gl = std::move(made).value();
    }

    void keptSideOnEveryCoveredPixel_data() {
        QTest::addColumn<int>("mode"); // 0 exact adaptive, 1 exact uniform, 2 tessellated
        QTest::addColumn<int>("shading");
        QTest::addColumn<int>("planes");
        const char* modes[] = {"adaptive", "uniform", "tessellated"};
        for (int m = 0; m < 3; ++m)
            for (int planes = 1; planes <= kMaxSectionPlanes; ++planes)
                QTest::addRow("%s, %d plane(s)", modes[m], planes)
                    << m << int(AnalysisMode::Phong) << planes;
        QTest::addRow("adaptive, zebra") << 0 << int(AnalysisMode::Zebra) << 2;
        QTest::addRow("uniform, gaussian") << 1 << int(AnalysisMode::Gaussian) << 2;
    }
    void keptSideOnEveryCoveredPixel() {
        QFETCH(int, mode);
        QFETCH(int, shading);
        QFETCH(int, planes);
        const Scene scene = teapotAndSphere();
        glm::dvec3 lo, hi;
        sceneBounds(scene, lo, hi);
        const glm::dvec3 mid = 0.5 * (lo + hi);
        const std::vector<SectionPlane> all{
            SectionPlane{mid, glm::dvec3(0.3, -1.0, 0.2), false},
            SectionPlane{mid + glm::dvec3(0.0, 0.0, 0.3), glm::dvec3(0.0, 0.2, 1.0), false},
            SectionPlane{mid - glm::dvec3(0.5, 0.0, 0.0), glm::dvec3(1.0, 0.0, 0.1), true}};
        RenderOptions options;
        options.mode = mode == 2 ? RenderMode::Tessellated : RenderMode::Exact;
        options.partitioning = mode == 0 ? RenderOptions::Partitioning::Adaptive
                                         : RenderOptions::Partitioning::Uniform;
        // Coarse uniform partitions: the base polygon lies far from the surface, so a cut by
        // the polygon's point instead of the exact one would show.
        options.partitionsU = options.partitionsV = mode == 1 ? 3 : 0;
        options.analysis.mode = AnalysisMode(shading);
        options.sections.assign(all.begin(), all.begin() + planes);
        const Camera camera = fitCamera(scene, 1.0);
        const AovBuffer aov = render(scene, camera, options);
        QVERIFY(!aov.data.empty());
        bool ok = false;
        const Counts c = checkKept(aov, options.sections, 1e-6 * diagonal(scene), ok);
        QVERIFY(ok);
        QVERIFY2(c.surface > 300, qPrintable(QString::number(c.surface)));
        // Without the planes more of the scene shows: they did cut.
        RenderOptions whole = options;
        whole.sections.clear();
        bool wholeOk = false;
        const Counts w = checkKept(render(scene, camera, whole), {}, 0.0, wholeOk);
        QVERIFY(wholeOk);
        QVERIFY2(w.surface > c.surface + c.caps, qPrintable(QString::number(w.surface)));
        QCOMPARE(w.caps, 0);
    }

    /// The sphere cut through its centre by a plane facing the eye shows a disk of cap; every
    /// pixel whose ray meets the plane inside the sphere (by more than the pixel's footprint)
    /// is a cap pixel, at 1x and at 64x zoom on the cap's rim (adaptive partitions: the exact
    /// outline), and at 1x inside the chords in uniform and tessellated mode.
    void capCoversItsOutline_data() {
        QTest::addColumn<double>("zoom");
        QTest::addColumn<int>("mode");
        QTest::addRow("1x adaptive") << 1.0 << 0;
        QTest::addRow("64x adaptive") << 64.0 << 0;
        // The base polygon's and the mesh's outlines are their chords', as their silhouettes
        // are: there the cap is checked inside the chords' (kChordMargin).
        QTest::addRow("1x uniform") << 1.0 << 1;
        QTest::addRow("1x tessellated") << 1.0 << 2;
    }
    void capCoversItsOutline() {
        QFETCH(double, zoom);
        QFETCH(int, mode);
        const Scene scene = sphereSolid();
        const SectionPlane plane{glm::dvec3(0.0), glm::dvec3(0.6, -1.0, 0.5), false};
        const glm::dvec3 n = plane.removedSide();
        Camera camera;
        camera.authored = true;
        camera.up = glm::dvec3(0.0, 0.0, 1.0);
        camera.fovYDegrees = 35.0;
        if (zoom == 1.0) {
            camera.target = glm::dvec3(0.0);
            camera.eye = glm::dvec3(2.0, -4.5, 2.5);
        } else {
            // On the cap's rim: a point of the section circle, seen from the same side.
            const glm::dvec3 t = glm::normalize(glm::cross(n, glm::dvec3(0.0, 0.0, 1.0)));
            camera.target = t;
            camera.eye = t + glm::dvec3(2.0, -4.5, 2.5);
            camera.fovYDegrees =
                glm::degrees(2.0 * std::atan(std::tan(glm::radians(35.0) * 0.5) / zoom));
        }
        RenderOptions options;
        options.mode = mode == 2 ? RenderMode::Tessellated : RenderMode::Exact;
        options.partitioning = mode == 0 ? RenderOptions::Partitioning::Adaptive
                                         : RenderOptions::Partitioning::Uniform;
        options.sections = {plane};
        const AovBuffer aov = render(scene, camera, options);
        QVERIFY(!aov.data.empty());
        bool ok = false;
        const Counts c = checkKept(aov, options.sections, 1e-6 * diagonal(scene), ok);
        QVERIFY(ok);
        QVERIFY2(c.caps > 100, qPrintable(QString::number(c.caps)));
        // A pixel's footprint on the plane, in model units (generous: the view's height at the
        // target's distance over its pixels, times 2).
        double footprint = 2.0 * 2.0 * glm::length(camera.eye - camera.target) *
                           std::tan(glm::radians(camera.fovYDegrees) * 0.5) / kSide;
        // Uniform and tessellated: the 12 x 12 cells' chords lie up to 1 - cos(15 degrees) =
        // 0.034 inside the sphere; 0.05 with the rational parametrisation's uneven spacing.
        if (mode != 0)
            footprint += 0.05;
        int inside = 0;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const glm::dvec3 d = pixelRay(camera, x, y, kSide, kSide);
                const double along = glm::dot(d, n);
                if (along == 0.0)
                    continue;
                const double t = glm::dot(plane.position - camera.eye, n) / along;
                const glm::dvec3 at = camera.eye + t * d;
                if (!(t > 0.0) || glm::length(at) > 1.0 - footprint)
                    continue;
                ++inside;
                const float id = aov.pixel(x, y)[0];
                QVERIFY2(id == float(kSectionCapId),
                         qPrintable(QStringLiteral("pixel (%1, %2) inside the cap: id %3")
                                        .arg(x)
                                        .arg(y)
                                        .arg(id)));
            }
        QVERIFY(inside > 100);
        if (zoom > 1.0) // the rim crosses the view: more than the cap shows
            QVERIFY2(c.surface + c.background > 100,
                     qPrintable(QStringLiteral("%1 + %2").arg(c.surface).arg(c.background)));
        // --no-caps: the same view shows the sphere's inside instead.
        options.sectionCaps = false;
        const Counts open =
            checkKept(render(scene, camera, options), options.sections, 1e-6 * diagonal(scene), ok);
        QVERIFY(ok);
        QCOMPARE(open.caps, 0);
    }

    /// A plane that removes everything draws an empty view; bad planes are refused.
    /// The planner leaves out what a plane removes whole (its control bounds on the removed
    /// side), and keeps skipping the back faces of a closed solid no plane crosses: the
    /// teapot and the sphere beside it, cut across the teapot only, then across the sphere.
    /// The cut stays exact on every pixel either way.
    void planLeavesOutRemovedSurfacesAndUncutSolidsBackFaces() {
        const Scene scene = teapotAndSphere();
        const Camera camera = fitCamera(scene, 1.0);
        glm::dvec3 lo, hi; // the sphere's centre: (hi.x - 1, 0, 0.8)
        sceneBounds(scene, lo, hi);
        RenderOptions options;
        // x = 0 through the teapot, removing x > 0: the sphere (x >= hi.x + 0.2) goes whole.
        options.sections = {SectionPlane{glm::dvec3(0.0), glm::dvec3(1, 0, 0), false}};
        QString error;
        AovBuffer aov = render(scene, camera, options, &error);
        QVERIFY2(!aov.data.empty(), qPrintable(error));
        const FrameReport cut = m_gl->lastReport();
        bool ok = false;
        checkKept(aov, options.sections, 1e-6 * diagonal(scene), ok);
        QVERIFY(ok);
        QVERIFY2(cut.culled >= 2, qPrintable(QString::number(cut.culled))); // sphere + spout
        QCOMPARE(cut.solidsBackCulled, 0);                                  // removed: not drawn
        // Flipped: the sphere is kept whole, uncut: its back faces are skipped again.
        options.sections[0].flip = true;
        aov = render(scene, camera, options, &error);
        QVERIFY2(!aov.data.empty(), qPrintable(error));
        checkKept(aov, options.sections, 1e-6 * diagonal(scene), ok);
        QVERIFY(ok);
        QCOMPARE(m_gl->lastReport().solidsBackCulled, 1);
        // Through the sphere's centre, removing the half that faces the eye: its back faces
        // carry the cap.
        const glm::dvec3 centre(hi.x - 1.0, 0.0, 0.8);
        options.sections = {SectionPlane{centre, glm::normalize(camera.eye - centre), false}};
        aov = render(scene, camera, options, &error);
        QVERIFY2(!aov.data.empty(), qPrintable(error));
        const Counts c = checkKept(aov, options.sections, 1e-6 * diagonal(scene), ok);
        QVERIFY(ok);
        QCOMPARE(m_gl->lastReport().solidsBackCulled, 0);
        QVERIFY(c.caps > 0);
    }

    /// A cut frame splits the cut surfaces' cells (RenderOptions::splitCellsBySections): those
    /// every plane keeps are drawn as an uncut frame's (pre-pass, deferred pass), only those a
    /// plane crosses with exact depth and the section test. Against the same frame drawn the
    /// old way, every cell with exact depth: the same surface (or cap) on every pixel but
    /// where two surfaces meet, where the pre-pass decides by the polygons' depth (no more
    /// pixels than the uncut frame's pre-pass differs there from its exact-depth frame, plus
    /// 0.2 % of the covered pixels); the same exact point on every pixel that shows the same
    /// surface, and that point on the surface at the pixel's (u, v) by the CPU kernel. A
    /// crossed cell drawn the kept way (its pre-pass depth hiding what the cut opens), one
    /// drawn without the section test, or a kept cell left out, fails.
    void cellSplitMatchesAllExactDepth_data() {
        // 0 teapot and sphere, 1 sphere, 2 trimmed plate, 3 torus and a plane (affine: its
        // crossed cell is drawn with its polygon's depth, which is its exact point's)
        QTest::addColumn<int>("scene");
        QTest::addColumn<int>("planes");
        QTest::addColumn<double>("zoom");
        QTest::addRow("teapot and sphere, 1 plane") << 0 << 1 << 1.0;
        QTest::addRow("teapot and sphere, 3 planes") << 0 << 3 << 1.0;
        QTest::addRow("teapot and sphere, 1 plane, 3x") << 0 << 1 << 3.0;
        QTest::addRow("sphere, cap") << 1 << 1 << 1.0;
        QTest::addRow("trimmed plate, 2 planes") << 2 << 2 << 1.0;
        QTest::addRow("torus and a plane, 1 plane") << 3 << 1 << 1.0;
    }
    void cellSplitMatchesAllExactDepth() {
        QFETCH(int, scene);
        QFETCH(int, planes);
        QFETCH(double, zoom);
        Scene model;
        if (scene == 2) {
            auto plate = kwtest::loadSample(QStringLiteral("trimmed_plate"));
            QVERIFY2(plate, qPrintable(plate.message()));
            model = *plate;
        } else if (scene == 3) {
            auto torus = kwtest::loadSample(QStringLiteral("torus"));
            QVERIFY2(torus, qPrintable(torus.message()));
            model = *torus;
            model.surfaces.push_back(kwtest::makeSurface(
                model.nextId++,
                makePlane(glm::dvec3(-2.0, -0.8, 0.3), glm::dvec3(1.6, 0.0, 0.0),
                          glm::dvec3(0.0, 1.6, 0.0)),
                1));
        } else {
            model = scene == 0 ? teapotAndSphere() : sphereSolid();
        }
        glm::dvec3 lo, hi;
        sceneBounds(model, lo, hi);
        const glm::dvec3 mid = 0.5 * (lo + hi);
        Camera camera = fitCamera(model, 1.0);
        camera.fovYDegrees =
            glm::degrees(2.0 * std::atan(std::tan(glm::radians(camera.fovYDegrees) * 0.5) / zoom));
        const std::vector<SectionPlane> all{
            SectionPlane{mid, scene == 1 ? camera.eye - mid : glm::dvec3(0.3, -1.0, 0.2), false},
            SectionPlane{mid + glm::dvec3(0.0, 0.0, 0.1), glm::dvec3(0.0, 0.2, 1.0), false},
            SectionPlane{mid - glm::dvec3(0.5, 0.0, 0.0), glm::dvec3(1.0, 0.0, 0.1), true}};
        RenderOptions options; // adaptive, as the editor and `knotwork render` draw
        options.partitioning = RenderOptions::Partitioning::Adaptive;
        options.sections.assign(all.begin(), all.begin() + planes);
        const double tolerance = 1e-6 * diagonal(model);
        const AovBuffer split = render(model, camera, options);
        QVERIFY(!split.data.empty());
        const FrameReport report = m_gl->lastReport();
        // The split is in effect: some cells crossed, most kept.
        QVERIFY2(report.partitions.sectionCrossedCells > 0,
                 qPrintable(QString::number(report.partitions.sectionCrossedCells)));
        QVERIFY2(report.partitions.cells > report.partitions.sectionCrossedCells,
                 qPrintable(QStringLiteral("%1 cells, %2 crossed")
                                .arg(report.partitions.cells)
                                .arg(report.partitions.sectionCrossedCells)));
        if (scene == 3) // the plane drawn as its polygon
            QVERIFY(report.partitions.affineSurfaces >= 1);
        qInfo("%lld cells, %lld crossed, %d surfaces deferred",
              qlonglong(report.partitions.cells),
              qlonglong(report.partitions.sectionCrossedCells), report.partitions.deferredSurfaces);
        bool ok = false;
        const Counts c = checkKept(split, options.sections, tolerance, ok);
        QVERIFY(ok);
        QVERIFY(c.surface + c.caps > 300);
        RenderOptions old = options;
        old.splitCellsBySections = false;
        const AovBuffer exactDepth = render(model, camera, old);
        QVERIFY(!exactDepth.data.empty());
        QCOMPARE(m_gl->lastReport().partitions.sectionCrossedCells, std::int64_t(0));
        // The uncut frame's own difference between the pre-pass and exact depth.
        RenderOptions uncut;
        uncut.partitioning = options.partitioning;
        const AovBuffer prepass = render(model, camera, uncut);
        uncut.shading = RenderOptions::Shading::ExactDepth;
        const AovBuffer uncutExact = render(model, camera, uncut);
        QVERIFY(!prepass.data.empty() && !uncutExact.data.empty());
        // Pixels showing another surface, and pixels of the same surface at points farther
        // apart than 1e-4 of the diagonal (where a silhouette folds, the two ways may take
        // the ray's other meeting with the surface).
        const double far = 1e-4 * diagonal(model);
        const auto differing = [far](const AovBuffer& a, const AovBuffer& b, int& farPoints) {
            int n = 0;
            farPoints = 0;
            for (int y = 0; y < a.height; ++y)
                for (int x = 0; x < a.width; ++x) {
                    const float *pa = a.pixel(x, y), *pb = b.pixel(x, y);
                    n += pa[0] != pb[0];
                    farPoints += pa[0] == pb[0] && pa[0] != -1.0f &&
                                 glm::length(glm::dvec3(pa[3], pa[4], pa[5]) -
                                             glm::dvec3(pb[3], pb[4], pb[5])) > far;
                }
            return n;
        };
        int uncutFar = 0, farPoints = 0;
        const int uncutDiffering = differing(prepass, uncutExact, uncutFar);
        const int differ = differing(split, exactDepth, farPoints);
        int covered = 0;
        for (int y = 0; y < split.height; ++y)
            for (int x = 0; x < split.width; ++x)
                covered += split.pixel(x, y)[0] != -1.0f || exactDepth.pixel(x, y)[0] != -1.0f;
        // Caps (id < 0) are on their plane (checkKept); surfaces against the kernel.
        const kwtest::AovComparison kernel = kwtest::compareAovWithKernel(model, split);
        qInfo("%d of %d covered pixels show another surface than the exact-depth frame's, %d "
              "another point (uncut: %d, %d); the kernel's point by %g (diagonal %g)",
              differ, covered, farPoints, uncutDiffering, uncutFar, kernel.maxPosition,
              diagonal(model));
        QVERIFY2(differ <= uncutDiffering + covered / 500,
                 qPrintable(QStringLiteral("%1 pixels differ").arg(differ)));
        QVERIFY2(farPoints <= uncutFar + covered / 1000,
                 qPrintable(QStringLiteral("%1 pixels at another point").arg(farPoints)));
        QCOMPARE(kernel.unknownIds, 0);
        QVERIFY2(kernel.maxPosition <= 1e-4 * kernel.modelSize,
                 qPrintable(QString::number(kernel.maxPosition)));
    }

    /// The wireframe and the control net are cut as the surfaces are: a plane that removes
    /// everything leaves the background alone, lines included.
    void linesAreCut() {
        const Scene scene = sphereSolid();
        const Camera camera = fitCamera(scene, 1.0);
        RenderOptions options;
        options.wireframe = options.controlNet = true;
        options.sections = {SectionPlane{glm::dvec3(0.0, 0.0, -5.0), glm::dvec3(0, 0, -1), true}};
        QString error;
        QVERIFY2(!render(scene, camera, options, &error).data.empty(), qPrintable(error));
        const QImage image = m_gl->colorImage();
        const QRgb background = image.pixel(0, 0);
        int lines = 0;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                lines += image.pixel(x, y) != background;
        QCOMPARE(lines, 0);
        // Uncut, the same lines show.
        options.sections.clear();
        QVERIFY2(!render(scene, camera, options, &error).data.empty(), qPrintable(error));
        const QImage whole = m_gl->colorImage();
        int shown = 0;
        for (int y = 0; y < whole.height(); ++y)
            for (int x = 0; x < whole.width(); ++x)
                shown += whole.pixel(x, y) != background;
        QVERIFY(shown > 1000);
    }

    void emptyViewAndBadPlanes() {
        const Scene scene = sphereSolid();
        Camera camera = fitCamera(scene, 1.0);
        RenderOptions options;
        options.sections = {SectionPlane{glm::dvec3(0.0, 0.0, -5.0), glm::dvec3(0, 0, -1), true}};
        QString error;
        const AovBuffer empty = render(scene, camera, options, &error);
        QVERIFY2(!empty.data.empty(), qPrintable(error));
        bool ok = false;
        const Counts c = checkKept(empty, options.sections, 1e-6, ok);
        QVERIFY(ok);
        QCOMPARE(c.background, kSide * kSide);
        options.sections = {SectionPlane{glm::dvec3(0.0), glm::dvec3(0.0), false}};
        QVERIFY(render(scene, camera, options, &error).data.empty());
        QVERIFY2(error.contains(QStringLiteral("zero length")), qPrintable(error));
        options.sections.assign(kMaxSectionPlanes + 1, SectionPlane{});
        QVERIFY(render(scene, camera, options, &error).data.empty());
        QVERIFY2(error.contains(QStringLiteral("at most")), qPrintable(error));
    }

    /// `knotwork render --section`: an image; a zero normal is one line of error, exit 2 and
    /// no image; a plane that hides everything still writes the (empty) image.
    void commandLine() {
        const QString png = kwtest::outputDir().filePath(QStringLiteral("sections_cli.png"));
        const QString sample = QStringLiteral(KW_SAMPLES_DIR "/teapot.knot");
        QFile::remove(png);
        Run r = knotwork({QStringLiteral("render"), sample, QStringLiteral("-o"), png,
                          QStringLiteral("--size"), QStringLiteral("96x96"),
                          QStringLiteral("--section"), QStringLiteral("0,0,0,0,0,0")});
        QVERIFY(r.code != 0);
        QVERIFY2(r.err.trimmed().count(QLatin1Char('\n')) == 0 &&
                     r.err.contains(QStringLiteral("--section")) &&
                     r.err.contains(QStringLiteral("zero length")),
                 qPrintable(r.err));
        QVERIFY(!QFile::exists(png));
        r = knotwork({QStringLiteral("render"), sample, QStringLiteral("-o"), png,
                      QStringLiteral("--size"), QStringLiteral("96x96"),
                      QStringLiteral("--section"), QStringLiteral("0,0,0,1,0")});
        QVERIFY(r.code != 0);
        QVERIFY2(r.err.contains(QStringLiteral("six numbers")), qPrintable(r.err));
        r = knotwork({QStringLiteral("render"), sample, QStringLiteral("-o"), png,
                      QStringLiteral("--size"), QStringLiteral("96x96"),
                      QStringLiteral("--section"), QStringLiteral("0,0,-100,0,0,1"),
                      QStringLiteral("--section"), QStringLiteral("0,0,0,0,1,0"),
                      QStringLiteral("--no-caps")});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QImage image(png);
        QVERIFY(!image.isNull());
        const QRgb background = image.pixel(0, 0);
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                QCOMPARE(image.pixel(x, y), background);
    }
};

QTEST_MAIN(TestRenderSections)
#include "tst_render_sections.moc"
