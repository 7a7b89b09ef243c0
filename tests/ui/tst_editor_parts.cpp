// Editor parts without GL: camera math, pixel <-> world mapping, control-point picking and the
// CPU trim mask.
#include "model/nurbs/nurbs_shapes.h"
#include "ui/cameracontroller.h"
#include "ui/controlpointpicker.h"
#include "ui/trimmask.h"
#include "ui/uvpanel.h"

#include <QTest>
#include <cmath>

using namespace kw;

namespace {

Surface flatPatch(std::uint32_t id, double z = 0.0) {
    Surface s;
    s.id = SurfaceId{id};
    s.name = QStringLiteral("patch");
    NurbsSurface& g = s.geometry;
    g.degreeU = g.degreeV = 1;
    g.countU = g.countV = 3;
    g.knotsU = g.knotsV = {0, 0, 0.5, 1, 1};
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            g.points.emplace_back(i - 1.0, j - 1.0, z);
            g.weights.push_back(1.0);
        }
    return s;
}

NurbsCurve2 polyline(std::vector<glm::dvec2> pts) {
    NurbsCurve2 c;
    c.degree = 1;
    c.points = std::move(pts);
    c.weights.assign(c.points.size(), 1.0);
    c.knots.push_back(0.0);
    for (size_t k = 0; k < c.points.size(); ++k)
        c.knots.push_back(double(k) / double(c.points.size() - 1));
    c.knots.push_back(1.0);
    return c;
}

TrimLoop square(std::uint32_t id, double lo, double hi) {
    return {TrimLoopId{id}, {polyline({{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}, {lo, lo}})}};
}

double dist(QPointF a, QPointF b) {
    return std::hypot(a.x() - b.x(), a.y() - b.y());
}

} // namespace

class TestEditorParts : public QObject {
    Q_OBJECT
private Q_SLOTS:
    // The UV panel's axis labels: rounded to the domain's span, so that the two ends of a
    // narrow panel do not run into each other; no "-0".
    void domainLabelsAreRounded() {
        QCOMPARE(domainLabel(-0.00293838, 0.72), QStringLiteral("-0.003"));
        QCOMPARE(domainLabel(0.71705, 0.72), QStringLiteral("0.717"));
        QCOMPARE(domainLabel(6.283185307, 6.283185307), QStringLiteral("6.28"));
        QCOMPARE(domainLabel(-20.8806, 20.8806), QStringLiteral("-20.9"));
        QCOMPARE(domainLabel(1234.5678, 1000.0), QStringLiteral("1235"));
        QCOMPARE(domainLabel(-1e-9, 1.0), QStringLiteral("0.00"));
        QCOMPARE(domainLabel(1.0, 0.0), QStringLiteral("1.00")); // a degenerate span
    }
    void orbitKeepsDistanceAndStaysUpright() {
        CameraController c;
        Camera cam;
        cam.eye = {0, -5, 1};
        cam.target = {0, 0, 0};
        c.setCamera(cam);
        const double d0 = glm::length(cam.eye - cam.target);
        c.orbit(0, 0);
        QVERIFY(glm::length(c.camera().eye - cam.eye) < 1e-12);
        c.orbit(225, 0); // 90 degrees about z
        QVERIFY(std::abs(glm::length(c.camera().eye - c.camera().target) - d0) < 1e-12);
        QVERIFY(std::abs(c.camera().eye.z - cam.eye.z) < 1e-12);
        QVERIFY(std::abs(c.camera().eye.y) < 1e-9);
        for (int k = 0; k < 50; ++k)
            c.orbit(3, 40); // far past the pole
        const glm::dvec3 off = glm::normalize(c.camera().eye - c.camera().target);
        QVERIFY(off.z <= std::sin(glm::radians(89.0)) + 1e-12);
        QVERIFY(std::abs(glm::length(c.camera().eye - c.camera().target) - d0) < 1e-9);
        c.orbit(std::nan(""), 1.0); // ignored
        QVERIFY(std::isfinite(c.camera().eye.x));
    }

    void zoomAndPan() {
        CameraController c;
        c.setCamera(Camera{});
        const double d0 = glm::length(c.camera().eye - c.camera().target);
        c.zoom(1);
        QVERIFY(std::abs(glm::length(c.camera().eye - c.camera().target) -
                         d0 * CameraController::kZoomPerStep) < 1e-12);
        c.zoom(-1);
        QVERIFY(std::abs(glm::length(c.camera().eye - c.camera().target) - d0) < 1e-12);
        // Pan: the old target moves with the mouse, by the same number of pixels.
        Scene scene;
        scene.surfaces.push_back(flatPatch(1));
        const QSize size(400, 300);
        const glm::dvec3 target = c.camera().target;
        c.pan(30, -20, size);
        const ViewProjection after(c.camera(), scene, size);
        const QPointF moved = *after.project(target);
        QVERIFY2(dist(moved, QPointF(200 + 30, 150 - 20)) < 1e-6,
                 qPrintable(QStringLiteral("%1,%2").arg(moved.x()).arg(moved.y())));
    }

    void standardViewsLookAlongAxesAndFit() {
        Scene scene;
        scene.surfaces.push_back(flatPatch(1));
        CameraController c;
        c.setStandardView(StandardView::Front, scene, 1.0);
        glm::dvec3 f = glm::normalize(c.camera().target - c.camera().eye);
        QVERIFY(glm::length(f - glm::dvec3(0, 1, 0)) < 1e-12);
        c.setStandardView(StandardView::Top, scene, 1.0);
        f = glm::normalize(c.camera().target - c.camera().eye);
        QVERIFY(glm::length(f - glm::dvec3(0, 0, -1)) < 1e-12);
        // Fitted: every control point projects inside the view.
        const ViewProjection view(c.camera(), scene, QSize(300, 300));
        for (const glm::dvec3& p : scene.surfaces[0].geometry.points) {
            const QPointF px = *view.project(p);
            QVERIFY(px.x() > 0 && px.x() < 300 && px.y() > 0 && px.y() < 300);
        }
        // Orbiting away from the top view works (no stuck pole).
        const glm::dvec3 eye = c.camera().eye;
        c.orbit(0, -20);
        QVERIFY(glm::length(c.camera().eye - eye) > 1e-3);
    }

    void viewPlaneAndAxisUnprojection() {
        Scene scene;
        scene.surfaces.push_back(flatPatch(1));
        const Camera cam = fitCamera(scene, 4.0 / 3.0);
        const ViewProjection view(cam, scene, QSize(400, 300));
        const glm::dvec3 anchor(0.3, -0.2, 0.1);
        const QPointF pixel(123.5, 77.25);
        const glm::dvec3 p = view.onViewPlane(pixel, anchor);
        QVERIFY(dist(*view.project(p), pixel) < 1e-7);
        QVERIFY(std::abs(view.depth(p) - view.depth(anchor)) < 1e-9);
        const glm::dvec3 onX = view.onAxis(pixel, anchor, {1, 0, 0});
        QCOMPARE(onX.y, anchor.y);
        QCOMPARE(onX.z, anchor.z);
        // The anchor's own pixel maps back to the anchor.
        QVERIFY(glm::length(view.onAxis(*view.project(anchor), anchor, {0, 0, 1}) - anchor) < 1e-9);
    }

    void pickerNearestAndRubberBand() {
        Document doc;
        Scene scene;
        scene.surfaces.push_back(flatPatch(1));
        scene.surfaces.push_back(flatPatch(2, -0.5)); // behind the first, seen from above
        QVERIFY(doc.resetScene(scene));
        Camera cam;
        cam.eye = {0, 0, 10};
        cam.target = {0, 0, 0};
        cam.up = {0, 1, 0};
        const ViewProjection view(cam, doc.scene(), QSize(400, 400));
        ControlPointPicker picker;
        picker.update(doc, view);
        QCOMPARE(picker.projected().size(), size_t(18));
        const QPointF corner = *picker.pixelOf({SurfaceId{1}, 2, 2});
        // Within the radius: the nearest; the front surface's point wins a near tie.
        QCOMPARE(picker.nearest(corner + QPointF(2, 1)),
                 std::optional(ControlPointRef{SurfaceId{1}, 2, 2}));
        QCOMPARE(picker.nearest(corner + QPointF(40, 40)), std::nullopt);
        // Centre point: surface 1's (0, 0, 0) and surface 2's (0, 0, -0.5) project to the same
        // pixel; the front one is picked.
        QCOMPARE(picker.nearest(QPointF(200, 200)),
                 std::optional(ControlPointRef{SurfaceId{1}, 1, 1}));
        const auto band = picker.inRect(QRectF(QPointF(190, 210), QPointF(400, 0)));
        // Points with x >= 0 and y >= 0 of both surfaces (y up on screen): 4 each.
        QCOMPARE(band.size(), size_t(8));
        QVERIFY(std::is_sorted(band.begin(), band.end()));
    }

    void trimMaskParity() {
        Surface s = flatPatch(1);
        QImage none = trimMaskImage(s, QSize(64, 64));
        QCOMPARE(keptFraction(none), 1.0);
        s.trims.push_back(square(2, 0.0, 1.0));   // outer: the whole domain
        s.trims.push_back(square(3, 0.25, 0.75)); // hole: a quarter of it
        const QImage m = trimMaskImage(s, QSize(64, 64));
        QVERIFY(std::abs(keptFraction(m) - 0.75) < 1e-9);
        QCOMPARE(qGray(m.pixel(32, 32)), 0);        // in the hole
        QCOMPARE(qGray(m.pixel(4, 4)), 255);        // kept
        s.trims.push_back(square(4, 0.375, 0.625)); // island inside the hole
        QVERIFY(std::abs(keptFraction(trimMaskImage(s, QSize(64, 64))) - 0.8125) < 1e-9);
        QVERIFY(trimMaskImage(s, QSize()).isNull());
        // Curved trims are sampled: a circle covers about pi r^2.
        Surface c = flatPatch(5);
        TrimLoop circle{TrimLoopId{6}, {}};
        NurbsCurve2 arc;
        arc.degree = 2;
        arc.knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
        const double w = std::sqrt(0.5);
        arc.points = {{0.9, 0.5}, {0.9, 0.9}, {0.5, 0.9}, {0.1, 0.9}, {0.1, 0.5},
                      {0.1, 0.1}, {0.5, 0.1}, {0.9, 0.1}, {0.9, 0.5}};
        arc.weights = {1, w, 1, w, 1, w, 1, w, 1};
        circle.curves.push_back(arc);
        c.trims.push_back(circle);
        const double kept = keptFraction(trimMaskImage(c, QSize(256, 256)));
        QVERIFY2(std::abs(kept - M_PI * 0.16) < 0.005, qPrintable(QString::number(kept)));
    }
};

QTEST_GUILESS_MAIN(TestEditorParts)
#include "tst_editor_parts.moc"
