// Command tests: texts, merging (nudges, slider sweeps), rejection of invalid edits, exact undo.
#include "model/document/document.h"
#include "model_fixtures.h"
#include "signallog.h"
#include "tests/support/expected_test_util.h"
#include "ui/edit/commands.h"

#include <QRegularExpression>
#include <QTest>
#include <QUndoStack>
#include <cmath>
#include <limits>

using namespace kw;
using namespace kw::test;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Fixture {
    Document doc;
    QUndoStack stack;
    Fixture() {
        if (!doc.resetScene(threeSurfaceScene()))
            qFatal("fixture scene invalid");
    }
    glm::dvec3 point(SurfaceId id, int i) const {
        return doc.surface(id)->geometry.points[size_t(i)];
    }
    bool nudge(SurfaceId id, std::vector<int> idx, glm::dvec3 by, MoveKind kind) {
        std::vector<glm::dvec3> from, to;
        for (int i : idx) {
            from.push_back(point(id, i));
            to.push_back(point(id, i) + by);
        }
        return bool(pushCommand(&stack, MoveControlPoints::create(&doc, id, idx, from, to, kind)));
    }
};

} // namespace

class TestCommands : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void moveTextAndUndo();
    void twoNudgesAreOneStep();
    void dragsAndOtherPointsDoNotMerge();
    void nudgeBackIsDropped();
    void sliderSweepIsOneStep();
    void weightMaterialLightCameraMerge();
    void rejectInvalidKnotVector();
    void setKnotVector();
    void insertKnotAndElevateDegree();
    void insertKnotAndElevateRejected();
    void removeSurfaceRestoresIndexAndId();
    void addSurfaceAllocatesIdsOnlyWhenValid();
    void createRefusesWithTheDocumentsReason();
    void trimLoopCommands();
    void moveTrimPointsMerge();
    void lightCommands();
    void refusedStepIsDropped();
    void nullDocumentIsRejected();
};

void TestCommands::moveTextAndUndo() {
    Fixture f;
    const Scene before = f.doc.scene();
    QVERIFY(f.nudge(SurfaceId{2}, {1, 5, 9}, {0, 0, 1}, MoveKind::Drag));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Move 3 control points"));
    QCOMPARE(f.point(SurfaceId{2}, 5), before.surfaces[1].geometry.points[5] + glm::dvec3(0, 0, 1));
    f.stack.undo();
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(f.nudge(SurfaceId{2}, {4}, {1, 0, 0}, MoveKind::Drag));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Move control point"));
    QString error;
    error = kwtest::refusal(MoveControlPoints::create(&f.doc, SurfaceId{2}, {20}, {{0, 0, 0}},
                                                      {{1, 1, 1}}, MoveKind::Drag));
    QVERIFY(!error.isNull());
    QVERIFY2(error.contains(QStringLiteral("out of range")), qPrintable(error));
    QVERIFY(!MoveControlPoints::create(&f.doc, SurfaceId{2}, {1}, {{0, 0, 0}}, {{kNaN, 1, 1}}));
    QVERIFY(!MoveControlPoints::create(&f.doc, SurfaceId{2}, {1, 1}, {{0, 0, 0}, {0, 0, 0}},
                                       {{1, 1, 1}, {1, 1, 1}}));
    QVERIFY(!MoveControlPoints::create(&f.doc, SurfaceId{8}, {1}, {{0, 0, 0}}, {{1, 1, 1}}));
}

void TestCommands::twoNudgesAreOneStep() {
    Fixture f;
    const Scene before = f.doc.scene();
    const glm::dvec3 p = f.point(SurfaceId{1}, 5);
    QVERIFY(f.nudge(SurfaceId{1}, {5, 6}, {0.1, 0, 0}, MoveKind::Nudge));
    QVERIFY(f.nudge(SurfaceId{1}, {5, 6}, {0.1, 0, 0}, MoveKind::Nudge));
    QVERIFY(f.nudge(SurfaceId{1}, {5, 6}, {0, 0.2, 0}, MoveKind::Nudge));
    QCOMPARE(f.stack.count(), 1);
    const glm::dvec3 moved = f.point(SurfaceId{1}, 5);
    QVERIFY(glm::length(moved - (p + glm::dvec3(0.2, 0.2, 0))) < 1e-12);
    f.stack.undo();
    QCOMPARE(f.doc.scene(), before);
    f.stack.redo();
    QCOMPARE(f.point(SurfaceId{1}, 5), moved);
}

void TestCommands::dragsAndOtherPointsDoNotMerge() {
    Fixture f;
    QVERIFY(f.nudge(SurfaceId{1}, {5}, {0.1, 0, 0}, MoveKind::Drag));
    QVERIFY(f.nudge(SurfaceId{1}, {5}, {0.1, 0, 0}, MoveKind::Drag));
    QCOMPARE(f.stack.count(), 2); // each drag is its own step
    QVERIFY(f.nudge(SurfaceId{1}, {5}, {0.1, 0, 0}, MoveKind::Nudge));
    QVERIFY(f.nudge(SurfaceId{1}, {6}, {0.1, 0, 0}, MoveKind::Nudge));
    QVERIFY(f.nudge(SurfaceId{2}, {6}, {0.1, 0, 0}, MoveKind::Nudge));
    QCOMPARE(f.stack.count(), 5);
}

void TestCommands::nudgeBackIsDropped() {
    Fixture f;
    const Scene before = f.doc.scene();
    QVERIFY(f.nudge(SurfaceId{3}, {2}, {0.5, 0, 0}, MoveKind::Nudge));
    QVERIFY(f.nudge(SurfaceId{3}, {2}, {-0.5, 0, 0}, MoveKind::Nudge));
    QCOMPARE(f.stack.count(), 0); // the merged edit changed nothing: obsolete, removed
    QCOMPARE(f.doc.scene(), before);
}

void TestCommands::sliderSweepIsOneStep() {
    Fixture f;
    for (int n = 11; n <= 40; ++n)
        QVERIFY(pushCommand(&f.stack, SetPartitions::create(&f.doc, SurfaceId{2}, n, n)));
    QCOMPARE(f.stack.count(), 1);
    QCOMPARE(f.stack.undoText(), QStringLiteral("Set partitions to 40 × 40"));
    QCOMPARE(f.doc.surface(SurfaceId{2})->partitionsU, 40);
    f.stack.undo();
    QCOMPARE(f.doc.surface(SurfaceId{2})->partitionsU, 10);
    QCOMPARE(f.doc.surface(SurfaceId{2})->partitionsV, 10);
    f.stack.redo();
    QVERIFY(pushCommand(&f.stack, SetPartitions::create(&f.doc, SurfaceId{3}, 5, 6)));
    QCOMPARE(f.stack.count(), 2); // another surface: another step
    QString error;
    error = kwtest::refusal(SetPartitions::create(&f.doc, SurfaceId{3}, 0, 6));
    QVERIFY(!error.isNull());
    QVERIFY(error.contains(QStringLiteral("partitions")));
    QVERIFY(!SetPartitions::create(&f.doc, SurfaceId{3}, 5, kMaxPartitions + 1));
}

void TestCommands::weightMaterialLightCameraMerge() {
    Fixture f;
    const Scene before = f.doc.scene();
    for (double w : {1.5, 2.0, 2.5})
        QVERIFY(pushCommand(&f.stack, SetWeight::create(&f.doc, SurfaceId{1}, 5, w)));
    QCOMPARE(f.stack.count(), 1);
    QCOMPARE(f.stack.undoText(), QStringLiteral("Set weight to 2.5"));
    QVERIFY(!SetWeight::create(&f.doc, SurfaceId{1}, 5, 0.0));
    QVERIFY(!SetWeight::create(&f.doc, SurfaceId{1}, 16, 1.0));
    Material m;
    for (double kd : {0.1, 0.2, 0.3}) {
        m.kd = kd;
        QVERIFY(pushCommand(&f.stack, SetMaterial::create(&f.doc, SurfaceId{1}, m)));
    }
    QCOMPARE(f.stack.count(), 2);
    Light l = f.doc.scene().lights[0];
    for (double x : {0.1, 0.2, 0.3}) {
        l.diffuse = glm::dvec3(x);
        QVERIFY(pushCommand(&f.stack, SetLights::changeLight(&f.doc, 0, l)));
    }
    QCOMPARE(f.stack.count(), 3);
    QCOMPARE(f.stack.undoText(), QStringLiteral("Change light 1"));
    Camera c = f.doc.scene().camera;
    for (double x : {1.0, 2.0, 3.0}) {
        c.eye.x = x;
        QVERIFY(pushCommand(&f.stack, SetCamera::create(&f.doc, c)));
    }
    QCOMPARE(f.stack.count(), 4);
    QCOMPARE(f.doc.scene().camera.eye.x, 3.0);
    f.stack.setIndex(0);
    QCOMPARE(f.doc.scene(), before);
}

void TestCommands::rejectInvalidKnotVector() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    const SurfaceId id{2}; // 5 points, degree 3 in u: 9 knots
    QString error;
    error = kwtest::refusal(
        SetKnotVector::create(&f.doc, id, Direction::U, {0, 0, 0, 0, 0.7, 0.5, 1, 1, 1}));
    QVERIFY(!error.isNull());
    QVERIFY2(error.startsWith(QStringLiteral("knot vector u")), qPrintable(error));
    error.clear();
    error =
        kwtest::refusal(SetKnotVector::create(&f.doc, id, Direction::U, {0, 0, 0, 0, 1, 1, 1, 1}));
    QVERIFY(!error.isNull());
    QVERIFY(!error.isEmpty());
    QVERIFY(!SetKnotVector::create(&f.doc, id, Direction::V, {0, 0, 0, 0, kNaN, 1, 1, 1}));
    // Multiplicity 5 > degree + 1; an empty domain.
    QVERIFY(
        !SetKnotVector::create(&f.doc, id, Direction::U, {0, 0, 0, 0, 0.5, 0.5, 0.5, 0.5, 0.5}));
    QVERIFY(!SetKnotVector::create(&f.doc, id, Direction::U, {0, 0, 0, 0, 0, 0, 0, 0, 0}));
    QVERIFY(!SetKnotVector::create(&f.doc, SurfaceId{99}, Direction::U, {}));
    QCOMPARE(f.stack.count(), 0);
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
}

void TestCommands::setKnotVector() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    const std::vector<double> knots = {0, 0, 0, 0, 0.3, 1, 1, 1, 1};
    QVERIFY(
        pushCommand(&f.stack, SetKnotVector::create(&f.doc, SurfaceId{2}, Direction::U, knots)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Edit knot vector u"));
    QCOMPARE(f.doc.surface(SurfaceId{2})->geometry.knotsU, knots);
    QCOMPARE(log.take(), QStringList({"changed 2 Knots"}));
    f.stack.undo();
    QCOMPARE(f.doc.scene(), before);
    QCOMPARE(log.take(), QStringList({"changed 2 Knots"}));
}

void TestCommands::insertKnotAndElevateDegree() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    const NurbsSurface g0 = f.doc.surface(SurfaceId{1})->geometry;
    QVERIFY(pushCommand(&f.stack, InsertKnot::create(&f.doc, SurfaceId{1}, Direction::U, 0.5)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Insert knot u = 0.5"));
    const NurbsSurface& g1 = f.doc.surface(SurfaceId{1})->geometry;
    QCOMPARE(g1.countU, g0.countU + 1);
    QCOMPARE(g1.countV, g0.countV);
    QCOMPARE(log.take(), QStringList({"changed 1 Points|Knots"}));
    QVERIFY(glm::length(surfacePoint(g1, 0.3, 0.6) - surfacePoint(g0, 0.3, 0.6)) < 1e-9);
    QVERIFY(pushCommand(&f.stack, ElevateDegree::create(&f.doc, SurfaceId{1}, Direction::V)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Elevate degree v to 4"));
    QCOMPARE(f.doc.surface(SurfaceId{1})->geometry.degreeV, 4);
    QVERIFY(pushCommand(&f.stack, InsertKnot::create(&f.doc, SurfaceId{1}, Direction::V, 0.25, 2)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Insert knot v = 0.25 (×2)"));
    const Scene end = f.doc.scene();
    f.stack.setIndex(0);
    QCOMPARE(f.doc.scene(), before);
    f.stack.setIndex(3);
    QCOMPARE(f.doc.scene(), end);
}

void TestCommands::insertKnotAndElevateRejected() {
    Fixture f;
    const Scene before = f.doc.scene();
    QString error;
    error = kwtest::refusal(InsertKnot::create(&f.doc, SurfaceId{1}, Direction::U, 1.5, 1));
    QVERIFY(!error.isNull());
    QVERIFY2(error.contains(QStringLiteral("(0, 1)")), qPrintable(error));
    QVERIFY(!InsertKnot::create(&f.doc, SurfaceId{1}, Direction::U, 0.0));
    QVERIFY(!InsertKnot::create(&f.doc, SurfaceId{1}, Direction::U, 0.5, 4)); // > degree
    QVERIFY(!InsertKnot::create(&f.doc, SurfaceId{1}, Direction::U, kNaN));
    QVERIFY(!InsertKnot::create(&f.doc, SurfaceId{1}, Direction::U, 0.5, 0));
    error = kwtest::refusal(ElevateDegree::create(&f.doc, SurfaceId{1}, Direction::U, kMaxDegree));
    QVERIFY(!error.isNull());
    QVERIFY2(error.contains(QStringLiteral("maximum")), qPrintable(error));
    QVERIFY(!ElevateDegree::create(&f.doc, SurfaceId{1}, Direction::U, 0));
    QVERIFY(!ElevateDegree::create(&f.doc, SurfaceId{42}, Direction::U));
    QCOMPARE(f.doc.scene(), before);
}

void TestCommands::removeSurfaceRestoresIndexAndId() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    QVERIFY(pushCommand(&f.stack, RemoveSurface::create(&f.doc, SurfaceId{1})));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Remove surface “Alpha”"));
    QCOMPARE(f.doc.indexOf(SurfaceId{1}), -1);
    QVERIFY(pushCommand(&f.stack, RemoveSurface::create(&f.doc, SurfaceId{3})));
    log.take();
    f.stack.undo();
    f.stack.undo();
    QCOMPARE(log.take(), QStringList({"aboutToInsert @1", "inserted 3 @1", "aboutToInsert @0",
                                      "inserted 1 @0"}));
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(!RemoveSurface::create(&f.doc, SurfaceId{77}));
}

void TestCommands::addSurfaceAllocatesIdsOnlyWhenValid() {
    Fixture f;
    const std::uint32_t next = f.doc.scene().nextId;
    Surface bad = makeSurface(0, QStringLiteral("Bad"), patch());
    bad.geometry.knotsU.push_back(2.0);
    QString error;
    error = kwtest::refusal(AddSurface::create(&f.doc, bad, -1));
    QVERIFY(!error.isNull());
    QVERIFY(error.contains(QStringLiteral("surface")));
    QVERIFY(!AddSurface::create(&f.doc, makeSurface(2, QStringLiteral("Dup"), patch())));
    QVERIFY(!AddSurface::create(&f.doc, makeSurface(0, QStringLiteral("Far"), patch()), 5));
    QCOMPARE(f.doc.scene().nextId, next);

    Surface s = makeSurface(0, QStringLiteral("Delta"), patch(5, 5));
    s.trims.push_back(rectLoop(TrimLoopId{}, 0.2, 0.2, 0.4, 0.4));
    auto cmd = AddSurface::create(&f.doc, s, 1);
    QVERIFY(cmd);
    const SurfaceId id = (*cmd)->surfaceId();
    QCOMPARE(id.value, next);
    QVERIFY(pushCommand(&f.stack, std::move(cmd)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Add surface “Delta”"));
    QCOMPARE(f.doc.indexOf(id), 1);
    QCOMPARE(f.doc.surface(id)->trims[0].id.value, next + 1);
    f.stack.undo();
    QCOMPARE(f.doc.indexOf(id), -1);
    f.stack.redo();
    QCOMPARE(f.doc.indexOf(id), 1); // same id, same index
}

void TestCommands::createRefusesWithTheDocumentsReason() {
    // A create asks the document's own rule (model/document/edit_checks.h): what the document
    // would refuse is refused before anything changes, with the document's reason, ids
    // included (one counter for surfaces and loops).
    Fixture f;
    const Scene before = f.doc.scene();
    const Surface onLoopId = makeSurface(10, QStringLiteral("Taken"), patch()); // loop 10's id
    const QString surfaceIdUsed = QStringLiteral("surface id 10 already used");
    QCOMPARE(kwtest::refusal(AddSurface::create(&f.doc, onLoopId)), surfaceIdUsed);
    QCOMPARE(f.doc.insertSurface(3, onLoopId).message(), surfaceIdUsed);
    Surface loopOnSurfaceId = makeSurface(0, QStringLiteral("Loop"), patch(5, 5));
    loopOnSurfaceId.trims.push_back(rectLoop(TrimLoopId{2}, 0.2, 0.2, 0.4, 0.4));
    QCOMPARE(kwtest::refusal(AddSurface::create(&f.doc, loopOnSurfaceId)),
             QStringLiteral("trim loop id 2 already used"));
    const TrimLoop onSurfaceId = rectLoop(TrimLoopId{1}, 0.1, 0.1, 0.2, 0.2);
    const QString loopIdUsed = QStringLiteral("trim loop id 1 already used");
    QCOMPARE(kwtest::refusal(AddTrimLoop::create(&f.doc, SurfaceId{2}, onSurfaceId)), loopIdUsed);
    QCOMPARE(f.doc.insertTrimLoop(SurfaceId{2}, 0, onSurfaceId).message(), loopIdUsed);
    QCOMPARE(kwtest::refusal(RenameSurface::create(&f.doc, SurfaceId{1}, QStringLiteral(" "))),
             f.doc.setName(SurfaceId{1}, QStringLiteral(" ")).message());
    QCOMPARE(f.doc.scene(), before); // nextId included: no id was used up
    QCOMPARE(f.stack.count(), 0);
}

void TestCommands::trimLoopCommands() {
    Fixture f;
    const Scene before = f.doc.scene();
    auto add = AddTrimLoop::create(&f.doc, SurfaceId{2}, rectLoop({}, 0.1, 0.1, 0.2, 0.2));
    QVERIFY(add);
    const TrimLoopId loop = (*add)->loopId();
    QVERIFY(loop.isValid());
    QVERIFY(pushCommand(&f.stack, std::move(add)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Add trim loop (4 curves) to “Beta”"));
    QVERIFY(pushCommand(&f.stack, RemoveTrimLoop::create(&f.doc, SurfaceId{1}, TrimLoopId{10})));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Remove trim loop 10 from “Alpha”"));
    QCOMPARE(f.doc.surface(SurfaceId{1})->trims.size(), size_t(1));
    f.stack.undo();
    QCOMPARE(f.doc.surface(SurfaceId{1})->trims[0].id, TrimLoopId{10}); // back at index 0
    f.stack.undo();
    QCOMPARE(f.doc.scene().surfaces, before.surfaces);
    TrimLoop empty;
    QVERIFY(!AddTrimLoop::create(&f.doc, SurfaceId{2}, empty));
    QVERIFY(!AddTrimLoop::create(&f.doc, SurfaceId{2}, rectLoop(TrimLoopId{12}, 0, 0, 1, 1)));
    QVERIFY(!AddTrimLoop::create(&f.doc, SurfaceId{2}, rectLoop({}, 0, 0, 1, 1), 2));
    QVERIFY(!RemoveTrimLoop::create(&f.doc, SurfaceId{2}, TrimLoopId{10}));
}

void TestCommands::moveTrimPointsMerge() {
    Fixture f;
    const Scene before = f.doc.scene();
    // Move the shared corner of curves 0 and 1 of loop 10 together, keeping the loop closed.
    const std::vector<TrimPointRef> refs = {{SurfaceId{1}, TrimLoopId{10}, 0, 1},
                                            {SurfaceId{1}, TrimLoopId{10}, 1, 0}};
    glm::dvec2 p = before.surfaces[0].trims[0].curves[0].points[1];
    for (int k = 0; k < 3; ++k) {
        const glm::dvec2 q = p + glm::dvec2(0.01, 0.0);
        QVERIFY(pushCommand(&f.stack,
                            MoveTrimPoints::create(&f.doc, refs, {p, p}, {q, q}, MoveKind::Nudge)));
        p = q;
    }
    QCOMPARE(f.stack.count(), 1);
    QCOMPARE(f.stack.undoText(), QStringLiteral("Move 2 trim points"));
    const auto& loop = f.doc.surface(SurfaceId{1})->trims[0];
    QCOMPARE(loop.curves[0].points[1], p);
    QCOMPARE(loop.curves[1].points[0], p);
    f.stack.undo();
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(!MoveTrimPoints::create(&f.doc, {{SurfaceId{1}, TrimLoopId{10}, 0, 2}}, {p}, {p}));
    QVERIFY(!MoveTrimPoints::create(&f.doc, {refs[0], refs[0]}, {p, p}, {p, p}));
    QVERIFY(!MoveTrimPoints::create(&f.doc, {refs[0]}, {p}, {{kNaN, 0}}));
    QVERIFY(!MoveTrimPoints::create(&f.doc, {}, {}, {}));
}

void TestCommands::lightCommands() {
    Fixture f;
    const auto lights = f.doc.scene().lights;
    QVERIFY(pushCommand(&f.stack, SetLights::addLight(&f.doc, Light{})));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Add light"));
    QCOMPARE(f.doc.scene().lights.size(), size_t(3));
    QVERIFY(pushCommand(&f.stack, SetLights::removeLight(&f.doc, 0)));
    QCOMPARE(f.stack.undoText(), QStringLiteral("Remove light 1"));
    QVERIFY(pushCommand(&f.stack, SetLights::removeLight(&f.doc, 0)));
    QVERIFY(pushCommand(&f.stack, SetLights::changeLight(&f.doc, 0, lights[1])));
    QString error;
    error = kwtest::refusal(SetLights::removeLight(&f.doc, 0));
    QVERIFY(!error.isNull()); // the last light stays
    QVERIFY(error.contains(QStringLiteral("last light")));
    QVERIFY(!SetLights::changeLight(&f.doc, 3, Light{}));
    Light bad;
    bad.vector = glm::dvec3(0);
    QVERIFY(!SetLights::changeLight(&f.doc, 0, bad));
    QVERIFY(pushCommand(&f.stack, SetLights::create(&f.doc, std::vector<Light>(8))));
    QVERIFY(!SetLights::addLight(&f.doc, Light{}));
    QVERIFY(!SetCamera::create(&f.doc, Camera{{0, 0, 0}, {0, 0, 0}}));
    f.stack.setIndex(0);
    QCOMPARE(f.doc.scene().lights, lights);
}

void TestCommands::refusedStepIsDropped() {
    // Someone changed the document behind the stack: the command cannot undo, says so, and is
    // dropped rather than leaving the stack out of step.
    Fixture f;
    QVERIFY(
        pushCommand(&f.stack, RenameSurface::create(&f.doc, SurfaceId{2}, QStringLiteral("X"))));
    QVERIFY(f.doc.removeSurface(SurfaceId{2}));
    // The warning gives the document's reason.
    QTest::ignoreMessage(QtWarningMsg, QRegularExpression(QStringLiteral(
                                           "document refused undo of .*no surface with id 2")));
    f.stack.undo();
    QCOMPARE(f.stack.count(), 0);
    QVERIFY(!RenameSurface::create(&f.doc, SurfaceId{1}, QStringLiteral("Alpha")));
    QVERIFY(!RenameSurface::create(&f.doc, SurfaceId{1}, QStringLiteral(" ")));
}

void TestCommands::nullDocumentIsRejected() {
    QString error;
    error = kwtest::refusal(MoveControlPoints::create(nullptr, SurfaceId{1}, {0}, {{0, 0, 0}},
                                                      {{1, 1, 1}}, MoveKind::Drag));
    QVERIFY(!error.isNull());
    QCOMPARE(error, QStringLiteral("no document"));
    error.clear();
    error = kwtest::refusal(InsertKnot::create(nullptr, SurfaceId{1}, Direction::U, 0.5, 1));
    QVERIFY(!error.isNull());
    QCOMPARE(error, QStringLiteral("no document"));
    QVERIFY(!AddSurface::create(nullptr, makeSurface(0, QStringLiteral("A"), patch())));
    QVERIFY(!MoveTrimPoints::create(nullptr, {{SurfaceId{1}, TrimLoopId{10}, 0, 0}}, {{0, 0}},
                                    {{1, 1}}));
    QVERIFY(!SetLights::addLight(nullptr, Light{}));
    QVERIFY(!SetLights::removeLight(nullptr, 0));
    QVERIFY(!SetLights::changeLight(nullptr, 0, Light{}));
    QVERIFY(!SetLights::create(nullptr, {Light{}}));
    QVERIFY(!SetCamera::create(nullptr, Camera{}));
    QVERIFY(!RemoveTrimLoop::create(nullptr, SurfaceId{1}, TrimLoopId{10}));
    QUndoStack stack;
    QVERIFY(!pushCommand(&stack, nullptr));
    QVERIFY(!pushCommand(nullptr, SetCamera::create(nullptr, Camera{})));
    QCOMPARE(stack.count(), 0);
}

QTEST_GUILESS_MAIN(TestCommands)
#include "tst_commands.moc"
