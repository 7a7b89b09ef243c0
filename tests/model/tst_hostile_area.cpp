// faceIntegrals on hostile trims: loops reaching past the (u, v) domain count only the part
// inside it, nested and crossing loops are taken even-odd whatever their orientation, and a
// curve that would make the adaptive quadrature run for minutes stops at the budget and says so.
#include "model/analysis/mass_properties.h"
#include "model/nurbs/nurbs_shapes.h"
#include "tests/support/model_fixtures.h"

#include <QTest>
#include <cmath>
#include <numbers>

using namespace kw;

namespace {

constexpr double kPi = std::numbers::pi;

Surface face(const NurbsSurface& g) {
    Surface s;
    s.id = SurfaceId{1};
    s.geometry = g;
    return s;
}

Surface unitPlane() {
    return face(makePlane(glm::dvec3(0.0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)));
}

/// A closed polygon loop through `p`.
TrimLoop polygon(const std::vector<glm::dvec2>& p, std::uint32_t id) {
    TrimLoop l;
    l.id = TrimLoopId{id};
    for (size_t k = 0; k < p.size(); ++k)
        l.curves.push_back(test::segment(p[k], p[(k + 1) % p.size()]));
    return l;
}

TrimLoop box(glm::dvec2 lo, glm::dvec2 hi, std::uint32_t id, bool ccw = true) {
    std::vector<glm::dvec2> p = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
    if (!ccw)
        std::reverse(p.begin(), p.end());
    return polygon(p, id);
}

QByteArray text(const FaceIntegrals& f) {
    return QStringLiteral("area %1, approximate %2, evaluations %3")
        .arg(f.area, 0, 'g', 17)
        .arg(f.approximate)
        .arg(f.evaluations)
        .toUtf8();
}

} // namespace

class TestHostileArea : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void loopsPastTheDomain();
    void loopAroundTheWholeDomain();
    void nestedLoopsOfOneOrientation();
    void crossingLoops();
    void selfCrossingLoop();
    void curvedFacePastTheDomain();
    void budgetStopsAndSays();
};

// A square [-0.5, 0.5]^2 on the unit plane keeps only its quarter inside the domain; the
// clamped density used to count the other three quarters too.
void TestHostileArea::loopsPastTheDomain() {
    for (bool ccw : {true, false}) {
        Surface p = unitPlane();
        p.trims.push_back(box({-0.5, -0.5}, {0.5, 0.5}, 1, ccw));
        const FaceIntegrals f = faceIntegrals(p);
        QVERIFY2(std::abs(f.area - 0.25) < 1e-12, text(f));
        QVERIFY(!f.approximate);
    }
    // Reaching past the right and top edges.
    Surface p = unitPlane();
    p.trims.push_back(box({0.75, 0.5}, {3.0, 9.0}, 1));
    const FaceIntegrals f = faceIntegrals(p);
    QVERIFY2(std::abs(f.area - 0.125) < 1e-12, text(f));
}

// A loop enclosing the whole domain keeps all of it, not more.
void TestHostileArea::loopAroundTheWholeDomain() {
    Surface p = unitPlane();
    p.trims.push_back(box({-2, -3}, {4, 5}, 1, false));
    const FaceIntegrals f = faceIntegrals(p);
    QVERIFY2(std::abs(f.area - 1.0) < 1e-12, text(f));
}

// Three nested squares, all counter-clockwise: even-odd keeps the outer ring and the core.
void TestHostileArea::nestedLoopsOfOneOrientation() {
    Surface p = unitPlane();
    p.trims.push_back(box({0.1, 0.1}, {0.9, 0.9}, 1));
    p.trims.push_back(box({0.3, 0.3}, {0.7, 0.7}, 2));
    p.trims.push_back(box({0.4, 0.4}, {0.6, 0.6}, 3));
    const FaceIntegrals f = faceIntegrals(p);
    QVERIFY2(std::abs(f.area - (0.64 - 0.16 + 0.04)) < 1e-12, text(f));
}

// Two overlapping squares: their union less their overlap, for either orientation of each.
void TestHostileArea::crossingLoops() {
    for (bool a : {true, false})
        for (bool b : {true, false}) {
            Surface p = unitPlane();
            p.trims.push_back(box({0.1, 0.1}, {0.6, 0.6}, 1, a));
            p.trims.push_back(box({0.4, 0.4}, {0.9, 0.9}, 2, b));
            const FaceIntegrals f = faceIntegrals(p);
            QVERIFY2(std::abs(f.area - (0.25 + 0.25 - 2 * 0.04)) < 1e-12, text(f));
        }
}

// A bow tie: its two triangles wind opposite ways (Green's theorem alone gives 0), even-odd
// keeps both.
void TestHostileArea::selfCrossingLoop() {
    Surface p = unitPlane();
    p.trims.push_back(polygon({{0.1, 0.1}, {0.9, 0.9}, {0.9, 0.1}, {0.1, 0.9}}, 1));
    const FaceIntegrals f = faceIntegrals(p);
    QVERIFY2(std::abs(f.area - 0.32) < 1e-12, text(f));
}

// On a cylinder (radius 2, height 3) a loop around the domain keeps the whole 12 pi, and a box
// reaching past three edges keeps what the same box cut at the edges keeps (a loop inside the
// domain, measured as a whole). A quarter disc about the plane's corner: pi / 16.
void TestHostileArea::curvedFacePastTheDomain() {
    Surface c = face(makeCylinder(glm::dvec3(0.0), 2.0, 3.0));
    const double full = faceIntegrals(c).area;
    QVERIFY(std::abs(full - 12 * kPi) < 1e-9 * full);
    c.trims.push_back(box({-1, -1}, {2, 2}, 1));
    FaceIntegrals f = faceIntegrals(c);
    QVERIFY2(std::abs(f.area - full) < 1e-10 * full, text(f));
    c.trims = {box({0.0, 0.0}, {0.3, 1.0}, 1)};
    const double inside = faceIntegrals(c).area;
    c.trims = {box({-1.0, -0.5}, {0.3, 4.0}, 1)};
    f = faceIntegrals(c);
    QVERIFY2(std::abs(f.area - inside) < 1e-10 * full, text(f));
    QVERIFY(inside > 0.2 * full && inside < 0.4 * full);

    Surface p = unitPlane();
    p.trims = {TrimLoop{TrimLoopId{1}, {makeCircle2({0.0, 0.0}, 0.5, false)}}};
    f = faceIntegrals(p);
    QVERIFY2(std::abs(f.area - kPi / 16.0) < 1e-12, text(f));
}

// A plane of 10,000 knot spans in v: every inner integral cuts at each knot, so an exact measure
// would take some ten million evaluations. It stops at the budget, says it is approximate, and
// (the density being constant) still gets the area. A sphere under a small budget likewise;
// under the default one it is exact.
void TestHostileArea::budgetStopsAndSays() {
    NurbsSurface g;
    g.degreeU = g.degreeV = 1;
    g.countU = 2;
    g.countV = 10001;
    g.knotsU = {0, 0, 1, 1};
    g.knotsV = {0};
    for (int k = 0; k < g.countV; ++k)
        g.knotsV.push_back(double(k) / (g.countV - 1));
    g.knotsV.push_back(1.0);
    for (int j = 0; j < g.countV; ++j)
        for (int i = 0; i < g.countU; ++i) {
            g.points.push_back({double(i), double(j) / (g.countV - 1), 0.0});
            g.weights.push_back(1.0);
        }
    Surface p = face(g);
    p.trims = {box({0.1, 0.1}, {0.9, 0.9}, 1)};
    FaceIntegrals f = faceIntegrals(p);
    QVERIFY2(f.approximate, text(f));
    QVERIFY2(f.evaluations <= kAreaEvaluationBudget + 100'000, text(f));
    QVERIFY2(std::abs(f.area - 0.64) < 1e-12, text(f));

    Surface sphere = face(makeSphere(glm::dvec3(0.0), 1.0));
    sphere.trims = {box({0.1, 0.1}, {0.9, 0.9}, 1)};
    f = faceIntegrals(sphere, glm::dvec3(0.0), 1e-11, 2000);
    QVERIFY2(f.approximate && f.evaluations <= 2000 + 100'000, text(f));
    const FaceIntegrals exact = faceIntegrals(sphere);
    QVERIFY2(!exact.approximate, text(exact));
    QVERIFY2(std::abs(f.area - exact.area) < 1e-3 * exact.area, text(f));
}

QTEST_GUILESS_MAIN(TestHostileArea)
#include "tst_hostile_area.moc"
