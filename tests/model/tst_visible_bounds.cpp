// Model tests: the trims' parameter box, the bounds of the exact trimmed geometry and the
// camera fitCamera builds from them (a face on a much larger control net fills the view).
#include "model/nurbs/nurbs_shapes.h"
#include "model/nurbs/visible_bounds.h"

#include <QTest>
#include <glm/gtc/matrix_transform.hpp>

using namespace kw;

namespace {

/// A 20 x 20 plane at z = 0 around the origin, trimmed to a disc of radius 20 r at its centre.
Surface smallFaceOnBigNet(double r) {
    Surface s;
    s.id = SurfaceId{1};
    s.geometry = makePlane({-10, -10, 0}, {20, 0, 0}, {0, 20, 0});
    TrimLoop loop;
    loop.id = TrimLoopId{1};
    loop.curves.push_back(makeCircle2({0.5, 0.5}, r));
    s.trims.push_back(loop);
    return s;
}

} // namespace

class TstVisibleBounds : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void parameterBoxFollowsTheTrims() {
        const Surface s = smallFaceOnBigNet(0.02);
        const ParameterBox box = trimParameterBox(s);
        // The circle's control polygon is its bounding square.
        QVERIFY(std::abs(box.u.first - 0.48) < 1e-12 && std::abs(box.u.last - 0.52) < 1e-12);
        QVERIFY(std::abs(box.v.first - 0.48) < 1e-12 && std::abs(box.v.last - 0.52) < 1e-12);
        Surface plain = s;
        plain.trims.clear();
        QCOMPARE(trimParameterBox(plain), (ParameterBox{{0, 1}, {0, 1}}));
        // Loops outside the domain keep nothing of it: the whole domain, not an empty box.
        Surface outside = smallFaceOnBigNet(0.1);
        outside.trims[0].curves[0] = makeCircle2({3.0, 3.0}, 0.1);
        QCOMPARE(trimParameterBox(outside), (ParameterBox{{0, 1}, {0, 1}}));
    }

    void boundsAreTheTrimmedGeometry() {
        glm::dvec3 lo, hi;
        QVERIFY(surfaceVisibleBounds(smallFaceOnBigNet(0.02), lo, hi));
        QVERIFY(glm::length(lo - glm::dvec3(-0.4, -0.4, 0.0)) < 1e-3);
        QVERIFY(glm::length(hi - glm::dvec3(0.4, 0.4, 0.0)) < 1e-3);
        // Untrimmed: the surface itself, inside its control bounds.
        Surface ball;
        ball.id = SurfaceId{2};
        ball.geometry = makeTorus({1, 2, 3}, 2.0, 0.5);
        QVERIFY(surfaceVisibleBounds(ball, lo, hi));
        QVERIFY(glm::length(lo - glm::dvec3(-1.5, -0.5, 2.5)) < 1e-9);
        QVERIFY(glm::length(hi - glm::dvec3(3.5, 4.5, 3.5)) < 1e-9);
    }

    void cacheFollowsTheContent() {
        Scene scene;
        scene.surfaces.push_back(smallFaceOnBigNet(0.02));
        glm::dvec3 lo, hi;
        QVERIFY(sceneVisibleBounds(scene, lo, hi));
        QVERIFY(std::abs(hi.x - 0.4) < 1e-3);
        scene.surfaces[0].trims[0].curves[0] = makeCircle2({0.5, 0.5}, 0.1);
        QVERIFY(sceneVisibleBounds(scene, lo, hi));
        QVERIFY(std::abs(hi.x - 2.0) < 1e-3);
        scene.surfaces[0].geometry.points[3].z = 1.0; // a corner rises: the disc tilts
        QVERIFY(sceneVisibleBounds(scene, lo, hi));
        QVERIFY(hi.z > 0.01);
    }

    void fitFramesASmallFaceOnABigNet() {
        Scene scene;
        scene.surfaces.push_back(smallFaceOnBigNet(0.02));
        const double aspect = 4.0 / 3.0;
        const Camera cam = fitCamera(scene, aspect);
        const glm::dmat4 vp =
            glm::perspective(glm::radians(cam.fovYDegrees), aspect, 0.01, 1000.0) *
            glm::lookAt(cam.eye, cam.target, cam.up);
        glm::dvec2 lo(1e9), hi(-1e9);
        for (int k = 0; k < 64; ++k) {
            const double a = 2.0 * 3.14159265358979 * k / 64;
            const glm::dvec4 c = vp * glm::dvec4(0.4 * std::cos(a), 0.4 * std::sin(a), 0.0, 1.0);
            const glm::dvec2 ndc = glm::dvec2(c) / c.w;
            lo = glm::min(lo, ndc);
            hi = glm::max(hi, ndc);
        }
        // NDC spans [-1, 1]: the face's screen box covers over a quarter of the frame and lies
        // inside it.
        const double covered = (hi.x - lo.x) * (hi.y - lo.y) / 4.0;
        qDebug("the face's screen box covers %.0f%% of the frame", 100.0 * covered);
        QVERIFY(covered >= 0.25);
        QVERIFY(lo.x >= -1.0 && lo.y >= -1.0 && hi.x <= 1.0 && hi.y <= 1.0);
    }

    // render --zoom F@X,Y: the point shown at image fractions (X, Y) becomes the centre, seen
    // from the same eye with an F times narrower field of view.
    void zoomCentresThePointAndMovesNearer() {
        Camera cam;
        cam.eye = {3.0, -4.0, 2.0};
        cam.target = {0.5, 0.25, -0.5};
        const double aspect = 16.0 / 9.0;
        const glm::dvec2 at(0.2, 0.7);
        const Camera z = zoomedCamera(cam, 8.0, at, aspect);
        const glm::dmat4 vp = glm::perspective(glm::radians(cam.fovYDegrees), aspect, 0.01, 100.0) *
                              glm::lookAt(cam.eye, cam.target, cam.up);
        const glm::dvec4 c = vp * glm::dvec4(z.target, 1.0);
        const glm::dvec2 ndc = glm::dvec2(c) / c.w;
        // NDC y points up, image fractions down.
        QVERIFY(std::abs(ndc.x - (2.0 * at.x - 1.0)) < 1e-12);
        QVERIFY(std::abs(ndc.y - (1.0 - 2.0 * at.y)) < 1e-12);
        QCOMPARE(z.eye, cam.eye);
        QVERIFY(std::abs(std::tan(glm::radians(z.fovYDegrees) * 0.5) * 8.0 -
                         std::tan(glm::radians(cam.fovYDegrees) * 0.5)) < 1e-12);
        // The centre with factor 1 is the camera itself.
        const Camera same = zoomedCamera(cam, 1.0, glm::dvec2(0.5), aspect);
        QVERIFY(glm::length(same.eye - cam.eye) < 1e-12 &&
                glm::length(same.target - cam.target) < 1e-12);
    }
};

QTEST_GUILESS_MAIN(TstVisibleBounds)
#include "tst_visible_bounds.moc"
