// GL test: faces that kept an analytic form are shaded at the pixel's ray's meeting with it,
// found in closed form (RenderOptions::analyticFaces): the AOV against the CPU kernel and
// against the Newton path, a torus (the quartic), a trimmed face, and a face whose form an
// edit dropped.
#include "expected_test_util.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/analytic_table.h"
#include "render_test_util.h"
#include "trim_test_util.h"

#include <QGuiApplication>
#include <cmath>

Q_DECLARE_METATYPE(glm::dvec3)

using namespace kw;

namespace {

constexpr double kPi = 3.14159265358979323846;

AnalyticParamMap halfAngle(double offset, double scale) {
    return AnalyticParamMap{AnalyticParamMap::Kind::HalfAngle, offset, scale};
}
AnalyticParamMap linear(double offset, double scale) {
    return AnalyticParamMap{AnalyticParamMap::Kind::Linear, offset, scale};
}

/// The form of kw::makeRevolution's shapes about +z through `centre`: u is the 9-point circle
/// from +x counter-clockwise (four quarter arcs), so a = 2 pi u by half angles.
AnalyticForm revolved(AnalyticForm::Kind kind, const glm::dvec3& centre) {
    AnalyticForm f;
    f.kind = kind;
    f.origin = centre;
    f.u = halfAngle(0.0, 2.0 * kPi);
    return f;
}

/// A cone of apex radius `r0` at `base`, half angle `angle`, slant length `length` along v.
Surface coneSurface(std::uint32_t id, const glm::dvec3& base, double r0, double angle,
                    double length) {
    NurbsCurve2 line;
    line.degree = 1;
    line.points = {glm::dvec2(r0, 0.0),
                   glm::dvec2(r0 + length * std::sin(angle), length * std::cos(angle))};
    line.weights = {1.0, 1.0};
    line.knots = {0.0, 0.0, 1.0, 1.0};
    Surface s = kwtest::makeSurface(id, makeRevolution(base, line), 8);
    s.analytic = revolved(AnalyticForm::Kind::Cone, base);
    s.analytic.radius = r0;
    s.analytic.semiAngle = angle;
    s.analytic.v = linear(0.0, length);
    return s;
}

Surface cylinderSurface(std::uint32_t id, const glm::dvec3& base, double r, double h) {
    Surface s = kwtest::makeSurface(id, makeCylinder(base, r, h), 8);
    s.analytic = revolved(AnalyticForm::Kind::Cylinder, base);
    s.analytic.radius = r;
    s.analytic.v = linear(0.0, h);
    return s;
}

Surface sphereSurface(std::uint32_t id, const glm::dvec3& centre, double r) {
    Surface s = kwtest::makeSurface(id, makeSphere(centre, r), 8);
    s.analytic = revolved(AnalyticForm::Kind::Sphere, centre);
    s.analytic.radius = r;
    s.analytic.v = halfAngle(-0.5 * kPi, kPi); // south pole to north pole, two quarter arcs
    return s;
}

Surface torusSurface(std::uint32_t id, const glm::dvec3& centre, double R, double r) {
    Surface s = kwtest::makeSurface(id, makeTorus(centre, R, r), 8);
    s.analytic = revolved(AnalyticForm::Kind::Torus, centre);
    s.analytic.radius = R;
    s.analytic.minorRadius = r;
    s.analytic.v = halfAngle(0.0, 2.0 * kPi); // from the outer equator, upward
    return s;
}

/// The surface with u and v exchanged (its control net transposed): the form's maps stay with
/// the parameters they take, and `swapped` says u now gives b.
Surface swapped(Surface s) {
    NurbsSurface& g = s.geometry;
    NurbsSurface t = g;
    t.degreeU = g.degreeV;
    t.degreeV = g.degreeU;
    t.countU = g.countV;
    t.countV = g.countU;
    t.knotsU = g.knotsV;
    t.knotsV = g.knotsU;
    for (int j = 0; j < g.countV; ++j)
        for (int i = 0; i < g.countU; ++i) {
            t.points[size_t(i * t.countU + j)] = g.points[size_t(j * g.countU + i)];
            t.weights[size_t(i * t.countU + j)] = g.weights[size_t(j * g.countU + i)];
        }
    g = t;
    std::swap(s.analytic.u, s.analytic.v);
    s.analytic.swapped = true;
    std::swap(s.partitionsU, s.partitionsV);
    return s;
}

/// `s` turned by `angle` about `axis` through the origin, its form with it; `mirror` also
/// reflects it in the plane x = 0 (a left-handed frame, and the NURBS's normal turned over).
Surface turned(Surface s, const glm::dvec3& axis, double angle, bool mirror) {
    const glm::dvec3 k = glm::normalize(axis);
    const auto apply = [&](glm::dvec3 p, bool point) {
        (void)point;
        if (mirror)
            p.x = -p.x;
        return p * std::cos(angle) + glm::cross(k, p) * std::sin(angle) +
               k * glm::dot(k, p) * (1.0 - std::cos(angle));
    };
    for (glm::dvec3& p : s.geometry.points)
        p = apply(p, true);
    AnalyticForm& f = s.analytic;
    f.origin = apply(f.origin, true);
    f.xAxis = apply(f.xAxis, false);
    f.yAxis = apply(f.yAxis, false);
    f.zAxis = apply(f.zAxis, false);
    return s;
}

Scene sceneOf(std::vector<Surface> surfaces) {
    Scene scene;
    std::uint32_t next = 1;
    for (Surface& s : surfaces)
        next = std::max(next, s.id.value + 1);
    for (Surface& s : surfaces)
        for (TrimLoop& l : s.trims)
            next = std::max(next, l.id.value + 1);
    scene.surfaces = std::move(surfaces);
    scene.nextId = next;
    return scene;
}

RenderOptions adaptive(bool analytic) {
    RenderOptions o;
    o.partitioning = RenderOptions::Partitioning::Adaptive;
    o.pixelTolerance = 0.5;
    o.analyticFaces = analytic;
    return o;
}

/// How far the covered pixels' points lie from their rays. Pixels showing the domain's edge
/// (a (u, v) on the boundary of the fixtures' [0, 1]^2) are left out: past the face's edge a
/// pixel shows the edge's point (clamped), off its ray by design.
struct RayFigures {
    int covered = 0;
    double worst = 0.0; ///< the farthest an inner pixel's point projects from its centre, px
    int off = 0;        ///< inner pixels whose point projects more than 0.01 px from it
};
RayFigures rayFigures(const AovBuffer& aov, const glm::dmat4& vp) {
    RayFigures r;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            const float* a = aov.pixel(x, y);
            if (a[0] < 0.0f)
                continue;
            ++r.covered;
            const bool edge =
                std::min(std::min(a[1], 1.0f - a[1]), std::min(a[2], 1.0f - a[2])) < 1e-5f;
            if (edge)
                continue;
            const double d = kwtest::rayOffsetPixels(aov, x, y, vp);
            r.worst = std::max(r.worst, d);
            r.off += d > 0.01;
        }
    return r;
}

/// Of two frames' AOVs of one size: the pixels each shows a surface at, and those whose surface
/// ids differ.
struct IdCounts {
    int a = 0, b = 0, differ = 0;
};
IdCounts idCounts(const AovBuffer& a, const AovBuffer& b) {
    IdCounts n;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            n.a += a.pixel(x, y)[0] >= 0.0f;
            n.b += b.pixel(x, y)[0] >= 0.0f;
            n.differ += a.pixel(x, y)[0] != b.pixel(x, y)[0];
        }
    return n;
}

} // namespace

class TestRenderAnalytic : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
        auto made = kwtest::offscreenRenderer(QSize(384, 384), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    // Each fixture's form is what the import would keep: the test would fail with a wrong one
    // (the kernel's point at the AOV's (u, v) would not be the point shown).
    void formsAreUsable() {
        for (const Surface& s :
             {cylinderSurface(1, glm::dvec3(0.0), 1.0, 2.0), sphereSurface(1, glm::dvec3(0.0), 1.0),
              torusSurface(1, glm::dvec3(0.0), 1.0, 0.3),
              coneSurface(1, glm::dvec3(0.0), 0.5, 0.4, 1.5)})
            QVERIFY(analyticUsable(s.analytic));
        AnalyticForm bad = cylinderSurface(1, glm::dvec3(0.0), 1.0, 2.0).analytic;
        bad.yAxis = glm::dvec3(1.0, 0.0, 0.0); // not a frame
        QVERIFY(!analyticUsable(bad));
        bad = cylinderSurface(1, glm::dvec3(0.0), 1.0, 2.0).analytic;
        bad.u.scale = 0.0;
        QVERIFY(!analyticUsable(bad));
        QVERIFY(!analyticUsable(AnalyticForm{}));
    }

    // The closed form shows, at every pixel, the surface point on the pixel's ray (to float
    // rounding, far below the Newton step's residual), the NURBS's own point at the (u, v) it
    // reports (kernel position and normal within the exact pass's tolerances), and the image
    // the Newton path shows.
    void analyticMatchesKernelAndNewton_data() {
        QTest::addColumn<Scene>("scene");
        QTest::addColumn<double>("zoom");
        const glm::dvec3 o(0.0);
        QTest::newRow("cylinder") << sceneOf({cylinderSurface(1, o, 1.0, 2.0)}) << 1.0;
        QTest::newRow("sphere") << sceneOf({sphereSurface(1, o, 1.0)}) << 1.0;
        QTest::newRow("torus") << sceneOf({torusSurface(1, o, 1.0, 0.35)}) << 1.0;
        QTest::newRow("torus 6x") << sceneOf({torusSurface(1, o, 1.0, 0.35)}) << 6.0;
        // A spindle torus (r > R), as CAD domes are: part of it lies where R + r cos b < 0.
        QTest::newRow("spindle torus") << sceneOf({torusSurface(1, o, 0.4, 1.0)}) << 1.0;
        QTest::newRow("cone") << sceneOf({coneSurface(1, o, 0.3, 0.5, 1.5)}) << 1.0;
        QTest::newRow("swapped cylinder")
            << sceneOf({swapped(cylinderSurface(1, o, 1.0, 2.0))}) << 1.0;
        QTest::newRow("turned mirrored torus")
            << sceneOf({turned(torusSurface(1, glm::dvec3(0.5, 0.2, 0.1), 1.0, 0.4),
                               glm::dvec3(1.0, 2.0, 0.5), 0.7, true)})
            << 1.0;
        QTest::newRow("four forms")
            << sceneOf({cylinderSurface(1, glm::dvec3(-2.5, 0.0, 0.0), 0.8, 1.5),
                        sphereSurface(2, glm::dvec3(0.0, 2.5, 0.5), 0.9),
                        torusSurface(3, glm::dvec3(2.5, 0.0, 0.5), 1.0, 0.3),
                        coneSurface(4, glm::dvec3(0.0, -2.5, 0.0), 0.2, 0.6, 1.4)})
            << 1.0;
    }
    void analyticMatchesKernelAndNewton() {
        QFETCH(Scene, scene);
        QFETCH(double, zoom);
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        Camera cam = fitCamera(doc.scene(), 1.0);
        cam.eye = cam.target + (cam.eye - cam.target) / zoom;
        const glm::dmat4 vp(frameCamera(cam, doc.scene(), 1.0).viewProjection);

        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(true)));
        const AovBuffer on = m_renderer->aov();
        QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces,
                 int(doc.scene().surfaces.size()));
        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(false)));
        const AovBuffer off = m_renderer->aov();
        QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces, 0);

        const kwtest::AovComparison k = kwtest::compareAovWithKernel(doc.scene(), on);
        const RayFigures onRay = rayFigures(on, vp), offRay = rayFigures(off, vp);
        // Where both show the same surface: how far apart their (u, v) and normals are.
        int same = 0, otherId = 0, apart = 0, unexplained = 0;
        const glm::dvec3 eye = cam.eye;
        const double size = glm::length(cam.eye - cam.target);
        double uvApart = 0.0, normalApart = 0.0;
        for (int y = 0; y < on.height; ++y)
            for (int x = 0; x < on.width; ++x) {
                const float* a = on.pixel(x, y);
                const float* b = off.pixel(x, y);
                if (a[0] != b[0]) {
                    ++otherId;
                    continue;
                }
                if (a[0] < 0.0f)
                    continue;
                ++same;
                const double duv = std::hypot(a[1] - b[1], a[2] - b[2]);
                const glm::dvec3 na(a[6], a[7], a[8]), nb(b[6], b[7], b[8]);
                const double dn = glm::degrees(std::acos(std::clamp(glm::dot(na, nb), -1.0, 1.0)));
                if (duv > 2e-3 || dn > 1.0) {
                    // Where they differ, the closed form shows the ray's first meeting with the
                    // face: not farther from the eye than the Newton path's point (which near a
                    // fold can be on the hidden sheet; 1 % of the view's distance for a grazing
                    // ray's sub-pixel offsets), unless that one is off its ray or an edge's
                    // point (clamped: a ray passing just over a rim meets the inside).
                    ++apart;
                    const double dOn = glm::length(glm::dvec3(a[3], a[4], a[5]) - eye);
                    const double dOff = glm::length(glm::dvec3(b[3], b[4], b[5]) - eye);
                    const bool edge =
                        std::min(std::min(b[1], 1.0f - b[1]), std::min(b[2], 1.0f - b[2])) < 1e-5f;
                    unexplained += dOn > dOff + 1e-2 * size && !edge &&
                                   kwtest::rayOffsetPixels(off, x, y, vp) <= 0.01;
                }
                uvApart = std::max(uvApart, duv);
                normalApart = std::max(normalApart, dn);
            }
        qInfo("analytic: %d px, %d compared with the kernel, position %.3g x model, normal "
              "%.4f deg at (%d, %d); ray offset %.4f px, %d px > 0.01 px (Newton path %.4f px, %d "
              "px); against the Newton "
              "path: %d px of another id, %d px apart (%d unexplained), at most (u, v) %.3g apart, "
              "normals %.4f deg",
              k.covered, k.compared, k.maxPosition / k.modelSize, k.maxAngleDeg, k.worstX, k.worstY,
              onRay.worst, onRay.off, offRay.worst, offRay.off, otherId, apart, unexplained,
              uvApart, normalApart);
        QCOMPARE(k.unknownIds, 0);
        QVERIFY(k.compared >= 1000);
        QVERIFY(k.maxPosition <= 1e-5 * k.modelSize);
        QVERIFY(k.maxAngleDeg <= 0.05);
        // On the ray: the Newton step leaves up to ~0.1 px; the closed form float rounding, but
        // where the ray just misses the surface (a silhouette's pixel centre just outside it).
        QVERIFY2(onRay.off <= onRay.covered / 2000, "pixels show a point off their ray");
        QCOMPARE(onRay.covered, offRay.covered);
        QVERIFY(otherId <= same / 2000);
        // Both show the point under the pixel, but for the Newton step's residual, its
        // mirrored normals at folds, and a rim's pixel where the ray passes just over the edge
        // to the inside (the closed form shows the inside, the Newton step the edge).
        QVERIFY(apart <= same / 200);
        QCOMPARE(unexplained, 0);
    }

    // A trimmed analytic face: the trims are tested at the closed form's (u, v), the pixels
    // kept are those the Newton path keeps, and the trims remove what they remove there.
    void trimmedAnalyticFace() {
        Surface s = cylinderSurface(1, glm::dvec3(0.0), 1.0, 2.0);
        s.trims.push_back(kwtest::discLoop(2, 0.3));
        Surface whole = cylinderSurface(1, glm::dvec3(0.0), 1.0, 2.0);
        Document doc, wholeDoc;
        KW_VERIFY_OK(doc.resetScene(sceneOf({s})));
        KW_VERIFY_OK(wholeDoc.resetScene(sceneOf({whole})));
        const Camera cam = fitCamera(wholeDoc.scene(), 1.0);
        for (const bool deferred : {true, false}) {
            RenderOptions on = adaptive(true), off = adaptive(false);
            on.deferredPass = off.deferredPass = deferred;
            KW_VERIFY_OK(m_renderer->render(wholeDoc, cam, on));
            const AovBuffer untrimmed = m_renderer->aov();
            int all = 0;
            for (int y = 0; y < untrimmed.height; ++y)
                for (int x = 0; x < untrimmed.width; ++x)
                    all += untrimmed.pixel(x, y)[0] >= 0.0f;
            KW_VERIFY_OK(m_renderer->render(doc, cam, on));
            QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces, 1);
            const AovBuffer a = m_renderer->aov();
            KW_VERIFY_OK(m_renderer->render(doc, cam, off));
            const AovBuffer b = m_renderer->aov();
            const auto [keptA, keptB, differ] = idCounts(a, b);
            const kwtest::AovComparison k = kwtest::compareAovWithKernel(doc.scene(), a);
            qInfo("deferred %d: %d px untrimmed, %d kept (Newton path %d), %d differ, kernel "
                  "position %.3g x model, normal %.4f deg",
                  int(deferred), all, keptA, keptB, differ, k.maxPosition / k.modelSize,
                  k.maxAngleDeg);
            QVERIFY(keptA > 2000 && keptA < all * 9 / 10); // the trims cut it
            QVERIFY(differ <= keptA / 500);
            QVERIFY(k.maxPosition <= 1e-5 * k.modelSize);
            QVERIFY(k.maxAngleDeg <= 0.05);
        }
    }

    // An edit of the face's points drops its form (the document's rule): the next frame draws
    // it the NURBS way, and shows the edited surface, not the form it had.
    void editedFaceFallsBack() {
        Document doc;
        KW_VERIFY_OK(doc.resetScene(sceneOf({torusSurface(1, glm::dvec3(0.0), 1.0, 0.35)})));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(true)));
        QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces, 1);
        const SurfaceId id = doc.scene().surfaces[0].id;
        const glm::dvec3 p = doc.scene().surfaces[0].geometry.points[20];
        QVERIFY(doc.setControlPoints(id, {20}, {p + glm::dvec3(0.0, 0.0, 0.4)}));
        QCOMPARE(int(doc.scene().surfaces[0].analytic.kind), int(AnalyticForm::Kind::None));
        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(true)));
        QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces, 0);
        const AovBuffer after = m_renderer->aov();
        // The same frame as the Newton path's: a form left on the GPU would show the torus it
        // was, not the bump.
        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(false)));
        const AovBuffer newton = m_renderer->aov();
        int covered = 0, differ = 0;
        for (int y = 0; y < after.height; ++y)
            for (int x = 0; x < after.width; ++x) {
                const float* a = after.pixel(x, y);
                const float* b = newton.pixel(x, y);
                covered += a[0] >= 0.0f;
                bool same = true;
                for (int c = 0; c < 9; ++c)
                    same = same && a[c] == b[c];
                differ += !same;
            }
        QVERIFY(covered > 10000);
        QCOMPARE(differ, 0);
    }

    // A move of the whole face keeps its form, moved along (the document's rule): the next
    // frame uploads the moved row and draws the face in closed form where it now is. A stale
    // row would intersect the form where it was, far from the kernel's point.
    void movedFaceKeepsItsFormOnTheGpu() {
        Document doc;
        KW_VERIFY_OK(doc.resetScene(sceneOf({sphereSurface(1, glm::dvec3(0.0), 1.0)})));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(true)));
        QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces, 1);
        // A placement (as TransformSurfaces makes it): the form follows.
        std::vector<glm::dvec3> moved = doc.scene().surfaces[0].geometry.points;
        for (glm::dvec3& p : moved)
            p += glm::dvec3(0.3, -0.2, 0.1);
        QVERIFY(doc.placeControlPoints(doc.scene().surfaces[0].id, moved));
        QCOMPARE(int(doc.scene().surfaces[0].analytic.kind), int(AnalyticForm::Kind::Sphere));
        KW_VERIFY_OK(m_renderer->render(doc, cam, adaptive(true)));
        QCOMPARE(m_renderer->lastReport().partitions.analyticSurfaces, 1);
        const kwtest::AovComparison k =
            kwtest::compareAovWithKernel(doc.scene(), m_renderer->aov());
        QVERIFY(k.compared >= 1000);
        QVERIFY(k.maxPosition <= 1e-5 * k.modelSize);
        QVERIFY(k.maxAngleDeg <= 0.05);
    }

    // A close-up beside a cylinder, a cone or a sphere (a trimmed one too) asks the polygon for
    // thousands of cells; the face is drawn by its cover instead (RenderOptions::
    // coverMinCells): one box, far less memory, and the same pixels as the
    // polygon's frame: the same faces shown, the same points and normals but for float
    // rounding, and the kernel's surface at every pixel.
    void coverDrawsCloseUps_data() {
        QTest::addColumn<Scene>("scene");
        QTest::addColumn<glm::dvec3>("eye");
        QTest::addColumn<glm::dvec3>("target");
        const glm::dvec3 o(0.0);
        QTest::newRow("cylinder") << sceneOf({cylinderSurface(1, o, 1.0, 2.0)})
                                  << glm::dvec3(1.01, -0.3, 1.0) << glm::dvec3(1.0, 0.5, 1.2);
        Surface holed = cylinderSurface(1, o, 1.0, 2.0);
        holed.trims.push_back(kwtest::discLoop(2, 0.3));
        QTest::newRow("trimmed cylinder")
            << sceneOf({holed}) << glm::dvec3(-0.3, 1.03, 1.0) << glm::dvec3(-1.0, 0.4, 1.1);
        QTest::newRow("cone") << sceneOf({coneSurface(1, o, 0.3, 0.5, 1.5)})
                              << glm::dvec3(0.7, -0.2, 0.66) << glm::dvec3(0.55, 0.45, 0.8);
        QTest::newRow("sphere") << sceneOf({sphereSurface(1, o, 1.0)})
                                << glm::dvec3(0.0, -1.04, 0.2) << glm::dvec3(0.6, -0.7, 0.35);
    }
    void coverDrawsCloseUps() {
        QFETCH(Scene, scene);
        QFETCH(glm::dvec3, eye);
        QFETCH(glm::dvec3, target);
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        Camera cam = fitCamera(doc.scene(), 1.0);
        cam.eye = eye;
        cam.target = target;
        // A renderer of its own: the pools' bytes are then the cover's alone.
        auto made = kwtest::offscreenRenderer(QSize(384, 384), true);
        QVERIFY2(made, qPrintable(made.message()));
        std::unique_ptr<OffscreenRenderer> fresh = std::move(made).value();
        const RenderOptions cover = adaptive(true);
        KW_VERIFY_OK(fresh->render(doc, cam, cover));
        const FrameReport rc = fresh->lastReport();
        const AovBuffer a = fresh->aov();
        const QImage ia = fresh->colorImage().convertToFormat(QImage::Format_RGBA8888);
        RenderOptions polygon = adaptive(true);
        polygon.coverMinCells = 1e30;
        KW_VERIFY_OK(fresh->render(doc, cam, polygon));
        const FrameReport rp = fresh->lastReport();
        const AovBuffer b = fresh->aov();
        const QImage ib = fresh->colorImage().convertToFormat(QImage::Format_RGBA8888);
        const kwtest::AovComparison k = kwtest::compareAovWithKernel(doc.scene(), a);
        const kwtest::AovComparison kp = kwtest::compareAovWithKernel(doc.scene(), b);
        int covered = 0, otherId = 0, apart = 0;
        double position = 0.0, normal = 0.0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) {
                const float* p = a.pixel(x, y);
                const float* q = b.pixel(x, y);
                covered += p[0] >= 0.0f;
                if (p[0] != q[0]) {
                    ++otherId;
                    continue;
                }
                if (p[0] < 0.0f)
                    continue;
                const glm::dvec3 np(p[6], p[7], p[8]), nq(q[6], q[7], q[8]);
                const double d =
                    glm::length(glm::dvec3(p[3], p[4], p[5]) - glm::dvec3(q[3], q[4], q[5]));
                apart += d > 2.4e-7 * k.modelSize;
                position = std::max(position, d);
                normal = std::max(normal,
                                  glm::degrees(std::acos(std::clamp(glm::dot(np, nq), -1.0, 1.0))));
            }
        qInfo("cover: %lld boxes, %lld B on the GPU, %lld B host; polygon: %lld cells, %lld B "
              "on the GPU, %lld B host; %d px covered, %d of another id, points %.3g x model "
              "apart, normals %.5f deg; kernel: position %.3g x model, normal %.4f deg",
              (long long)rc.partitions.cells, (long long)rc.gpuBytes.basePolygons,
              (long long)rc.hostCopyBytes, (long long)rp.partitions.cells,
              (long long)rp.gpuBytes.basePolygons, (long long)rp.hostCopyBytes, covered, otherId,
              position / k.modelSize, normal, k.maxPosition / k.modelSize, k.maxAngleDeg);
        const glm::dmat4 vp(frameCamera(cam, doc.scene(), 1.0).viewProjection);
        const RayFigures ra = rayFigures(a, vp), rb = rayFigures(b, vp);
        // The colour image: channels differing by more than 1 level (a normal's float rounding
        // on a grazing ray can move the last bit).
        int colourApart = 0, worstLevel = 0;
        for (int y = 0; y < ia.height(); ++y)
            for (int x = 0; x < ia.width(); ++x) {
                const QRgb p = ia.pixel(x, y), q = ib.pixel(x, y);
                const int level =
                    std::max({std::abs(qRed(p) - qRed(q)), std::abs(qGreen(p) - qGreen(q)),
                              std::abs(qBlue(p) - qBlue(q))});
                worstLevel = std::max(worstLevel, level);
                colourApart += level > 1;
            }
        qInfo("polygon's frame: kernel %.3g x model, %.4f deg; on the ray: cover %.4f px worst, "
              "%d > 0.01 px, polygon %.4f px, %d; %d px points more than 2.4e-7 x model apart "
              "(along grazing rays); colour: %d px more than 1 level apart, worst %d",
              kp.maxPosition / kp.modelSize, kp.maxAngleDeg, ra.worst, ra.off, rb.worst, rb.off,
              apart, colourApart, worstLevel);
        QCOMPARE(rc.partitions.coverSurfaces, 1);
        QCOMPARE(rc.partitions.analyticSurfaces, 1);
        QCOMPARE(rp.partitions.coverSurfaces, 0);
        // The view is a close-up the default covers, and the cover is a small part of it.
        QVERIFY(double(rp.partitions.cells) > cover.coverMinCells);
        QVERIFY(rc.partitions.cells * 20 <= rp.partitions.cells);
        QVERIFY(rc.gpuBytes.basePolygons * 8 <= rp.gpuBytes.basePolygons);
        QVERIFY(rc.hostCopyBytes < rp.hostCopyBytes);
        QVERIFY(covered > 20000);
        QCOMPARE(k.unknownIds, 0);
        QVERIFY(k.maxPosition <= 1e-5 * k.modelSize);
        QVERIFY(k.maxAngleDeg <= 0.05);
        // The polygon's frame shows the same: the same face at every pixel but where a
        // silhouette's pixel centre lies within rounding of it (the fins' solve there, the
        // closed form here); each point on its pixel's ray to float rounding, both (their
        // points differ only along grazing rays, where the rounding of a screen offset of
        // 0.005 px moves a point far along the ray: up to 1e-4 x model, normals 0.03 deg);
        // the same colours.
        QVERIFY(otherId <= covered / 1000);
        QVERIFY(ra.off <= ra.covered / 2000);
        QVERIFY(ra.worst <= 0.02);
        QVERIFY(normal <= 0.05);
        QVERIFY(colourApart <= covered / 1000);
    }

    // A cover keeps what the polygon's skirts keep past the face's edges: a pixel whose ray
    // meets the form's continuation within a quarter pixel of the edge shows the edge (B-rep
    // faces meet within the model's tolerance). Covered at every size (coverMinCells 0), the
    // fitted cylinder and cone cover the polygon's pixels; without that reach they lost 108
    // and 105 pixels along their rims.
    void coverKeepsTheSkirtsReach_data() {
        QTest::addColumn<Scene>("scene");
        const glm::dvec3 o(0.0);
        QTest::newRow("cylinder") << sceneOf({cylinderSurface(1, o, 1.0, 2.0)});
        QTest::newRow("cone") << sceneOf({coneSurface(1, o, 0.3, 0.5, 1.5)});
    }
    void coverKeepsTheSkirtsReach() {
        QFETCH(Scene, scene);
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        RenderOptions cover = adaptive(true), polygon = adaptive(true);
        cover.coverMinCells = 0.0;
        polygon.coverMinCells = 1e30;
        KW_VERIFY_OK(m_renderer->render(doc, cam, cover));
        QCOMPARE(m_renderer->lastReport().partitions.coverSurfaces, 1);
        const AovBuffer a = m_renderer->aov();
        KW_VERIFY_OK(m_renderer->render(doc, cam, polygon));
        QCOMPARE(m_renderer->lastReport().partitions.coverSurfaces, 0);
        const AovBuffer b = m_renderer->aov();
        const auto [coveredA, coveredB, otherId] = idCounts(a, b);
        qInfo("cover %d px, polygon %d px, %d of another id", coveredA, coveredB, otherId);
        QVERIFY(coveredB > 20000);
        QVERIFY(otherId <= coveredB / 2000);
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderAnalytic)

#include "tst_render_analytic.moc"
