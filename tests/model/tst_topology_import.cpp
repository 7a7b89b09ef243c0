// The topology kept by the CAD import (model/cad/occttopology.cpp) on the closed solids of
// tests/data: every shell closed and every seam within its edge's tolerance as imported, the
// record through .knot, and a control point on a shared boundary moved by d opening that edge
// by d; `knotwork info --json` reports the same.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/cad/cadimport.h"
#include "model/document/document.h"
#include "model/document/seamgaps.h"
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"

#include <QElapsedTimer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QTest>
#include <set>

using namespace kw;

namespace {

QString data(const QString& name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/") + name;
}

std::optional<ImportResult> import(const QString& name) {
    Expected<ImportResult> r = importFile(data(name));
    if (!r) {
        qWarning("%s", qPrintable(r.message()));
        return std::nullopt;
    }
    return std::move(*r);
}

double modelSize(const Scene& scene) {
    glm::dvec3 lo, hi;
    return sceneBounds(scene, lo, hi) ? glm::length(hi - lo) : 1.0;
}

/// One side's edge S(c(t)) on its surface.
struct EdgeCurve {
    const NurbsSurface* surface = nullptr;
    const NurbsCurve2* curve = nullptr;
    Interval domain;
    EdgeCurve(const Scene& scene, const EdgeUse& side) {
        for (const Surface& s : scene.surfaces)
            if (s.id == side.surface)
                for (const TrimLoop& l : s.trims)
                    if (l.id == side.loop) {
                        surface = &s.geometry;
                        curve = &l.curves[size_t(side.curve)];
                    }
        domain = curveDomain(*curve);
    }
    glm::dvec3 point(double t) const {
        const glm::dvec2 uv = curvePoint(*curve, t);
        return surfacePoint(*surface, uv.x, uv.y);
    }
    /// The edge's direction at t, in the direction of increasing t, by a small step inwards
    /// from an end (`inwards` +1 at the start, -1 at the end).
    glm::dvec3 tangent(double t, double inwards) const {
        const double h = 1e-5 * (domain.last - domain.first) * inwards;
        return (point(t + h) - point(t)) * inwards;
    }
};

/// A control point that a clamped surface interpolates (a corner of its net) where a side of
/// a shared edge starts or ends, with the edge's direction there.
struct CornerOnEdge {
    EdgeId edge;
    SurfaceId surface;
    int index = -1; ///< NurbsSurface::index of the corner
    glm::dvec3 tangent{0.0};
};

std::optional<CornerOnEdge> cornerOnEdge(const Scene& scene) {
    for (const SharedEdge& e : scene.topology.edges) {
        if (e.sides[0].surface == e.sides[1].surface)
            continue; // a seam: moving its corner opens it from both sides at once
        const EdgeUse& side = e.sides[0];
        const Surface* s = nullptr;
        for (const Surface& x : scene.surfaces)
            s = x.id == side.surface ? &x : s;
        const TrimLoop* loop = nullptr;
        for (const TrimLoop& l : s->trims)
            loop = l.id == side.loop ? &l : loop;
        const NurbsSurface& g = s->geometry;
        const NurbsCurve2& c = loop->curves[size_t(side.curve)];
        const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
        const double tol = 1e-9 * std::hypot(du.last - du.first, dv.last - dv.first);
        const Interval dc = curveDomain(c);
        for (double t : {dc.first, dc.last}) {
            const glm::dvec2 uv = curvePoint(c, t);
            const bool atU0 = std::abs(uv.x - du.first) <= tol,
                       atU1 = std::abs(uv.x - du.last) <= tol;
            const bool atV0 = std::abs(uv.y - dv.first) <= tol,
                       atV1 = std::abs(uv.y - dv.last) <= tol;
            if (!(atU0 || atU1) || !(atV0 || atV1))
                continue;
            const double step = 1e-4 * (dc.last - dc.first) * (t == dc.first ? 1.0 : -1.0);
            const glm::dvec2 near = curvePoint(c, t + step);
            const glm::dvec3 tangent =
                surfacePoint(g, near.x, near.y) - surfacePoint(g, uv.x, uv.y);
            if (!(glm::length(tangent) > 0.0))
                continue;
            return CornerOnEdge{e.id, s->id,
                                g.index(atU0 ? 0 : g.countU - 1, atV0 ? 0 : g.countV - 1),
                                glm::normalize(tangent)};
        }
    }
    return std::nullopt;
}

} // namespace

class TestTopologyImport : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void closedSolidsImportClosed_data();
    void closedSolidsImportClosed();
    void movedBoundaryPointOpensItsEdge();
    void infoReportsTopology();
};

void TestTopologyImport::closedSolidsImportClosed_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<int>("solids");
    QTest::newRow("Pump_Nut.brep") << "Pump_Nut.brep" << 1;
    QTest::newRow("screw.step") << "screw.step" << 1;
    QTest::newRow("Axis_of_bearing.brep") << "Axis_of_bearing.brep" << 17;
}

// As imported, every shell of a closed solid is closed, every face in a shell, every seam
// within its tolerance; the record reads back equal from .knot.
void TestTopologyImport::closedSolidsImportClosed() {
    QFETCH(QString, file);
    QFETCH(int, solids);
    const std::optional<ImportResult> r = import(file);
    QVERIFY(r);
    const Scene& scene = r->scene;
    KW_VERIFY_OK(checkScene(scene));
    QVERIFY(!scene.topology.edges.empty());
    std::set<int> solidNumbers;
    size_t faces = 0;
    for (const Shell& shell : scene.topology.shells) {
        QVERIFY2(shell.closed, qPrintable(QStringLiteral("shell %1").arg(shell.id.value)));
        QVERIFY(shell.solid >= 0);
        solidNumbers.insert(shell.solid);
        faces += shell.faces.size();
    }
    QCOMPARE(int(solidNumbers.size()), solids);
    QCOMPARE(faces, scene.surfaces.size());
    QElapsedTimer clock;
    clock.start();
    const std::vector<SeamGap> gaps = seamGaps(scene);
    const qint64 ms = clock.elapsed();
    QCOMPARE(gaps.size(), scene.topology.edges.size());
    double worst = 0.0;
    for (const SeamGap& g : gaps) {
        QVERIFY2(!g.open(), qPrintable(QStringLiteral("edge %1 between surfaces %2 and %3: gap "
                                                      "%4 above its tolerance %5")
                                           .arg(g.edge.value)
                                           .arg(g.faceA.value)
                                           .arg(g.faceB.value)
                                           .arg(g.gap)
                                           .arg(g.tolerance)));
        worst = std::max(worst, g.gap);
    }
    qInfo("%s: %zu shared edges, %zu shells, largest gap %.3g (model size %.3g), seamGaps %lld "
          "ms",
          qPrintable(file), gaps.size(), scene.topology.shells.size(), worst, modelSize(scene), ms);
    // `reversed` says which way each side runs along the edge: where side A starts, side B
    // starts too (same flags) or ends (different flags), running the same way as A there.
    const double size = modelSize(scene);
    for (const SharedEdge& e : scene.topology.edges) {
        const EdgeCurve a(scene, e.sides[0]), b(scene, e.sides[1]);
        const bool same = e.sides[0].reversed == e.sides[1].reversed;
        const glm::dvec3 pa = a.point(a.domain.first), ta = a.tangent(a.domain.first, 1.0);
        const glm::dvec3 pb = b.point(same ? b.domain.first : b.domain.last);
        // B's direction along the edge: against increasing t where it runs the other way.
        const glm::dvec3 tb =
            same ? b.tangent(b.domain.first, 1.0) : -b.tangent(b.domain.last, -1.0);
        QVERIFY2(glm::length(pa - pb) <= e.tolerance + 1e-9 * size &&
                     glm::dot(ta, tb) > 0.9 * glm::length(ta) * glm::length(tb),
                 qPrintable(QStringLiteral("edge %1: sides %2 and %3 run %4")
                                .arg(e.id.value)
                                .arg(e.sides[0].reversed)
                                .arg(e.sides[1].reversed)
                                .arg(glm::dot(ta, tb))));
        // In a consistently oriented closed shell the two sides of an edge run opposite ways.
        QVERIFY(!same);
    }
    for (const ShellState& s : closedShells(scene, gaps))
        QVERIFY(s.closed);
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("part.knot"));
    QString error;
    KW_VERIFY_OK(writeKnotFile(path, scene));
    const auto back = readKnotFile(path);
    QVERIFY2(back, qPrintable(back.message()));
    QVERIFY(back->topology == scene.topology);
    // And through OBJ's '# knotwork' lines.
    Scene fromObj;
    ImportReport report;
    KW_VERIFY_OK(parseObj(writeObj(scene), QStringLiteral("part.obj"), fromObj, report));
    QVERIFY(fromObj.topology == scene.topology);
}

// A control point on a shared boundary (a corner of the net, which the surface interpolates,
// where the edge begins or ends) moved by d across the edge: that edge's gap is d (1 %), and
// the shell is open; the undo closes it again.
void TestTopologyImport::movedBoundaryPointOpensItsEdge() {
    const std::optional<ImportResult> r = import(QStringLiteral("Pump_Nut.brep"));
    QVERIFY(r);
    Document doc;
    QVERIFY(doc.resetScene(r->scene));
    const std::optional<CornerOnEdge> corner = cornerOnEdge(doc.scene());
    QVERIFY(corner);
    // Across the edge: perpendicular to its direction at the corner.
    glm::dvec3 across = glm::cross(corner->tangent, glm::dvec3(0.3, 0.5, 0.8));
    across = glm::normalize(across);
    const double d = 1e-4 * modelSize(doc.scene());
    const glm::dvec3 p = doc.surface(corner->surface)->geometry.points[size_t(corner->index)];
    QVERIFY(doc.setControlPoints(corner->surface, {corner->index}, {p + d * across}));
    const std::vector<SeamGap> gaps = seamGaps(doc.scene());
    bool found = false;
    for (const SeamGap& g : gaps)
        if (g.edge == corner->edge) {
            found = true;
            QVERIFY2(std::abs(g.gap - d) <= 0.01 * d,
                     qPrintable(QStringLiteral("gap %1, moved %2").arg(g.gap).arg(d)));
            QVERIFY(g.open());
        } else if (!edgeTouches(*findSharedEdge(doc.scene().topology, g.edge), corner->surface)) {
            QVERIFY(!g.open()); // faces not edited keep their seams with each other
        }
    QVERIFY(found);
    const Shell* shell = shellOfSurface(doc.scene().topology, corner->surface);
    QVERIFY(shell);
    for (const ShellState& s : closedShells(doc.scene(), gaps))
        if (s.shell == shell->id)
            QVERIFY(!s.closed && s.openEdges >= 1);
    QVERIFY(doc.setControlPoints(corner->surface, {corner->index}, {p}));
    for (const ShellState& s : closedShells(doc.scene(), seamGaps(doc.scene())))
        QVERIFY(s.closed);
}

// `knotwork info --json` shows the record: the shared edges, the shell closed; and in a saved
// edit, the open edge with its gap.
void TestTopologyImport::infoReportsTopology() {
    Run run = knotwork(
        {QStringLiteral("info"), data(QStringLiteral("Pump_Nut.brep")), QStringLiteral("--json")});
    QCOMPARE(run.code, 0);
    QJsonObject topology =
        QJsonDocument::fromJson(run.out.toUtf8()).object()[QStringLiteral("topology")].toObject();
    QVERIFY(topology[QStringLiteral("sharedEdges")].toInt() > 0);
    QCOMPARE(topology[QStringLiteral("openEdges")].toArray().size(), 0);
    QJsonArray shells = topology[QStringLiteral("shells")].toArray();
    QCOMPARE(shells.size(), 1);
    QVERIFY(shells[0].toObject()[QStringLiteral("closed")].toBool());
    QCOMPARE(shells[0].toObject()[QStringLiteral("solid")].toInt(), 0);

    const std::optional<ImportResult> r = import(QStringLiteral("Pump_Nut.brep"));
    QVERIFY(r);
    Scene edited = r->scene;
    const std::optional<CornerOnEdge> corner = cornerOnEdge(edited);
    QVERIFY(corner);
    const double d = 1e-3 * modelSize(edited);
    for (Surface& s : edited.surfaces)
        if (s.id == corner->surface) {
            s.geometry.points[size_t(corner->index)] +=
                d * glm::normalize(glm::cross(corner->tangent, glm::dvec3(0.3, 0.5, 0.8)));
            s.analytic = {}; // as the Document's edit drops it: the file refuses a stale form
        }
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("edited.knot"));
    QString error;
    KW_VERIFY_OK(writeKnotFile(path, edited));
    run = knotwork({QStringLiteral("info"), path, QStringLiteral("--json")});
    QCOMPARE(run.code, 0);
    topology =
        QJsonDocument::fromJson(run.out.toUtf8()).object()[QStringLiteral("topology")].toObject();
    const QJsonArray open = topology[QStringLiteral("openEdges")].toArray();
    QVERIFY(!open.isEmpty());
    bool found = false;
    for (const QJsonValue& v : open)
        if (v[QStringLiteral("edge")].toInteger() == corner->edge.value) {
            found = true;
            QVERIFY(std::abs(v[QStringLiteral("gap")].toDouble() - d) <= 0.01 * d);
        }
    QVERIFY(found);
    QVERIFY(!topology[QStringLiteral("shells")][0][QStringLiteral("closed")].toBool());
    run = knotwork({QStringLiteral("info"), path});
    QCOMPARE(run.code, 0);
    QVERIFY2(run.out.contains(QStringLiteral("edge %1 between surfaces").arg(corner->edge.value)),
             qPrintable(run.out));
}

QTEST_GUILESS_MAIN(TestTopologyImport)
#include "tst_topology_import.moc"
