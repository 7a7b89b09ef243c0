// Kernel shape tests: exact sphere, cylinder, torus and circle; analytic normals, including the
// degenerate-normal rule at sphere poles, collapsed apexes and fully collapsed corners.
#include "kernel_test_util.h"
#include "model/nurbs/nurbs_shapes.h"

#include <QTest>
#include <functional>

using namespace kw;

namespace {

/// The same surface with u and v exchanged: the collapsed edges of a sphere then make Sv, not
/// Su, vanish, which exercises the other branch of the degenerate-normal rule.
NurbsSurface transposed(const NurbsSurface& s) {
    NurbsSurface t;
    t.degreeU = s.degreeV;
    t.degreeV = s.degreeU;
    t.countU = s.countV;
    t.countV = s.countU;
    t.knotsU = s.knotsV;
    t.knotsV = s.knotsU;
    for (int j = 0; j < t.countV; ++j)
        for (int i = 0; i < t.countU; ++i) {
            t.points.push_back(s.points[size_t(s.index(j, i))]);
            t.weights.push_back(s.weights[size_t(s.index(j, i))]);
        }
    return t;
}

/// Parameters on a grid including both domain ends, plus a few seeded random ones.
std::vector<double> samples(std::mt19937& rng) {
    std::vector<double> t;
    for (int k = 0; k <= 16; ++k)
        t.push_back(k / 16.0);
    for (int k = 0; k < 8; ++k)
        t.push_back(std::uniform_real_distribution<double>(0.0, 1.0)(rng));
    return t;
}

using Analytic = std::function<bool(const glm::dvec3& p, double& distance, glm::dvec3& normal)>;

/// Checks every sampled point lies on the analytic surface to 1e-12 * size and that the frame
/// normal equals the analytic outward normal (times `orientation`) to 1e-9.
void checkShape(const NurbsSurface& s, double size, const Analytic& analytic,
                double orientation = 1.0) {
    QVERIFY2(checkNurbsSurface(s).has_value(), qPrintable(checkNurbsSurface(s).message()));
    std::mt19937 rng(3);
    const std::vector<double> us = samples(rng), vs = samples(rng);
    for (double u : us) {
        for (double v : vs) {
            const SurfaceFrame f = surfaceFrame(s, u, v);
            double distance = 0.0;
            glm::dvec3 normal(0.0);
            QVERIFY(analytic(f.point, distance, normal));
            QVERIFY2(
                std::abs(distance) <= 1e-12 * size,
                qPrintable(QString("(%1, %2): off the surface by %3").arg(u).arg(v).arg(distance)));
            const double err = glm::length(f.normal - orientation * normal);
            QVERIFY2(err <= 1e-9, qPrintable(QString("(%1, %2): normal (%3, %4, %5), expected "
                                                     "(%6, %7, %8)")
                                                 .arg(u)
                                                 .arg(v)
                                                 .arg(f.normal.x)
                                                 .arg(f.normal.y)
                                                 .arg(f.normal.z)
                                                 .arg(orientation * normal.x)
                                                 .arg(orientation * normal.y)
                                                 .arg(orientation * normal.z)));
        }
    }
}

} // namespace

class TestNurbsShapes : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphere_data();
    void sphere();
    void spherePoles();
    void cylinder();
    void torus();
    void plane();
    void circle();
    void apexOfRevolvedParabola();
    void collapsedCornerFallsBack();
};

void TestNurbsShapes::sphere_data() {
    QTest::addColumn<glm::dvec3>("center");
    QTest::addColumn<double>("radius");
    QTest::addColumn<bool>("swapUV");
    QTest::newRow("unit at origin") << glm::dvec3(0.0) << 1.0 << false;
    // Tolerances are relative to the radius, so the centre stays on the same scale.
    QTest::newRow("small, offset") << glm::dvec3(3e-3, -2e-3, 7.5e-3) << 1e-3 << false;
    QTest::newRow("large, offset") << glm::dvec3(-100.0, 50.0, 20.0) << 250.0 << false;
    QTest::newRow("unit, u and v swapped") << glm::dvec3(0.5) << 2.0 << true;
}

void TestNurbsShapes::sphere() {
    QFETCH(glm::dvec3, center);
    QFETCH(double, radius);
    QFETCH(bool, swapUV);
    NurbsSurface s = makeSphere(center, radius);
    QCOMPARE(s.degreeU, 2);
    QCOMPARE(s.degreeV, 2);
    QCOMPARE(s.countU, 9);
    QCOMPARE(s.countV, 5);
    if (swapUV)
        s = transposed(s);
    checkShape(
        s, radius,
        [&](const glm::dvec3& p, double& d, glm::dvec3& n) {
            d = glm::length(p - center) - radius;
            n = (p - center) / glm::length(p - center);
            return true;
        },
        swapUV ? -1.0 : 1.0);
}

void TestNurbsShapes::spherePoles() {
    // Su vanishes along the whole v = 0 and v = 1 edges; the normal there is the limit normal.
    const glm::dvec3 c(1.0, 2.0, 3.0);
    const NurbsSurface s = makeSphere(c, 2.0);
    for (double u : {0.0, 0.1, 0.25, 0.6, 1.0}) {
        const SurfaceFrame south = surfaceFrame(s, u, 0.0);
        const SurfaceFrame north = surfaceFrame(s, u, 1.0);
        QVERIFY(glm::length(south.du) < 1e-12); // the edge really is collapsed
        QVERIFY(glm::length(south.point - (c - glm::dvec3(0, 0, 2))) < 1e-12);
        QVERIFY(glm::length(north.point - (c + glm::dvec3(0, 0, 2))) < 1e-12);
        QVERIFY(glm::length(south.normal - glm::dvec3(0, 0, -1)) < 1e-12);
        QVERIFY(glm::length(north.normal - glm::dvec3(0, 0, 1)) < 1e-12);
        // Continuity: approaching the pole from the interior converges to the pole normal.
        const SurfaceFrame near = surfaceFrame(s, u, 1e-6);
        QVERIFY(glm::length(near.normal - south.normal) < 1e-5);
    }
    // With u and v swapped, Sv vanishes instead and the other branch gives the same limit.
    const NurbsSurface t = transposed(s);
    QVERIFY(glm::length(surfaceFrame(t, 0.0, 0.3).normal - glm::dvec3(0, 0, 1)) < 1e-12);
    QVERIFY(glm::length(surfaceFrame(t, 1.0, 0.3).normal - glm::dvec3(0, 0, -1)) < 1e-12);
}

void TestNurbsShapes::cylinder() {
    const glm::dvec3 base(0.5, -1.0, 2.0);
    const double r = 3.0, h = 4.0;
    const NurbsSurface s = makeCylinder(base, r, h);
    QCOMPARE(s.degreeV, 1);
    checkShape(s, r, [&](const glm::dvec3& p, double& d, glm::dvec3& n) {
        const glm::dvec3 q = p - base;
        d = std::hypot(q.x, q.y) - r;
        n = glm::normalize(glm::dvec3(q.x, q.y, 0.0));
        return q.z >= -1e-12 && q.z <= h + 1e-12;
    });
    QVERIFY(glm::length(surfacePoint(s, 0.3, 1.0).z - (base.z + h)) < 1e-12);
}

void TestNurbsShapes::torus() {
    const glm::dvec3 c(-1.0, 0.0, 0.25);
    const double R = 2.0, r = 0.5;
    const NurbsSurface s = makeTorus(c, R, r);
    QCOMPARE(s.countU, 9);
    QCOMPARE(s.countV, 9);
    checkShape(s, r, [&](const glm::dvec3& p, double& d, glm::dvec3& n) {
        const glm::dvec3 q = p - c;
        const glm::dvec3 ring = R * glm::normalize(glm::dvec3(q.x, q.y, 0.0));
        d = glm::length(q - ring) - r;
        n = glm::normalize(q - ring);
        return true;
    });
}

void TestNurbsShapes::plane() {
    const glm::dvec3 o(1, 2, 3), eu(2, 0, 0), ev(0, 0, 3);
    const NurbsSurface s = makePlane(o, eu, ev);
    QVERIFY(checkNurbsSurface(s).has_value());
    const SurfaceFrame f = surfaceFrame(s, 0.25, 0.5);
    QVERIFY(glm::length(f.point - (o + 0.25 * eu + 0.5 * ev)) < 1e-15);
    QVERIFY(glm::length(f.du - eu) < 1e-15);
    QVERIFY(glm::length(f.normal - glm::dvec3(0, -1, 0)) < 1e-15);
    const NurbsSurface b = makeBilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1});
    QVERIFY(glm::length(surfacePoint(b, 0.5, 0.5) - glm::dvec3(0.5, 0.5, 0.25)) < 1e-15);
}

void TestNurbsShapes::circle() {
    const glm::dvec2 c(0.3, 0.7);
    const double r = 0.125;
    for (bool clockwise : {false, true}) {
        const NurbsCurve2 k = makeCircle2(c, r, clockwise);
        QVERIFY2(checkNurbsCurve(k).has_value(), qPrintable(checkNurbsCurve(k).message()));
        QCOMPARE(curveDomain(k), (Interval{0.0, 1.0}));
        QCOMPARE(k.points.front(), k.points.back()); // closed
        double signedArea = 0.0;
        glm::dvec2 prev = curvePoint(k, 0.0);
        for (int i = 1; i <= 400; ++i) {
            const double t = i / 400.0;
            const CurveDerivatives2 d = curveDerivatives(k, t);
            QVERIFY(std::abs(glm::length(d.point - c) - r) <= 1e-12 * r);
            // The tangent is perpendicular to the radius.
            QVERIFY(std::abs(glm::dot(d.d1, d.point - c)) <= 1e-12 * r * glm::length(d.d1));
            signedArea += 0.5 * (prev.x * d.point.y - prev.y * d.point.x);
            prev = d.point;
        }
        // The inscribed 400-gon's area is short of pi r^2 by about (2 pi / 400)^2 / 6 = 4e-5.
        QVERIFY(std::abs(std::abs(signedArea) - M_PI * r * r) < 1e-4 * M_PI * r * r);
        QCOMPARE(signedArea > 0.0, !clockwise);
    }
}

void TestNurbsShapes::apexOfRevolvedParabola() {
    // Revolving the parabola z = 1 - x^2 (a quadratic Bezier from the apex) collapses v = 0 to
    // the apex, like the teapot lid: Su = 0 there and the rule must give the smooth normal.
    NurbsCurve2 profile;
    profile.degree = 2;
    profile.knots = {0, 0, 0, 1, 1, 1};
    profile.points = {{0.0, 1.0}, {0.5, 1.0}, {1.0, 0.0}};
    profile.weights = {1, 1, 1};
    const NurbsSurface s = makeRevolution(glm::dvec3(0.0), profile);
    // Orientation: Su x Sv points down here (u around +z, v outward), so the apex normal is -z.
    for (double u : {0.0, 0.3, 0.5, 0.99}) {
        const SurfaceFrame f = surfaceFrame(s, u, 0.0);
        QVERIFY(glm::length(f.normal - glm::dvec3(0, 0, -1)) < 1e-12);
        const SurfaceFrame near = surfaceFrame(s, u, 1e-5);
        QVERIFY(glm::length(near.normal - f.normal) < 1e-4);
    }
}

void TestNurbsShapes::collapsedCornerFallsBack() {
    // S(u, v) = A + u v (B - A): Su and Sv both vanish at (0, 0), and nearby Su is parallel to
    // Sv, so every step of the rule fails and the documented last resort (0, 0, 1) is used.
    const glm::dvec3 a(1, 1, 1), b(2, 3, 4);
    const NurbsSurface s = makeBilinear(a, a, a, b);
    QCOMPARE(surfaceFrame(s, 0.0, 0.0).normal, glm::dvec3(0, 0, 1));
    // A surface collapsed to one point everywhere.
    const NurbsSurface dot = makeSphere(glm::dvec3(5.0), 0.0);
    QCOMPARE(surfaceFrame(dot, 0.4, 0.7).normal, glm::dvec3(0, 0, 1));
    // ... also where rounding leaves non-zero derivative noise (weights sqrt(2)/2, odd centre).
    const NurbsSurface dot2 = makeSphere(glm::dvec3(0.1, 0.3, 0.7), 0.0);
    for (double u : {0.1, 0.33, 0.9})
        QCOMPARE(surfaceFrame(dot2, u, 0.61).normal, glm::dvec3(0, 0, 1));
    // S = (u v, v, 0): the v = 0 edge collapses; Suv x Sv gives the interior's +z (step 2).
    const NurbsSurface tri = makeBilinear({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {1, 1, 0});
    QCOMPARE(surfaceFrame(tri, 0.0, 0.0).normal, glm::dvec3(0, 0, 1));
    QCOMPARE(surfaceFrame(tri, 0.7, 0.0).normal, glm::dvec3(0, 0, 1));
    // S = (v^2, u^2, 0) as a biquadratic Bezier patch: Su, Sv and Suv all vanish at (0, 0),
    // so step 2 fails and the normal of the nearby interior point, -z, is used (step 3).
    NurbsSurface q;
    q.degreeU = q.degreeV = 2;
    q.countU = q.countV = 3;
    q.knotsU = q.knotsV = {0, 0, 0, 1, 1, 1};
    const double sq[3] = {0.0, 0.0, 1.0}; // Bezier coefficients of t^2
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
            q.points.emplace_back(sq[j], sq[i], 0.0);
    q.weights.assign(9, 1.0);
    QVERIFY(glm::length(surfaceDerivatives(q, 0.0, 0.0).suv) == 0.0);
    QCOMPARE(surfaceFrame(q, 0.0, 0.0).normal, glm::dvec3(0, 0, -1));
    QCOMPARE(surfaceFrame(q, 0.5, 0.5).normal, glm::dvec3(0, 0, -1));
}

QTEST_APPLESS_MAIN(TestNurbsShapes)
#include "tst_nurbs_shapes.moc"
