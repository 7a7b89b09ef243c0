// Kernel curvature tests: analytic sphere, cylinder and torus to 1e-10; fundamental forms and
// principal curvatures of random surfaces of every degree against finite differences of the
// normal; never NaN at collapsed edges.
#include "kernel_test_util.h"
#include "model/nurbs/nurbs_curvature.h"
#include "model/nurbs/nurbs_shapes.h"

#include <QTest>

using namespace kw;

namespace {

constexpr double kTol = 1e-10;
/// At a collapsed edge the values are those a step of 1e-4 of the domain inside; there the
/// normal part of Suu is O(step^2) against rounding of O(1) terms: 1e-8 relative.
constexpr double kCollapsedTol = 1e-7;

/// |a - b| <= tol * scale, with a message naming the quantity and the sample.
bool near(double a, double b, double scale, const char* what, double u, double v, QString& why,
          double tol = kTol) {
    if (std::abs(a - b) <= tol * scale)
        return true;
    why = QString("%1 at (u, v) = (%2, %3): %4, expected %5 (error %6)")
              .arg(what)
              .arg(u)
              .arg(v)
              .arg(a, 0, 'g', 17)
              .arg(b, 0, 'g', 17)
              .arg(std::abs(a - b));
    return false;
}

/// Common checks: k1 >= k2, K = k1 k2, H = (k1 + k2) / 2, orthonormal tangent directions.
bool consistent(const SurfaceCurvature& c, double scale, QString& why) {
    if (!(c.k1 >= c.k2)) {
        why = QString("k1 %1 < k2 %2").arg(c.k1).arg(c.k2);
        return false;
    }
    const double d[] = {c.k1 * c.k2 - c.gaussian,  0.5 * (c.k1 + c.k2) - c.mean,
                        glm::length(c.dir1) - 1.0, glm::length(c.dir2) - 1.0,
                        glm::dot(c.dir1, c.dir2),  glm::dot(c.dir1, c.normal),
                        glm::dot(c.dir2, c.normal)};
    for (double x : d)
        if (!(std::abs(x) <= 1e-9 * std::max(1.0, scale))) {
            why = QString("inconsistent curvature record (residual %1)").arg(x);
            return false;
        }
    return true;
}

} // namespace

class TestNurbsCurvature : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphere();
    void cylinder();
    void torus();
    void againstNormalDifferences_data();
    void againstNormalDifferences();
    void collapsedEdgesAreFinite();
    void invalidSurfaceGivesZero();
};

void TestNurbsCurvature::sphere() {
    for (double r : {0.25, 1.0, 7.5}) {
        const NurbsSurface s = makeSphere(glm::dvec3(1.0, -2.0, 0.5), r);
        for (int i = 0; i <= 16; ++i) {
            for (int j = 0; j <= 16; ++j) { // j = 0 and 16 are the poles
                const double u = i / 16.0, v = j / 16.0;
                const SurfaceCurvature c = surfaceCurvature(s, u, v);
                QString why;
                const double k = 1.0 / r;
                const double tol = (j == 0 || j == 16) ? kCollapsedTol : kTol;
                QVERIFY2(near(c.gaussian, k * k, k * k, "K", u, v, why, tol), qPrintable(why));
                QVERIFY2(near(c.mean, k, k, "H", u, v, why, tol), qPrintable(why));
                QVERIFY2(near(c.k1, k, k, "k1", u, v, why, tol), qPrintable(why));
                QVERIFY2(near(c.k2, k, k, "k2", u, v, why, tol), qPrintable(why));
                QVERIFY2(consistent(c, k * k, why), qPrintable(why));
                QCOMPARE(c.regular, j != 0 && j != 16);
            }
        }
    }
}

void TestNurbsCurvature::cylinder() {
    for (double r : {0.5, 3.0}) {
        const NurbsSurface s = makeCylinder(glm::dvec3(0.0, 1.0, -1.0), r, 2.5);
        for (int i = 0; i <= 16; ++i) {
            for (int j = 0; j <= 4; ++j) {
                const double u = i / 16.0, v = j / 4.0;
                const SurfaceCurvature c = surfaceCurvature(s, u, v);
                QString why;
                const double k = 1.0 / r;
                QVERIFY2(near(c.gaussian, 0.0, k * k, "K", u, v, why), qPrintable(why));
                QVERIFY2(near(c.mean, 0.5 * k, k, "H", u, v, why), qPrintable(why));
                QVERIFY2(near(c.k1, k, k, "k1", u, v, why), qPrintable(why));
                QVERIFY2(near(c.k2, 0.0, k, "k2", u, v, why), qPrintable(why));
                QVERIFY2(consistent(c, k * k, why), qPrintable(why));
                // k1 runs around the axis, k2 along it.
                QVERIFY2(std::abs(c.dir1.z) < kTol, qPrintable(QString("dir1.z %1").arg(c.dir1.z)));
                QVERIFY(std::abs(std::abs(c.dir2.z) - 1.0) < kTol);
            }
        }
    }
}

void TestNurbsCurvature::torus() {
    const double R = 3.0, r = 1.0;
    const glm::dvec3 centre(0.5, 0.25, -2.0);
    const NurbsSurface s = makeTorus(centre, R, r);
    for (int i = 0; i <= 12; ++i) {
        for (int j = 0; j <= 24; ++j) {
            const double u = i / 12.0, v = j / 24.0;
            const SurfaceCurvature c = surfaceCurvature(s, u, v);
            // The tube angle from the point itself (the rational parameterisation is not
            // uniform in angle): cos v = (distance from the axis - R) / r.
            const glm::dvec3 p = c.point - centre;
            const double cosv = (std::hypot(p.x, p.y) - R) / r;
            const double kTube = 1.0 / r;               // along the meridian
            const double kRing = cosv / (R + r * cosv); // along the parallel
            QString why;
            QVERIFY2(near(c.gaussian, cosv / (r * (R + r * cosv)), 1.0, "K", u, v, why),
                     qPrintable(why));
            QVERIFY2(near(c.mean, 0.5 * (kTube + kRing), 1.0, "H", u, v, why), qPrintable(why));
            QVERIFY2(near(c.k1, std::max(kTube, kRing), 1.0, "k1", u, v, why), qPrintable(why));
            QVERIFY2(near(c.k2, std::min(kTube, kRing), 1.0, "k2", u, v, why), qPrintable(why));
            QVERIFY2(consistent(c, 1.0, why), qPrintable(why));
            // k1 = 1/r is the meridian curvature (kRing < 1/r everywhere): dir1 lies in the
            // plane through the axis, so it has no component along the parallel.
            const glm::dvec3 parallel = glm::normalize(glm::dvec3(-p.y, p.x, 0.0));
            QVERIFY2(std::abs(glm::dot(c.dir1, parallel)) < 1e-9,
                     qPrintable(QString("dir1 . parallel = %1").arg(glm::dot(c.dir1, parallel))));
        }
    }
}

void TestNurbsCurvature::againstNormalDifferences_data() {
    QTest::addColumn<int>("degreeU");
    QTest::addColumn<int>("degreeV");
    QTest::addColumn<bool>("rational");
    for (int p = 1; p <= kMaxDegree; ++p) {
        QTest::addRow("p%d x %d rational", p, p) << p << p << true;
        QTest::addRow("p%d x %d polynomial", p, std::max(1, p - 1))
            << p << std::max(1, p - 1) << false;
    }
}

// Independent of the second derivatives: since n . Su = 0, L = Suu . n = -Su . n_u,
// M = -Su . n_v = -Sv . n_u and N = -Sv . n_v, with n_u, n_v central differences of the unit
// normal of surfaceFrame (first derivatives only).
void TestNurbsCurvature::againstNormalDifferences() {
    QFETCH(int, degreeU);
    QFETCH(int, degreeV);
    QFETCH(bool, rational);
    std::mt19937 rng(777u + unsigned(degreeU * 17 + degreeV) + (rational ? 500u : 0u));
    int checked = 0;
    for (int trial = 0; trial < 30; ++trial) {
        const NurbsSurface s =
            kwtest::randomSurface(rng, degreeU, degreeV, degreeU + 1 + int(rng() % 4),
                                  degreeV + 1 + int(rng() % 4), rational);
        double wu = 0.0, wv = 0.0;
        const double u = kwtest::randomInSpan(rng, s.knotsU, degreeU, 0.1, wu);
        const double v = kwtest::randomInSpan(rng, s.knotsV, degreeV, 0.1, wv);
        const SurfaceCurvature c = surfaceCurvature(s, u, v);
        const SurfaceFrame f = surfaceFrame(s, u, v);
        // Skip nearly singular samples (random nets can fold): FD conditioning is poor there.
        const double sinAngle =
            glm::length(glm::cross(f.du, f.dv)) / (glm::length(f.du) * glm::length(f.dv));
        if (!(sinAngle > 0.05))
            continue;
        QVERIFY(c.regular);
        const double hu = 1e-5 * wu, hv = 1e-5 * wv;
        const glm::dvec3 nu =
            (surfaceFrame(s, u + hu, v).normal - surfaceFrame(s, u - hu, v).normal) / (2 * hu);
        const glm::dvec3 nv =
            (surfaceFrame(s, u, v + hv).normal - surfaceFrame(s, u, v - hv).normal) / (2 * hv);
        const double L = -glm::dot(f.du, nu), N = -glm::dot(f.dv, nv);
        const double M = -0.5 * (glm::dot(f.du, nv) + glm::dot(f.dv, nu));
        const double scale = glm::length(f.du) * glm::length(nu) +
                             glm::length(f.dv) * glm::length(nv) +
                             glm::length(f.du) * glm::length(nv) + 1e-3;
        QVERIFY2(std::abs(c.L - L) <= 1e-5 * scale,
                 qPrintable(QString("L %1 vs fd %2").arg(c.L).arg(L)));
        QVERIFY2(std::abs(c.M - M) <= 1e-5 * scale,
                 qPrintable(QString("M %1 vs fd %2").arg(c.M).arg(M)));
        QVERIFY2(std::abs(c.N - N) <= 1e-5 * scale,
                 qPrintable(QString("N %1 vs fd %2").arg(c.N).arg(N)));
        QCOMPARE(c.E, glm::dot(f.du, f.du));
        QCOMPARE(c.G, glm::dot(f.dv, f.dv));
        // Principal curvatures are the extreme normal curvatures: sample k(t) = -II/I along
        // tangents of angle t and compare the extremes.
        double kmax = -1e300, kmin = 1e300;
        for (int a = 0; a < 720; ++a) {
            const double t = a * M_PI / 720.0;
            const double x = std::cos(t), y = std::sin(t);
            const double I = c.E * x * x + 2 * c.F * x * y + c.G * y * y;
            const double II = c.L * x * x + 2 * c.M * x * y + c.N * y * y;
            kmax = std::max(kmax, -II / I);
            kmin = std::min(kmin, -II / I);
        }
        const double ks = std::abs(c.k1) + std::abs(c.k2) + 1e-9;
        QVERIFY2(c.k1 >= kmax - 1e-9 * ks,
                 qPrintable(QString("k1 %1 vs sampled max %2").arg(c.k1).arg(kmax)));
        QVERIFY2(c.k2 <= kmin + 1e-9 * ks,
                 qPrintable(QString("k2 %1 vs sampled min %2").arg(c.k2).arg(kmin)));
        QString why;
        QVERIFY2(consistent(c, ks * ks, why), qPrintable(why));
        // The normal curvature along dir1 is k1 and along dir2 is k2: with the sampled bounds
        // above, k1 and k2 are the extremes.
        for (int which = 0; which < 2; ++which) {
            const glm::dvec3 t = which == 0 ? c.dir1 : c.dir2;
            // Solve t = a Su + b Sv in the tangent plane (2x2 normal equations).
            const double r1 = glm::dot(t, f.du), r2 = glm::dot(t, f.dv);
            const double det = c.E * c.G - c.F * c.F;
            const double a = (c.G * r1 - c.F * r2) / det, b = (c.E * r2 - c.F * r1) / det;
            const double kn = -(c.L * a * a + 2 * c.M * a * b + c.N * b * b) /
                              (c.E * a * a + 2 * c.F * a * b + c.G * b * b);
            const double expected = which == 0 ? c.k1 : c.k2;
            QVERIFY2(std::abs(kn - expected) <= 1e-7 * ks,
                     qPrintable(QString("normal curvature along dir%1 %2, expected %3")
                                    .arg(which + 1)
                                    .arg(kn)
                                    .arg(expected)));
        }
        ++checked;
    }
    QVERIFY2(checked >= 10, qPrintable(QString("only %1 well-conditioned samples").arg(checked)));
}

void TestNurbsCurvature::collapsedEdgesAreFinite() {
    // The teapot-lid style collapse: a degree 3 x 2 patch whose whole v = 0 row is one point,
    // and a surface with a fully collapsed span (every control point equal).
    std::mt19937 rng(31);
    NurbsSurface s = kwtest::randomSurface(rng, 3, 2, 5, 4, true);
    for (int i = 0; i < s.countU; ++i)
        s.points[size_t(s.index(i, 0))] = glm::dvec3(0.2, 0.3, 0.4);
    NurbsSurface flat = s;
    for (glm::dvec3& p : flat.points)
        p = glm::dvec3(1.0, 2.0, 3.0);
    const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
    for (const NurbsSurface* x : {&s, &flat}) {
        for (int i = 0; i <= 8; ++i) {
            for (int j = 0; j <= 8; ++j) {
                const double u = du.first + (du.last - du.first) * i / 8.0;
                const double v = dv.first + (dv.last - dv.first) * j / 8.0;
                const SurfaceCurvature c = surfaceCurvature(*x, u, v);
                const double all[] = {c.gaussian, c.mean, c.k1, c.k2, c.E,      c.F,
                                      c.G,        c.L,    c.M,  c.N,  c.dir1.x, c.dir2.y};
                for (double a : all)
                    QVERIFY(std::isfinite(a));
                QVERIFY(c.k1 >= c.k2);
                QVERIFY(std::abs(glm::length(c.dir1) - 1.0) < 1e-12);
                QVERIFY(std::abs(glm::dot(c.dir1, c.normal)) < 1e-9);
                if (x == &flat)
                    QCOMPARE(c.gaussian, 0.0);
                // Point and normal are exactly surfaceFrame's (every step of its rule occurs
                // here: regular, collapsed row, all points equal).
                const SurfaceFrame f = surfaceFrame(*x, u, v);
                QCOMPARE(c.point, f.point);
                QCOMPARE(c.normal, f.normal);
            }
        }
    }
    // At the collapsed row the values are those of the interior step point.
    const SurfaceCurvature edge = surfaceCurvature(s, 0.5 * (du.first + du.last), dv.first);
    QVERIFY(!edge.regular);
    const SurfaceCurvature inside =
        surfaceCurvature(s, 0.5 * (du.first + du.last), dv.first + 1e-4 * (dv.last - dv.first));
    QCOMPARE(edge.gaussian, inside.gaussian);
    QCOMPARE(edge.mean, inside.mean);
}

void TestNurbsCurvature::invalidSurfaceGivesZero() {
    const SurfaceCurvature c = surfaceCurvature(NurbsSurface{}, 0.5, 0.5);
    QCOMPARE(c.gaussian, 0.0);
    QCOMPARE(c.mean, 0.0);
    QCOMPARE(c.normal, glm::dvec3(0.0, 0.0, 1.0));
}

QTEST_APPLESS_MAIN(TestNurbsCurvature)
#include "tst_nurbs_curvature.moc"
