// CPU reference (render/reference_render.h) against analytic ray casting, and the edge metrics
// (render/edge_metrics.h) on hand-made frames. No GL: the reference is plain CPU code.
#include "model/nurbs/nurbs_shapes.h"
#include "model/nurbs/trim.h"
#include "render/edge_metrics.h"
#include "render/reference_render.h"
#include "render/render_types.h"

#include <QTest>

using namespace kw;

namespace {

Surface surfaceOf(const NurbsSurface& g, std::uint32_t id) {
    Surface s;
    s.id = SurfaceId{id};
    s.geometry = g;
    return s;
}

/// A frame w x h of background with the given pixels covered by surface 1 (normal +z, Z 1).
AovBuffer frameWith(int w, int h, const std::vector<glm::ivec2>& coveredPixels) {
    AovBuffer b;
    b.width = w;
    b.height = h;
    b.data.assign(size_t(w * h * AovBuffer::kChannels), 0.0f);
    for (int k = 0; k < w * h; ++k)
        b.data[size_t(k * AovBuffer::kChannels)] = -1.0f;
    for (const glm::ivec2& p : coveredPixels) {
        float* o = b.data.data() + size_t((p.y * w + p.x) * AovBuffer::kChannels);
        o[0] = 1.0f;
        o[8] = 1.0f;
        o[9] = 1.0f;
    }
    return b;
}

} // namespace

class TstReferenceRender : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphereMatchesAnalyticRays();
    void trimmedHoleShowsWhatIsBehind();
    void faceReachingBehindTheEyeIsClipped();
    void metricsOnHandMadeFrames();
};

void TstReferenceRender::sphereMatchesAnalyticRays() {
    const glm::dvec3 centre(0.2, -0.1, 0.3);
    const double radius = 1.0;
    Scene scene;
    scene.surfaces.push_back(surfaceOf(makeSphere(centre, radius), 1));
    Camera cam;
    cam.eye = {1.0, -4.0, 1.5};
    cam.target = centre;
    cam.authored = true;
    const int w = 240, h = 180;
    ReferenceStats stats;
    const AovBuffer ref = renderReference(scene, cam, w, h, {}, &stats);
    const CameraMatrices m = cameraMatrices(cam, scene, double(w) / h);
    const glm::dmat4 inv = glm::inverse(m.projection * m.view);
    const double focal = 0.5 * h / std::tan(glm::radians(cam.fovYDegrees) * 0.5);
    long long hits = 0, mismatches = 0;
    double worstPoint = 0.0, worstNormal = 0.0, worstDepth = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::dvec4 q =
                inv * glm::dvec4(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 0.0, 1.0);
            const glm::dvec3 d = glm::normalize(glm::dvec3(q) / q.w - m.eye);
            // |E + t d - c| = R: t = b - sqrt(b^2 - |E - c|^2 + R^2), b = d.(c - E).
            const double b = glm::dot(d, centre - m.eye);
            const double closest = glm::length(m.eye + b * d - centre);
            const bool hit = closest < radius;
            const float* p = ref.pixel(x, y);
            if (hit != (p[0] >= 0.0f)) {
                ++mismatches;
                // Screen distance of this pixel centre from the silhouette, to first order.
                const double tangentDepth = std::sqrt(glm::dot(centre - m.eye, centre - m.eye));
                const double px = std::abs(closest - radius) * focal / tangentDepth;
                QVERIFY2(px <= 0.25, qPrintable(QString("pixel (%1, %2) is %3 px from the "
                                                        "silhouette")
                                                    .arg(x)
                                                    .arg(y)
                                                    .arg(px)));
                continue;
            }
            if (!hit)
                continue;
            ++hits;
            // Within a quarter pixel of the silhouette the ray may miss the exact sphere while
            // the tessellation covers the centre (ReferenceOptions::pixelTolerance).
            const double silhouettePx =
                (radius - closest) * focal / std::sqrt(glm::dot(centre - m.eye, centre - m.eye));
            if (silhouettePx < 0.25)
                continue;
            const double t = b - std::sqrt(radius * radius - closest * closest);
            const glm::dvec3 exact = m.eye + t * d;
            const glm::dvec3 shown(p[3], p[4], p[5]);
            worstPoint = std::max(worstPoint, glm::length(shown - exact));
            const glm::dvec3 n(p[6], p[7], p[8]);
            worstNormal = std::max(worstNormal, glm::length(n - (exact - centre) / radius));
            worstDepth =
                std::max(worstDepth, std::abs(double(p[9]) - glm::dot(exact - m.eye, m.forward)));
        }
    qDebug("%lld hits, %lld coverage mismatches, %lld triangles, %lld Newton failures, %.0f ms; "
           "worst point %.2g, normal %.2g, depth %.2g",
           hits, mismatches, stats.triangles, stats.newtonFailures, stats.milliseconds, worstPoint,
           worstNormal, worstDepth);
    QVERIFY(hits > 5000);
    QVERIFY(mismatches < 20);
    // Float AOVs: single precision of values ~ 5 model units.
    QVERIFY(worstPoint < 2e-6);
    QVERIFY(worstNormal < 2e-6);
    QVERIFY(worstDepth < 2e-6);
    QVERIFY(stats.newtonFailures <= mismatches + 4);
}

void TstReferenceRender::trimmedHoleShowsWhatIsBehind() {
    // A plate at z = 0 with a circular hole, and a second plate behind it at z = -1.
    Scene scene;
    Surface front = surfaceOf(makePlane({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}), 1);
    TrimLoop hole;
    hole.id = TrimLoopId{1};
    hole.curves.push_back(makeCircle2({0.5, 0.5}, 0.25));
    TrimLoop outer;
    outer.id = TrimLoopId{2};
    outer.curves.push_back(makeCircle2({0.5, 0.5}, 0.49));
    front.trims = {outer, hole};
    scene.surfaces.push_back(front);
    scene.surfaces.push_back(surfaceOf(makePlane({-2, -2, -1}, {4, 0, 0}, {0, 4, 0}), 2));
    Camera cam;
    cam.eye = {0.0, 0.0, 5.0};
    cam.target = {0.0, 0.0, 0.0};
    cam.up = {0.0, 1.0, 0.0};
    cam.authored = true;
    const int w = 200, h = 200;
    const AovBuffer ref = renderReference(scene, cam, w, h);
    const TrimRegion region = makeTrimRegion(front.trims, 1e-6);
    long long front1 = 0, back2 = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = ref.pixel(x, y);
            QVERIFY(p[0] >= 0.0f); // the back plate fills the view
            if (p[0] == 1.0f) {
                ++front1;
                QVERIFY(trimRegionContains(region, {p[1], p[2]}) ||
                        trimRegionDistance(region, {p[1], p[2]}) < 0.01);
            } else {
                ++back2;
                QCOMPARE(p[5], -1.0f);
            }
        }
    QVERIFY(front1 > 1000);
    QVERIFY(back2 > 1000);
    // The hole's centre shows the back plate, the ring the front one.
    QCOMPARE(ref.pixel(w / 2, h / 2)[0], 2.0f);
}

void TstReferenceRender::faceReachingBehindTheEyeIsClipped() {
    // A close-up over a floor that extends behind the eye (one bilinear cell: a single pair of
    // triangles, each with corners behind the eye). Every pixel below the horizon shows the
    // floor at the depth of the ray's hit, as the GPU's clipped polygon does.
    Scene scene;
    scene.surfaces.push_back(surfaceOf(makePlane({-10, -10, 0}, {20, 0, 0}, {0, 20, 0}), 1));
    Camera cam;
    cam.eye = {0.0, -9.0, 0.5};
    cam.target = {0.0, -7.0, 0.0};
    cam.authored = true;
    const int w = 64, h = 48;
    const AovBuffer ref = renderReference(scene, cam, w, h);
    const CameraMatrices m = cameraMatrices(cam, scene, double(w) / h);
    const glm::dmat4 inv = glm::inverse(m.projection * m.view);
    long long floor = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::dvec4 q =
                inv * glm::dvec4(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 0.0, 1.0);
            const glm::dvec3 d = glm::normalize(glm::dvec3(q) / q.w - m.eye);
            if (!(d.z < -1e-3))
                continue; // at or above the horizon
            const double t = -m.eye.z / d.z;
            const glm::dvec3 hit = m.eye + t * d;
            if (std::abs(hit.x) > 9.9 || std::abs(hit.y) > 9.9)
                continue; // beyond the floor's far edge
            const float* p = ref.pixel(x, y);
            QCOMPARE(p[0], 1.0f);
            QVERIFY(std::abs(double(p[9]) - t * glm::dot(d, m.forward)) < 1e-6 * t);
            ++floor;
        }
    QVERIFY(floor > w * h / 3);
}

void TstReferenceRender::metricsOnHandMadeFrames() {
    // Reference: a 10 x 10 square of surface 1 in a 20 x 20 frame.
    std::vector<glm::ivec2> square;
    for (int y = 5; y < 15; ++y)
        for (int x = 5; x < 15; ++x)
            square.emplace_back(x, y);
    const AovBuffer reference = frameWith(20, 20, square);
    EdgeMetrics m;
    QVERIFY(compareWithReference(reference, reference, 0.0, m));
    QCOMPARE(m.silhouetteMismatched, 0LL);
    QCOMPARE(m.crackPixels, 0LL);
    QCOMPARE(m.idDisagreements, 0LL);
    QCOMPARE(m.normalMaxDegrees, 0.0);
    // The band: pixels with a differing 8-neighbour (the square's outer ring and the ring
    // around it), grown by one pixel; the square's inner 6 x 6 lies outside it.
    QCOMPARE(m.edgeBandPixels, 14LL * 14LL - 6LL * 6LL);
    QCOMPARE(m.normalPixels, 36LL);
    // A 2-pixel vertical gap (x = 9, 10) through the square is a crack; a 3-pixel one is not.
    std::vector<glm::ivec2> cracked, slotted;
    for (const glm::ivec2& p : square) {
        if (p.x != 9 && p.x != 10)
            cracked.push_back(p);
        if (p.x < 8 || p.x > 10)
            slotted.push_back(p);
    }
    QCOMPARE(crackPixels(frameWith(20, 20, cracked)), 20LL);
    QCOMPARE(crackPixels(frameWith(20, 20, slotted)), 0LL);
    QVERIFY(compareWithReference(frameWith(20, 20, cracked), reference, 0.0, m));
    QCOMPARE(m.crackPixels, 20LL);
    QCOMPARE(m.crackPixelsCoveredInReference, 20LL);
    QCOMPARE(m.idDisagreements, 12LL); // rows 7..12 of the gap lie outside the edge band
    // One extra pixel two pixels outside the square: silhouette error 2 px (to (14, y)).
    std::vector<glm::ivec2> bumped = square;
    bumped.emplace_back(16, 9);
    QVERIFY(compareWithReference(frameWith(20, 20, bumped), reference, 0.0, m));
    QCOMPARE(m.silhouetteMismatched, 1LL);
    QCOMPARE(m.silhouetteMaxPixels, 2.0);
    QCOMPARE(m.idDisagreements, 0LL); // (16, 9) lies in the edge band
    // Another surface at the square's centre: a disagreement, and at the same depth one of the
    // coincident ones (touching parts); nearer it is not.
    AovBuffer other = frameWith(20, 20, square);
    other.data[size_t((10 * 20 + 10) * AovBuffer::kChannels)] = 2.0f;
    QVERIFY(compareWithReference(other, reference, 1e-3, m));
    QCOMPARE(m.idDisagreements, 1LL);
    QCOMPARE(m.idCoincident, 1LL);
    other.data[size_t((10 * 20 + 10) * AovBuffer::kChannels) + 9] = 0.9f;
    QVERIFY(compareWithReference(other, reference, 1e-3, m));
    QCOMPARE(m.idDisagreements, 1LL);
    QCOMPARE(m.idCoincident, 0LL);
    // The normal at the centre tilted past edge-on, so that it faces the eye the other way
    // (the hidden sheet behind a fold): counted only with the eye given; tilted as far but
    // towards the eye it agrees.
    AovBuffer tilted = frameWith(20, 20, square);
    float* centre = tilted.data.data() + size_t((10 * 20 + 10) * AovBuffer::kChannels);
    centre[6] = 1.0f;
    centre[8] = -0.5f;
    const glm::dvec3 eye(0.3, 0.0, 1.0);
    QVERIFY(compareWithReference(tilted, reference, 1e-3, m, 0.0, &eye));
    QCOMPARE(m.facingDisagreements, 1LL);
    QVERIFY(compareWithReference(tilted, reference, 1e-3, m));
    QCOMPARE(m.facingDisagreements, 0LL);
    centre[8] = 1.0f;
    QVERIFY(compareWithReference(tilted, reference, 1e-3, m, 0.0, &eye));
    QCOMPARE(m.facingDisagreements, 0LL);
    // The square's right half 1 deeper: the same surface over itself (a torus's rim over its
    // far side). With the pixel's angle known that jump is an edge, and the band grows by the
    // two columns on either side of it (rows 4..15, clipped to the old band's inside).
    AovBuffer stepped = frameWith(20, 20, square);
    for (const glm::ivec2& p : square)
        if (p.x >= 10)
            stepped.data[size_t((p.y * 20 + p.x) * AovBuffer::kChannels) + 9] = 2.0f;
    QVERIFY(compareWithReference(stepped, stepped, 0.0, m));
    QCOMPARE(m.edgeBandPixels, 14LL * 14LL - 6LL * 6LL);
    QVERIFY(compareWithReference(stepped, stepped, 0.0, m, 0.01));
    QCOMPARE(m.edgeBandPixels, 14LL * 14LL - 6LL * 6LL + 4LL * 6LL);
    // Sizes must agree.
    const Status sizes =
        compareWithReference(frameWith(20, 20, square), frameWith(10, 20, {}), 0.0, m);
    QVERIFY(!sizes);
    QVERIFY(sizes.message().contains(QLatin1String("20x20")));
}

QTEST_GUILESS_MAIN(TstReferenceRender)
#include "tst_reference_render.moc"
