// Kernel tests of the base-polygon bound near the eye (render/surface_bound.h): the least depth
// of the part of a box inside the view frustum, and the partitions of a surface that passes
// beside and behind the eye, whose bounds reach past the near plane.
#include "model/nurbs/nurbs_shapes.h"
#include "render/adaptive_partitions.h"
#include "render/surface_bound.h"

#include <QTest>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

using namespace kw;

namespace {

/// A camera at `eye` looking at `target` with a perspective of `fov` degrees at w x h pixels
/// and its near plane at `nearDepth`, culling what is off screen, as the renderer scores it.
ScreenScale viewScale(const Camera& cam, int w, int h, double nearDepth) {
    ScreenScale scale = screenScale(cam, w, h, nearDepth);
    scale.cullOutsideView = true;
    scale.viewProjection =
        glm::perspective(glm::radians(cam.fovYDegrees), double(w) / double(h), nearDepth, 1e4) *
        glm::lookAt(cam.eye, cam.target, cam.up);
    scale.viewportPixels = glm::dvec2(w, h);
    return scale;
}

/// True when p lies inside the frustum's side planes and at or past the near plane.
bool inFrustum(const ScreenScale& scale, const glm::dvec3& p) {
    const glm::dvec4 c = scale.viewProjection * glm::dvec4(p, 1.0);
    return glm::dot(p - scale.eye, scale.forward) >= scale.nearDepth && std::abs(c.x) <= c.w &&
           std::abs(c.y) <= c.w;
}

std::int64_t cells(const PartitionChoice& c) {
    return std::int64_t(c.breaksU.size() - 1) * std::int64_t(c.breaksV.size() - 1);
}

/// The largest screen distance between the polygon of `c`'s cells and the surface at the same
/// (u, v), over 5 x 5 samples of each cell's first triangle that lie in view; `seen` counts
/// them.
double worstInView(const NurbsSurface& s, const ScreenScale& scale, const PartitionChoice& c, int w,
                   int h, int& seen) {
    const auto pixel = [&](const glm::dvec3& p) {
        const glm::dvec4 q = scale.viewProjection * glm::dvec4(p, 1.0);
        return glm::dvec2((q.x / q.w * 0.5 + 0.5) * w, (q.y / q.w * 0.5 + 0.5) * h);
    };
    double worst = 0.0;
    seen = 0;
    for (size_t i = 0; i + 1 < c.breaksU.size(); ++i)
        for (size_t j = 0; j + 1 < c.breaksV.size(); ++j) {
            const double u0 = c.breaksU[i], u1 = c.breaksU[i + 1];
            const double v0 = c.breaksV[j], v1 = c.breaksV[j + 1];
            const glm::dvec3 ll = surfacePoint(s, u0, v0), lr = surfacePoint(s, u1, v0);
            const glm::dvec3 ur = surfacePoint(s, u1, v1);
            for (int a = 0; a <= 4; ++a)
                for (int b = 0; a + b <= 4; ++b) {
                    const double l1 = a / 4.0, l2 = b / 4.0, l0 = 1.0 - l1 - l2;
                    const double ua = l0 * u0 + (l1 + l2) * u1, va = (l0 + l1) * v0 + l2 * v1;
                    const glm::dvec3 pa = l0 * ll + l1 * lr + l2 * ur;
                    if (!inFrustum(scale, pa))
                        continue;
                    ++seen;
                    worst =
                        std::max(worst, glm::length(pixel(pa) - pixel(surfacePoint(s, ua, va))));
                }
        }
    return worst;
}

} // namespace

class TstNearEyeBound : public QObject {
    Q_OBJECT
private Q_SLOTS:
    // Boxes whose least depth in view is known: beside the frustum's side, around the eye,
    // wholly in view, wholly outside; and random boxes against a dense sampling.
    void depthInFrustumOfBoxes() {
        Camera cam; // at the origin looking down -z through 90 degrees: |x|, |y| <= depth
        cam.eye = {0.0, 0.0, 0.0};
        cam.target = {0.0, 0.0, -1.0};
        cam.up = {0.0, 1.0, 0.0};
        cam.fovYDegrees = 90.0;
        const ScreenScale scale = viewScale(cam, 100, 100, 0.01);
        const auto depthOf = [&](glm::dvec3 lo, glm::dvec3 hi) {
            return boxMinDepthInFrustum(scale, lo, hi);
        };
        // Beside the view at x in [5, 10], reaching from behind the eye to depth 20: what is
        // in view lies at depth 5 or more (x <= depth), though the box reaches depth -10.
        QCOMPARE(boxMinDepth(scale, {5, -1, -20}, {10, 1, 10}), -10.0);
        QVERIFY(std::abs(depthOf({5, -1, -20}, {10, 1, 10}) - 5.0) < 1e-9);
        // Around the eye: the near rectangle lies inside.
        QVERIFY(std::abs(depthOf({-1, -1, -1}, {1, 1, 1}) - 0.01) < 1e-12);
        // Beside the view and no deeper than 3: nothing of it in view.
        QCOMPARE(depthOf({5, -1, -3}, {10, 1, 3}), std::numeric_limits<double>::infinity());
        // Wholly behind the eye.
        QCOMPARE(depthOf({-1, -1, 1}, {1, 1, 2}), std::numeric_limits<double>::infinity());
        // Wholly in view: its own least depth.
        QVERIFY(std::abs(depthOf({-1, -1, -9}, {1, 1, -4}) - 4.0) < 1e-9);
        // Random boxes: never above a sampled point in view, and close to the least sampled.
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> at(-6.0, 6.0), size(0.1, 8.0);
        int inView = 0;
        for (int k = 0; k < 300; ++k) {
            const glm::dvec3 lo(at(rng), at(rng), at(rng));
            const glm::dvec3 hi = lo + glm::dvec3(size(rng), size(rng), size(rng));
            const double d = depthOf(lo, hi);
            double sampled = std::numeric_limits<double>::infinity();
            const int n = 24;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j)
                    for (int l = 0; l <= n; ++l) {
                        const glm::dvec3 p =
                            lo +
                            (hi - lo) * glm::dvec3(double(i) / n, double(j) / n, double(l) / n);
                        if (inFrustum(scale, p))
                            sampled = std::min(sampled, glm::dot(p - scale.eye, scale.forward));
                    }
            QVERIFY2(d <= sampled + 1e-9,
                     qPrintable(QString("box %1: %2 above sampled %3").arg(k).arg(d).arg(sampled)));
            if (sampled == std::numeric_limits<double>::infinity())
                continue;
            ++inView;
            // A sample lies within one grid step of the least point.
            const double step = glm::length(hi - lo) / n;
            QVERIFY2(sampled - d <= step,
                     qPrintable(QString("box %1: %2, sampled %3").arg(k).arg(d).arg(sampled)));
            QVERIFY(d >= boxMinDepth(scale, lo, hi) - 1e-9 && d >= scale.nearDepth - 1e-12);
        }
        QVERIFY(inView > 50);
    }

    // A long cylinder passing beside the eye and behind it, seen along its side from a
    // hundredth of its length away: its control bounds reach past the near plane, where a
    // bound from their least depth is no bound at all (the uniform cut falls back to
    // 256 x 256). What is in view lies far deeper: the tensor grid meets the tolerance there
    // within 256 x 256 cells, and the polygon's points on screen lie within it of the surface's.
    void surfaceBesideTheEyeMeetsTolerance() {
        const NurbsSurface s = makeCylinder({0.0, 0.0, -50.0}, 1.0, 100.0);
        Camera cam;
        cam.eye = {0.0, -1.3, 10.0};
        cam.target = {0.0, -1.0, 0.0};
        cam.up = {0.0, 0.0, 1.0};
        cam.fovYDegrees = 20.0;
        const int w = 400, h = 400;
        const ScreenScale scale = viewScale(cam, w, h, 1e-4);
        const std::vector<SpanBound> spans = surfaceSpanBounds(s, 4);
        const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
        const PartitionChoice t = chooseBreaks(spans, du, dv, scale, 0.5);
        const PartitionChoice u = choosePartitions(spans, du, dv, scale, 0.5);
        qDebug("beside the eye: breaks %d x %d (%.3f px, met %d), uniform %d x %d (%.3f px, met "
               "%d)",
               t.nu, t.nv, t.boundPixels, int(t.met), u.nu, u.nv, u.boundPixels, int(u.met));
        QVERIFY(t.met && t.boundPixels <= 0.5);
        QVERIFY(cells(t) < std::int64_t(kMaxPartitions) * kMaxPartitions);
        int seen = 0;
        const double worst = worstInView(s, scale, t, w, h, seen);
        qDebug("%d samples in view, worst %.3f px", seen, worst);
        QVERIFY(seen > 1000);
        QVERIFY2(worst <= 0.5, qPrintable(QString("measured %1 px").arg(worst)));
    }

    // The eye inside a bore, near its wall, looking along it: the coarse sub-rectangles'
    // control bounds hold the eye's surroundings in view (a bound of nothing), though the wall
    // stays 0.05 away. chooseCut bounds those spans again, finer: it meets the tolerance, and
    // the polygon's points in view lie within it of the surface's.
    void finerBoundsInsideABore() {
        const NurbsSurface s = makeCylinder({0.0, 0.0, -50.0}, 1.0, 100.0);
        Camera cam;
        cam.eye = {0.95, 0.1, 0.0};
        cam.target = {0.95, 0.1, -10.0};
        cam.up = {0.0, 1.0, 0.0};
        cam.fovYDegrees = 20.0;
        const int w = 400, h = 400;
        const ScreenScale scale = viewScale(cam, w, h, 1e-4);
        int count = 0;
        for (int ku = s.degreeU; ku < s.countU; ++ku)
            count += s.knotsU[size_t(ku)] < s.knotsU[size_t(ku + 1)];
        const std::vector<SpanBound> spans =
            surfaceSpanBounds(s, AdaptivePartitions::gridFor(count));
        const ParameterBox box{surfaceDomainU(s), surfaceDomainV(s)};
        const PartitionChoice coarse = chooseBreaks(spans, box.u, box.v, scale, 0.5);
        const PartitionChoice c = chooseCut(s, spans, box, scale, 0.5, 1, 1);
        qDebug("inside a bore: coarse bounds %d x %d (met %d), chosen %d x %d (%.3f px, met %d)",
               coarse.nu, coarse.nv, int(coarse.met), c.nu, c.nv, c.boundPixels, int(c.met));
        QVERIFY(!coarse.met);
        QVERIFY(c.met && c.boundPixels <= 0.5);
        int seen = 0;
        const double worst = worstInView(s, scale, c, w, h, seen);
        qDebug("%d samples in view, worst %.3f px", seen, worst);
        QVERIFY(seen > 1000);
        QVERIFY2(worst <= 0.5, qPrintable(QString("measured %1 px").arg(worst)));
    }
};

QTEST_APPLESS_MAIN(TstNearEyeBound)
#include "tst_near_eye_bound.moc"
