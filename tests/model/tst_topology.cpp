// The topology a B-rep import keeps (model/document/topology.h) without OpenCASCADE: .knot round
// trip with every field and old files, the reader's errors for inconsistent references, the CAD
// hand-over, Document's edits and their exact undo, the gap closing's renumbering, and the seam
// gaps of edited faces (model/document/seamgaps.h) on a cube of six faces.
#include "expected_test_util.h"
#include "model/cad/handover.h"
#include "model/document/document.h"
#include "model/document/seamgaps.h"
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"
#include "model/nurbs/trim.h"
#include "topology_fixtures.h"
#include "ui/edit/commands.h"
#include "ui/edit/modelcommands.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

using namespace kw;
using namespace kw::test;

namespace {

// The cube with every topology field away from its default.
Scene richCube() {
    Scene scene = cubeScene();
    scene.topology.edges[3].tolerance = 0.1 + 0.2; // a double that text would round
    scene.topology.edges[5].sides[0].reversed = true;
    Shell& shell = scene.topology.shells.front();
    shell.faces.pop_back();
    Shell second;
    second.id = ShellId{7};
    second.closed = false;
    second.solid = -1;
    second.faces = {SurfaceId{6}};
    shell.solid = 3;
    scene.topology.shells.push_back(second);
    return scene;
}

QJsonObject asJson(const Scene& scene) {
    return QJsonDocument::fromJson(sceneToJson(scene)).object();
}

// Sets the value at a path of member names and array indices in a JSON tree.
void setAt(QJsonValueRef ref, QStringList path, const QJsonValue& value) {
    if (path.isEmpty()) {
        ref = value;
        return;
    }
    const QString head = path.takeFirst();
    bool isIndex = false;
    const int index = head.toInt(&isIndex);
    if (isIndex) {
        QJsonArray a = ref.toArray();
        setAt(a[index], path, value);
        ref = a;
    } else {
        QJsonObject o = ref.toObject();
        setAt(o[head], path, value);
        ref = o;
    }
}

QByteArray withValue(const Scene& scene, const QString& path, const QJsonValue& value) {
    QJsonObject root = asJson(scene);
    QStringList parts = path.split(QLatin1Char('.'));
    const QString head = parts.takeFirst();
    setAt(root[head], parts, value);
    return QJsonDocument(root).toJson();
}

// The edges with a side at the corner S(0, 0) of `surface` (curves 0 and 3 of its loop).
std::vector<EdgeId> cornerEdges(const Scene& scene, SurfaceId surface) {
    std::vector<EdgeId> out;
    for (const SharedEdge& e : scene.topology.edges)
        for (const EdgeUse& side : e.sides)
            if (side.surface == surface && (side.curve == 0 || side.curve == 3))
                out.push_back(e.id);
    return out;
}

} // namespace

class TestTopology : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void cubeFixtureIsValid();
    void knotFileKeepsEveryField();
    void filesWithoutTopologyStayValid();
    void readerRejectsInconsistentReferences_data();
    void readerRejectsInconsistentReferences();
    void handoverKeepsTopology();
    void objKeepsTopology();
    void removeSurfaceKeepsRecordConsistent();
    void removeTrimLoopKeepsRecordConsistent();
    void replaceTrimLoopKeepsItsEdges();
    void bridgedGapRenumbersSides();
    void topologyOfSelectedFaces();
    void unEditedCubeIsClosed();
    void movedCornerOpensItsTwoEdges_data();
    void movedCornerOpensItsTwoEdges();
    void movedTrimCurveOpensItsEdge();
    void manyEdgesSharedOverThreads();
};

void TestTopology::cubeFixtureIsValid() {
    const Scene scene = cubeScene();
    KW_VERIFY_OK(checkScene(scene));
    QCOMPARE(scene.topology.edges.size(), size_t(12));
    for (const SharedEdge& e : scene.topology.edges) {
        QVERIFY(e.sides[0].surface != e.sides[1].surface);
        QVERIFY(e.sides[1].reversed); // U x V points out of every face: neighbours run opposite
    }
}

// Every field written reads back equal (doubles bit for bit), and the file says the current
// version.
void TestTopology::knotFileKeepsEveryField() {
    const Scene scene = richCube();
    KW_VERIFY_OK(checkScene(scene));
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("cube.knot"));
    KW_VERIFY_OK(writeKnotFile(path, scene));
    const auto back = readKnotFile(path);
    QVERIFY2(back, qPrintable(back.message()));
    QVERIFY(back->topology == scene.topology);
    QVERIFY(*back == scene);
    QCOMPARE(asJson(scene).value(QStringLiteral("version")).toString(),
             QStringLiteral("%1.%2").arg(kKnotFormatMajor).arg(kKnotFormatMinor));
    const QJsonObject shell =
        asJson(scene)[QStringLiteral("topology")][QStringLiteral("shells")][1].toObject();
    QVERIFY(!shell.contains(QStringLiteral("solid"))); // -1 is left out
}

// A scene without topology writes no "topology" member, and a 1.2 file (the samples) reads
// with an empty one.
void TestTopology::filesWithoutTopologyStayValid() {
    Scene plain = cubeScene();
    plain.topology = {};
    QVERIFY(!asJson(plain).contains(QStringLiteral("topology")));
    const auto sphere = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/sphere.knot"));
    QVERIFY2(sphere, qPrintable(sphere.message()));
    QVERIFY(sphere->topology.empty());
    QJsonObject old = asJson(cubeScene());
    old.insert(QStringLiteral("version"), QStringLiteral("1.2"));
    old.remove(QStringLiteral("topology"));
    const auto read = sceneFromJson(QJsonDocument(old).toJson(), "old.knot");
    QVERIFY2(read, qPrintable(read.message()));
    QVERIFY(read->topology.empty());
    QCOMPARE(read->surfaces.size(), size_t(6));
}

void TestTopology::readerRejectsInconsistentReferences_data() {
    QTest::addColumn<QString>("path");
    QTest::addColumn<QJsonValue>("value");
    QTest::addColumn<QString>("expected");
    const QString e0 = QStringLiteral("topology.edges.0.");
    QTest::newRow("unknown surface")
        << e0 + "sides.1.surface" << QJsonValue(99)
        << "t.knot: $.topology.edges[0].sides[1].surface: edge 1 names surface 99, which the "
           "scene does not have";
    QTest::newRow("loop of another surface")
        << e0 + "sides.0.loop" << QJsonValue(12)
        << "t.knot: $.topology.edges[0].sides[0].loop: edge 1 names trim loop 12 of surface 1, "
           "which that surface does not have";
    QTest::newRow("curve out of range")
        << e0 + "sides.0.curve" << QJsonValue(4)
        << "t.knot: $.topology.edges[0].sides[0].curve: edge 1 names curve 4 of trim loop 11, "
           "which has 4 curve(s)";
    QTest::newRow("curve of two edges")
        << "topology.edges.1.sides.0.curve" << QJsonValue(0)
        << "t.knot: $.topology.edges[1].sides[0]: curve 0 of trim loop 11 is already a side of "
           "another edge (or of this one)";
    QTest::newRow("ids out of order")
        << "topology.edges.1.id" << QJsonValue(1)
        << "t.knot: $.topology.edges[1].id: edge id 1 does not follow 1 (edges are listed once "
           "each, in ascending id order)";
    QTest::newRow("negative tolerance")
        << e0 + "tolerance" << QJsonValue(-1e-7)
        << "t.knot: $.topology.edges[0].tolerance: -1e-07 is outside the allowed range [0, inf]";
    QTest::newRow("one side")
        << e0 + "sides" << QJsonValue(QJsonArray{QJsonObject{}})
        << "t.knot: $.topology.edges[0].sides: expected 2 sides, one per face, found 1 elements";
    QTest::newRow("reversed not a flag")
        << e0 + "sides.1.reversed" << QJsonValue(1)
        << "t.knot: $.topology.edges[0].sides[1].reversed: expected true or false, found the "
           "number 1";
    QTest::newRow("unknown shell face")
        << "topology.shells.0.faces.2" << QJsonValue(40)
        << "t.knot: $.topology.shells[0].faces[2]: shell 1 names surface 40, which the scene "
           "does not have";
    QTest::newRow("face listed twice")
        << "topology.shells.0.faces.2" << QJsonValue(2)
        << "t.knot: $.topology.shells[0].faces[2]: surface 2 does not follow 2 (a shell lists "
           "each face once, in ascending id order)";
    QTest::newRow("missing closed")
        << "topology.shells.0.closed" << QJsonValue(QJsonValue::Undefined)
        << "t.knot: $.topology.shells[0].closed: missing required member";
}

// A reference to what the scene does not have is refused with the file and the JSON path.
void TestTopology::readerRejectsInconsistentReferences() {
    QFETCH(QString, path);
    QFETCH(QJsonValue, value);
    QFETCH(QString, expected);
    QByteArray json;
    if (value.isUndefined()) {
        QJsonObject root = asJson(cubeScene());
        QJsonObject topology = root[QStringLiteral("topology")].toObject();
        QJsonArray shells = topology[QStringLiteral("shells")].toArray();
        QJsonObject shell = shells[0].toObject();
        shell.remove(QStringLiteral("closed"));
        shells[0] = shell;
        topology[QStringLiteral("shells")] = shells;
        root[QStringLiteral("topology")] = topology;
        json = QJsonDocument(root).toJson();
    } else {
        json = withValue(cubeScene(), path, value);
    }
    const auto result = sceneFromJson(json, QStringLiteral("t.knot"));
    QVERIFY(!result);
    QCOMPARE(result.message(), expected);
}

void TestTopology::handoverKeepsTopology() {
    ImportResult r;
    r.scene = richCube();
    for (size_t k = 0; k < r.scene.surfaces.size(); ++k)
        r.sourceFaces.push_back(int(k + 1));
    const QByteArray block = encodeImportHandover(r);
    const auto back = decodeImportHandover(block);
    QVERIFY2(back, qPrintable(back.message()));
    QVERIFY(back->scene.topology == r.scene.topology);
    QVERIFY(back->scene == r.scene);
    // A reference the scene does not have is refused, naming it.
    ImportResult bad = r;
    bad.scene.topology.edges[2].sides[1].surface = SurfaceId{77};
    const auto refused = decodeImportHandover(encodeImportHandover(bad));
    QVERIFY(!refused);
    const QString why = refused.message();
    QVERIFY2(why.contains(QLatin1String("topology: edges[2].sides[1].surface")), qPrintable(why));
    // Cut anywhere inside the topology, the block is refused as truncated.
    const qsizetype cut = block.size() - 200;
    QVERIFY(!decodeImportHandover(block.left(cut)));
}

// The OBJ writer keeps the record in '# knotwork' lines, so .knot -> OBJ -> .knot is exact; a
// file cut among those lines, or naming what it does not have, is refused with the line.
void TestTopology::objKeepsTopology() {
    const Scene scene = richCube();
    const QByteArray obj = writeObj(scene);
    Scene back;
    ImportReport report;
    KW_VERIFY_OK(parseObj(obj, QStringLiteral("t.obj"), back, report));
    QVERIFY(back.topology == scene.topology);
    QVERIFY(back == scene);

    QByteArray cut = obj.left(obj.lastIndexOf("# knotwork shell"));
    const auto failed = parseObj(cut, QStringLiteral("t.obj"), back, report);
    QVERIFY(!failed);
    QVERIFY2(
        failed.message().contains(QLatin1String("'# knotwork topology 12 2' but the file holds 12 "
                                                "edge(s) and 1 shell(s)")),
        qPrintable(failed.message()));

    // Edge 3's first side names surface 99.
    QList<QByteArray> lines = obj.split('\n');
    int line = 0;
    for (int k = 0; k < lines.size(); ++k)
        if (lines[k].startsWith("# knotwork edge 3 ")) {
            QList<QByteArray> t = lines[k].split(' ');
            t[5] = "99";
            lines[k] = t.join(' ');
            line = k + 1;
        }
    QVERIFY(line > 0);
    const auto badEdge = parseObj(lines.join('\n'), QStringLiteral("t.obj"), back, report);
    QVERIFY(!badEdge);
    QVERIFY2(badEdge.message().startsWith(
                 QStringLiteral("t.obj:%1: knotwork topology: edges[2]").arg(line)),
             qPrintable(badEdge.message()));
}

// Removing a face takes its edges and its place in the shell, and opens the shell; undo and
// redo restore the record exactly, also when two faces were removed.
void TestTopology::removeSurfaceKeepsRecordConsistent() {
    Document doc;
    QUndoStack stack;
    const Scene cube = cubeScene();
    QVERIFY(doc.resetScene(cube));
    QVERIFY(pushCommand(&stack, RemoveSurface::create(&doc, SurfaceId{2})));
    const Topology& t = doc.scene().topology;
    QCOMPARE(t.edges.size(), size_t(8));
    for (const SharedEdge& e : t.edges)
        QVERIFY(!edgeTouches(e, SurfaceId{2}));
    QCOMPARE(t.shells.front().faces.size(), size_t(5));
    QVERIFY(!t.shells.front().closed);
    KW_VERIFY_OK(checkScene(doc.scene()));
    const Topology afterOne = t;
    QVERIFY(pushCommand(&stack, RemoveSurface::create(&doc, SurfaceId{5})));
    QCOMPARE(t.edges.size(), size_t(5)); // face 5 shares one edge with face 2
    KW_VERIFY_OK(checkScene(doc.scene()));
    stack.undo();
    QVERIFY(doc.scene().topology == afterOne);
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
    stack.redo();
    stack.redo();
    QCOMPARE(doc.scene().topology.edges.size(), size_t(5));
    stack.undo();
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
    // A face added later carries no topology and removing it changes none.
    Surface extra = cube.surfaces.front();
    extra.id = {};
    extra.trims.front().id = {};
    QVERIFY(pushCommand(&stack, AddSurface::create(&doc, extra)));
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
}

// Removing a loop takes the edges with a side on it (the shell is no longer closed); its undo
// puts them back.
void TestTopology::removeTrimLoopKeepsRecordConsistent() {
    Document doc;
    QUndoStack stack;
    const Scene cube = cubeScene();
    QVERIFY(doc.resetScene(cube));
    QVERIFY(pushCommand(&stack, RemoveTrimLoop::create(&doc, SurfaceId{3}, TrimLoopId{13})));
    QCOMPARE(doc.scene().topology.edges.size(), size_t(8));
    QVERIFY(!doc.scene().topology.shells.front().closed);
    QCOMPARE(doc.scene().topology.shells.front().faces.size(), size_t(6));
    KW_VERIFY_OK(checkScene(doc.scene()));
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
    stack.redo();
    QCOMPARE(doc.scene().topology.edges.size(), size_t(8));
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
}

// An edit of a loop's curves (ReplaceTrimLoop) keeps its edges when it keeps its curve count;
// one that changes the count drops them, and its undo restores them.
void TestTopology::replaceTrimLoopKeepsItsEdges() {
    Document doc;
    QUndoStack stack;
    const Scene cube = cubeScene();
    QVERIFY(doc.resetScene(cube));
    TrimLoop moved = cube.surfaces[0].trims[0];
    moved.curves[1].points[0].x = moved.curves[0].points[1].x = 0.9;
    QVERIFY(pushCommand(
        &stack, ReplaceTrimLoop::create(&doc, SurfaceId{1}, moved, QStringLiteral("move"))));
    QVERIFY(doc.scene().topology == cube.topology);
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
    TrimLoop split = cube.surfaces[0].trims[0];
    split.curves[0] = cubeSegment({0, 0}, {0.5, 0});
    split.curves.insert(split.curves.begin() + 1, cubeSegment({0.5, 0}, {1, 0}));
    QVERIFY(pushCommand(
        &stack, ReplaceTrimLoop::create(&doc, SurfaceId{1}, split, QStringLiteral("split"))));
    QCOMPARE(doc.scene().topology.edges.size(), size_t(8));
    QVERIFY(!doc.scene().topology.shells.front().closed);
    KW_VERIFY_OK(checkScene(doc.scene()));
    stack.undo();
    QVERIFY(doc.scene().topology == cube.topology);
}

// A straight curve inserted to close a gap (closeSceneTrimLoops, as every import ends) moves
// the sides on later curves of that loop to their new numbers.
void TestTopology::bridgedGapRenumbersSides() {
    Scene scene = cubeScene();
    TrimLoop& loop = scene.surfaces[0].trims[0];
    loop.curves[2].points[0] = {1.0, 0.8}; // a gap of 0.2 after curve 1
    const std::vector<EdgeUse> before = [&] {
        std::vector<EdgeUse> sides;
        for (const SharedEdge& e : scene.topology.edges)
            for (const EdgeUse& s : e.sides)
                if (s.surface == SurfaceId{1})
                    sides.push_back(s);
        return sides;
    }();
    QVERIFY(!closeSceneTrimLoops(scene).isEmpty());
    QCOMPARE(loop.curves.size(), size_t(5));
    KW_VERIFY_OK(checkScene(scene));
    size_t k = 0;
    for (const SharedEdge& e : scene.topology.edges)
        for (const EdgeUse& s : e.sides)
            if (s.surface == SurfaceId{1}) {
                QCOMPARE(s.curve, before[k].curve < 2 ? before[k].curve : before[k].curve + 1);
                ++k;
            }
    QCOMPARE(k, size_t(4));
}

// Export Selected's record: the edges among the selected faces, their shells cut down.
void TestTopology::topologyOfSelectedFaces() {
    const Scene two = cubesScene(2);
    std::vector<SurfaceId> faces;
    for (std::uint32_t k = 17; k <= 22; ++k)
        faces.push_back(SurfaceId{k}); // the second cube
    Topology part = topologyOfFaces(two.topology, faces);
    QCOMPARE(part.edges.size(), size_t(12));
    QCOMPARE(part.shells.size(), size_t(1));
    QVERIFY(part.shells[0] == two.topology.shells[1]);
    faces.pop_back();
    faces.push_back(SurfaceId{1}); // and one face of the first
    std::sort(faces.begin(), faces.end());
    part = topologyOfFaces(two.topology, faces);
    QCOMPARE(part.edges.size(), size_t(8));
    QCOMPARE(part.shells.size(), size_t(2));
    QVERIFY(!part.shells[0].closed && !part.shells[1].closed);
    QCOMPARE(part.shells[0].faces, std::vector<SurfaceId>{SurfaceId{1}});
    Scene selected = two;
    std::erase_if(selected.surfaces, [&](const Surface& s) {
        return !std::binary_search(faces.begin(), faces.end(), s.id);
    });
    selected.topology = part;
    KW_VERIFY_OK(checkScene(selected));
}

void TestTopology::unEditedCubeIsClosed() {
    const Scene scene = cubeScene(2.5);
    const std::vector<SeamGap> gaps = seamGaps(scene);
    QCOMPARE(gaps.size(), size_t(12));
    for (const SeamGap& g : gaps) {
        QVERIFY2(g.gap <= 1e-12, qPrintable(QString::number(g.gap)));
        QVERIFY(!g.open());
    }
    const std::vector<ShellState> shells = closedShells(scene, gaps);
    QCOMPARE(shells.size(), size_t(1));
    QVERIFY(shells.front().closed);
    QCOMPARE(shells.front().openEdges, 0);
    QCOMPARE(shells.front().faces, 6);
    QCOMPARE(shells.front().solid, 0);
}

void TestTopology::movedCornerOpensItsTwoEdges_data() {
    QTest::addColumn<int>("face");
    QTest::addColumn<glm::dvec3>("direction");
    QTest::addColumn<double>("d");
    // The top face's corner S(0, 0) = (0, 0, 2) of a cube of side 2: out of the face, and
    // along each of its two edges (a boundary moved along itself).
    QTest::newRow("normal") << 1 << glm::dvec3(0, 0, 1) << 1e-3;
    QTest::newRow("along u") << 1 << glm::dvec3(1, 0, 0) << 0.05;
    QTest::newRow("along v, inwards") << 1 << glm::dvec3(0, 1, 0) << 2e-4;
    QTest::newRow("slanted") << 4 << glm::normalize(glm::dvec3(-1, 0, 1)) << 3e-3;
}

// A control point on a shared boundary moved by d: the two edges through it are d apart (the
// point is the corner S(0, 0), which a clamped surface interpolates), the others stay closed,
// and the shell is open; moved back, it is closed again.
void TestTopology::movedCornerOpensItsTwoEdges() {
    QFETCH(int, face);
    QFETCH(glm::dvec3, direction);
    QFETCH(double, d);
    Document doc;
    QVERIFY(doc.resetScene(cubeScene(2.0)));
    const SurfaceId id{std::uint32_t(face + 1)};
    const glm::dvec3 corner = doc.surface(id)->geometry.points[0];
    QVERIFY(doc.setControlPoints(id, {0}, {corner + d * direction}));
    const std::vector<SeamGap> gaps = seamGaps(doc.scene());
    const std::vector<EdgeId> moved = cornerEdges(doc.scene(), id);
    QCOMPARE(moved.size(), size_t(2));
    for (const SeamGap& g : gaps) {
        if (std::find(moved.begin(), moved.end(), g.edge) != moved.end()) {
            QVERIFY2(std::abs(g.gap - d) <= 0.01 * d,
                     qPrintable(QStringLiteral("edge %1: gap %2, moved %3")
                                    .arg(g.edge.value)
                                    .arg(g.gap)
                                    .arg(d)));
            QVERIFY(g.open());
            QVERIFY(glm::length(g.where - (corner + d * direction)) <= 1e-9 ||
                    glm::length(g.where - corner) <= 1e-9);
        } else {
            QVERIFY2(g.gap <= 1e-12, qPrintable(QString::number(g.gap)));
        }
    }
    std::vector<ShellState> shells = closedShells(doc.scene(), gaps);
    QVERIFY(!shells.front().closed);
    QCOMPARE(shells.front().openEdges, 2);
    QVERIFY(std::abs(shells.front().largestGap - d) <= 0.01 * d);
    QVERIFY(doc.setControlPoints(id, {0}, {corner}));
    shells = closedShells(doc.scene(), seamGaps(doc.scene()));
    QVERIFY(shells.front().closed);
}

// A trim curve's end moved inside its face by d (in a face of scale 1 in (u, v) and 3D) opens
// the edges that curve and its neighbour are, by d.
void TestTopology::movedTrimCurveOpensItsEdge() {
    Document doc;
    QVERIFY(doc.resetScene(cubeScene()));
    const double d = 0.01;
    // Curve 1 (u = 1) of face 6 moved to u = 1 - d: its whole edge, and the ends of its
    // neighbours' edges.
    const SurfaceId id{6};
    const TrimLoopId loop{16};
    QVERIFY(
        doc.setTrimPoints({{id, loop, 0, 1}, {id, loop, 1, 0}, {id, loop, 1, 1}, {id, loop, 2, 0}},
                          {{1 - d, 0}, {1 - d, 0}, {1 - d, 1}, {1 - d, 1}}));
    const std::vector<SeamGap> gaps = seamGaps(doc.scene());
    int open = 0;
    for (const SeamGap& g : gaps) {
        if (!g.open())
            continue;
        ++open;
        QVERIFY2(std::abs(g.gap - d) <= 0.01 * d, qPrintable(QString::number(g.gap)));
    }
    QCOMPARE(open, 3);
    QVERIFY(!closedShells(doc.scene(), gaps).front().closed);
}

// Enough edges to share them out over threads: the same gaps as cube by cube, in order.
void TestTopology::manyEdgesSharedOverThreads() {
    Document doc;
    QVERIFY(doc.resetScene(cubesScene(30)));
    const SurfaceId moved{16 * 29 + 2}; // the top face of the last cube
    const glm::dvec3 corner = doc.surface(moved)->geometry.points[0];
    QVERIFY(doc.setControlPoints(moved, {0}, {corner + glm::dvec3(0, 0, 0.01)}));
    const std::vector<SeamGap> gaps = seamGaps(doc.scene());
    QCOMPARE(gaps.size(), size_t(360));
    Scene last = cubeScene();
    for (Surface& s : last.surfaces)
        for (glm::dvec3& p : s.geometry.points)
            p.x += 58.0;
    last.surfaces[1].geometry.points[0] += glm::dvec3(0, 0, 0.01);
    const std::vector<SeamGap> alone = seamGaps(last);
    for (size_t k = 0; k < gaps.size(); ++k) {
        QCOMPARE(gaps[k].edge, doc.scene().topology.edges[k].id);
        if (k < 348)
            QVERIFY(!gaps[k].open());
        else
            QCOMPARE(gaps[k].gap, alone[k - 348].gap);
    }
    const std::vector<ShellState> shells = closedShells(doc.scene(), gaps);
    QCOMPARE(shells.size(), size_t(30));
    // Outside the precondition: a side the scene lacks is an open seam, not a crash.
    Scene broken = doc.scene();
    broken.topology.edges[5].sides[1].curve = 9;
    broken.topology.edges[6].sides[0].surface = SurfaceId{9999};
    const std::vector<SeamGap> lacking = seamGaps(broken);
    QVERIFY(std::isinf(lacking[5].gap) && lacking[5].open());
    QVERIFY(std::isinf(lacking[6].gap) && lacking[6].open());
    QVERIFY(!closedShells(broken, lacking)[0].closed);
    for (size_t c = 0; c < 30; ++c)
        QCOMPARE(shells[c].closed, c != 29);
}

QTEST_GUILESS_MAIN(TestTopology)
#include "tst_topology.moc"
