// GL test: the exact renderer's AOV (position, normal at each pixel's (u, v)) against the CPU
// kernel, for every sample and for scenes built in code (poles, high degree, multiplicities).
#include "expected_test_util.h"
#include "kernel_test_util.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render_test_util.h"

#include <QGuiApplication>
#include <QScopeGuard>
#include <map>

using namespace kw;

namespace {

/// The options every frame here starts from: the defaults, with the per-cell gather forced on
/// or off when KW_GATHER_MIN_CELL_PX is set (tests/render.cmake runs this test once with
/// each, as tst_render_exact_gather and tst_render_exact_fetch).
RenderOptions baseOptions() {
    RenderOptions o;
    bool ok = false;
    const double threshold = qEnvironmentVariable("KW_GATHER_MIN_CELL_PX").toDouble(&ok);
    if (ok)
        o.gatherMinCellPixels = threshold;
    return o;
}

} // namespace

class TestRenderExact : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    void addScene(const char* name, const Scene& scene) { QTest::newRow(name) << scene; }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(512, 512), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
        qInfo("GL: %s", qPrintable(m_renderer->renderer().glDescription()));
    }

    void aovMatchesKernel_data() {
        QTest::addColumn<Scene>("scene");
        for (const char* name : {"bicubic", "sphere", "torus", "trimmed_plate", "teapot"}) {
            QString error;
            const auto s = kwtest::loadSample(QString::fromLatin1(name));
            QVERIFY2(s, qPrintable(s.message()));
            addScene(name, *s);
        }
        {
            // A rational sphere seen from above its north pole: pixels right at the collapsed
            // edge exercise the limit-normal rule.
            Scene s;
            s.surfaces.push_back(kwtest::makeSurface(1, makeSphere(glm::dvec3(0.0), 1.0), 12));
            s.camera.eye = glm::dvec3(0.25, -0.35, 3.2);
            s.camera.target = glm::dvec3(0.0, 0.0, 0.4);
            s.camera.authored = true;
            addScene("code: sphere pole", s);
        }
        {
            Scene s;
            s.surfaces.push_back(kwtest::makeSurface(7, makeTorus(glm::dvec3(0.5), 2.0, 0.7), 16));
            addScene("code: rational torus", s);
        }
        {
            Scene s;
            s.surfaces.push_back(
                kwtest::makeSurface(3, kwtest::wavyPatch(5, 4, kwtest::clampedUniform(5, 9),
                                                         kwtest::clampedUniform(4, 7))));
            addScene("code: degree 5 x 4", s);
        }
        {
            Scene s;
            s.surfaces.push_back(
                kwtest::makeSurface(4,
                                    kwtest::wavyPatch(15, 2, kwtest::clampedUniform(15, 16),
                                                      kwtest::clampedUniform(2, 5)),
                                    8));
            addScene("code: degree 15 x 2", s);
        }
        {
            // The largest variants that take the per-cell gather path (28 vec4 of cell data).
            Scene s;
            s.surfaces.push_back(
                kwtest::makeSurface(8, kwtest::wavyPatch(4, 3, kwtest::clampedUniform(4, 7),
                                                         kwtest::clampedUniform(3, 6))));
            addScene("code: degree 4 x 3", s);
            Scene t;
            t.surfaces.push_back(
                kwtest::makeSurface(9, kwtest::wavyPatch(7, 1, kwtest::clampedUniform(7, 9),
                                                         kwtest::clampedUniform(1, 4))));
            addScene("code: degree 7 x 1", t);
        }
        {
            // Interior multiplicities: u has a triple knot (a C0 crease for degree 3) and a
            // double one; v a double knot.
            Scene s;
            s.surfaces.push_back(kwtest::makeSurface(
                5, kwtest::wavyPatch(3, 3, {0, 0, 0, 0, 0.3, 0.3, 0.3, 0.6, 0.6, 1, 1, 1, 1},
                                     {0, 0, 0, 0, 0.45, 0.45, 1, 1, 1, 1})));
            addScene("code: interior multiplicity", s);
        }
    }

    // Affine faces (planes) skip the Newton step onto the pixel's ray in adaptive mode
    // (ExactSurfacePass, kw::surfaceIsAffine): their polygon's (u, v) must already be the point
    // under the pixel, and a face that is flat but not affine, or stops being affine when a
    // point is dragged, must still get the step. A loose tolerance (2 px) makes the polygon's
    // own error plain: without the step, a face shows points up to that far off their rays.
    void affineFacesShowThePointOnTheirRay() {
        // A CAD plane (degree 1 x 1) with a hole, a plane of degree 3 x 2 on uneven knots, and
        // the same with one inner point moved within its plane (flat, not affine).
        Scene s;
        Surface holed = kwtest::makeSurface(1, makePlane({-3.4, -1, 0}, {2, 0, 0.8}, {0, 2, 0}), 1);
        holed.trims.push_back(kwtest::loopOf(2, {makeCircle2({0.5, 0.5}, 0.3, true)}));
        s.surfaces.push_back(holed);
        const NurbsSurface high = kwtest::refinedPlane({-1, -1, 0}, {2, 0, -0.6}, {0, 2, 0});
        s.surfaces.push_back(kwtest::makeSurface(3, high, 1));
        NurbsSurface flat = high;
        for (glm::dvec3& p : flat.points)
            p.x += 2.4, p.z += 0.6;
        const int inner = flat.index(2, 1);
        flat.points[size_t(inner)] += glm::dvec3(0.5, 0.3, -0.3);
        s.surfaces.push_back(kwtest::makeSurface(4, flat, 1));
        s.nextId = 5;
        s.camera.eye = glm::dvec3(0.5, -6.0, 7.0);
        s.camera.target = glm::dvec3(0.0);
        s.camera.up = glm::dvec3(0.0, 0.0, 1.0);
        s.camera.authored = true;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(s));
        RenderOptions opt = baseOptions();
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        opt.pixelTolerance = 2.0;
        // Per surface id: covered pixels and the farthest ray offset in pixels. Pixels showing
        // a point on the domain's edge are left out: there the skirts reach up to
        // kSkirtReachPixels past it and show the edge's point (ExactSurfacePass).
        const auto offsets = [&](std::map<int, std::pair<int, double>>& out) {
            QString e;
            KW_VERIFY_OK(m_renderer->render(doc, doc.scene().camera, opt));
            const AovBuffer aov = m_renderer->aov();
            const glm::dmat4 vp(frameCamera(doc.scene().camera, doc.scene(), 1.0).viewProjection);
            for (int y = 0; y < aov.height; ++y)
                for (int x = 0; x < aov.width; ++x) {
                    const float* a = aov.pixel(x, y);
                    if (a[0] < 0.0f || std::min({a[1], a[2], 1.0f - a[1], 1.0f - a[2]}) < 1e-6f)
                        continue;
                    auto& [n, worst] = out[int(a[0])];
                    ++n;
                    worst = std::max(worst, kwtest::rayOffsetPixels(aov, x, y, vp));
                }
            for (const auto& [id, r] : out)
                qInfo("surface %d: %d pixels, farthest %.4f px off its ray", id, r.first, r.second);
        };
        std::map<int, std::pair<int, double>> before;
        offsets(before);
        QCOMPARE(m_renderer->lastReport().partitions.affineSurfaces, 2);
        QCOMPARE(int(before.size()), 3);
        for (const auto& [id, r] : before) {
            QVERIFY2(r.first > 5000, qPrintable(QString("surface %1").arg(id)));
            // The affine faces' points are their pixels' (float rounding aside); the flat one's
            // come from the Newton step, quadratically close.
            QVERIFY2(r.second < (id == 4 ? 0.1 : 0.02), qPrintable(QString("surface %1").arg(id)));
        }
        // A drag bends the degree 3 x 2 plane: the step comes back for it.
        const int k = high.index(3, 2);
        QVERIFY(doc.setControlPoints(SurfaceId{3}, {k},
                                     {high.points[size_t(k)] + glm::dvec3(0.0, 0.0, 0.8)}));
        std::map<int, std::pair<int, double>> after;
        offsets(after);
        QCOMPARE(m_renderer->lastReport().partitions.affineSurfaces, 1);
        QVERIFY(after[3].first > 5000);
        QVERIFY(after[3].second < 0.1);
    }

    // Exact visibility in a close-up with the eye inside the scene's bounds: there the near plane
    // is 1e-5 of the far one, and GL's depth range resolved only about 1e-3 of the distance, so a
    // ring 1e-4 above a plate z-fought with it and the ring's hole (trimmed away, but equal in
    // depth to the plate behind) showed the ring. Reversed depth resolves both: the ring where it
    // is, the plate through its hole.
    void nearLayersResolveWithTheEyeInsideTheBounds() {
        const double gap = 1e-4;
        Scene s;
        s.surfaces.push_back(
            kwtest::makeSurface(1, makePlane({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 1));
        Surface ring = kwtest::makeSurface(2, makePlane({-1, -1, gap}, {2, 0, 0}, {0, 2, 0}), 1);
        ring.trims.push_back(kwtest::loopOf(3, {makeCircle2({0.5, 0.5}, 0.45)}));
        ring.trims.push_back(kwtest::loopOf(4, {makeCircle2({0.5, 0.5}, 0.2)}));
        s.surfaces.push_back(ring);
        // Far off to the side and out of view: it makes the bounds hold the eye.
        s.surfaces.push_back(
            kwtest::makeSurface(5, makePlane({100, -100, -100}, {1, 0, 0}, {0, 1, 0}), 1));
        s.nextId = 6;
        s.camera.eye = glm::dvec3(0.05, -0.02, 2.0);
        s.camera.target = glm::dvec3(0.0);
        s.camera.up = glm::dvec3(0.0, 1.0, 0.0);
        s.camera.authored = true;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(s));
        const CameraMatrices m = cameraMatrices(s.camera, doc.scene(), 1.0);
        QVERIFY(m.nearPlane < 2e-3); // the case: the eye inside the bounds
        for (const RenderOptions::Shading shading :
             {RenderOptions::Shading::DepthPrepass, RenderOptions::Shading::ExactDepth}) {
            RenderOptions opt = baseOptions();
            opt.shading = shading;
            KW_VERIFY_OK(m_renderer->render(doc, s.camera, opt));
            const AovBuffer aov = m_renderer->aov();
            const glm::dmat4 inv = glm::inverse(m.projection * m.view);
            int ring2 = 0, hole1 = 0, wrong = 0;
            for (int y = 0; y < aov.height; ++y)
                for (int x = 0; x < aov.width; ++x) {
                    const glm::dvec4 q =
                        inv * glm::dvec4(2.0 * (x + 0.5) / aov.width - 1.0,
                                         1.0 - 2.0 * (y + 0.5) / aov.height, 0.0, 1.0);
                    const glm::dvec3 d = glm::normalize(glm::dvec3(q) / q.w - m.eye);
                    const glm::dvec3 hit = m.eye + (-m.eye.z / d.z) * d;
                    const double r = glm::length(glm::dvec2(hit) - glm::dvec2(0.0));
                    // Plate (u, v) = (x + 1) / 2: radius 0.45 / 0.2 in (u, v) is 0.9 / 0.4 here.
                    const float id = aov.pixel(x, y)[0];
                    if (r > 0.42 && r < 0.88) {
                        ++ring2;
                        wrong += id != 2.0f;
                    } else if (r < 0.38) {
                        ++hole1;
                        wrong += id != 1.0f;
                    }
                }
            qInfo("shading %d: %d ring and %d hole pixels, %d show the wrong face", int(shading),
                  ring2, hole1, wrong);
            QVERIFY(ring2 > 10000 && hole1 > 10000);
            QCOMPARE(wrong, 0);
        }
    }

    void aovMatchesKernel() {
        QFETCH(Scene, scene);
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = scene.camera.authored ? scene.camera : fitCamera(scene, 1.0);
        RenderOptions opt = baseOptions();
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer aov = m_renderer->aov();
        QCOMPARE(aov.width, 512);
        const kwtest::AovComparison r = kwtest::compareAovWithKernel(doc.scene(), aov);
        qInfo("covered %d compared %d, max position error %.3g (%.3g x model size), max normal "
              "angle %.4f deg at (%d, %d)",
              r.covered, r.compared, r.maxPosition, r.maxPosition / r.modelSize, r.maxAngleDeg,
              r.worstX, r.worstY);
        QCOMPARE(r.unknownIds, 0);
        QVERIFY2(r.compared >= 1000, "fewer than 1000 pixels covered");
        QVERIFY(r.maxPosition <= 1e-5 * r.modelSize);
        QVERIFY(r.maxAngleDeg <= 0.05);
    }

    // Adaptive mode shows at each pixel the surface point on the pixel's ray: one Newton step
    // from the polygon's (u, v), which lies within the pixel tolerance of it (kwOntoRay). Near
    // a silhouette, where the projection bends sharply, the step can land farther from the
    // pixel centre than it started; it is undone there, so no pixel shows a point farther off
    // its ray than the tolerance. Without the undo the torus (512², fitted) showed a point
    // 30 px off its ray and the teapot at 4x one 1.8 px off.
    void adaptivePixelsShowThePointOnTheirRay_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<double>("zoom");
        for (const char* name : {"torus", "teapot"})
            for (const double zoom : {1.0, 4.0})
                QTest::addRow("%s %gx", name, zoom) << QString::fromLatin1(name) << zoom;
    }
    void adaptivePixelsShowThePointOnTheirRay() {
        QFETCH(QString, name);
        QFETCH(double, zoom);
        QString error;
        const auto s = kwtest::loadSample(name);
        QVERIFY2(s, qPrintable(s.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*s));
        Camera cam = fitCamera(doc.scene(), 1.0);
        cam.eye = cam.target + (cam.eye - cam.target) / zoom;
        RenderOptions opt = baseOptions();
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        opt.pixelTolerance = 0.5;
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer aov = m_renderer->aov();
        const glm::dmat4 vp(frameCamera(cam, doc.scene(), 1.0).viewProjection);
        int covered = 0, off = 0, worstX = -1, worstY = -1;
        double worst = 0.0;
        for (int y = 0; y < aov.height; ++y)
            for (int x = 0; x < aov.width; ++x) {
                if (aov.pixel(x, y)[0] < 0.0f)
                    continue;
                ++covered;
                const double d = kwtest::rayOffsetPixels(aov, x, y, vp);
                off += d > opt.pixelTolerance + 0.05;
                if (d > worst)
                    worst = d, worstX = x, worstY = y;
            }
        qInfo("%d covered pixels, %d show a point more than %.2f px off their ray, farthest "
              "%.3f px at (%d, %d)",
              covered, off, opt.pixelTolerance + 0.05, worst, worstX, worstY);
        QVERIFY(covered > 10000);
        QCOMPARE(off, 0);
    }

    void shadingVariantsAgree_data() {
        QTest::addColumn<int>("shading");
        QTest::newRow("exact depth") << int(RenderOptions::Shading::ExactDepth);
    }
    void shadingVariantsAgree() {
        // The exact-depth variant matches the kernel too, and shows the same surface as the
        // default pre-pass almost everywhere (exact depth may move the seam between two
        // surfaces by a few pixels).
        QFETCH(int, shading);
        QString error;
        const auto s = kwtest::loadSample(QStringLiteral("teapot"));
        QVERIFY2(s, qPrintable(s.message()));
        Document doc;
        QVERIFY(doc.resetScene(*s));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        RenderOptions opt = baseOptions();
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer prepass = m_renderer->aov();
        opt.shading = RenderOptions::Shading(shading);
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer forward = m_renderer->aov();
        const kwtest::AovComparison r = kwtest::compareAovWithKernel(doc.scene(), forward);
        QVERIFY(r.compared >= 1000);
        QVERIFY(r.maxPosition <= 1e-5 * r.modelSize);
        QVERIFY(r.maxAngleDeg <= 0.05);
        int differentId = 0;
        for (int y = 0; y < 512; ++y)
            for (int x = 0; x < 512; ++x)
                differentId += prepass.pixel(x, y)[0] != forward.pixel(x, y)[0];
        qInfo("%d of %d covered pixels show another surface than with the pre-pass", differentId,
              r.covered);
        QVERIFY(differentId <= r.covered / 100);
    }

    void deferredPassMatchesForward_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<double>("zoom");
        QTest::addColumn<int>("samples");
        QTest::newRow("teapot fitted") << QStringLiteral("teapot") << 1.0 << 1;
        // Some surfaces' cells large enough for the forward way, the rest deferred.
        QTest::newRow("teapot 6x") << QStringLiteral("teapot") << 6.0 << 1;
        QTest::newRow("torus, 4 samples") << QStringLiteral("torus") << 1.0 << 4;
        // Trimmed: the pre-pass's cells near a curve write their stencil in a second pass.
        QTest::newRow("plate beside star") << QStringLiteral("plate+star") << 1.0 << 1;
        QTest::newRow("plate beside star 3x") << QStringLiteral("plate+star") << 3.0 << 1;
        // The drag moves the whole plane (its polygon's cells stay as they were: the batches
        // are patched, not built again), past the rectangle its route had.
        QTest::newRow("plane beside torus") << QStringLiteral("plane+torus") << 1.0 << 1;
    }
    void deferredPassMatchesForward() {
        // The deferred exact pass (RenderOptions::deferredPass) shades each pixel from the
        // pre-pass's (u, v), surface and cell: the same image and AOV as the forward pass,
        // before and after a drag moves a surface past where its route was drawn.
        QFETCH(QString, sample);
        QFETCH(double, zoom);
        QFETCH(int, samples);
        QString error;
        auto s = sample == QLatin1String("plate+star") ? kwtest::plateBesideStar(2.4)
                 : sample == QLatin1String("plane+torus")
                     ? kwtest::loadSample(QStringLiteral("torus"))
                     : kwtest::loadSample(sample);
        QVERIFY2(s, qPrintable(s.message()));
        const bool plane = sample == QLatin1String("plane+torus");
        // The plane's one cell covers thousands of pixels: it would be drawn the forward way
        // (RenderOptions::deferMaxCellPixels) unless every surface is deferred.
        if (plane) {
            s->surfaces.insert(
                s->surfaces.begin(),
                kwtest::makeSurface(s->nextId++,
                                    makePlane(glm::dvec3(-1.2, -0.4, 0.9),
                                              glm::dvec3(0.8, 0.0, 0.0), glm::dvec3(0.0, 0.8, 0.0)),
                                    1));
        }
        Document doc;
        QVERIFY(doc.resetScene(*s));
        Camera cam = fitCamera(doc.scene(), 1.0);
        cam.eye = cam.target + (cam.eye - cam.target) / zoom;
        RenderOptions opt = baseOptions();
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        opt.samples = samples;
        if (plane)
            opt.deferMaxCellPixels = 1e30;
        const auto compare = [&](const char* when) {
            opt.deferredPass = true;
            KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
            const int deferred = m_renderer->lastReport().partitions.deferredSurfaces;
            const QImage colour = m_renderer->colorImage();
            const AovBuffer aov = m_renderer->aov();
            opt.deferredPass = false;
            KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
            QCOMPARE(m_renderer->lastReport().partitions.deferredSurfaces, 0);
            const QImage forwardColour = m_renderer->colorImage();
            const AovBuffer forward = m_renderer->aov();
            int covered = 0, otherId = 0, otherColour = 0, worst = 0;
            for (int y = 0; y < aov.height; ++y)
                for (int x = 0; x < aov.width; ++x) {
                    covered += forward.pixel(x, y)[0] >= 0.0f;
                    otherId += aov.pixel(x, y)[0] != forward.pixel(x, y)[0];
                    const QRgb a = colour.pixel(x, y), b = forwardColour.pixel(x, y);
                    const int d =
                        std::max({std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                                  std::abs(qBlue(a) - qBlue(b))});
                    otherColour += d > 2;
                    worst = std::max(worst, d);
                }
            qInfo("%s: %d surfaces deferred; of %d covered pixels %d show another surface, %d "
                  "another colour (worst %d / 255)",
                  when, deferred, covered, otherId, otherColour, worst);
            QVERIFY2(deferred > 0, when);
            QVERIFY2(covered > 10000, when);
            QVERIFY2(otherId <= covered / 2000, when);
            QVERIFY2(otherColour <= covered / 2000, when);
        };
        compare("before the drag");
        if (QTest::currentTestFailed())
            return;
        // Pull one control point of the first surface far out towards the eye and sideways
        // (the plane: all of them, sideways).
        const Surface& first = doc.scene().surfaces.front();
        const NurbsSurface& g = first.geometry;
        const glm::dvec3 side = glm::normalize(glm::cross(cam.target - cam.eye, cam.up));
        const double size = glm::length(cam.target - cam.eye) / zoom;
        std::vector<int> moved;
        std::vector<glm::dvec3> to;
        for (int k = 0; k < int(g.points.size()); ++k)
            if (plane || k == g.index(g.countU / 2, g.countV / 2)) {
                moved.push_back(k);
                to.push_back(g.points[size_t(k)] + (plane ? 0.25 : 0.3) * size * side +
                             (plane ? 0.0 : 0.2) * (cam.eye - cam.target) / zoom);
            }
        // A deferred frame before the drag, so that the one after it patches its batches.
        opt.deferredPass = true;
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        QVERIFY(doc.setControlPoints(first.id, moved, to));
        compare("after the drag");
    }

    void overlaysLeaveTheAovAlone() {
        // Wireframe and control net draw into the colour target only.
        QString error;
        const auto s = kwtest::loadSample(QStringLiteral("torus"));
        QVERIFY2(s, qPrintable(s.message()));
        Document doc;
        QVERIFY(doc.resetScene(*s));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        RenderOptions opt = baseOptions();
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer plain = m_renderer->aov();
        const QImage plainColor = m_renderer->colorImage();
        opt.wireframe = opt.controlNet = true;
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        QVERIFY(m_renderer->aov().data == plain.data);
        QVERIFY(m_renderer->colorImage() != plainColor);
    }

    void backgroundIsMinusOne() {
        Document doc;
        QString error;
        KW_VERIFY_OK(m_renderer->render(doc, Camera{}, baseOptions()));
        const AovBuffer aov = m_renderer->aov();
        QCOMPARE(aov.pixel(0, 0)[0], -1.0f);
        QCOMPARE(aov.pixel(511, 511)[0], -1.0f);
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderExact)
#include "tst_render_exact.moc"
