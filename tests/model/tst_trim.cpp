// Trim loops: flattening tolerance, even-odd classification and trimmed area (model/nurbs/trim.h).
#include "model/analysis/mass_properties.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_shapes.h"
#include "model/nurbs/trim.h"
#include "model_fixtures.h"

#include <QtTest>
#include <cmath>
#include <memory>

using namespace kw;
using namespace kw::test;

namespace {

// An exact circle of radius r about c: four rational quadratic quarter arcs.
TrimLoop circleLoop(TrimLoopId id, glm::dvec2 c, double r) {
    TrimLoop loop;
    loop.id = id;
    const double w = std::sqrt(0.5);
    const glm::dvec2 dirs[5] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 0}};
    for (int q = 0; q < 4; ++q) {
        NurbsCurve2 arc;
        arc.degree = 2;
        arc.knots = {0, 0, 0, 1, 1, 1};
        arc.points = {c + r * dirs[q], c + r * (dirs[q] + dirs[q + 1]), c + r * dirs[q + 1]};
        arc.weights = {1, w, 1};
        loop.curves.push_back(arc);
    }
    return loop;
}

double distanceToPolyline(glm::dvec2 p, const std::vector<glm::dvec2>& poly) {
    double best = 1e300;
    for (size_t i = 0; i + 1 < poly.size(); ++i) {
        const glm::dvec2 a = poly[i], ab = poly[i + 1] - a;
        const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
        best = std::min(best, glm::length(p - (a + t * ab)));
    }
    return best;
}

} // namespace

class TestTrim : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void flatteningStaysWithinTolerance_data();
    void flatteningStaysWithinTolerance();
    void classificationIsEvenOdd();
    void spansMatchClassification();
    void columnClassificationMatchesPointwise();
    void hugeCoordinatesDoNotOverflow();
    void areaOfPlateWithHoleAndIsland();
    void areaOfUntrimmedSphere();
    void areaOfTrimmedSampleConverges();
    void segmentAndReverseKeepTheCurve();
    void reversingAHugeDomainKeepsTheKnotsApart();
};

void TestTrim::flatteningStaysWithinTolerance_data() {
    QTest::addColumn<double>("tolerance");
    QTest::newRow("1e-2") << 1e-2;
    QTest::newRow("1e-4") << 1e-4;
    QTest::newRow("1e-6") << 1e-6;
}

void TestTrim::flatteningStaysWithinTolerance() {
    QFETCH(double, tolerance);
    const TrimLoop circle = circleLoop(TrimLoopId{1}, {0.5, 0.5}, 0.3);
    for (const NurbsCurve2& arc : circle.curves) {
        const std::vector<glm::dvec2> poly = tessellateTrimCurve(arc, tolerance);
        QCOMPARE(poly.front(), arc.points.front());
        QVERIFY(glm::length(poly.back() - arc.points.back()) < 1e-15);
        for (int k = 0; k <= 1000; ++k) {
            const glm::dvec2 p = curvePoint(arc, k / 1000.0);
            QVERIFY2(distanceToPolyline(p, poly) <= tolerance * 1.01,
                     qPrintable(QString::number(distanceToPolyline(p, poly))));
        }
        // Not absurdly fine either: a circle arc needs about sqrt(r / (8 tol)) * angle pieces.
        QVERIFY(poly.size() < 8 * std::sqrt(0.3 / (8 * tolerance)) + 16);
    }
    const TrimPolygon loop = tessellateTrimLoop(circle, tolerance);
    QVERIFY(loop.front() != loop.back()); // closed implicitly
}

void TestTrim::classificationIsEvenOdd() {
    TrimRegion none = makeTrimRegion({}, 1e-6);
    QVERIFY(trimRegionContains(none, {0.5, 0.5})); // untrimmed: everything visible

    // Outer square, a circular hole, and a square island inside the hole.
    const std::vector<TrimLoop> trims = {rectLoop(TrimLoopId{1}, 0.1, 0.1, 0.9, 0.9),
                                         circleLoop(TrimLoopId{2}, {0.5, 0.5}, 0.3),
                                         rectLoop(TrimLoopId{3}, 0.45, 0.45, 0.55, 0.55)};
    const TrimRegion r = makeTrimRegion(trims, 1e-6);
    QCOMPARE(r.loops.size(), size_t(3));
    QVERIFY(!trimRegionContains(r, {0.05, 0.5}));  // outside the outer loop
    QVERIFY(trimRegionContains(r, {0.15, 0.15}));  // between outer loop and hole
    QVERIFY(!trimRegionContains(r, {0.5, 0.3}));   // in the hole
    QVERIFY(trimRegionContains(r, {0.5, 0.5}));    // on the island
    QVERIFY(!trimRegionContains(r, {0.95, 0.95})); // outside again
    // Orientation does not matter: reversing a loop changes nothing.
    std::vector<TrimLoop> reversed = trims;
    std::reverse(reversed[1].curves.begin(), reversed[1].curves.end());
    for (NurbsCurve2& c : reversed[1].curves) {
        std::reverse(c.points.begin(), c.points.end());
        std::reverse(c.weights.begin(), c.weights.end());
    }
    const TrimRegion rr = makeTrimRegion(reversed, 1e-6);
    for (double u = 0.01; u < 1.0; u += 0.037)
        for (double v = 0.013; v < 1.0; v += 0.041)
            QCOMPARE(trimRegionContains(rr, {u, v}), trimRegionContains(r, {u, v}));
}

void TestTrim::spansMatchClassification() {
    const std::vector<TrimLoop> trims = {rectLoop(TrimLoopId{1}, 0.1, 0.1, 0.9, 0.9, true),
                                         circleLoop(TrimLoopId{2}, {0.5, 0.5}, 0.3)};
    const TrimRegion r = makeTrimRegion(trims, 1e-6);
    for (double u = 0.005; u < 1.0; u += 0.031) {
        const std::vector<Interval> spans = trimRegionSpans(r, u, 0.0, 1.0);
        for (double v = 0.0017; v < 1.0; v += 0.0123) {
            bool inSpan = false;
            for (const Interval& s : spans)
                inSpan = inSpan || (v > s.first && v < s.last);
            QCOMPARE(inSpan, trimRegionContains(r, {u, v}));
        }
    }
}

// trimRegionContainsColumn (surfaceVisibleBounds, hence fitCamera) must answer exactly as
// trimRegionContains, also on the polygon's own vertices and its loops' bounding boxes, where the
// half-open rule and the per-loop box test decide.
void TestTrim::columnClassificationMatchesPointwise() {
    std::vector<TrimRegion> regions;
    regions.push_back(makeTrimRegion({}, 1e-6));
    regions.push_back(makeTrimRegion({rectLoop(TrimLoopId{1}, 0.1, 0.1, 0.9, 0.9),
                                      circleLoop(TrimLoopId{2}, {0.5, 0.5}, 0.3),
                                      rectLoop(TrimLoopId{3}, 0.45, 0.45, 0.55, 0.55)},
                                     1e-6));
    for (const char* name : {"trimmed_plate", "star_island"}) {
        QString error;
        const auto scene =
            readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(QLatin1String(name)));
        QVERIFY2(scene, qPrintable(scene.message()));
        for (const Surface& s : scene->surfaces)
            if (!s.trims.empty())
                regions.push_back(makeTrimRegion(s.trims, trimTolerance(s.geometry)));
    }
    QVERIFY(regions.size() >= 4);
    int inside = 0, outside = 0;
    for (const TrimRegion& r : regions) {
        std::vector<double> us, vs;
        for (double t = -0.05; t < 1.1; t += 0.0173) {
            us.push_back(t);
            vs.push_back(t * 0.97 + 0.004);
        }
        for (size_t l = 0; l < r.loops.size(); ++l) {
            us.insert(us.end(), {r.lo[l].x, r.hi[l].x});
            vs.insert(vs.end(), {r.lo[l].y, r.hi[l].y});
            for (size_t k = 0; k < r.loops[l].size(); k += 7) {
                us.push_back(r.loops[l][k].x);
                vs.push_back(r.loops[l][k].y);
            }
        }
        std::unique_ptr<bool[]> column(new bool[vs.size()]);
        for (double u : us) {
            trimRegionContainsColumn(r, u, vs.data(), int(vs.size()), column.get());
            for (size_t k = 0; k < vs.size(); ++k) {
                QCOMPARE(column[k], trimRegionContains(r, {u, vs[k]}));
                (column[k] ? inside : outside) += 1;
            }
        }
    }
    QVERIFY(inside > 100 && outside > 100); // both answers were exercised
}

// Finite but huge polygon points (a file can hold them): the crossing of an edge with a
// vertical line used to overflow to -inf, so spans and classification disagreed (fuzz_trim,
// tests/fuzz/repro/trim/crossing-overflow).
void TestTrim::hugeCoordinatesDoNotOverflow() {
    TrimRegion r;
    r.loops = {{{1, 1}, {-1e306, 378835.7}, {-2.5e305, 94709.7}}};
    r.lo = {{-1e306, 1}};
    r.hi = {{1, 378835.7}};
    for (const double u : {-0.33566, -1e300, -2e305, 0.5}) {
        const std::vector<Interval> spans = trimRegionSpans(r, u, -1e6, 1e6);
        for (const Interval& s : spans) {
            QVERIFY(std::isfinite(s.first) && std::isfinite(s.last));
            QVERIFY(trimRegionContains(r, {u, 0.5 * (s.first + s.last)}));
        }
        // Below the polygon's box: outside, and no span reaches there.
        QVERIFY(!trimRegionContains(r, {u, -0.14}));
        for (const Interval& s : spans)
            QVERIFY(s.first > -0.14);
    }
    QVERIFY(std::isfinite(trimRegionDistance(r, {0.0, 0.0})));
}

void TestTrim::areaOfPlateWithHoleAndIsland() {
    // A flat patch (u, v) in [0, 1]^2 -> (4u, 2v, 0): its area is 8 x the (u, v) area.
    const NurbsSurface plate = makeBilinear({0, 0, 0}, {4, 0, 0}, {0, 2, 0}, {4, 2, 0});
    QVERIFY(std::abs(trimmedSurfaceArea(plate, {}) - 8.0) < 1e-12);
    const double pi = std::acos(-1.0);
    std::vector<TrimLoop> trims = {rectLoop(TrimLoopId{1}, 0.1, 0.1, 0.9, 0.9),
                                   circleLoop(TrimLoopId{2}, {0.5, 0.5}, 0.3)};
    const double expected = 8.0 * (0.64 - pi * 0.09);
    // The circle is an exact rational arc: the area is exact to rounding, not to a flattening.
    double area = trimmedSurfaceArea(plate, trims);
    QVERIFY2(std::abs(area - expected) / expected < 1e-10,
             qPrintable(QString::number(area, 'g', 17)));
    trims.push_back(rectLoop(TrimLoopId{3}, 0.45, 0.45, 0.55, 0.55)); // island: 0.01 back
    area = trimmedSurfaceArea(plate, trims);
    QVERIFY(std::abs(area - (expected + 0.08)) / expected < 1e-10);
}

void TestTrim::areaOfUntrimmedSphere() {
    QString error;
    const auto scene = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/sphere.knot"));
    QVERIFY2(scene, qPrintable(scene.message()));
    const double pi = std::acos(-1.0);
    const double area = trimmedSurfaceArea(scene->surfaces.front().geometry, {});
    QVERIFY2(std::abs(area - 4 * pi) / (4 * pi) < 1e-8, qPrintable(QString::number(area, 'g', 17)));
}

void TestTrim::areaOfTrimmedSampleConverges() {
    // The curved trimmed plate sample with every trim curve cut in two at an uneven parameter
    // and every loop run backwards: the same boundary timed differently (as a CAD reader's
    // re-fitted p-curve is) has the same area to 1e-10, which a measure over flattened trims
    // (chord error 1e-5 of the domain) does not give.
    const auto scene = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/trimmed_plate.knot"));
    QVERIFY2(scene, qPrintable(scene.message()));
    const Surface& s = scene->surfaces.front();
    QVERIFY(!s.trims.empty());
    std::vector<TrimLoop> retimed = s.trims;
    for (TrimLoop& loop : retimed) {
        std::vector<NurbsCurve2> curves;
        for (const NurbsCurve2& c : loop.curves) {
            const Interval d = curveDomain(c);
            const double cut = d.first + 0.37 * (d.last - d.first);
            curves.push_back(trimCurveSegment(c, d.first, cut));
            curves.push_back(trimCurveSegment(c, cut, d.last));
        }
        loop.curves.clear();
        for (auto c = curves.rbegin(); c != curves.rend(); ++c)
            loop.curves.push_back(trimCurveReversed(*c));
    }
    const double area = trimmedSurfaceArea(s.geometry, s.trims);
    const double again = trimmedSurfaceArea(s.geometry, retimed);
    QVERIFY2(std::abs(area - again) / area < 1e-10,
             qPrintable(QStringLiteral("%1 vs %2").arg(area, 0, 'g', 17).arg(again, 0, 'g', 17)));
    QVERIFY(area < trimmedSurfaceArea(s.geometry, {})); // holes remove area
}

void TestTrim::segmentAndReverseKeepTheCurve() {
    // A rational cubic with an interior double knot; pieces starting at the domain start, at a
    // knot, and between knots.
    NurbsCurve2 c;
    c.degree = 3;
    c.knots = {0, 0, 0, 0, 0.3, 0.6, 0.6, 1, 1, 1, 1};
    c.points = {{0, 0}, {1, 2}, {2, -1}, {3, 3}, {4, 0}, {5, 2}, {6, 1}};
    c.weights = {1, 0.5, 2, 1, 0.7, 1.5, 1};
    for (auto [a, b] : {std::pair{0.0, 0.45}, {0.3, 1.0}, {0.12, 0.77}, {0.6, 0.61}}) {
        const NurbsCurve2 piece = trimCurveSegment(c, a, b);
        QVERIFY(checkNurbsCurve(piece).has_value());
        QCOMPARE(curveDomain(piece).first, a);
        QCOMPARE(curveDomain(piece).last, b);
        for (int k = 0; k <= 20; ++k) {
            const double t = a + (b - a) * k / 20.0;
            QVERIFY2(glm::length(curvePoint(piece, t) - curvePoint(c, t)) < 1e-13,
                     qPrintable(QStringLiteral("[%1, %2] at %3").arg(a).arg(b).arg(t)));
        }
    }
    const NurbsCurve2 r = trimCurveReversed(c);
    QVERIFY(checkNurbsCurve(r).has_value());
    QCOMPARE(curveDomain(r), (Interval{-1.0, 0.0}));
    for (int k = 0; k <= 20; ++k)
        QVERIFY(glm::length(curvePoint(r, -k / 20.0) - curvePoint(c, k / 20.0)) < 1e-13);
}

void TestTrim::reversingAHugeDomainKeepsTheKnotsApart() {
    // fuzz_trim (tests/fuzz/repro/trim/reversed-invalid): a valid unclamped line over
    // [-1.49, 1e308]. Reflected about the domain middle, every knot but the first two rounded
    // to 1e308: multiplicity 5 > degree + 1, an invalid curve. Negated knots are exact.
    NurbsCurve2 c;
    c.degree = 1;
    c.knots = {-1.9511711299305714,
               -1.4871137560082399,
               -1.0478370336461433,
               -0.76835278858625156,
               0.75761043717097731,
               1e308,
               1e308};
    c.points = {{0.65, 0.82}, {0.38, -0.86}, {-0.05, -0.05}, {-0.05, -0.05}, {-0.05, -0.05}};
    c.weights = {1, 1, 1, 1, 1};
    QVERIFY(checkNurbsCurve(c).has_value());
    const NurbsCurve2 r = trimCurveReversed(c);
    QVERIFY2(checkNurbsCurve(r).has_value(), qPrintable(checkNurbsCurve(r).message()));
    QCOMPARE(curveDomain(r), (Interval{-1e308, 1.4871137560082399}));
    for (size_t i = 0; i < c.knots.size(); ++i)
        QCOMPARE(r.knots[i], -c.knots[c.knots.size() - 1 - i]);
    for (double t : {-1.4871137560082399, -1.2, -0.9, 0.0, 0.5, 1e300, 1e308})
        QVERIFY2(glm::length(curvePoint(r, -t) - curvePoint(c, t)) < 1e-14,
                 qPrintable(QString::number(t)));
}

QTEST_GUILESS_MAIN(TestTrim)
#include "tst_trim.moc"
