// Document::reviewAnalytic's cost: a point drag step, a weight, knot or degree edit drops an
// analytic face's form at once, running no similarity fit (Document::analyticFits counts them);
// only placements (TransformSurfaces, unit conversion) fit, once per face; undo still gives back
// the very forms; the document keeps no copy of the imported net (AnalyticOrigin holds digests).
#include "model/document/document.h"
#include "model/nurbs/analytic_eval.h"
#include "model/nurbs/nurbs_shapes.h"
#include "tests/support/analytic_fixtures.h"
#include "ui/edit/commands.h"
#include "ui/edit/modelcommands.h"

#include <QTest>
#include <QUndoStack>
#include <numbers>
#include <type_traits>

using namespace kw;
using Kind = AnalyticForm::Kind;

// The record per analytic face is plain data of a fixed size: a copy of the net (vectors of
// points, weights, knots) cannot come back into it unnoticed.
static_assert(std::is_trivially_copyable_v<Document::AnalyticOrigin>);
static_assert(sizeof(Document::AnalyticOrigin) <= 3 * sizeof(AnalyticForm) + 64);

namespace {

// An imported-looking cylinder and its form.
Scene scene() {
    Surface s = test::importedCylinder();
    Scene sc;
    sc.surfaces.push_back(s);
    sc.nextId = 2;
    return sc;
}

const AnalyticForm& formOf(const Document& d) {
    return d.surface(SurfaceId{1})->analytic;
}

} // namespace

class TestAnalyticEdits : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void dragStepsRunNoFit();
    void otherGeometryEditsRunNoFit();
    void placementsFitOnce();
};

// A drag of one control point, 200 steps, then moved back and undone: the form is gone from the
// first step, back at the press-time values, and not one fit ran.
void TestAnalyticEdits::dragStepsRunNoFit() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QVERIFY(original.kind == Kind::Cylinder);
    const glm::dvec3 p = doc.surface(SurfaceId{1})->geometry.points[7];
    for (int k = 1; k <= 200; ++k) {
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {7}, {p + glm::dvec3(0, 0, 1e-3 * k)}));
        QCOMPARE(formOf(doc).kind, Kind::None);
    }
    QVERIFY(doc.setControlPoints(SurfaceId{1}, {7}, {p}));
    QVERIFY(formOf(doc) == original);
    QUndoStack stack;
    QVERIFY(pushCommand(
        &stack, MoveControlPoints::create(&doc, SurfaceId{1}, {7}, {p}, {p + glm::dvec3(0.5)})));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == original);
    // Every point of the net dragged by one offset is still a point edit: dropped, no fit.
    std::vector<int> all(doc.surface(SurfaceId{1})->geometry.points.size());
    std::vector<glm::dvec3> from, to;
    for (size_t k = 0; k < all.size(); ++k) {
        all[k] = int(k);
        from.push_back(doc.surface(SurfaceId{1})->geometry.points[k]);
        to.push_back(from.back() + glm::dvec3(1, 0, 0));
    }
    QVERIFY(doc.setControlPoints(SurfaceId{1}, all, to));
    QCOMPARE(formOf(doc).kind, Kind::None);
    QVERIFY(doc.setControlPoints(SurfaceId{1}, all, from));
    QVERIFY(formOf(doc) == original);
    QCOMPARE(doc.analyticFits(), std::uint64_t(0));
}

void TestAnalyticEdits::otherGeometryEditsRunNoFit() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QUndoStack stack;
    QVERIFY(pushCommand(&stack, SetWeight::create(&doc, SurfaceId{1}, 5, 0.7)));
    QCOMPARE(formOf(doc).kind, Kind::None);
    QVERIFY(pushCommand(&stack, InsertKnot::create(&doc, SurfaceId{1}, Direction::U, 0.3)));
    QCOMPARE(formOf(doc).kind, Kind::None);
    QVERIFY(pushCommand(&stack, ElevateDegree::create(&doc, SurfaceId{1}, Direction::V)));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    stack.undo();
    QCOMPARE(formOf(doc).kind, Kind::None); // the weight edit still stands
    stack.undo();
    QVERIFY(formOf(doc) == original);
    QCOMPARE(doc.analyticFits(), std::uint64_t(0));
}

// A move fits once and carries the form; a drag after it drops it without a fit, and its undo
// gives back the moved form, still without one; the unit conversion fits once more.
void TestAnalyticEdits::placementsFitOnce() {
    Document doc;
    QVERIFY(doc.resetScene(scene()));
    const AnalyticForm original = formOf(doc);
    QUndoStack stack;
    glm::dmat4 m(glm::dmat3(0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0));
    m[3] = glm::dvec4(3.0, -1.0, 2.0, 1.0);
    QVERIFY(pushCommand(
        &stack, TransformSurfaces::create(&doc, {SurfaceId{1}}, m, QStringLiteral("Rotate"))));
    QCOMPARE(doc.analyticFits(), std::uint64_t(1));
    const AnalyticForm moved = formOf(doc);
    QCOMPARE(moved.kind, Kind::Cylinder);
    QVERIFY(glm::length(moved.origin - glm::dvec3(1.0, 0.0, -1.0)) < 1e-12);
    const glm::dvec3 p = doc.surface(SurfaceId{1})->geometry.points[10];
    QVERIFY(pushCommand(
        &stack, MoveControlPoints::create(&doc, SurfaceId{1}, {10}, {p}, {p + glm::dvec3(0.1)})));
    QCOMPARE(formOf(doc).kind, Kind::None);
    stack.undo();
    QVERIFY(formOf(doc) == moved);
    QCOMPARE(doc.analyticFits(), std::uint64_t(1));
    stack.undo(); // the very values it came in with: no fit needed
    QVERIFY(formOf(doc) == original);
    QCOMPARE(doc.analyticFits(), std::uint64_t(1));
    QVERIFY(pushCommand(&stack, SetUnits::create(&doc, LengthUnit::Inch, true)));
    QCOMPARE(doc.analyticFits(), std::uint64_t(2));
    QCOMPARE(formOf(doc).kind, Kind::Cylinder);
    QVERIFY(std::abs(formOf(doc).radius - 2.0 / 25.4) < 1e-15);
}

QTEST_GUILESS_MAIN(TestAnalyticEdits)
#include "tst_analytic_edits.moc"
