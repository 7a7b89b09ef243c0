// Match Surface (model/document/matchsurface.h) on created patches: G0, G1 and G2 reached as the
// continuity kernel measures them, the neighbour untouched, a trimmed target approximated and
// said so, bad requests refused.
#include "model/document/matchsurface.h"
#include "model/nurbs/nurbs_construct.h"

#include <QTest>
#include <cmath>

using namespace kw;

namespace {

/// Patch 1: flat, 5 x 5 cubic, x in [-1, 1]. Patch 2: 6 x 4 of degree 3 x 2, x in [1.05, 3],
/// curved (z = 0.3 (x - 1)^2 + 0.1 y^2 + 0.05 y), so its u = first edge lies near patch 1's
/// u = last edge, with other knots along it, off by a gap and at an angle.
Scene twoPatches(bool rationalTarget = false) {
    Scene scene;
    NurbsSurface a = makePatch({0, 0, 0}, 3, 3, 5, 5, 2, 2);
    NurbsSurface b = makePatch({2.025, 0, 0}, 3, 2, 6, 4, 1.95, 2);
    for (glm::dvec3& p : b.points)
        p.z = 0.3 * (p.x - 1.0) * (p.x - 1.0) + 0.1 * p.y * p.y + 0.05 * p.y + 0.02;
    if (rationalTarget)
        for (size_t k = 0; k < b.weights.size(); ++k)
            b.weights[k] = 1.0 + 0.3 * double(k % 3);
    for (const NurbsSurface& g : {a, b}) {
        Surface s;
        s.id = SurfaceId{scene.nextId++};
        s.name = QStringLiteral("Patch %1").arg(s.id.value);
        s.geometry = g;
        scene.surfaces.push_back(s);
    }
    return scene;
}

NurbsSurface transposed(const NurbsSurface& s) {
    NurbsSurface t = s;
    std::swap(t.degreeU, t.degreeV);
    std::swap(t.countU, t.countV);
    std::swap(t.knotsU, t.knotsV);
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            t.points[size_t(t.index(j, i))] = s.points[size_t(s.index(i, j))];
            t.weights[size_t(t.index(j, i))] = s.weights[size_t(s.index(i, j))];
        }
    return t;
}

/// `s` with both parameters running the other way (the same surface).
NurbsSurface reversedBoth(const NurbsSurface& s) {
    NurbsSurface r = s;
    std::reverse(r.points.begin(), r.points.end());
    std::reverse(r.weights.begin(), r.weights.end());
    for (std::vector<double>* k : {&r.knotsU, &r.knotsV}) {
        const double sum = k->front() + k->back();
        std::reverse(k->begin(), k->end());
        for (double& x : *k)
            x = sum - x;
    }
    return r;
}

MatchRequest request(MatchContinuity c) {
    MatchRequest r;
    r.surface = SurfaceId{1};
    r.edge = DomainEdge::U1;
    r.target = ContinuitySide{SurfaceId{2}, TrimLoopId{}, -1, DomainEdge::U0};
    r.continuity = c;
    return r;
}

} // namespace

class TestMatchSurface : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void reachesTheContinuityAsked_data();
    void reachesTheContinuityAsked();
    void nearestSideIsTheFacingEdge();
    void trimmedTargetIsApproximatedAndSaysSo();
    void badRequestsAreRefused();
};

void TestMatchSurface::reachesTheContinuityAsked_data() {
    QTest::addColumn<int>("continuity");
    QTest::addColumn<bool>("rational");
    QTest::addColumn<bool>("turned"); // A transposed (edge V1), B reversed both ways (edge U1)
    QTest::newRow("G0") << int(MatchContinuity::G0) << false << false;
    QTest::newRow("G1") << int(MatchContinuity::G1) << false << false;
    QTest::newRow("G2") << int(MatchContinuity::G2) << false << false;
    QTest::newRow("G1, rational target") << int(MatchContinuity::G1) << true << false;
    QTest::newRow("G2, rational target") << int(MatchContinuity::G2) << true << false;
    QTest::newRow("G1, turned") << int(MatchContinuity::G1) << false << true;
    QTest::newRow("G2, turned, rational") << int(MatchContinuity::G2) << true << true;
}

// G1 within 0.01 degrees, G2 within 1 %, measured by the kernel; the far edge and the target
// stay where they were.
void TestMatchSurface::reachesTheContinuityAsked() {
    QFETCH(int, continuity);
    QFETCH(bool, rational);
    QFETCH(bool, turned);
    Scene scene = twoPatches(rational);
    MatchRequest req = request(MatchContinuity(continuity));
    if (turned) {
        scene.surfaces[0].geometry = transposed(scene.surfaces[0].geometry);
        scene.surfaces[1].geometry = reversedBoth(scene.surfaces[1].geometry);
        req.edge = DomainEdge::V1;
        req.target.domainEdge = DomainEdge::U1;
    }
    const MatchContinuity c = MatchContinuity(continuity);
    const ContinuityReport before = continuityReport(scene, {});
    QCOMPARE(int(before.edges.size()), 0); // 0.05 apart: not even found as one edge
    QString error;
    const auto r = matchSurface(scene, req, {});
    QVERIFY2(r, qPrintable(r.message()));
    QVERIFY(r->exact);
    QVERIFY2(r->reached, qPrintable(r->summary));
    QVERIFY2(r->measured.g0 < 1e-9, qPrintable(r->summary));
    if (c != MatchContinuity::G0)
        QVERIFY2(r->measured.g1Degrees <= 0.01, qPrintable(r->summary));
    if (c == MatchContinuity::G2)
        QVERIFY2(r->measured.g2Percent <= 1.0, qPrintable(r->summary));
    else if (c == MatchContinuity::G1)
        QVERIFY2(r->measured.g2Percent > 1.0, qPrintable(r->summary)); // flat against curved
    QVERIFY(r->summary.startsWith(QStringLiteral("Matched")));
    qInfo("%s", qPrintable(r->summary));
    // The opposite edge (u = first; turned, v = first) is where it was.
    const NurbsSurface& old = scene.surfaces[0].geometry;
    for (double t : {0.0, 0.3, 0.77, 1.0}) {
        const double u = turned ? t : 0.0, v = turned ? 0.0 : t;
        QVERIFY(glm::length(surfacePoint(r->geometry, u, v) - surfacePoint(old, u, v)) < 1e-12);
    }
    // And once applied, the whole-scene report finds the edge in that class.
    Scene after = scene;
    after.surfaces[0].geometry = r->geometry;
    const ContinuityReport report = continuityReport(after, {});
    QCOMPARE(int(report.edges.size()), 1);
    QCOMPARE(report.edges[0].continuity, r->measured.continuity);
}

void TestMatchSurface::nearestSideIsTheFacingEdge() {
    const Scene scene = twoPatches();
    const std::optional<ContinuitySide> side =
        nearestSide(scene, SurfaceId{1}, DomainEdge::U1, SurfaceId{2});
    QVERIFY(side);
    QCOMPARE(side->domainEdge, DomainEdge::U0);
}

// A target edge that is a trim curve across the neighbour's domain: fitted, not exact; the
// result says what was reached with its deviation.
void TestMatchSurface::trimmedTargetIsApproximatedAndSaysSo() {
    Scene scene = twoPatches();
    Surface& b = scene.surfaces[1];
    TrimLoop loop;
    loop.id = TrimLoopId{50};
    // A wavy cut across the middle of b's domain, closed along b's domain edges.
    NurbsCurve2 cut;
    cut.degree = 3;
    cut.points = {{0.3, 0.0}, {0.45, 0.3}, {0.2, 0.7}, {0.35, 1.0}};
    cut.weights.assign(4, 1.0);
    cut.knots = {0, 0, 0, 0, 1, 1, 1, 1};
    const auto line = [](glm::dvec2 p, glm::dvec2 q) {
        NurbsCurve2 l;
        l.degree = 1;
        l.points = {p, q};
        l.weights = {1, 1};
        l.knots = {0, 0, 1, 1};
        return l;
    };
    loop.curves = {cut, line({0.35, 1.0}, {1.0, 1.0}), line({1.0, 1.0}, {1.0, 0.0}),
                   line({1.0, 0.0}, {0.3, 0.0})};
    b.trims.push_back(loop);
    MatchRequest r = request(MatchContinuity::G1);
    r.target = ContinuitySide{SurfaceId{2}, TrimLoopId{50}, 0, DomainEdge::None};
    QString error;
    const auto m = matchSurface(scene, r, {});
    QVERIFY2(m, qPrintable(m.message()));
    QVERIFY(!m->exact);
    // Close (a fit), though not necessarily within G0's 0.001.
    QVERIFY2(m->measured.g0 < 0.01, qPrintable(m->summary));
    QVERIFY(m->measured.g1Degrees < 5.0);
    if (!m->reached)
        QVERIFY2(m->summary.contains(QStringLiteral("not reached")) &&
                     m->summary.contains(QStringLiteral("G0 ")),
                 qPrintable(m->summary));
    qInfo("%s", qPrintable(m->summary));
}

void TestMatchSurface::badRequestsAreRefused() {
    Scene scene = twoPatches();
    MatchRequest r = request(MatchContinuity::G1);
    r.surface = SurfaceId{9};
    const auto unknownSurface = matchSurface(scene, r, {});
    QVERIFY(!unknownSurface);
    QVERIFY(unknownSurface.message().contains(QStringLiteral("9")));
    r = request(MatchContinuity::G1);
    r.target = ContinuitySide{SurfaceId{1}, TrimLoopId{}, -1, DomainEdge::U1};
    const auto sameEdge = matchSurface(scene, r, {});
    QVERIFY(!sameEdge);
    r = request(MatchContinuity::G1);
    r.target = ContinuitySide{SurfaceId{2}, TrimLoopId{4}, 0, DomainEdge::None};
    const auto noEdge = matchSurface(scene, r, {});
    QVERIFY(!noEdge);
    QVERIFY(noEdge.message().contains(QStringLiteral("no such edge")));
    TrimLoop loop;
    loop.id = TrimLoopId{60};
    scene.surfaces[0].trims.push_back(loop);
    const auto trimmed = matchSurface(scene, request(MatchContinuity::G1), {});
    QVERIFY(!trimmed);
    QVERIFY(trimmed.message().contains(QStringLiteral("trimmed")));
}

QTEST_GUILESS_MAIN(TestMatchSurface)
#include "tst_matchsurface.moc"
