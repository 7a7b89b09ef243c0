// Model test (CPU side): trim curves as monotone arcs, the hybrid trim grid's
// conservative edge texels and lists, and its exact classification against model/nurbs/trim.h.
#include "model/cad/cadimport.h"
#include "model/io/knotfile.h"
#include "model/nurbs/trim.h"
#include "render/trim_grid.h"
#include "tests/support/expected_test_util.h"
#include "trim_test_util.h"

#include <QElapsedTimer>
#include <QtTest>
#include <ctime>
#include <random>

using namespace kw;
using namespace kwtest;

namespace {

std::vector<Surface> trimmedSurfacesOf(const QString& path) {
    const auto scene = readKnotFile(path);
    if (!scene)
        qFatal("%s", qPrintable(scene.message()));
    std::vector<Surface> out;
    for (const Surface& s : scene->surfaces)
        if (!s.trims.empty())
            out.push_back(s);
    return out;
}

// A random valid curve of the given degree: control points in the unit square, weights in
// [0.2, 5], clamped uniform knots with one double interior knot when there is room and the
// curve stays continuous there (degree >= 2).
NurbsCurve2 randomCurve(std::mt19937& rng, int degree, int count) {
    std::uniform_real_distribution<double> unit(0.0, 1.0), weight(0.2, 5.0);
    NurbsCurve2 c;
    c.degree = degree;
    for (int k = 0; k < count; ++k) {
        c.points.push_back({unit(rng), unit(rng)});
        c.weights.push_back(weight(rng));
    }
    c.knots.assign(size_t(degree) + 1, 0.0);
    const int interior = count - degree - 1;
    for (int k = 1; k <= interior; ++k)
        c.knots.push_back(k == 2 && interior > 2 && degree >= 2 ? c.knots.back()
                                                                : double(k) / (interior + 1));
    c.knots.insert(c.knots.end(), size_t(degree) + 1, 1.0);
    return c;
}

// How a grid's classification compares with model/nurbs/trim.h's on random points of the grid's
// rectangle (plus a margin outside it).
struct Agreement {
    long points = 0, band = 0, disagree = 0, arcsDisagree = 0; ///< band: disagreements near a curve
};

Agreement compare(const TrimArcs& arcs, const TrimGrid& grid, const TrimRegion& region,
                  double bandWidth, int samples, unsigned seed) {
    std::mt19937 rng(seed);
    const glm::dvec4 r = grid.rect;
    const glm::dvec2 pad(0.05 * (r.y - r.x), 0.05 * (r.w - r.z));
    std::uniform_real_distribution<double> u(r.x - pad.x, r.y + pad.x), v(r.z - pad.y, r.w + pad.y);
    Agreement a;
    for (int k = 0; k < samples; ++k) {
        const glm::dvec2 p(u(rng), v(rng));
        ++a.points;
        const bool exact = trimGridContains(grid, arcs, p);
        if (exact != trimArcsContain(arcs, p))
            ++a.arcsDisagree;
        if (exact != trimRegionContains(region, p))
            ++(trimRegionDistance(region, p) <= bandWidth ? a.band : a.disagree);
    }
    return a;
}

} // namespace

class TestTrimExact : public QObject {
    Q_OBJECT

    // Every grid classification of a surface's trims agrees with model/nurbs/trim.h outside a band
    // of 1e-6 times the domain diagonal around the curves (the flattening tolerance of the
    // reference is 1e-7 of it), at the complexity resolution and at coarse ones.
    void checkSurface(const Surface& s, const QString& name, int samples) {
        const double diag = trimTolerance(s.geometry, 1.0);
        const TrimRegion region = makeTrimRegion(s.trims, 1e-7 * diag);
        const TrimArcs arcs = makeTrimArcs(s.trims, trimTolerance(s.geometry));
        QCOMPARE(int(region.loops.size()), arcs.loops);
        for (glm::ivec2 size : {trimGridResolution(arcs), glm::ivec2(1, 1), glm::ivec2(7, 3)}) {
            const TrimGrid grid = makeTrimGrid(arcs, size);
            const Agreement a = compare(arcs, grid, region, 1e-6 * diag, samples, 7);
            QVERIFY2(a.disagree == 0 && a.arcsDisagree == 0,
                     qPrintable(QStringLiteral("%1 at %2x%3: %4 of %5 points disagree with "
                                               "trim.h, %6 with the arcs (%7 more in the band)")
                                    .arg(name)
                                    .arg(size.x)
                                    .arg(size.y)
                                    .arg(a.disagree)
                                    .arg(a.points)
                                    .arg(a.arcsDisagree)
                                    .arg(a.band)));
            QVERIFY(a.band <= a.points / 1000);
        }
    }

private Q_SLOTS:
    void arcsAreMonotoneAndFollowTheCurve() {
        std::mt19937 rng(11);
        for (int degree = 1; degree <= kMaxDegree; ++degree) {
            const NurbsCurve2 c = randomCurve(rng, degree, degree + 4);
            QVERIFY(checkNurbsCurve(c).has_value());
            const std::vector<TrimArc> arcs = monotoneTrimArcs(c);
            QVERIFY(!arcs.empty());
            QCOMPARE(arcs.front().start, curvePoint(c, curveDomain(c).first));
            QCOMPARE(arcs.back().end, curvePoint(c, curveDomain(c).last));
            const std::vector<glm::dvec2> poly = tessellateTrimCurve(c, 1e-9);
            TrimRegion line; // the flattened curve as one "loop" for trimRegionDistance
            line.loops.push_back(poly);
            for (size_t k = 0; k < arcs.size(); ++k) {
                const TrimArc& a = arcs[k];
                if (k + 1 < arcs.size())
                    QCOMPARE(a.end, arcs[k + 1].start);
                QVERIFY(glm::length(trimArcPoint(a, 0.0) - a.start) < 1e-12);
                QVERIFY(glm::length(trimArcPoint(a, 1.0) - a.end) < 1e-12);
                glm::dvec2 prev = a.start;
                const glm::dvec2 dir = glm::sign(a.end - a.start);
                for (int s = 1; s <= 64; ++s) {
                    const glm::dvec2 p = trimArcPoint(a, s / 64.0);
                    // Monotone: never goes back against the direction from start to end.
                    QVERIFY2((p.x - prev.x) * dir.x >= -1e-12 && (p.y - prev.y) * dir.y >= -1e-12,
                             qPrintable(QStringLiteral("degree %1 arc %2").arg(degree).arg(k)));
                    // On the curve: near the closed polyline, ignoring its closing chord.
                    double d = 1e300;
                    for (size_t i = 0; i + 1 < poly.size(); ++i) {
                        const glm::dvec2 ab = poly[i + 1] - poly[i];
                        const double t =
                            std::clamp(glm::dot(p - poly[i], ab) / glm::dot(ab, ab), 0.0, 1.0);
                        d = std::min(d, glm::length(p - (poly[i] + t * ab)));
                    }
                    QVERIFY2(d < 1e-6,
                             qPrintable(QStringLiteral("degree %1: %2").arg(degree).arg(d)));
                    prev = p;
                }
            }
        }
    }

    void rationalArcsStayOnTheCircle() {
        // trimmed_plate's corners are rational quadratic quarter circles: every arc point keeps
        // its distance to the corner centre.
        const std::vector<Surface> plate =
            trimmedSurfacesOf(QStringLiteral(KW_SAMPLES_DIR "/trimmed_plate.knot"));
        QVERIFY(!plate.empty());
        int checked = 0;
        for (const TrimLoop& loop : plate.front().trims)
            for (const NurbsCurve2& c : loop.curves) {
                if (c.degree != 2 || c.weights[1] == 1.0)
                    continue;
                // Centre: the corner of the control polygon mirrored across the chord midpoint.
                const glm::dvec2 centre = c.points[0] + c.points[2] - c.points[1];
                const double r = glm::length(c.points[0] - centre);
                for (const TrimArc& a : monotoneTrimArcs(c))
                    for (int s = 0; s <= 32; ++s)
                        QVERIFY(std::abs(glm::length(trimArcPoint(a, s / 32.0) - centre) - r) <
                                1e-12);
                ++checked;
            }
        QVERIFY(checked > 0);
    }

    void turningPointsOfAParabola() {
        // u(t) = 2t(1-t) has its extremum at t = 1/2; v is monotone. With weights (1, 3, 1) the
        // rational curve is symmetric, so the turning point stays at 1/2.
        for (double w : {1.0, 3.0}) {
            const std::vector<glm::dvec3> hw{{0, 0, 1}, {w * 1.0, w * 0.5, w}, {0, 1, 1}};
            const std::vector<double> r = trimArcTurningPoints(hw);
            QCOMPARE(int(r.size()), 1);
            QVERIFY(std::abs(r[0] - 0.5) < 1e-12);
        }
        // A straight line and a horizontal line: none.
        QVERIFY(trimArcTurningPoints({{0, 0, 1}, {1, 1, 1}}).empty());
        QVERIFY(trimArcTurningPoints({{0, 0.5, 1}, {0.5, 0.5, 1}, {1, 0.5, 1}}).empty());
    }

    void edgeTexelsAreConservative() {
        // Every point of every arc lies in an edge texel (or on a texel border next to one), and
        // every texel without entries is classified as a whole by its base bit.
        const std::vector<Surface> star =
            trimmedSurfacesOf(QStringLiteral(KW_SAMPLES_DIR "/star_island.knot"));
        QVERIFY(!star.empty());
        const TrimArcs arcs = makeTrimArcs(star.front().trims, 1e-6);
        const TrimGrid grid = makeTrimGrid(arcs, trimGridResolution(arcs));
        const double du = (grid.rect.y - grid.rect.x) / grid.width;
        const double dv = (grid.rect.w - grid.rect.z) / grid.height;
        for (const TrimArc& a : arcs.arcs)
            for (int s = 0; s <= 200; ++s) {
                const glm::dvec2 p = trimArcPoint(a, s / 200.0);
                bool edge = false;
                for (double ox : {-1e-9, 0.0, 1e-9})
                    for (double oy : {-1e-9, 0.0, 1e-9})
                        edge = edge || grid.isEdge(grid.texelOf(p + glm::dvec2(ox * du, oy * dv)));
                QVERIFY(edge);
            }
        int whole = 0;
        for (int j = 0; j < grid.height; ++j)
            for (int i = 0; i < grid.width; ++i) {
                const int k = j * grid.width + i;
                if (grid.isEdge(k))
                    continue;
                ++whole;
                for (double fx : {0.01, 0.5, 0.99})
                    for (double fy : {0.01, 0.5, 0.99}) {
                        const glm::dvec2 p(grid.rect.x + (i + fx) * du,
                                           grid.rect.z + (j + fy) * dv);
                        QCOMPARE(bool(grid.base[size_t(k)]), trimArcsContain(arcs, p));
                    }
            }
        QVERIFY(whole > grid.texelCount() / 2);
    }

    void samplesAgreeWithTrimH() {
        for (const QString& name : {QStringLiteral("trimmed_plate"), QStringLiteral("star_island")})
            for (const Surface& s :
                 trimmedSurfacesOf(QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(name)))
                checkSurface(s, name, 20000);
    }

    void messyLoopsAgreeWithTrimH() {
        // Gaps bridged, a degree-15 hole, a cubic island, degenerate loops dropped.
        Surface s;
        s.geometry.degreeU = s.geometry.degreeV = 1;
        s.geometry.countU = s.geometry.countV = 2;
        s.geometry.knotsU = s.geometry.knotsV = {0, 0, 1, 1};
        s.geometry.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
        s.geometry.weights.assign(4, 1.0);
        s.trims = messyLoops(1);
        QStringList fromArcs, fromRegion;
        makeTrimArcs(s.trims, trimTolerance(s.geometry), &fromArcs);
        makeTrimRegion(s.trims, trimTolerance(s.geometry), &fromRegion);
        QCOMPARE(fromArcs, fromRegion);
        checkSurface(s, QStringLiteral("messy"), 20000);
    }

    void hammerFacesAgreeWithTrimH() {
#ifndef KW_HAVE_OCCT
        QSKIP("built without OpenCASCADE (KW_HAVE_OCCT): hammer.iges cannot be imported");
#else
        const auto imported = importFile(QStringLiteral(KW_TEST_DATA_DIR "/hammer.iges"));
        QVERIFY2(imported, qPrintable(imported.message()));
        int faces = 0;
        for (const Surface& s : imported->scene.surfaces)
            if (!s.trims.empty()) {
                checkSurface(s, QStringLiteral("hammer face %1").arg(s.id.value), 2000);
                ++faces;
            }
        qInfo("hammer.iges: %d trimmed faces", faces);
        QVERIFY(faces > 10);
#endif
    }

    void resolutionFollowsComplexity() {
        TrimArcs few, many;
        few.arcs.resize(4);
        many.arcs.resize(400);
        const glm::ivec2 a = trimGridResolution(few), b = trimGridResolution(many);
        QVERIFY(a.x >= kMinTrimGridSize && a.x < b.x);
        QCOMPARE(b.x, 512);
        QCOMPARE(trimGridResolution(many, 64).x, 64);
    }

    void buildCostOfThePlate() {
        // The rebuild a trim drag needs (arcs + grid), reported for docs/PERFORMANCE.md.
        const std::vector<Surface> plate =
            trimmedSurfacesOf(QStringLiteral(KW_SAMPLES_DIR "/trimmed_plate.knot"));
        QElapsedTimer timer;
        timer.start();
        const std::clock_t cpu = std::clock();
        const int runs = 20;
        TrimGridStats stats;
        for (int k = 0; k < runs; ++k) {
            const TrimArcs arcs = makeTrimArcs(plate.front().trims, 1e-6);
            const TrimGrid grid = makeTrimGrid(arcs, trimGridResolution(arcs));
            stats = trimGridStats(grid, arcs);
        }
        qInfo("trimmed_plate: %.3f ms wall, %.3f ms CPU per arcs + grid build; %lld arcs, %d edge "
              "texels, %lld pieces, longest list %d, %lld bytes",
              timer.nsecsElapsed() / 1e6 / runs,
              double(std::clock() - cpu) * 1000.0 / CLOCKS_PER_SEC / runs, (long long)stats.arcs,
              stats.edgeTexels, (long long)stats.pieces, stats.maxEntries, (long long)stats.bytes);
        QVERIFY(stats.entries >= stats.edgeTexels && stats.entries >= stats.pieces);
    }
};

QTEST_GUILESS_MAIN(TestTrimExact)
#include "tst_trim_exact.moc"
