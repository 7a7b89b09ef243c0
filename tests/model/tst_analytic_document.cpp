// A face's closed form (Surface::analytic) through the document and the project file: an edit
// of its geometry drops it, undo brings it back, a move, rotation, uniform scale or unit
// conversion carries it along, edits of anything else keep it; .knot 1.5 saves and reads it,
// older files read without it, and a malformed form is an error naming its place.
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "model/nurbs/analytic_eval.h"
#include "model/nurbs/nurbs_shapes.h"
#include "tests/support/analytic_fixtures.h"
#include "ui/edit/commands.h"
#include "ui/edit/modelcommands.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <numbers>
#include <numeric>

using namespace kw;
using Kind = AnalyticForm::Kind;

namespace {

constexpr double kPi = std::numbers::pi;

Scene scene() {
    Scene sc;
    sc.surfaces.push_back(test::importedCylinder());
    Surface plane;
    plane.id = SurfaceId{2};
    plane.name = QStringLiteral("Free");
    plane.geometry = makePlane({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    sc.surfaces.push_back(plane);
    sc.nextId = 3;
    return sc;
}

double diagonal(const NurbsSurface& g) {
    glm::dvec3 lo, hi;
    surfaceControlBounds(g, lo, hi);
    return glm::length(hi - lo);
}

const AnalyticForm& formOf(const Document& d) {
    return d.surface(SurfaceId{1})->analytic;
}

} // namespace

class TestAnalyticDocument : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void geometryEditsDropUndoRestores();
    void otherEditsKeep();
    void similaritiesCarryAlong();
    void unitConversionScales();
    void removalAndUndo();
    void knotFileRoundTrip();
    void olderFilesHaveNone();
    void malformedFormsAreErrors_data();
    void malformedFormsAreErrors();
};

void TestAnalyticDocument::geometryEditsDropUndoRestores() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QCOMPARE(original.kind, Kind::Cylinder);
    QUndoStack stack;
    const Surface& s = *doc.surface(SurfaceId{1});
    const glm::dvec3 p = s.geometry.points[3];

    // A control point dragged: none; undone: the very form.
    QVERIFY(pushCommand(&stack, MoveControlPoints::create(&doc, SurfaceId{1}, {3}, {p},
                                                          {p + glm::dvec3(0.0, 0.0, 0.1)})));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == original);
    stack.redo();
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();

    // A weight, a knot insertion, a degree elevation: each drops it, each undo restores it.
    QVERIFY(pushCommand(&stack, SetWeight::create(&doc, SurfaceId{1}, 1, 0.9)));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == original);
    QVERIFY(pushCommand(&stack, InsertKnot::create(&doc, SurfaceId{1}, Direction::V, 0.5)));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == original);
    QVERIFY(pushCommand(&stack, ElevateDegree::create(&doc, SurfaceId{1}, Direction::U)));
    QCOMPARE(formOf(doc).kind, Kind::None);
    // Two edits deep, then both undone.
    QVERIFY(pushCommand(&stack, SetWeight::create(&doc, SurfaceId{1}, 2, 0.8)));
    stack.undo();
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == original);

    // The document's own mutators, without commands: the same rule.
    std::vector<glm::dvec3> pts = s.geometry.points;
    QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {pts[0] + glm::dvec3(1e-9, 0, 0)}));
    QCOMPARE(formOf(doc).kind, Kind::None);
    QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {pts[0]}));
    QVERIFY(formOf(doc) == original);
    // A free-form face never gains one.
    QVERIFY(doc.setControlPoints(SurfaceId{2}, {0}, {glm::dvec3(0, 0, 0.5)}));
    QCOMPARE(doc.surface(SurfaceId{2})->analytic.kind, Kind::None);
}

void TestAnalyticDocument::otherEditsKeep() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QVERIFY(doc.setName(SurfaceId{1}, QStringLiteral("Renamed")));
    Material m;
    m.color = {0.2, 0.4, 0.6};
    QVERIFY(doc.setMaterial(SurfaceId{1}, m));
    QVERIFY(doc.setPartitions(SurfaceId{1}, 4, 7));
    QVERIFY(doc.setHidden(SurfaceId{1}, true));
    TrimLoop loop;
    loop.id = doc.allocateTrimLoopId();
    loop.curves.push_back(makeCircle2({0.5, 0.5}, 0.2));
    QVERIFY(doc.insertTrimLoop(SurfaceId{1}, 0, loop));
    QVERIFY(formOf(doc) == original);
    QVERIFY(doc.removeTrimLoop(SurfaceId{1}, loop.id));
    QVERIFY(formOf(doc) == original);
}

// Rotation, translation, uniform scale and a mirror move the form with the NURBS; a stretch
// drops it; undo gives back the very form.
void TestAnalyticDocument::similaritiesCarryAlong() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QUndoStack stack;
    const glm::dmat3 rot(glm::dvec3(0.36, 0.48, -0.8), glm::dvec3(-0.8, 0.6, 0.0),
                         glm::dvec3(0.48, 0.64, 0.6));
    const auto affine = [](const glm::dmat3& m, const glm::dvec3& t) {
        glm::dmat4 a(m);
        a[3] = glm::dvec4(t, 1.0);
        return a;
    };
    for (const glm::dmat4& t : {affine(rot, {4, -5, 6}), affine(3.0 * rot, {0, 0, 0}),
                                affine(glm::dmat3(-1, 0, 0, 0, 1, 0, 0, 0, 1), {1, 1, 1}),
                                affine(glm::dmat3(1.0), {1e3, 0, 0})}) {
        QVERIFY(pushCommand(
            &stack, TransformSurfaces::create(&doc, {SurfaceId{1}}, t, QStringLiteral("Move"))));
        const Surface& s = *doc.surface(SurfaceId{1});
        QVERIFY(s.analytic.kind == Kind::Cylinder);
        QVERIFY(checkAnalyticForm(s.analytic, s.geometry).has_value());
        QVERIFY(analyticDeviation(s.analytic, s.geometry) <= 1e-12 * diagonal(s.geometry) * 1e3);
        // A drag after the move drops it; its undo gives the moved form back.
        const AnalyticForm moved = s.analytic;
        const glm::dvec3 p = s.geometry.points[4];
        QVERIFY(pushCommand(&stack, MoveControlPoints::create(&doc, SurfaceId{1}, {4}, {p},
                                                              {p + glm::dvec3(0.1)})));
        QCOMPARE(formOf(doc).kind, Kind::None);
        stack.undo();
        QVERIFY(formOf(doc) == moved);
        stack.undo();
        QVERIFY(formOf(doc) == original);
    }
    const glm::dmat4 stretch = affine(glm::dmat3(1, 0, 0, 0, 2, 0, 0, 0, 1), {0, 0, 0});
    QVERIFY(pushCommand(&stack, TransformSurfaces::create(&doc, {SurfaceId{1}}, stretch,
                                                          QStringLiteral("Stretch"))));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == original);
}

void TestAnalyticDocument::unitConversionScales() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QUndoStack stack;
    QVERIFY(pushCommand(&stack, SetUnits::create(&doc, LengthUnit::Inch, true)));
    const Surface& s = *doc.surface(SurfaceId{1});
    QCOMPARE(s.analytic.kind, Kind::Cylinder);
    QVERIFY(std::abs(s.analytic.radius - 2.0 / 25.4) <= 1e-15);
    QVERIFY(analyticDeviation(s.analytic, s.geometry) <= 1e-12 * diagonal(s.geometry));
    stack.undo();
    QVERIFY(formOf(doc) == original);
}

void TestAnalyticDocument::removalAndUndo() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QUndoStack stack;
    const glm::dvec3 p = doc.surface(SurfaceId{1})->geometry.points[0];
    QVERIFY(pushCommand(
        &stack, MoveControlPoints::create(&doc, SurfaceId{1}, {0}, {p}, {p + glm::dvec3(0.3)})));
    QVERIFY(pushCommand(&stack, RemoveSurface::create(&doc, SurfaceId{1})));
    QVERIFY(!doc.surface(SurfaceId{1}));
    stack.undo(); // the face comes back edited, without a form
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo(); // the edit undone: the form again
    QVERIFY(formOf(doc) == original);
}

void TestAnalyticDocument::knotFileRoundTrip() {
    Scene sc = scene();
    sc.surfaces[0].analytic.swapped = false;
    // A cone too, with an indirect frame, to carry every member.
    Surface cone;
    cone.id = SurfaceId{3};
    cone.name = QStringLiteral("Cone");
    NurbsCurve2 line;
    line.degree = 1;
    line.knots = {0, 0, 1, 1};
    line.points = {{1.0, 0.0}, {3.0, 4.0}};
    line.weights = {1, 1};
    cone.geometry = makeRevolution({0, 0, 0}, line);
    for (glm::dvec3& q : cone.geometry.points)
        q.z = -q.z;
    cone.analytic.kind = Kind::Cone;
    cone.analytic.zAxis = {0, 0, -1};
    cone.analytic.radius = 1.0;
    cone.analytic.semiAngle = std::atan(0.5);
    cone.analytic.u = {AnalyticParamMap::Kind::HalfAngle, 0.0, 2 * kPi};
    cone.analytic.v = {AnalyticParamMap::Kind::Linear, 0.0, std::sqrt(20.0)};
    QVERIFY(analyticDeviation(cone.analytic, cone.geometry) <= 1e-12 * diagonal(cone.geometry));
    sc.surfaces.push_back(cone);
    sc.nextId = 4;
    const QByteArray json = sceneToJson(sc);
    const QJsonObject root = QJsonDocument::fromJson(json).object();
    QCOMPARE(root.value(QStringLiteral("version")).toString(), QStringLiteral("1.5"));
    const QJsonArray surfaces = root.value(QStringLiteral("surfaces")).toArray();
    QVERIFY(surfaces[0].toObject().contains(QStringLiteral("analytic")));
    QVERIFY(!surfaces[1].toObject().contains(QStringLiteral("analytic"))); // free-form: none
    QCOMPARE(surfaces[2]
                 .toObject()
                 .value(QStringLiteral("analytic"))
                 .toObject()
                 .value(QStringLiteral("kind"))
                 .toString(),
             QStringLiteral("cone"));
    const Expected<Scene> back = sceneFromJson(json, QStringLiteral("round.knot"));
    QVERIFY2(back, qPrintable(back.message()));
    QCOMPARE(back->surfaces.size(), sc.surfaces.size());
    for (size_t k = 0; k < sc.surfaces.size(); ++k)
        QVERIFY(back->surfaces[k].analytic == sc.surfaces[k].analytic);
    // Through a file on disk too.
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("a.knot"));
    QVERIFY(writeKnotFile(path, sc));
    const Expected<Scene> read = readKnotFile(path);
    QVERIFY2(read, qPrintable(read.message()));
    QVERIFY(read->surfaces[2].analytic == sc.surfaces[2].analytic);
}

// A 1.4 file (no member) reads with no form; so does a 1.5 file without one.
void TestAnalyticDocument::olderFilesHaveNone() {
    QJsonObject root = QJsonDocument::fromJson(sceneToJson(scene())).object();
    QJsonArray surfaces = root.value(QStringLiteral("surfaces")).toArray();
    QJsonObject first = surfaces[0].toObject();
    first.remove(QStringLiteral("analytic"));
    surfaces[0] = first;
    root.insert(QStringLiteral("surfaces"), surfaces);
    root.insert(QStringLiteral("version"), QStringLiteral("1.4"));
    const Expected<Scene> back =
        sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("old.knot"));
    QVERIFY2(back, qPrintable(back.message()));
    QCOMPARE(back->surfaces[0].analytic.kind, Kind::None);
    QVERIFY(back->surfaces[0].geometry == scene().surfaces[0].geometry);
}

void TestAnalyticDocument::malformedFormsAreErrors_data() {
    QTest::addColumn<QString>("member");
    QTest::addColumn<QJsonValue>("value");
    QTest::addColumn<QString>("expected");
    QTest::newRow("kind") << "kind" << QJsonValue(QStringLiteral("ellipsoid"))
                          << "$.surfaces[0].analytic.kind: expected \"plane\"";
    QTest::newRow("axis") << "xAxis" << QJsonValue(QJsonArray{1.0, 0.1, 0.0})
                          << "$.surfaces[0].analytic: an axis of the frame is not of unit length";
    QTest::newRow("origin") << "origin" << QJsonValue(QJsonArray{1.0, 0.0})
                            << "$.surfaces[0].analytic.origin: expected 3 numbers";
    QTest::newRow("radius") << "radius" << QJsonValue(-2.0)
                            << "$.surfaces[0].analytic: the radius must be > 0";
    QTest::newRow("missing radius") << "radius" << QJsonValue(QJsonValue::Undefined)
                                    << "$.surfaces[0].analytic.radius: missing required member";
    QTest::newRow("map") << "u"
                         << QJsonValue(QJsonObject{{"map", "spiral"}, {"offset", 0}, {"scale", 1}})
                         << "$.surfaces[0].analytic.u.map: expected \"linear\" or \"halfAngle\"";
    QTest::newRow("not this surface")
        << "radius" << QJsonValue(2.5) << "$.surfaces[0].analytic: the form lies ";
    QTest::newRow("swapped") << "swapped" << QJsonValue(1)
                             << "$.surfaces[0].analytic.swapped: expected true or false";
}

void TestAnalyticDocument::malformedFormsAreErrors() {
    QFETCH(QString, member);
    QFETCH(QJsonValue, value);
    QFETCH(QString, expected);
    QJsonObject root = QJsonDocument::fromJson(sceneToJson(scene())).object();
    QJsonArray surfaces = root.value(QStringLiteral("surfaces")).toArray();
    QJsonObject first = surfaces[0].toObject();
    QJsonObject form = first.value(QStringLiteral("analytic")).toObject();
    if (value.isUndefined())
        form.remove(member);
    else
        form.insert(member, value);
    first.insert(QStringLiteral("analytic"), form);
    surfaces[0] = first;
    root.insert(QStringLiteral("surfaces"), surfaces);
    const Expected<Scene> back =
        sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("bad.knot"));
    QVERIFY(!back);
    const QString message = back.message();
    QVERIFY2(message.startsWith(QStringLiteral("bad.knot")), qPrintable(message));
    QVERIFY2(message.contains(expected), qPrintable(message));
}

QTEST_GUILESS_MAIN(TestAnalyticDocument)
#include "tst_analytic_document.moc"
