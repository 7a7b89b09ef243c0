// Shared edges found by matching the boundaries of faces without a record (the export builds
// them as recorded edges instead of sewing): which pairs, their gaps and directions, and which
// groups are left to sewing.
#include "model/cad/matchedtopology.h"
#include "model/nurbs/nurbs_shapes.h"
#include "model_fixtures.h"

#include <QtTest>
#include <set>

using namespace kw;

namespace {

// A unit cube of six bilinear faces, each trimmed by the rectangle of its whole domain (as a
// loose IGES trimmed surface is); corner (1, 1, 1) of "top" moved up by `lift`.
Scene trimmedCube(double lift = 0.0) {
    using glm::dvec3;
    const dvec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    NurbsSurface top = makeBilinear(c[4], c[5], c[6], c[7]);
    top.points[3].z += lift;
    const NurbsSurface faces[6] = {
        makeBilinear(c[0], c[2], c[1], c[3]), top,
        makeBilinear(c[0], c[1], c[4], c[5]), makeBilinear(c[3], c[2], c[7], c[6]),
        makeBilinear(c[2], c[0], c[6], c[4]), makeBilinear(c[1], c[3], c[5], c[7])};
    Scene s;
    for (std::uint32_t k = 0; k < 6; ++k) {
        Surface f = test::makeSurface(2 * k + 1, QStringLiteral("f%1").arg(k), faces[k]);
        f.trims.push_back(test::rectLoop(TrimLoopId{2 * k + 2}, 0, 0, 1, 1));
        s.surfaces.push_back(f);
    }
    s.nextId = 13;
    return s;
}

} // namespace

class TestMatchedTopology : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void closedCubeIsOneClosedShell();
    void gapIsMeasured();
    void pairsBeyondMaxGapStayOpen();
    void looseToleranceKeepsBestPairs();
    void tJunctionLeavesGroupToSewing();
    void recordedFacesAreLeftAlone();
};

// Twelve edges, each a pair of whole curves running opposite ways on faces oriented alike (the
// cube's faces all face outward), one closed shell of the six faces, nothing left to sewing.
void TestMatchedTopology::closedCubeIsOneClosedShell() {
    const Scene s = trimmedCube();
    const MatchedTopology m = matchedTopology(s, 1e-6);
    QCOMPARE(int(m.edges.size()), 12);
    QCOMPARE(int(m.shells.size()), 1);
    QCOMPARE(int(m.shells[0].faces.size()), 6);
    QVERIFY(m.shells[0].closed);
    QCOMPARE(m.faces, 6);
    QCOMPARE(m.leftToSewing, 0);
    std::set<std::pair<std::uint32_t, int>> sides;
    for (const SharedEdge& e : m.edges) {
        QVERIFY(e.id.isValid());
        QVERIFY(e.tolerance <= 1e-12);
        // Both loops run counter-clockwise on faces that all face outward, so the two sides
        // of every edge run opposite ways.
        QVERIFY(!e.sides[0].reversed);
        QVERIFY(e.sides[1].reversed);
        QVERIFY(e.sides[0].surface != e.sides[1].surface);
        for (const EdgeUse& u : e.sides)
            QVERIFY(sides.insert({u.surface.value, u.curve}).second); // each curve once
    }
    QCOMPARE(int(sides.size()), 24);
}

// A corner lifted by d within the tolerance: the three edges at it are still paired, each with
// tolerance d (the measured gap; the lifted corner's edges move by d at the corner).
void TestMatchedTopology::gapIsMeasured() {
    const double d = 1e-4;
    const Scene s = trimmedCube(d);
    const MatchedTopology m = matchedTopology(s, 1e-3);
    QCOMPARE(int(m.edges.size()), 12);
    int lifted = 0;
    for (const SharedEdge& e : m.edges) {
        if (e.tolerance > 1e-12) {
            ++lifted;
            QVERIFY2(std::abs(e.tolerance - d) <= 0.01 * d,
                     qPrintable(QString::number(e.tolerance)));
        }
    }
    QCOMPARE(lifted, 2); // the two edges of "top" that end at the lifted corner
    // Beyond the tolerance those two sides pair with nothing: the shell is open.
    const MatchedTopology far = matchedTopology(s, 1e-5);
    QCOMPARE(int(far.edges.size()), 10);
    QVERIFY(!far.shells[0].closed);
}

// Within the matching tolerance but beyond `maxGap` (how far apart a reader keeps two sides'
// own p-curves on one edge): the two edges at the lifted corner are no edges but open seams
// with their gaps, their faces still one (open) shell through the other edges.
void TestMatchedTopology::pairsBeyondMaxGapStayOpen() {
    const double d = 1e-4;
    const Scene s = trimmedCube(d);
    const MatchedTopology m = matchedTopology(s, 1e-3, 0.5 * d);
    QCOMPARE(int(m.edges.size()), 10);
    QCOMPARE(int(m.tooFar.size()), 2);
    for (const MatchedTopology::FarPair& far : m.tooFar) {
        QVERIFY2(std::abs(far.gap - d) <= 0.01 * d, qPrintable(QString::number(far.gap)));
        QVERIFY(far.faces[0] == s.surfaces[1].id || far.faces[1] == s.surfaces[1].id);
    }
    for (const SharedEdge& e : m.edges)
        QVERIFY(e.tolerance <= 0.5 * d);
    QCOMPARE(int(m.shells.size()), 1);
    QCOMPARE(int(m.shells[0].faces.size()), 6);
    QVERIFY(!m.shells[0].closed);
    // A limit above the gap keeps all twelve.
    const MatchedTopology all = matchedTopology(s, 1e-3, 2.0 * d);
    QCOMPARE(int(all.edges.size()), 12);
    QVERIFY(all.tooFar.empty());
    QVERIFY(all.shells[0].closed);
}

// A tolerance as large as the faces (the sewing tolerance of a scene whose diagonal is large
// next to its parts): every curve lies within reach of several, none is taken for a point, and
// each keeps the partner whose ends meet it.
void TestMatchedTopology::looseToleranceKeepsBestPairs() {
    const MatchedTopology m = matchedTopology(trimmedCube(), 2.0);
    QCOMPARE(int(m.edges.size()), 12);
    QCOMPARE(int(m.shells.size()), 1);
    QVERIFY(m.shells[0].closed);
    QCOMPARE(m.leftToSewing, 0);
    for (const SharedEdge& e : m.edges)
        QVERIFY2(e.tolerance <= 1e-12, qPrintable(QString::number(e.tolerance)));
}

// One face's curve along part of a neighbour's (its trim halved): no edge can have both sides
// whole, so the whole group is left to sewing, which splits edges.
void TestMatchedTopology::tJunctionLeavesGroupToSewing() {
    Scene s = trimmedCube();
    s.surfaces[1].trims[0] = test::rectLoop(TrimLoopId{4}, 0, 0, 0.5, 1);
    const MatchedTopology m = matchedTopology(s, 1e-6);
    QVERIFY(m.edges.empty());
    QVERIFY(m.shells.empty());
    QCOMPARE(m.leftToSewing, 6);
}

// Faces the import's record touches keep it: only the others are matched, with ids above the
// record's.
void TestMatchedTopology::recordedFacesAreLeftAlone() {
    Scene s = trimmedCube();
    SharedEdge e;
    e.id = EdgeId{40};
    e.sides = {EdgeUse{SurfaceId{1}, TrimLoopId{2}, 0, false},
               EdgeUse{SurfaceId{5}, TrimLoopId{6}, 0, true}};
    s.topology.edges.push_back(e);
    Shell shell;
    shell.id = ShellId{7};
    shell.faces = {SurfaceId{1}, SurfaceId{5}};
    s.topology.shells.push_back(shell);
    const MatchedTopology m = matchedTopology(s, 1e-6);
    // The other four are paired among themselves (top, back, left and right: five edges); their
    // curves along the recorded faces are free, as the record's faces are built without them.
    QCOMPARE(int(m.edges.size()), 5);
    QCOMPARE(m.faces, 4);
    QCOMPARE(m.leftToSewing, 0);
    QCOMPARE(int(m.shells.size()), 1);
    QVERIFY(!m.shells[0].closed);
    for (const SharedEdge& found : m.edges) {
        QVERIFY(found.id.value > 40);
        for (const EdgeUse& u : found.sides)
            QVERIFY(u.surface != SurfaceId{1} && u.surface != SurfaceId{5});
    }
    QVERIFY(m.shells[0].id.value > 7);
    // A second, separate trimmed cube is one more closed shell.
    Scene other = trimmedCube();
    for (Surface& f : other.surfaces) {
        f.id.value += 100;
        for (TrimLoop& l : f.trims)
            l.id.value += 100;
        for (glm::dvec3& p : f.geometry.points)
            p.x += 5;
        s.surfaces.push_back(f);
    }
    const MatchedTopology both = matchedTopology(s, 1e-6);
    QCOMPARE(int(both.edges.size()), 17);
    QCOMPARE(int(both.shells.size()), 2);
    QCOMPARE(int(std::count_if(both.shells.begin(), both.shells.end(),
                               [](const Shell& sh) { return sh.closed; })),
             1);
}

QTEST_GUILESS_MAIN(TestMatchedTopology)
#include "tst_matched_topology.moc"
