// The continuity kernel (model/analysis/continuity.h) on cases whose answer is known: a sphere's
// seam, a loft cut at an inner knot, a crease of known angle, a boundary point moved by d, the
// recorded cube, and bad input (poles, collapsed and missing sides).
#include "model/analysis/continuity.h"
#include "model/nurbs/nurbs_construct.h"
#include "model/nurbs/nurbs_shapes.h"
#include "tests/support/expected_test_util.h"
#include "topology_fixtures.h"

#include <QTest>
#include <cmath>

using namespace kw;

namespace {

Scene sceneOf(const std::vector<NurbsSurface>& surfaces) {
    Scene scene;
    for (const NurbsSurface& g : surfaces) {
        Surface s;
        s.id = SurfaceId{scene.nextId++};
        s.name = QStringLiteral("Patch %1").arg(s.id.value);
        s.geometry = g;
        scene.surfaces.push_back(s);
    }
    return scene;
}

/// The two halves of `s` cut along v = t, an interior knot: the knot is inserted up to the
/// degree (A5.3), so both halves are exactly the pieces of the surface.
std::pair<NurbsSurface, NurbsSurface> splitV(const NurbsSurface& s, double t) {
    const int mult = int(std::count(s.knotsV.begin(), s.knotsV.end(), t));
    const NurbsSurface g = surfaceInsertKnotV(s, t, s.degreeV - mult);
    const int a = int(std::find(g.knotsV.begin(), g.knotsV.end(), t) - g.knotsV.begin());
    NurbsSurface lo = g, hi = g;
    lo.countV = a;
    lo.knotsV.assign(g.knotsV.begin(), g.knotsV.begin() + a);
    lo.knotsV.insert(lo.knotsV.end(), size_t(g.degreeV + 1), t);
    lo.points.assign(g.points.begin(), g.points.begin() + a * g.countU);
    lo.weights.assign(g.weights.begin(), g.weights.begin() + a * g.countU);
    hi.countV = g.countV - a + 1;
    hi.knotsV.assign(size_t(g.degreeV + 1), t);
    hi.knotsV.insert(hi.knotsV.end(), g.knotsV.begin() + a + g.degreeV, g.knotsV.end());
    hi.points.assign(g.points.begin() + (a - 1) * g.countU, g.points.end());
    hi.weights.assign(g.weights.begin() + (a - 1) * g.countU, g.weights.end());
    return {lo, hi};
}

/// The same surface with u running the other way: its normal points to the other side.
NurbsSurface reversedU(const NurbsSurface& s) {
    NurbsSurface r = s;
    const double sum = s.knotsU.front() + s.knotsU.back();
    for (size_t k = 0; k < s.knotsU.size(); ++k)
        r.knotsU[k] = sum - s.knotsU[s.knotsU.size() - 1 - k];
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            r.points[size_t(r.index(i, j))] = s.points[size_t(s.index(s.countU - 1 - i, j))];
            r.weights[size_t(r.index(i, j))] = s.weights[size_t(s.index(s.countU - 1 - i, j))];
        }
    return r;
}

/// A loft through five wavy sections, of degree maxDegreeV across them.
NurbsSurface wavyLoft(int maxDegreeV, std::vector<double>* parameters) {
    std::vector<NurbsCurve3> sections;
    for (int k = 0; k < 5; ++k) {
        std::vector<glm::dvec3> points;
        for (int i = 0; i < 5; ++i)
            points.push_back({double(i), 1.3 * k, std::sin(0.9 * k) + 0.2 * i * k});
        sections.push_back(*interpolateCurve3(points));
    }
    const Expected<NurbsSurface> s = makeLoft(sections, maxDegreeV, parameters);
    if (!s)
        qFatal("loft: %s", qPrintable(s.message()));
    return *s;
}

double interiorKnot(const std::vector<double>& knots, int degree) {
    const Interval d = knotDomain(knots, degree);
    for (double k : knots)
        if (k > d.first && k < d.last)
            return k;
    return -1.0;
}

const EdgeContinuity* edgeBetween(const ContinuityReport& r, SurfaceId a, SurfaceId b) {
    for (const EdgeContinuity& e : r.edges)
        if ((e.edge.sides[0].surface == a && e.edge.sides[1].surface == b) ||
            (e.edge.sides[0].surface == b && e.edge.sides[1].surface == a))
            return &e;
    return nullptr;
}

/// Two flat patches meeting along x = 1 at dihedral angle 180 - `degrees`: A in the plane
/// z = 0, B turned up about that line by `degrees`.
Scene crease(double degrees, bool flipB) {
    const double a = degrees * 3.14159265358979323846 / 180.0;
    const glm::dvec3 up{std::cos(a), 0.0, std::sin(a)};
    NurbsSurface patchA = makeBilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
    NurbsSurface patchB = flipB ? makeBilinear({1, 0, 0}, {1, 1, 0}, glm::dvec3{1, 0, 0} + up,
                                               glm::dvec3{1, 1, 0} + up)
                                : makeBilinear({1, 0, 0}, glm::dvec3{1, 0, 0} + up, {1, 1, 0},
                                               glm::dvec3{1, 1, 0} + up);
    // Bicubic, so that the kernel meets real derivatives rather than a bilinear's.
    for (NurbsSurface* s : {&patchA, &patchB})
        *s = surfaceElevateDegreeV(surfaceElevateDegreeU(*s, 2), 2);
    return sceneOf({patchA, patchB});
}

} // namespace

class TestContinuity : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphereSeamIsG2();
    void loftInnerBoundaryIsG2WhereC2_data();
    void loftInnerBoundaryIsG2WhereC2();
    void loftInnerBoundaryOfDegree2IsNotG2();
    void creaseAngle_data();
    void creaseAngle();
    void movedBoundaryPointGivesItsDistance_data();
    void movedBoundaryPointGivesItsDistance();
    void recordedCubeIsClosedWithCreases();
    void ownToleranceCountsForG0();
    void tolerancesChangeTheClass();
    void badInputIsCountedApart();
    void tolerancesAreChecked();
    void measureInBlocksReportsProgressAndStops();
};

// A sphere's u = 0 and u = 1 edges are one seam, curved alike on both sides; its v edges are
// poles, neither free nor measured.
void TestContinuity::sphereSeamIsG2() {
    const Scene scene = sceneOf({makeSphere({1, 2, 3}, 2.5)});
    const ContinuityReport r = continuityReport(scene, {});
    QCOMPARE(int(r.edges.size()), 1);
    QCOMPARE(int(r.topology.freeSides.size()), 0);
    QCOMPARE(int(r.topology.degenerateSides.size()), 2);
    QCOMPARE(r.topology.matchedFaces, 1);
    const EdgeContinuity& e = r.edges.front();
    QCOMPARE(e.edge.sides[0].domainEdge, DomainEdge::U0);
    QCOMPARE(e.edge.sides[1].domainEdge, DomainEdge::U1);
    QVERIFY2(e.g0 < 1e-12, qPrintable(QString::number(e.g0)));
    QVERIFY2(e.g1Degrees < 1e-6, qPrintable(QString::number(e.g1Degrees)));
    QVERIFY2(e.g2Percent < 1e-4, qPrintable(QString::number(e.g2Percent)));
    QVERIFY(e.g2Samples > 100); // all but the poles
    QCOMPARE(e.continuity, ContinuityClass::G2);
}

// Cut at its inner knot, a cubic loft through five sections is C2 there: the halves meet G2.
// Whichever way the halves' normals point (the curvature of a reversed face counts with the
// opposite sign).
void TestContinuity::loftInnerBoundaryIsG2WhereC2_data() {
    QTest::addColumn<bool>("reverseOne");
    QTest::newRow("same orientation") << false;
    QTest::newRow("one half reversed") << true;
}

void TestContinuity::loftInnerBoundaryIsG2WhereC2() {
    QFETCH(bool, reverseOne);
    const NurbsSurface loft = wavyLoft(3, nullptr);
    QCOMPARE(loft.degreeV, 3);
    const double t = interiorKnot(loft.knotsV, loft.degreeV);
    QVERIFY(t > 0.0);
    const auto [lo, hi] = splitV(loft, t);
    QVERIFY(checkNurbsSurface(lo).has_value() && checkNurbsSurface(hi).has_value());
    const Scene scene = sceneOf({lo, reverseOne ? reversedU(hi) : hi});
    const ContinuityReport r = continuityReport(scene, {});
    const EdgeContinuity* e = edgeBetween(r, SurfaceId{1}, SurfaceId{2});
    QVERIFY(e);
    QCOMPARE(int(r.edges.size()), 1);
    QCOMPARE(int(r.topology.freeSides.size()), 6);
    QVERIFY2(e->g0 < 1e-9 && e->g1Degrees < 1e-6 && e->g2Percent < 0.01,
             qPrintable(QStringLiteral("%1 %2 %3").arg(e->g0).arg(e->g1Degrees).arg(e->g2Percent)));
    QCOMPARE(e->continuity, ContinuityClass::G2);
}

// The same loft of degree 2 across the sections is only C1 at its inner knots: the curvature
// across the cut jumps, and the kernel says G1.
void TestContinuity::loftInnerBoundaryOfDegree2IsNotG2() {
    const NurbsSurface loft = wavyLoft(2, nullptr);
    QCOMPARE(loft.degreeV, 2);
    const auto [lo, hi] = splitV(loft, interiorKnot(loft.knotsV, loft.degreeV));
    const ContinuityReport r = continuityReport(sceneOf({lo, hi}), {});
    const EdgeContinuity* e = edgeBetween(r, SurfaceId{1}, SurfaceId{2});
    QVERIFY(e);
    QVERIFY2(e->g1Degrees < 1e-6 && e->g2Percent > 5.0,
             qPrintable(QStringLiteral("%1 %2").arg(e->g1Degrees).arg(e->g2Percent)));
    QCOMPARE(e->continuity, ContinuityClass::G1);
}

void TestContinuity::creaseAngle_data() {
    QTest::addColumn<double>("degrees");
    QTest::addColumn<bool>("flipB");
    QTest::newRow("37.5") << 37.5 << false;
    QTest::newRow("37.5, B reversed") << 37.5 << true;
    QTest::newRow("0.3") << 0.3 << false;
    QTest::newRow("71.25, B reversed") << 71.25 << true;
}

// Two patches meeting at a crease report its angle, whichever way their normals point.
void TestContinuity::creaseAngle() {
    QFETCH(double, degrees);
    QFETCH(bool, flipB);
    const ContinuityReport r = continuityReport(crease(degrees, flipB), {});
    const EdgeContinuity* e = edgeBetween(r, SurfaceId{1}, SurfaceId{2});
    QVERIFY(e);
    QVERIFY2(std::abs(e->g1Degrees - degrees) <= 0.01, qPrintable(QString::number(e->g1Degrees)));
    QVERIFY(e->g0 < 1e-12);
    QCOMPARE(e->continuity, degrees > 0.5 ? ContinuityClass::G0 : ContinuityClass::G2);
}

void TestContinuity::movedBoundaryPointGivesItsDistance_data() {
    QTest::addColumn<bool>("recorded");
    QTest::addColumn<double>("d");
    QTest::newRow("created patches, 0.004") << false << 0.004;
    QTest::newRow("created patches, 0.25") << false << 0.25;
    QTest::newRow("recorded cube, 0.004") << true << 0.004;
    QTest::newRow("recorded cube, 0.0005") << true << 0.0005;
}

// A corner control point (which a clamped surface interpolates) on a shared boundary moved by
// d out of the neighbour's plane opens that edge by d; the edges were found before the move,
// as the editor keeps them during a drag.
void TestContinuity::movedBoundaryPointGivesItsDistance() {
    QFETCH(bool, recorded);
    QFETCH(double, d);
    Scene scene = recorded ? test::cubeScene()
                           : sceneOf({makePatch({0, 0, 0}, 3, 3, 5, 5, 2, 2),
                                      makePatch({2, 0, 0}, 3, 3, 5, 5, 2, 2)});
    ContinuityReport r = continuityReport(scene, {});
    QCOMPARE(r.count(ContinuityClass::Open), 0);
    const int edges = int(r.edges.size());
    QCOMPARE(edges, recorded ? 12 : 1);
    // The corner at (1, -1, 0) of patch 2 (its u = 0 edge lies on patch 1's u = 1 edge); of the
    // cube, the corner (0, 0, 0) of face 1, moved along its outward normal -z.
    Surface& s = scene.surfaces[recorded ? 0 : 1];
    s.geometry.points[size_t(s.geometry.index(0, 0))].z -= d;
    QCOMPARE(updateContinuity(r, scene, {s.id}), recorded ? 4 : 1);
    double largest = 0.0;
    int open = 0;
    for (const EdgeContinuity& e : r.edges) {
        largest = std::max(largest, e.g0);
        open += e.continuity == ContinuityClass::Open;
    }
    QVERIFY2(std::abs(largest - d) <= 0.01 * d, qPrintable(QString::number(largest)));
    // Of the cube, the two edges of face 1 that meet at that corner open (face 1's other edges
    // stay closed); both exceed G0 unless d is within it.
    QCOMPARE(open, d > 0.001 ? (recorded ? 2 : 1) : 0);
    // The update is the full measure of the changed scene.
    const ContinuityReport full = continuityReport(scene, {});
    QCOMPARE(int(full.edges.size()), recorded ? edges : (d <= 0.01 ? 1 : 0));
    if (recorded)
        for (size_t k = 0; k < r.edges.size(); ++k)
            QCOMPARE(full.edges[k].g0, r.edges[k].g0);
}

// The recorded cube: 12 edges, none free, none open, every one a 90 degree crease.
void TestContinuity::recordedCubeIsClosedWithCreases() {
    const ContinuityReport r = continuityReport(test::cubeScene(2.0), {});
    QCOMPARE(int(r.edges.size()), 12);
    QCOMPARE(int(r.topology.freeSides.size()), 0);
    QCOMPARE(r.topology.matchedFaces, 0);
    QCOMPARE(r.count(ContinuityClass::G0), 12);
    for (const EdgeContinuity& e : r.edges) {
        QVERIFY(e.edge.recorded.isValid());
        QVERIFY(std::abs(e.g1Degrees - 90.0) < 1e-9);
    }
}

// A recorded edge is closed within the larger of G0 and its own tolerance.
void TestContinuity::ownToleranceCountsForG0() {
    Scene scene = test::cubeScene();
    for (SharedEdge& e : scene.topology.edges)
        e.tolerance = 0.01;
    Surface& s = scene.surfaces[0];
    s.geometry.points[size_t(s.geometry.index(0, 0))].z -= 0.005;
    const ContinuityReport r = continuityReport(scene, {});
    QCOMPARE(r.count(ContinuityClass::Open), 0);
    for (SharedEdge& e : scene.topology.edges)
        e.tolerance = 1e-7;
    QCOMPARE(continuityReport(scene, {}).count(ContinuityClass::Open), 2);
}

// The same edge under other tolerances changes class.
void TestContinuity::tolerancesChangeTheClass() {
    const Scene scene = crease(0.3, false);
    ContinuityTolerances t;
    QCOMPARE(continuityReport(scene, t).edges.at(0).continuity, ContinuityClass::G2);
    t.g1Degrees = 0.2;
    QCOMPARE(continuityReport(scene, t).edges.at(0).continuity, ContinuityClass::G0);
}

// Poles, collapsed trim curves and recorded sides naming what the scene lacks: no crash, each
// counted apart, nothing of them free or measured.
void TestContinuity::badInputIsCountedApart() {
    Scene scene = test::cubeScene();
    scene.topology.edges[5].sides[1].loop = TrimLoopId{999};
    scene.topology.edges[6].sides[0].curve = 17;
    // A collapsed trim curve at the corner of face 2, not part of any edge.
    scene.surfaces[1].trims[0].curves.push_back(test::cubeSegment({0, 0}, {0, 0}));
    // A pointed cone (its apex edge collapsed) and a sphere (two poles), without a record.
    scene.surfaces.push_back(sceneOf({makeCone({5, 0, 0}, 1.0, 2.0, 0.0)}).surfaces[0]);
    scene.surfaces.back().id = SurfaceId{40};
    scene.surfaces.push_back(sceneOf({makeSphere({9, 0, 0}, 1.0)}).surfaces[0]);
    scene.surfaces.back().id = SurfaceId{41};
    const ContinuityReport r = continuityReport(scene, {});
    QCOMPARE(r.topology.unresolvedSides, 2);
    QCOMPARE(int(r.edges.size()), 10 + 2); // the cube's resolved edges, two seams
    QCOMPARE(int(r.topology.degenerateSides.size()), 1 + 1 + 2);
    QCOMPARE(r.topology.matchedFaces, 2);
    // The cone's base circle is free; so are the cube's curves of the two broken edges, which
    // meet nothing that can be measured.
    QCOMPARE(int(r.topology.freeSides.size()), 1 + 4);
    for (const EdgeContinuity& e : r.edges)
        QVERIFY(std::isfinite(e.g0) && std::isfinite(e.g1Degrees) && std::isfinite(e.g2Percent));
}

void TestContinuity::tolerancesAreChecked() {
    KW_VERIFY_OK(checkContinuityTolerances({}));
    QVERIFY(!checkContinuityTolerances({0.0, 0.5, 5.0, 0.01}));
    QVERIFY(!checkContinuityTolerances({0.001, std::nan(""), 5.0, 0.01}));
    QVERIFY(!checkContinuityTolerances({0.1, 0.5, 5.0, 0.01}));
}

// measureContinuity (the overlay's background measure) gives continuityReport's values, tells
// its progress in edges up to the total, and stops at the first block after its callback says
// so, with the rest unmeasured.
void TestContinuity::measureInBlocksReportsProgressAndStops() {
    std::vector<NurbsSurface> grid;
    for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i)
            grid.push_back(makePatch({2.0 * i, 2.0 * j, 0.0}, 3, 3, 4, 4, 2, 2));
    const Scene scene = sceneOf(grid);
    const ContinuityReport whole = continuityReport(scene, {});
    QCOMPARE(int(whole.edges.size()), 2 * 16 * 15); // 480: two blocks
    ContinuityReport report = continuityWatch(scene, {});
    std::vector<size_t> seen;
    QVERIFY(measureContinuity(report, scene, [&](size_t done, size_t total) {
        seen.push_back(done);
        return total == whole.edges.size();
    }));
    QCOMPARE(seen, (std::vector<size_t>{0, 256, 480}));
    for (size_t k = 0; k < whole.edges.size(); ++k) {
        QCOMPARE(report.edges[k].g0, whole.edges[k].g0);
        QCOMPARE(report.edges[k].continuity, whole.edges[k].continuity);
        QVERIFY(report.edges[k].samples > 0);
    }
    ContinuityReport stopped = continuityWatch(scene, {});
    QVERIFY(!measureContinuity(stopped, scene, [](size_t done, size_t) { return done == 0; }));
    QVERIFY(stopped.edges[255].samples > 0);
    QCOMPARE(stopped.edges[256].samples, 0);
    QCOMPARE(stopped.edges.back().samples, 0);
}

QTEST_GUILESS_MAIN(TestContinuity)
#include "tst_continuity.moc"
