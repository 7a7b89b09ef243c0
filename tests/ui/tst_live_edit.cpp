// LiveEdit without widgets: a drag's steps follow live, the commit is one undo step, cancel
// restores, and a step the document's rule refuses changes nothing and says why.
#include "model_fixtures.h"
#include "tests/support/expected_test_util.h"
#include "ui/edit/commands.h"
#include "ui/edit/liveedit.h"

#include <QSignalSpy>
#include <QTest>
#include <QUndoStack>
#include <limits>

using namespace kw;
using namespace kw::test;

namespace {

struct Fixture {
    Document doc;
    QUndoStack stack;
    LiveEdit live{&doc, &stack};
    Fixture() {
        if (!doc.resetScene(threeSurfaceScene()))
            qFatal("fixture scene invalid");
    }
    const NurbsSurface& geometry(std::uint32_t id) const {
        return doc.surface(SurfaceId{id})->geometry;
    }
};

} // namespace

class TestLiveEdit : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void stepsFollowLiveAndCommitIsOneStep() {
        Fixture f;
        const NurbsSurface before = f.geometry(1);
        f.live.begin();
        for (int k = 1; k <= 5; ++k) // five steps of a drag
            KW_VERIFY_OK(
                f.live.moveControlPoints(SurfaceId{1}, {0, 5}, {glm::dvec3(k), glm::dvec3(-k)}));
        QCOMPARE(f.geometry(1).points[0], glm::dvec3(5));
        QCOMPARE(f.stack.count(), 0);
        QVERIFY(f.live.commit());
        QVERIFY(!f.live.isActive());
        QCOMPARE(f.stack.count(), 1);
        QCOMPARE(f.stack.undoText(), QStringLiteral("Move 2 control points"));
        QCOMPARE(f.geometry(1).points[5], glm::dvec3(-5));
        f.stack.undo(); // back to the press-time points, not to a step between
        QVERIFY(f.geometry(1) == before);
        f.stack.redo();
        QCOMPARE(f.geometry(1).points[0], glm::dvec3(5));
    }

    void severalSurfacesAreOneMacro() {
        Fixture f;
        f.live.begin();
        KW_VERIFY_OK(f.live.moveControlPoints({{SurfaceId{1}, 0, 0}, {SurfaceId{2}, 1, 1}},
                                              {glm::dvec3(1, 2, 3), glm::dvec3(4, 5, 6)}));
        QCOMPARE(f.live.movedSurfaces(), 2);
        QVERIFY(f.live.commit(QStringLiteral("Move surface"), QStringLiteral("Move %1 surfaces")));
        QCOMPARE(f.stack.count(), 1);
        QCOMPARE(f.stack.undoText(), QStringLiteral("Move 2 surfaces"));
    }

    void cancelRestoresPointsWeightsAndTrims() {
        Fixture f;
        const Scene before = f.doc.scene();
        f.live.begin();
        KW_VERIFY_OK(f.live.moveControlPoints(SurfaceId{2}, {3}, {glm::dvec3(9)}));
        KW_VERIFY_OK(f.live.setWeight(SurfaceId{2}, 3, 2.5));
        const TrimPointRef end{SurfaceId{1}, TrimLoopId{10}, 0, 1},
            start{SurfaceId{1}, TrimLoopId{10}, 1, 0};
        KW_VERIFY_OK(f.live.moveTrimPoints({end, start}, {{0.8, 0.2}, {0.8, 0.2}}));
        QVERIFY(!sameContent(f.doc.scene(), before));
        f.live.cancel();
        QVERIFY(!f.live.isActive());
        QVERIFY(sameContent(f.doc.scene(), before));
        QCOMPARE(f.stack.count(), 0);
    }

    void refusedStepChangesNothingAndSaysWhy() {
        Fixture f;
        QSignalSpy refused(&f.live, &LiveEdit::refused);
        f.live.begin();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        const glm::dvec3 p0 = f.geometry(1).points[0];
        QString why =
            kwtest::refusal(f.live.moveControlPoints(SurfaceId{1}, {0}, {glm::dvec3(nan)}));
        QCOMPARE(why, f.doc.checkControlPoints(SurfaceId{1}, {0}, {glm::dvec3(nan)}).message());
        QCOMPARE(why, QStringLiteral("control point positions must be finite"));
        QCOMPARE(f.geometry(1).points[0], p0);
        // A curve end moved without the coinciding start of the next curve opens the loop.
        const TrimPointRef end{SurfaceId{1}, TrimLoopId{10}, 0, 1};
        why = kwtest::refusal(f.live.moveTrimPoints({end}, {{0.8, 0.2}}));
        QVERIFY2(why.contains(QStringLiteral("is not closed")), qPrintable(why));
        QCOMPARE(refused.count(), 2);
        QCOMPARE(refused.at(1).at(0).toString(), why);
        // A point no longer in its net.
        why = kwtest::refusal(f.live.moveControlPoints({{SurfaceId{1}, 7, 0}}, {glm::dvec3(0)}));
        QVERIFY2(why.contains(QStringLiteral("no longer in the 4 × 4 net")), qPrintable(why));
        QVERIFY(!f.live.commit()); // nothing applied, nothing pushed
        QCOMPARE(f.stack.count(), 0);
    }

    void netChangedUnderTheDragIsRefusedAndDropped() {
        Fixture f;
        const SurfaceId id{2};
        QVERIFY(pushCommand(&f.stack, InsertKnot::create(&f.doc, id, Direction::U, 0.5)));
        f.live.begin();
        KW_VERIFY_OK(f.live.moveControlPoints(id, {6}, {glm::dvec3(7)}));
        // An undo by key under the drag takes the knot out: index 6 means another point now.
        f.stack.undo();
        const NurbsSurface undone = f.geometry(2);
        const QString why = kwtest::refusal(f.live.moveControlPoints(id, {6}, {glm::dvec3(8)}));
        QVERIFY2(why.contains(QStringLiteral("changed under the drag")), qPrintable(why));
        f.live.cancel(); // does not write the old indices into the new net
        QVERIFY(f.geometry(2) == undone);
    }

    void sceneResetEndsTheEdit() {
        Fixture f;
        f.live.begin();
        KW_VERIFY_OK(f.live.moveControlPoints(SurfaceId{1}, {0}, {glm::dvec3(3)}));
        QVERIFY(f.doc.resetScene(threeSurfaceScene()));
        QVERIFY(!f.live.isActive());
        const Scene fresh = f.doc.scene();
        f.live.cancel();
        QVERIFY(sameContent(f.doc.scene(), fresh));
    }

    void commandsUseTheDocumentsRule() {
        Fixture f;
        QString error;
        error = kwtest::refusal(MoveControlPoints::create(
            &f.doc, SurfaceId{1}, {99}, {glm::dvec3(0)}, {glm::dvec3(1)}, MoveKind::Drag));
        QVERIFY(!error.isNull());
        QCOMPARE(error, f.doc.checkControlPoints(SurfaceId{1}, {99}, {glm::dvec3(1)}).message());
        error = kwtest::refusal(SetWeight::create(&f.doc, SurfaceId{1}, 0, -1.0));
        QVERIFY(!error.isNull());
        QCOMPARE(error, f.doc.checkWeight(SurfaceId{1}, 0, -1.0).message());
        const TrimPointRef end{SurfaceId{1}, TrimLoopId{10}, 0, 1};
        error = kwtest::refusal(
            MoveTrimPoints::create(&f.doc, {end}, {{0.9, 0.1}}, {{0.8, 0.2}}, MoveKind::Drag));
        QVERIFY(!error.isNull());
        QCOMPARE(error, f.doc.checkTrimPoints({end}, {{0.8, 0.2}}).message());
    }
};

QTEST_GUILESS_MAIN(TestLiveEdit)
#include "tst_live_edit.moc"
