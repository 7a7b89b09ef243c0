// Messy trim input (item 3) on the CPU: gaps and open loops are closed with a warning,
// degenerate loops dropped with a warning, orientation does not matter, curves up to degree 15.
#include "expected_test_util.h"
#include "model/analysis/mass_properties.h"
#include "model/document/document.h"
#include "model/document/validation.h"
#include "model/nurbs/nurbs_shapes.h"
#include "model/nurbs/trim.h"
#include "trim_test_util.h"

#include <QtTest>

using namespace kw;
using namespace kwtest;

namespace {

bool anyContains(const QStringList& lines, const QString& a, const QString& b) {
    for (const QString& l : lines)
        if (l.contains(a) && l.contains(b))
            return true;
    return false;
}

} // namespace

class TestTrimMessy : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void messyLoopsAreRepairedAndReported() {
        QStringList warnings;
        const TrimRegion region = makeTrimRegion(messyLoops(10), 1e-4, &warnings);
        // The two degenerate loops (13: there and back, 14: collinear) are dropped.
        QCOMPARE(region.loops.size(), size_t(3));
        QVERIFY2(anyContains(warnings, "trim loop 13", "degenerate"),
                 qPrintable(warnings.join('\n')));
        QVERIFY2(anyContains(warnings, "trim loop 14", "degenerate"),
                 qPrintable(warnings.join('\n')));
        // Loop 10: the reversed edge leaves gaps before curves 2 and 3, and the loop stops 0.02
        // short.
        QVERIFY2(anyContains(warnings, "trim loop 10", "gap of 1 before curve 2"),
                 qPrintable(warnings.join('\n')));
        QVERIFY2(anyContains(warnings, "trim loop 10", "gap of 1 before curve 3"),
                 qPrintable(warnings.join('\n')));
        QVERIFY2(anyContains(warnings, "trim loop 10", "does not close (gap of 0.02)"),
                 qPrintable(warnings.join('\n')));
        // Nothing to say about the two ellipses (degree 15 clockwise, degree 3).
        QVERIFY2(!anyContains(warnings, "trim loop 11", ""), qPrintable(warnings.join('\n')));
        QVERIFY2(!anyContains(warnings, "trim loop 12", ""), qPrintable(warnings.join('\n')));
        // Loop 14 (three collinear points) is also open.
        QVERIFY2(anyContains(warnings, "trim loop 14", "does not close"),
                 qPrintable(warnings.join('\n')));
        QVERIFY2(warnings.size() == 6, qPrintable(warnings.join('\n')));
    }

    void parityIgnoresOrientationAndNesting() {
        const TrimRegion region = makeTrimRegion(messyLoops(10), 1e-5);
        // Outer (on the domain boundary) kept, degree-15 hole removed, island kept again.
        QVERIFY(trimRegionContains(region, {0.05, 0.05}));
        QVERIFY(trimRegionContains(region, {0.95, 0.5}));
        QVERIFY(!trimRegionContains(region, {0.5, 0.75}));
        QVERIFY(!trimRegionContains(region, {0.75, 0.5}));
        QVERIFY(trimRegionContains(region, {0.5, 0.5}));
        // Reversing every loop changes nothing.
        std::vector<TrimLoop> reversed = messyLoops(10);
        for (TrimLoop& l : reversed) {
            std::reverse(l.curves.begin(), l.curves.end());
            for (NurbsCurve2& c : l.curves)
                c = trimCurveReversed(c);
        }
        const TrimRegion back = makeTrimRegion(reversed, 1e-5);
        for (int k = 0; k < 400; ++k) {
            const glm::dvec2 uv((k % 20 + 0.37) / 20.0, (k / 20 + 0.61) / 20.0);
            QCOMPARE(trimRegionContains(back, uv), trimRegionContains(region, uv));
        }
    }

    void degree15CurveIsFlattenedWithinTolerance() {
        const NurbsCurve2 c = ellipseCurve(15, {0.5, 0.5}, {0.35, 0.3}, 24, true);
        QVERIFY(checkNurbsCurve(c).has_value());
        const double tol = 1e-4;
        const std::vector<glm::dvec2> pts = tessellateTrimCurve(c, tol);
        QVERIFY(pts.size() > 20);
        TrimRegion one;
        one.loops.push_back(pts);
        one.lo.push_back({0, 0});
        one.hi.push_back({1, 1});
        // Every curve point lies within tolerance of the polyline.
        for (int k = 0; k <= 1000; ++k)
            QVERIFY(trimRegionDistance(one, curvePoint(c, k / 1000.0)) <= tol * 1.01);
    }

    void wholeDomainTrimKeepsEverything() {
        Surface s;
        s.geometry = makeBilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
        s.trims.push_back(loopOf(2, {polylineCurve({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}})}));
        QVERIFY2(trimWarnings(s).isEmpty(), qPrintable(trimWarnings(s).join('\n')));
        const TrimRegion region = makeTrimRegion(s.trims, trimTolerance(s.geometry));
        for (int k = 0; k < 100; ++k)
            QVERIFY(trimRegionContains(region, {(k % 10 + 0.5) / 10.0, (k / 10 + 0.5) / 10.0}));
        QVERIFY(std::abs(trimmedSurfaceArea(s.geometry, s.trims) - 1.0) < 1e-9);
    }

    void onlyDegenerateLoopsLeaveTheSurfaceUntrimmed() {
        Surface s;
        s.geometry = makeBilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
        s.trims.push_back(loopOf(2, {polylineCurve({{0.2, 0.2}, {0.8, 0.8}, {0.2, 0.2}})}));
        const QStringList w = trimWarnings(s);
        QVERIFY2(w.size() == 1, qPrintable(w.join('\n')));
        QVERIFY(w[0].contains("degenerate"));
        const TrimRegion region = makeTrimRegion(s.trims, trimTolerance(s.geometry));
        QVERIFY(region.empty());
        QVERIFY(trimRegionContains(region, {0.5, 0.1}));
    }

    void importsCloseEveryValidLoopOfTheScene() {
        Scene scene;
        Surface s;
        s.id = SurfaceId{1};
        s.name = QStringLiteral("plate");
        s.geometry = makeBilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
        // Open by 0.3: bridged by a straight segment. Loop 3: closed already. Loop 4: a curve
        // with too few knots, left for checkScene to name.
        s.trims.push_back(loopOf(2, {polylineCurve({{0.1, 0.1}, {0.9, 0.1}, {0.9, 0.9}}),
                                     polylineCurve({{0.9, 0.9}, {0.1, 0.9}, {0.1, 0.4}})}));
        s.trims.push_back(
            loopOf(3, {polylineCurve({{0.4, 0.4}, {0.6, 0.4}, {0.4, 0.6}, {0.4, 0.4}})}));
        NurbsCurve2 bad = polylineCurve({{0.2, 0.2}, {0.3, 0.2}});
        bad.knots.pop_back();
        s.trims.push_back(loopOf(4, {bad}));
        scene.surfaces.push_back(s);
        const QStringList lines = closeSceneTrimLoops(scene);
        QVERIFY2(lines.size() == 1, qPrintable(lines.join('\n')));
        QVERIFY2(lines[0].startsWith("surface 'plate', trim loop 2: ") &&
                     lines[0].contains("bridged"),
                 qPrintable(lines[0]));
        const std::vector<TrimLoop>& trims = scene.surfaces[0].trims;
        KW_VERIFY_OK(checkTrimLoop(trims[0]));
        QCOMPARE(trims[0].curves.size(), size_t(3));
        QCOMPARE(trims[1], s.trims[1]);
        QCOMPARE(trims[2], s.trims[2]);
    }

    void curveEndsMoveWithTheirCoincidentEnds() {
        // A triangle of three 2-point lines (as imported CAD loops are) and a closed polyline.
        Scene scene;
        Surface s;
        s.id = SurfaceId{1};
        s.name = QStringLiteral("plate");
        s.geometry = makeBilinear({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0});
        s.trims.push_back(loopOf(2, {polylineCurve({{0.1, 0.1}, {0.9, 0.1}}),
                                     polylineCurve({{0.9, 0.1}, {0.5, 0.9}}),
                                     polylineCurve({{0.5, 0.9}, {0.1, 0.1}})}));
        s.trims.push_back(
            loopOf(3, {polylineCurve({{0.4, 0.4}, {0.6, 0.4}, {0.4, 0.6}, {0.4, 0.4}})}));
        const TrimLoopId tri = s.trims[0].id, poly = s.trims[1].id;
        scene.surfaces.push_back(s);
        scene.nextId = 4;
        // A curve's start goes with the previous curve's end; a closed curve's start with its
        // own end; an interior point and a ref to nothing alone.
        using Refs = std::vector<TrimPointRef>;
        QCOMPARE(trimPointWithCoincidentEnds(s, {s.id, tri, 1, 0}),
                 (Refs{{s.id, tri, 1, 0}, {s.id, tri, 0, 1}}));
        QCOMPARE(trimPointWithCoincidentEnds(s, {s.id, tri, 0, 0}),
                 (Refs{{s.id, tri, 0, 0}, {s.id, tri, 2, 1}}));
        QCOMPARE(trimPointWithCoincidentEnds(s, {s.id, poly, 0, 3}),
                 (Refs{{s.id, poly, 0, 3}, {s.id, poly, 0, 0}}));
        QCOMPARE(trimPointWithCoincidentEnds(s, {s.id, poly, 0, 1}), (Refs{{s.id, poly, 0, 1}}));
        QCOMPARE(trimPointWithCoincidentEnds(s, {s.id, poly, 0, 7}), (Refs{{s.id, poly, 0, 7}}));
        // Ends that meet within the closure tolerance, not exactly, also go together (the last
        // bit of a coordinate differs in the trimmed_plate sample).
        Surface off = s;
        off.trims[0].curves[2].points[1].y = std::nextafter(0.1, 1.0);
        KW_VERIFY_OK(checkTrimLoop(off.trims[0]));
        QCOMPARE(trimPointWithCoincidentEnds(off, {s.id, tri, 0, 0}),
                 (Refs{{s.id, tri, 0, 0}, {s.id, tri, 2, 1}}));
        QCOMPARE(trimPointWithCoincidentEnds(s, {s.id, TrimLoopId{9}, 0, 0}),
                 (Refs{{s.id, TrimLoopId{9}, 0, 0}}));
        // The document refuses the point alone (the loop would open) and takes the set.
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        const TrimPointRef start{s.id, tri, 0, 0};
        QVERIFY(!doc.setTrimPoint(start, {0.2, 0.15}));
        QCOMPARE(doc.scene().surfaces[0].trims, s.trims);
        const Refs refs = trimPointWithCoincidentEnds(s, start);
        QCOMPARE(refs.size(), size_t(2));
        QVERIFY(doc.setTrimPoints(refs, std::vector<glm::dvec2>(2, {0.2, 0.15})));
        QCOMPARE(doc.scene().surfaces[0].trims[0].curves[0].points[0], glm::dvec2(0.2, 0.15));
        QCOMPARE(doc.scene().surfaces[0].trims[0].curves[2].points[1], glm::dvec2(0.2, 0.15));
    }

    void distanceToTrims() {
        const TrimRegion region = makeTrimRegion(
            {loopOf(2,
                    {polylineCurve({{0.2, 0.2}, {0.8, 0.2}, {0.8, 0.8}, {0.2, 0.8}, {0.2, 0.2}})})},
            1e-6);
        QVERIFY(std::abs(trimRegionDistance(region, {0.5, 0.5}) - 0.3) < 1e-12);
        QVERIFY(std::abs(trimRegionDistance(region, {0.5, 0.1}) - 0.1) < 1e-12);
        QVERIFY(std::abs(trimRegionDistance(region, {0.9, 0.9}) - std::sqrt(0.02)) < 1e-12);
        QVERIFY(std::isinf(trimRegionDistance(TrimRegion{}, {0.5, 0.5})));
    }
};

QTEST_APPLESS_MAIN(TestTrimMessy)
#include "tst_trim_messy.moc"
