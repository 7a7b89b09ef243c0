// Kernel validation tests: every way a knot vector, surface or curve can be wrong, one row each.
#include "model/nurbs/nurbs.h"

#include <QTest>
#include <cmath>
#include <limits>

using namespace kw;

Q_DECLARE_METATYPE(std::vector<double>)
Q_DECLARE_METATYPE(kw::NurbsSurface)
Q_DECLARE_METATYPE(kw::NurbsCurve2)

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// A valid bicubic 4 x 4 surface with clamped uniform knots.
NurbsSurface validSurface() {
    NurbsSurface s;
    s.degreeU = s.degreeV = 3;
    s.countU = s.countV = 4;
    s.knotsU = s.knotsV = {0, 0, 0, 0, 1, 1, 1, 1};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            s.points.emplace_back(i, j, 0.1 * i * j);
    s.weights.assign(16, 1.0);
    return s;
}

NurbsCurve2 validCurve() {
    NurbsCurve2 c;
    c.degree = 2;
    c.knots = {0, 0, 0, 0.5, 1, 1, 1};
    c.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    c.weights = {1, 2, 1, 1};
    return c;
}

} // namespace

class TestNurbsValidate : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void knotVectors_data();
    void knotVectors();
    void surfaces_data();
    void surfaces();
    void curves_data();
    void curves();
};

void TestNurbsValidate::knotVectors_data() {
    QTest::addColumn<std::vector<double>>("knots");
    QTest::addColumn<int>("degree");
    QTest::addColumn<int>("count");
    QTest::addColumn<QString>("error"); // empty: valid

    using V = std::vector<double>;
    QTest::newRow("valid clamped") << V{0, 0, 0, 0, 1, 1, 1, 1} << 3 << 4 << "";
    QTest::newRow("valid unclamped") << V{0, 1, 2, 3, 4, 5, 6} << 2 << 4 << "";
    QTest::newRow("valid interior multiplicity degree+1")
        << V{0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1} << 2 << 6 << "";
    QTest::newRow("degree 0") << V{0, 1} << 0 << 1 << "degree 0 is below 1";
    QTest::newRow("degree negative") << V{0, 1} << -2 << 1 << "degree -2 is below 1";
    QTest::newRow("degree 16") << V(34, 0.0) << 16 << 17 << "degree 16 is above the maximum 15";
    QTest::newRow("too few points")
        << V{0, 0, 0, 1, 1, 1} << 3 << 2
        << "2 control points are too few for degree 3 (need at least degree + 1 = 4)";
    QTest::newRow("knot count") << V{0, 0, 0, 1, 1, 1, 1} << 3 << 4
                                << "knot vector has 7 knots, expected 8 (count 4 + degree 3 + 1)";
    QTest::newRow("decreasing") << V{0, 0, 0, 0, 0.5, 0.2, 1, 1, 1} << 3 << 5
                                << "knot 5 (0.2) is less than knot 4 (0.5)";
    QTest::newRow("multiplicity") << V{0, 0, 0, 0, 0.5, 0.5, 0.5, 0.5, 0.5, 1, 1, 1, 1} << 3 << 9
                                  << "knot 0.5 has multiplicity 5, above degree + 1 = 4";
    QTest::newRow("end multiplicity")
        << V{0, 0, 0, 0, 1, 1, 1} << 2 << 4 << "knot 0 has multiplicity 4, above degree + 1 = 3";
    QTest::newRow("nan knot") << V{0, 0, kNaN, 1, 1, 1} << 2 << 3 << "knot 2 (nan) is not finite";
    QTest::newRow("inf knot") << V{0, 0, 0, 1, 1, kInf} << 2 << 3 << "knot 5 (inf) is not finite";
    QTest::newRow("empty domain") << V{0, 1, 2, 2, 3, 4} << 2 << 3
                                  << "the domain [2, 2] (knots 2 and 3) is empty";
}

void TestNurbsValidate::knotVectors() {
    QFETCH(std::vector<double>, knots);
    QFETCH(int, degree);
    QFETCH(int, count);
    QFETCH(QString, error);
    QCOMPARE(checkKnotVector(knots, degree, count).message(), error);
}

void TestNurbsValidate::surfaces_data() {
    QTest::addColumn<NurbsSurface>("surface");
    QTest::addColumn<QString>("error");

    QTest::newRow("valid") << validSurface() << "";
    NurbsSurface s = validSurface();
    s.knotsU.pop_back();
    QTest::newRow("knot count U")
        << s << "knot vector U has 7 knots, expected 8 (count 4 + degree 3 + 1)";
    s = validSurface();
    s.degreeV = 0;
    QTest::newRow("degree V 0") << s << "V: degree 0 is below 1";
    s = validSurface();
    s.degreeU = 16;
    QTest::newRow("degree U 16") << s << "U: degree 16 is above the maximum 15";
    s = validSurface();
    s.knotsV[5] = 0.5;
    s.knotsV[4] = 0.7;
    QTest::newRow("decreasing V") << s << "V: knot 5 (0.5) is less than knot 4 (0.7)";
    s = validSurface();
    s.points.pop_back();
    QTest::newRow("point count")
        << s << "surface has 15 control points, expected 16 (countU 4 x countV 4)";
    s = validSurface();
    s.weights.push_back(1.0);
    QTest::newRow("weight count") << s
                                  << "surface has 17 weights, expected 16 (countU 4 x countV 4)";
    s = validSurface();
    s.weights[size_t(s.index(2, 3))] = -1.0;
    QTest::newRow("negative weight")
        << s << "weight of control point (2, 3) is -1, must be finite and > 0";
    s = validSurface();
    s.weights[size_t(s.index(1, 0))] = 0.0;
    QTest::newRow("zero weight") << s
                                 << "weight of control point (1, 0) is 0, must be finite and > 0";
    s = validSurface();
    s.weights[size_t(s.index(0, 2))] = kNaN;
    QTest::newRow("nan weight") << s
                                << "weight of control point (0, 2) is nan, must be finite and > 0";
    s = validSurface();
    s.points[size_t(s.index(3, 1))].y = kInf;
    QTest::newRow("inf coordinate")
        << s << "control point (3, 1) has a non-finite coordinate (3, inf, 0.30000000000000004)";
    s = validSurface();
    s.countU = 5;
    QTest::newRow("count U without knots")
        << s << "knot vector U has 8 knots, expected 9 (count 5 + degree 3 + 1)";
    QTest::newRow("default-constructed")
        << NurbsSurface{}
        << "U: 0 control points are too few for degree 1 (need at least degree + 1 = 2)";
}

void TestNurbsValidate::surfaces() {
    QFETCH(NurbsSurface, surface);
    QFETCH(QString, error);
    QCOMPARE(checkNurbsSurface(surface).message(), error);
    if (!error.isEmpty()) {
        // Evaluating an invalid surface must not crash and must not produce NaN normals.
        const SurfaceFrame f = surfaceFrame(surface, 0.5, 0.5);
        QVERIFY(std::isfinite(f.normal.x) && std::isfinite(f.normal.y) &&
                std::isfinite(f.normal.z));
    }
}

void TestNurbsValidate::curves_data() {
    QTest::addColumn<NurbsCurve2>("curve");
    QTest::addColumn<QString>("error");

    QTest::newRow("valid") << validCurve() << "";
    NurbsCurve2 c = validCurve();
    c.knots.push_back(1.0);
    QTest::newRow("knot count") << c
                                << "knot vector has 8 knots, expected 7 (count 4 + degree 2 + 1)";
    c = validCurve();
    c.weights.pop_back();
    QTest::newRow("weight count") << c << "curve has 3 weights, expected 4 (one per control point)";
    c = validCurve();
    c.weights[2] = -0.5;
    QTest::newRow("negative weight")
        << c << "weight of control point 2 is -0.5, must be finite and > 0";
    c = validCurve();
    c.points[1].x = kNaN;
    QTest::newRow("nan coordinate") << c << "control point 1 has a non-finite coordinate (nan, 0)";
    c = validCurve();
    c.degree = 0;
    QTest::newRow("degree 0") << c << "degree 0 is below 1";
    c = validCurve();
    c.knots[3] = -1.0;
    QTest::newRow("decreasing") << c << "knot 3 (-1) is less than knot 2 (0)";
}

void TestNurbsValidate::curves() {
    QFETCH(NurbsCurve2, curve);
    QFETCH(QString, error);
    QCOMPARE(checkNurbsCurve(curve).message(), error);
    bool finitePoints = true;
    for (const glm::dvec2& p : curve.points)
        finitePoints = finitePoints && std::isfinite(p.x) && std::isfinite(p.y);
    if (!error.isEmpty() && finitePoints) {
        // Structurally broken curves evaluate to finite values instead of crashing (non-finite
        // input coordinates are garbage in, garbage out: the contract requires a valid curve).
        const glm::dvec2 p = curvePoint(curve, 0.5);
        QVERIFY(std::isfinite(p.x) && std::isfinite(p.y));
    }
}

QTEST_APPLESS_MAIN(TestNurbsValidate)
#include "tst_nurbs_validate.moc"
