// Kernel evaluation tests: rational surface and curve derivatives against central differences,
// domain clamping, and the polynomial special case against the de Boor-free tensor-product sum.
#include "kernel_test_util.h"

#include <QTest>

using namespace kw;

namespace {

/// |a - b| <= tol * (1 + |b| + typical), with the message naming what was compared.
bool close(const glm::dvec3& a, const glm::dvec3& b, double typical, double tol, QString& why,
           const char* what) {
    const double err = glm::length(a - b);
    if (err <= tol * (1.0 + glm::length(b) + typical))
        return true;
    why = QString("%1: analytic (%2, %3, %4) vs finite difference (%5, %6, %7), error %8")
              .arg(what)
              .arg(a.x)
              .arg(a.y)
              .arg(a.z)
              .arg(b.x)
              .arg(b.y)
              .arg(b.z)
              .arg(err);
    return false;
}

} // namespace

class TestNurbsEval : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void surfaceDerivatives_data();
    void surfaceDerivatives();
    void curveDerivatives_data();
    void curveDerivatives();
    void pointMatchesTensorSum();
    void parametersAreClamped();
    void controlBounds();
};

void TestNurbsEval::surfaceDerivatives_data() {
    QTest::addColumn<int>("degreeU");
    QTest::addColumn<int>("degreeV");
    QTest::addColumn<bool>("rational");
    for (int p = 1; p <= kMaxDegree; p += (p < 6 ? 1 : 3)) {
        QTest::addRow("p%d x %d rational", p, p) << p << p << true;
        QTest::addRow("p%d x 2 rational", p) << p << 2 << true;
        QTest::addRow("p%d x %d polynomial", p, p) << p << p << false;
    }
}

void TestNurbsEval::surfaceDerivatives() {
    QFETCH(int, degreeU);
    QFETCH(int, degreeV);
    QFETCH(bool, rational);
    std::mt19937 rng(4242u + unsigned(degreeU * 31 + degreeV) + (rational ? 1000u : 0u));
    for (int trial = 0; trial < 25; ++trial) {
        const NurbsSurface s = kwtest::randomSurface(
            rng, degreeU, degreeV, degreeU + 1 + int(rng() % 5), degreeV + 1 + int(rng() % 5),
            rational, std::max(1, std::min(degreeU, degreeV) - 1));
        QVERIFY2(checkNurbsSurface(s).has_value(), qPrintable(checkNurbsSurface(s).message()));
        double wu = 0.0, wv = 0.0;
        const double u = kwtest::randomInSpan(rng, s.knotsU, degreeU, 0.1, wu);
        const double v = kwtest::randomInSpan(rng, s.knotsV, degreeV, 0.1, wv);
        const double hu = 1e-4 * wu;
        const double hv = 1e-4 * wv;
        const SurfaceDerivatives d = kw::surfaceDerivatives(s, u, v);
        const SurfaceDerivatives um = kw::surfaceDerivatives(s, u - hu, v);
        const SurfaceDerivatives up = kw::surfaceDerivatives(s, u + hu, v);
        const SurfaceDerivatives vm = kw::surfaceDerivatives(s, u, v - hv);
        const SurfaceDerivatives vp = kw::surfaceDerivatives(s, u, v + hv);
        QCOMPARE(surfacePoint(s, u, v), d.s);
        const double first = glm::length(d.su) + glm::length(d.sv);
        const double second = glm::length(d.suu) + glm::length(d.suv) + glm::length(d.svv);
        const double tol = 1e-5;
        QString why;
        QVERIFY2(close(d.su, (up.s - um.s) / (2 * hu), first, tol, why, "Su"), qPrintable(why));
        QVERIFY2(close(d.sv, (vp.s - vm.s) / (2 * hv), first, tol, why, "Sv"), qPrintable(why));
        QVERIFY2(close(d.suu, (up.su - um.su) / (2 * hu), second, tol, why, "Suu"),
                 qPrintable(why));
        QVERIFY2(close(d.svv, (vp.sv - vm.sv) / (2 * hv), second, tol, why, "Svv"),
                 qPrintable(why));
        QVERIFY2(close(d.suv, (vp.su - vm.su) / (2 * hv), second, tol, why, "Suv (from Su)"),
                 qPrintable(why));
        QVERIFY2(close(d.suv, (up.sv - um.sv) / (2 * hu), second, tol, why, "Suv (from Sv)"),
                 qPrintable(why));
        // The frame reports the same point and first partials.
        const SurfaceFrame f = surfaceFrame(s, u, v);
        QCOMPARE(f.point, d.s);
        QCOMPARE(f.du, d.su);
        QCOMPARE(f.dv, d.sv);
        QVERIFY(std::abs(glm::length(f.normal) - 1.0) < 1e-12);
        const glm::dvec3 n = glm::cross(d.su, d.sv);
        if (glm::length(n) > 1e-6 * glm::length(d.su) * glm::length(d.sv))
            QVERIFY(glm::length(f.normal - glm::normalize(n)) < 1e-12);
    }
}

void TestNurbsEval::curveDerivatives_data() {
    QTest::addColumn<int>("degree");
    QTest::addColumn<bool>("rational");
    for (int p = 1; p <= kMaxDegree; ++p) {
        QTest::addRow("p%d rational", p) << p << true;
        QTest::addRow("p%d polynomial", p) << p << false;
    }
}

void TestNurbsEval::curveDerivatives() {
    QFETCH(int, degree);
    QFETCH(bool, rational);
    std::mt19937 rng(99u + unsigned(degree) + (rational ? 100u : 0u));
    for (int trial = 0; trial < 40; ++trial) {
        const NurbsCurve2 c = kwtest::randomCurve(rng, degree, degree + 1 + int(rng() % 6),
                                                  rational, std::max(1, degree - 1));
        QVERIFY2(checkNurbsCurve(c).has_value(), qPrintable(checkNurbsCurve(c).message()));
        double w = 0.0;
        const double t = kwtest::randomInSpan(rng, c.knots, degree, 0.1, w);
        const double h = 1e-4 * w;
        const CurveDerivatives2 d = kw::curveDerivatives(c, t);
        const CurveDerivatives2 m = kw::curveDerivatives(c, t - h);
        const CurveDerivatives2 p = kw::curveDerivatives(c, t + h);
        QCOMPARE(curvePoint(c, t), d.point);
        QString why;
        const glm::dvec3 d1(d.d1, 0.0), d2(d.d2, 0.0);
        QVERIFY2(close(d1, glm::dvec3((p.point - m.point) / (2 * h), 0.0), 0.0, 1e-5, why, "C'"),
                 qPrintable(why));
        QVERIFY2(
            close(d2, glm::dvec3((p.d1 - m.d1) / (2 * h), 0.0), glm::length(d1), 1e-5, why, "C''"),
            qPrintable(why));
    }
}

void TestNurbsEval::pointMatchesTensorSum() {
    // S(u, v) = sum N_i(u) N_j(v) w_ij P_ij / sum N_i(u) N_j(v) w_ij with every basis function
    // evaluated separately (Eq. 4.15), independent of the derivative machinery.
    std::mt19937 rng(5);
    for (int trial = 0; trial < 50; ++trial) {
        const int pu = 1 + int(rng() % 6), pv = 1 + int(rng() % 6);
        const NurbsSurface s = kwtest::randomSurface(rng, pu, pv, pu + 3, pv + 2, true, 2);
        const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
        const double u = std::uniform_real_distribution<double>(du.first, du.last)(rng);
        const double v = std::uniform_real_distribution<double>(dv.first, dv.last)(rng);
        const int su = findSpan(pu, s.knotsU, u), sv = findSpan(pv, s.knotsV, v);
        double nu[kMaxDegree + 1], nv[kMaxDegree + 1];
        basisFunctions(su, u, pu, s.knotsU, nu);
        basisFunctions(sv, v, pv, s.knotsV, nv);
        glm::dvec3 num(0.0);
        double den = 0.0;
        for (int j = 0; j <= pv; ++j) {
            for (int i = 0; i <= pu; ++i) {
                const size_t idx = size_t(s.index(su - pu + i, sv - pv + j));
                const double b = nu[i] * nv[j] * s.weights[idx];
                num += b * s.points[idx];
                den += b;
            }
        }
        QVERIFY(glm::length(surfacePoint(s, u, v) - num / den) < 1e-13);
    }
}

void TestNurbsEval::parametersAreClamped() {
    std::mt19937 rng(8);
    const NurbsSurface s = kwtest::randomSurface(rng, 3, 2, 6, 5, true, 1);
    const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
    QCOMPARE(surfacePoint(s, du.first - 10.0, dv.last + 3.0), surfacePoint(s, du.first, dv.last));
    QCOMPARE(surfacePoint(s, std::nan(""), std::nan("")), surfacePoint(s, du.first, dv.first));
    // Clamped knots interpolate the corner control points.
    QVERIFY(glm::length(surfacePoint(s, du.first, dv.first) - s.points[0]) < 1e-14);
    QVERIFY(glm::length(surfacePoint(s, du.last, dv.last) - s.points.back()) < 1e-14);
    const NurbsCurve2 c = kwtest::randomCurve(rng, 3, 7, true);
    const Interval d = curveDomain(c);
    QCOMPARE(curvePoint(c, d.last + 1.0), curvePoint(c, d.last));
    QVERIFY(glm::length(curvePoint(c, d.last) - c.points.back()) < 1e-14);
}

void TestNurbsEval::controlBounds() {
    std::mt19937 rng(12);
    const NurbsSurface s = kwtest::randomSurface(rng, 2, 3, 5, 6, true, 1);
    glm::dvec3 lo, hi;
    surfaceControlBounds(s, lo, hi);
    for (const glm::dvec3& p : s.points)
        QVERIFY(glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi)));
    // Convex hull property: sampled points lie inside the bounds.
    for (int k = 0; k <= 20; ++k) {
        const glm::dvec3 p = surfacePoint(s, k / 20.0 * 10.0 - 5.0, std::sin(k) * 5.0);
        QVERIFY(glm::all(glm::lessThanEqual(lo - 1e-12, p)) &&
                glm::all(glm::lessThanEqual(p, hi + 1e-12)));
    }
    surfaceControlBounds(NurbsSurface{}, lo, hi);
    QCOMPARE(lo, glm::dvec3(0.0));
    QCOMPARE(hi, glm::dvec3(0.0));
}

QTEST_APPLESS_MAIN(TestNurbsEval)
#include "tst_nurbs_eval.moc"
