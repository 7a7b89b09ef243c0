// Keep Seams Closed (model/document/seamkeeper.h, Document::setControlPoints with a seam link): a
// drag of a teapot patch's boundary point keeps the seam closed (and tangent with Keep Tangency),
// as one undo step; a trimmed face's drag is reported by what it opens.
#include "model/analysis/continuity.h"
#include "model/document/document.h"
#include "model/document/seamkeeper.h"
#include "model/io/knotfile.h"
#include "topology_fixtures.h"
#include "ui/edit/commands.h"

#include <QTest>
#include <QUndoStack>

using namespace kw;

namespace {

Scene teapot() {
    QString error;
    const auto s = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/teapot.knot"));
    if (!s)
        qFatal("%s", qPrintable(s.message()));
    return *s;
}

/// A point inside a side (not a corner) of a patch, on a boundary another patch shares, where
/// the two meet G1 or better: its surface, index and the edge's index in `report`.
struct SeamPoint {
    SurfaceId surface;
    int index = -1;
    SurfaceId neighbour;
};

std::optional<SeamPoint> seamPoint(const Scene& scene, const ContinuityReport& report) {
    for (const EdgeContinuity& e : report.edges) {
        const ContinuitySide& a = e.edge.sides[0];
        const ContinuitySide& b = e.edge.sides[1];
        if (a.surface == b.surface || e.continuity == ContinuityClass::G0 ||
            e.continuity == ContinuityClass::Open)
            continue;
        const Surface* s = nullptr;
        for (const Surface& x : scene.surfaces)
            s = x.id == a.surface ? &x : s;
        const NurbsSurface& g = s->geometry;
        int i = 1, j = 1;
        switch (a.domainEdge) {
        case DomainEdge::U0:
            i = 0;
            break;
        case DomainEdge::U1:
            i = g.countU - 1;
            break;
        case DomainEdge::V0:
            j = 0;
            break;
        default:
            j = g.countV - 1;
            break;
        }
        return SeamPoint{a.surface, g.index(i, j), b.surface};
    }
    return std::nullopt;
}

const EdgeContinuity* edgeBetween(const ContinuityReport& r, SurfaceId a, SurfaceId b) {
    for (const EdgeContinuity& e : r.edges)
        if ((e.edge.sides[0].surface == a && e.edge.sides[1].surface == b) ||
            (e.edge.sides[0].surface == b && e.edge.sides[1].surface == a))
            return &e;
    return nullptr;
}

} // namespace

class TestSeamKeeper : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void dragKeepsTeapotSeam_data();
    void dragKeepsTeapotSeam();
    void wholeSurfaceMoveLinksNothing();
    void trimmedDragReportsWhatItOpens();
};

void TestSeamKeeper::dragKeepsTeapotSeam_data() {
    QTest::addColumn<int>("link");
    QTest::newRow("off") << int(Document::SeamLink::Off);
    QTest::newRow("keep seams closed") << int(Document::SeamLink::Position);
    QTest::newRow("keep tangency") << int(Document::SeamLink::Tangency);
}

// A drag in steps (as the view applies it), then the command the view pushes on release.
void TestSeamKeeper::dragKeepsTeapotSeam() {
    QFETCH(int, link);
    const Document::SeamLink seamLink = Document::SeamLink(link);
    const Scene original = teapot();
    const ContinuityReport before = continuityReport(original, {});
    const std::optional<SeamPoint> at = seamPoint(original, before);
    QVERIFY(at);
    Document doc;
    QVERIFY(doc.resetScene(original));
    doc.setSeamLink(seamLink);
    QUndoStack stack;
    const glm::dvec3 from = doc.surface(at->surface)->geometry.points[size_t(at->index)];
    const glm::dvec3 delta = 0.15 * glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
    for (int k = 1; k <= 5; ++k)
        QVERIFY(doc.setControlPoints(at->surface, {at->index}, {from + delta * (k / 5.0)}));
    auto command = MoveControlPoints::create(&doc, at->surface, {at->index}, {from}, {from + delta},
                                             MoveKind::Drag);
    QVERIFY(command);
    QVERIFY(pushCommand(&stack, std::move(command)));
    QCOMPARE(stack.count(), 1);
    // Measured on the edges as they were found before the drag (the overlay keeps them).
    ContinuityReport after = before;
    std::vector<SurfaceId> faces = {at->surface, at->neighbour};
    std::sort(faces.begin(), faces.end());
    updateContinuity(after, doc.scene(), faces);
    const EdgeContinuity* e = edgeBetween(after, at->surface, at->neighbour);
    const EdgeContinuity* e0 = edgeBetween(before, at->surface, at->neighbour);
    QVERIFY(e && e0);
    if (seamLink == Document::SeamLink::Off) {
        QVERIFY2(e->g0 > 0.01, qPrintable(QString::number(e->g0)));
    } else {
        QVERIFY2(e->g0 <= 1e-9, qPrintable(QString::number(e->g0)));
        if (seamLink == Document::SeamLink::Tangency)
            QVERIFY2(
                e->g1Degrees <= e0->g1Degrees + 0.01,
                qPrintable(QStringLiteral("%1 before %2").arg(e->g1Degrees).arg(e0->g1Degrees)));
        else
            QVERIFY2(e->g1Degrees > e0->g1Degrees + 0.01,
                     qPrintable(QString::number(e->g1Degrees)));
    }
    // One undo restores both patches (every patch, in fact); redo moves them again.
    stack.undo();
    for (size_t k = 0; k < original.surfaces.size(); ++k)
        for (size_t p = 0; p < original.surfaces[k].geometry.points.size(); ++p)
            QVERIFY(glm::length(doc.scene().surfaces[k].geometry.points[p] -
                                original.surfaces[k].geometry.points[p]) <= 1e-12);
    // Undo replays the link the step was made with, whatever the setting is now.
    doc.setSeamLink(Document::SeamLink::Off);
    stack.redo();
    ContinuityReport again = before;
    updateContinuity(again, doc.scene(), faces);
    QCOMPARE(edgeBetween(again, at->surface, at->neighbour)->g0, e->g0);
}

void TestSeamKeeper::wholeSurfaceMoveLinksNothing() {
    const Scene scene = teapot();
    const std::optional<SeamPoint> at = seamPoint(scene, continuityReport(scene, {}));
    QVERIFY(at);
    const Surface* s = nullptr;
    for (const Surface& x : scene.surfaces)
        s = x.id == at->surface ? &x : s;
    const NurbsSurface& g = s->geometry;
    std::vector<int> all;
    std::vector<glm::dvec3> moved;
    for (int k = 0; k < int(g.points.size()); ++k) {
        all.push_back(k);
        moved.push_back(g.points[size_t(k)] + glm::dvec3(1.0, 0.0, 0.0));
    }
    QVERIFY(linkedMoves(scene, s->id, all, moved, true).empty());
    // One of its boundary points alone carries the neighbour's (and, with tangency, the next
    // rows' on both sides).
    const std::vector<LinkedMove> g0 =
        linkedMoves(scene, s->id, {at->index}, {moved[size_t(at->index)]}, false);
    QVERIFY(!g0.empty());
    QVERIFY(std::any_of(g0.begin(), g0.end(),
                        [&](const LinkedMove& m) { return m.surface == at->neighbour; }));
    QVERIFY(linkedMoves(scene, s->id, {at->index}, {moved[size_t(at->index)]}, true).size() >
            g0.size());
}

// A trimmed face (the recorded cube) shares no control point: the drag opens its seams, and
// the report says how many and how far.
void TestSeamKeeper::trimmedDragReportsWhatItOpens() {
    Scene scene = test::cubeScene();
    ContinuityReport report = continuityReport(scene, {});
    QCOMPARE(seamOpeningText(seamsOpenAt(report, {SurfaceId{1}})), QString());
    QVERIFY(linkedMoves(scene, SurfaceId{1}, {0}, {glm::dvec3(0, 0, -0.8)}, true).empty());
    scene.surfaces[0].geometry.points[0].z -= 0.8;
    updateContinuity(report, scene, {SurfaceId{1}});
    QCOMPARE(seamOpeningText(seamsOpenAt(report, {SurfaceId{1}})),
             QStringLiteral("opens 2 seams, max gap 0.8"));
}

QTEST_GUILESS_MAIN(TestSeamKeeper)
#include "tst_seamkeeper.moc"
