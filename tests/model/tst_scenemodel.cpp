// SceneModel and Selection tests: structure, texts, roles and signals under a Fatal model tester.
#include "model/document/scenemodel.h"
#include "model/document/selection.h"
#include "model_fixtures.h"
#include "tests/support/expected_test_util.h"
#include "ui/edit/commands.h"

#include <QAbstractItemModelTester>
#include <QSignalSpy>
#include <QTest>
#include <QUndoStack>

using namespace kw;
using namespace kw::test;

namespace {

struct Fixture {
    Document doc;
    SceneModel model{doc};
    QAbstractItemModelTester tester{&model, QAbstractItemModelTester::FailureReportingMode::Fatal};
    Fixture() {
        if (!doc.resetScene(threeSurfaceScene()))
            qFatal("fixture scene invalid");
    }
    QString text(const QModelIndex& i) const { return model.data(i).toString(); }
};

} // namespace

class TestSceneModel : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void structureAndTexts();
    void roles();
    void insertAndRemoveSurfaces();
    void insertAndRemoveTrimLoops();
    void geometryChangeUpdatesNetRow();
    void renameGoesThroughCommand();
    void renameWithoutHandlerIsRefused();
    void reset();
    void persistentIndexesFollowIds();
    void selectionFollowsDocument();
    void pointsGoWithTheirSurfaceOutOfSight();
};

void TestSceneModel::structureAndTexts() {
    Fixture f;
    QCOMPARE(f.model.rowCount(), 3);
    QCOMPARE(f.model.columnCount(), 1);
    const QModelIndex alpha = f.model.index(0, 0);
    QCOMPARE(f.text(alpha), QStringLiteral("Alpha"));
    QCOMPARE(f.model.rowCount(alpha), 3); // control net + 2 loops
    QCOMPARE(f.text(f.model.index(0, 0, alpha)), QStringLiteral("Control net (4 × 4)"));
    const QModelIndex loop2 = f.model.index(2, 0, alpha);
    QCOMPARE(f.text(f.model.index(1, 0, alpha)), QStringLiteral("Trim loop 10 (4 curves)"));
    QCOMPARE(f.text(loop2), QStringLiteral("Trim loop 11 (4 curves)"));
    QCOMPARE(f.model.rowCount(loop2), 4);
    QCOMPARE(f.text(f.model.index(0, 0, loop2)), QStringLiteral("Curve 1, degree 1, 2 points"));
    QCOMPARE(f.text(f.model.index(2, 0, loop2)), QStringLiteral("Curve 3, degree 2, 3 points"));
    QCOMPARE(f.model.rowCount(f.model.index(0, 0, loop2)), 0);
    QCOMPARE(f.model.rowCount(f.model.index(0, 0, alpha)), 0);
    const QModelIndex beta = f.model.index(1, 0);
    QCOMPARE(f.model.rowCount(beta), 1);
    QCOMPARE(f.text(f.model.index(0, 0, beta)), QStringLiteral("Control net (5 × 4)"));
    QCOMPARE(f.text(f.model.index(0, 0, f.model.index(2, 0))),
             QStringLiteral("Control net (4 × 6)"));
    QCOMPARE(f.model.parent(loop2), alpha);
    QCOMPARE(f.model.parent(f.model.index(3, 0, loop2)), loop2);
    QVERIFY(!f.model.index(3, 0).isValid());
    QVERIFY(!f.model.index(0, 1).isValid());
}

void TestSceneModel::roles() {
    Fixture f;
    const QModelIndex gamma = f.model.index(2, 0);
    QCOMPARE(f.model.data(gamma, SceneModel::IdRole).value<SurfaceId>(), SurfaceId{3});
    QCOMPARE(f.model.data(gamma, Qt::EditRole).toString(), QStringLiteral("Gamma"));
    const QModelIndex loop = f.model.index(1, 0, gamma);
    QCOMPARE(f.model.data(loop, SceneModel::IdRole).value<TrimLoopId>(), TrimLoopId{12});
    QCOMPARE(f.model.data(loop, SceneModel::SurfaceIdRole).value<SurfaceId>(), SurfaceId{3});
    QCOMPARE(f.model.data(loop, SceneModel::KindRole).toInt(), int(SceneModel::Kind::TrimLoop));
    QVERIFY(!f.model.data(loop, Qt::EditRole).isValid());
    const QModelIndex curve = f.model.index(3, 0, loop);
    QCOMPARE(f.model.data(curve, SceneModel::SurfaceIdRole).value<SurfaceId>(), SurfaceId{3});
    QCOMPARE(f.model.data(curve, SceneModel::KindRole).toInt(), int(SceneModel::Kind::TrimCurve));
    QVERIFY(!f.model.data(curve, SceneModel::IdRole).isValid());
    QCOMPARE(f.model.surfaceIndex(SurfaceId{2}), f.model.index(1, 0));
    QCOMPARE(f.model.trimLoopIndex(SurfaceId{1}, TrimLoopId{11}),
             f.model.index(2, 0, f.model.index(0, 0)));
    QVERIFY(!f.model.trimLoopIndex(SurfaceId{2}, TrimLoopId{11}).isValid());
    QCOMPARE(f.model.surfaceOf(curve), SurfaceId{3});
}

void TestSceneModel::insertAndRemoveSurfaces() {
    Fixture f;
    QSignalSpy inserted(&f.model, &QAbstractItemModel::rowsInserted);
    QSignalSpy removed(&f.model, &QAbstractItemModel::rowsRemoved);
    Surface s = makeSurface(20, QStringLiteral("Delta"), patch(6, 4));
    s.trims.push_back(rectLoop(TrimLoopId{21}, 0.1, 0.1, 0.3, 0.3));
    QVERIFY(f.doc.insertSurface(1, s));
    QCOMPARE(inserted.count(), 1);
    QVERIFY(!inserted.at(0).at(0).value<QModelIndex>().isValid());
    QCOMPARE(inserted.at(0).at(1).toInt(), 1);
    QCOMPARE(inserted.at(0).at(2).toInt(), 1);
    QCOMPARE(f.model.rowCount(), 4);
    QCOMPARE(f.text(f.model.index(1, 0)), QStringLiteral("Delta"));
    QCOMPARE(f.text(f.model.index(0, 0, f.model.index(1, 0))),
             QStringLiteral("Control net (6 × 4)"));
    QCOMPARE(f.text(f.model.index(2, 0)), QStringLiteral("Beta"));

    QVERIFY(f.doc.removeSurface(SurfaceId{1}));
    QCOMPARE(removed.count(), 1);
    QCOMPARE(removed.at(0).at(1).toInt(), 0);
    QCOMPARE(f.model.rowCount(), 3);
    QCOMPARE(f.text(f.model.index(0, 0)), QStringLiteral("Delta"));
}

void TestSceneModel::insertAndRemoveTrimLoops() {
    Fixture f;
    QSignalSpy inserted(&f.model, &QAbstractItemModel::rowsInserted);
    QSignalSpy removed(&f.model, &QAbstractItemModel::rowsRemoved);
    QSignalSpy changed(&f.model, &QAbstractItemModel::dataChanged);
    QVERIFY(f.doc.insertTrimLoop(SurfaceId{2}, 0, rectLoop(TrimLoopId{40}, 0.5, 0.5, 0.7, 0.7)));
    QCOMPARE(inserted.count(), 1);
    const QModelIndex beta = f.model.index(1, 0);
    QCOMPARE(inserted.at(0).at(0).value<QModelIndex>(), beta);
    QCOMPARE(inserted.at(0).at(1).toInt(), 1); // after the control net row
    QCOMPARE(f.model.rowCount(beta), 2);
    QCOMPARE(f.text(f.model.index(1, 0, beta)), QStringLiteral("Trim loop 40 (4 curves)"));
    QVERIFY(changed.count() >= 1); // loop texts refreshed on the Trims aspect

    QVERIFY(f.doc.removeTrimLoop(SurfaceId{1}, TrimLoopId{10}));
    QCOMPARE(removed.count(), 1);
    QCOMPARE(removed.at(0).at(0).value<QModelIndex>(), f.model.index(0, 0));
    QCOMPARE(removed.at(0).at(1).toInt(), 1);
    QCOMPARE(f.model.rowCount(f.model.index(0, 0)), 2);
    QCOMPARE(f.model.data(f.model.index(1, 0, f.model.index(0, 0)), SceneModel::IdRole)
                 .value<TrimLoopId>(),
             TrimLoopId{11});
}

void TestSceneModel::geometryChangeUpdatesNetRow() {
    Fixture f;
    QSignalSpy changed(&f.model, &QAbstractItemModel::dataChanged);
    QVERIFY(f.doc.setGeometry(SurfaceId{2}, patch(7, 5, 5.0)));
    const QModelIndex net = f.model.controlNetIndex(SurfaceId{2});
    QCOMPARE(f.text(net), QStringLiteral("Control net (7 × 5)"));
    bool netChanged = false;
    for (const auto& args : changed)
        netChanged = netChanged || args.at(0).value<QModelIndex>() == net;
    QVERIFY(netChanged);
    // Moving a point changes no text: no dataChanged at all.
    changed.clear();
    QVERIFY(f.doc.setControlPoints(SurfaceId{2}, {0}, {{1, 2, 3}}));
    QCOMPARE(changed.count(), 0);
}

void TestSceneModel::renameGoesThroughCommand() {
    Fixture f;
    QUndoStack stack;
    f.model.setRenameHandler([&](SurfaceId id, const QString& name) {
        // A refused rename pushes nothing; the stack's count below says so.
        static_cast<void>(pushCommand(&stack, RenameSurface::create(&f.doc, id, name)));
    });
    const QModelIndex beta = f.model.index(1, 0);
    QVERIFY(f.model.flags(beta) & Qt::ItemIsEditable);
    QVERIFY(!(f.model.flags(f.model.index(0, 0, beta)) & Qt::ItemIsEditable));
    QSignalSpy changed(&f.model, &QAbstractItemModel::dataChanged);
    QVERIFY(f.model.setData(beta, QStringLiteral("Fender")));
    QCOMPARE(stack.count(), 1);
    QCOMPARE(stack.undoText(), QStringLiteral("Rename “Beta” to “Fender”"));
    QCOMPARE(f.doc.surface(SurfaceId{2})->name, QStringLiteral("Fender"));
    QCOMPARE(f.text(beta), QStringLiteral("Fender"));
    QCOMPARE(changed.count(), 1);
    QCOMPARE(changed.at(0).at(0).value<QModelIndex>(), beta);
    stack.undo();
    QCOMPARE(f.text(beta), QStringLiteral("Beta"));
    QCOMPARE(changed.count(), 2);
    // Blank names and unchanged names are refused without reaching the stack.
    QVERIFY(!f.model.setData(beta, QStringLiteral("  ")));
    QVERIFY(!f.model.setData(beta, QStringLiteral("Beta")));
    QVERIFY(!f.model.setData(f.model.index(0, 0, beta), QStringLiteral("net")));
    QVERIFY(!f.model.setData(beta, QStringLiteral("X"), Qt::DisplayRole));
    QCOMPARE(stack.count(), 1);
    QCOMPARE(stack.index(), 0);
}

void TestSceneModel::renameWithoutHandlerIsRefused() {
    Fixture f;
    const QModelIndex alpha = f.model.index(0, 0);
    QVERIFY(!(f.model.flags(alpha) & Qt::ItemIsEditable));
    QVERIFY(!f.model.setData(alpha, QStringLiteral("Other")));
    QCOMPARE(f.doc.surface(SurfaceId{1})->name, QStringLiteral("Alpha"));
}

void TestSceneModel::reset() {
    Fixture f;
    QSignalSpy aboutToReset(&f.model, &QAbstractItemModel::modelAboutToBeReset);
    QSignalSpy resetDone(&f.model, &QAbstractItemModel::modelReset);
    Scene one;
    one.surfaces.push_back(makeSurface(5, QStringLiteral("Solo"), patch(4, 4)));
    QVERIFY(f.doc.resetScene(one));
    QCOMPARE(aboutToReset.count(), 1);
    QCOMPARE(resetDone.count(), 1);
    QCOMPARE(f.model.rowCount(), 1);
    QCOMPARE(f.text(f.model.index(0, 0)), QStringLiteral("Solo"));
    QVERIFY(f.doc.resetScene(Scene{}));
    QCOMPARE(f.model.rowCount(), 0);
}

void TestSceneModel::persistentIndexesFollowIds() {
    Fixture f;
    const QPersistentModelIndex gammaLoop = f.model.trimLoopIndex(SurfaceId{3}, TrimLoopId{12});
    const QPersistentModelIndex alphaLoop2 = f.model.trimLoopIndex(SurfaceId{1}, TrimLoopId{11});
    QVERIFY(f.doc.removeSurface(SurfaceId{2}));
    QVERIFY(gammaLoop.isValid());
    QCOMPARE(gammaLoop.parent().row(), 1);
    QCOMPARE(gammaLoop.data(SceneModel::IdRole).value<TrimLoopId>(), TrimLoopId{12});
    QVERIFY(f.doc.removeTrimLoop(SurfaceId{1}, TrimLoopId{10}));
    QCOMPARE(alphaLoop2.row(), 1);
    QCOMPARE(alphaLoop2.data().toString(), QStringLiteral("Trim loop 11 (4 curves)"));
    QVERIFY(f.doc.removeSurface(SurfaceId{3}));
    QVERIFY(!gammaLoop.isValid());
}

void TestSceneModel::selectionFollowsDocument() {
    Fixture f;
    Selection sel(f.model);
    QSignalSpy changed(&sel, &Selection::changed);
    QVERIFY(
        sel.setControlPoints({{SurfaceId{2}, 4, 3}, {SurfaceId{1}, 0, 0}, {SurfaceId{2}, 4, 3}}));
    QCOMPARE(sel.controlPoints().size(), size_t(2)); // sorted, unique
    QCOMPARE(sel.controlPoints().front().surface, SurfaceId{1});
    QCOMPARE(changed.count(), 1);
    QVERIFY(!sel.setControlPoints({{SurfaceId{2}, 5, 0}})); // 5 x 4 net: i = 5 out of range
    QVERIFY(!sel.setControlPoints({{SurfaceId{9}, 0, 0}}));
    QCOMPARE(sel.controlPoints().size(), size_t(2));
    QVERIFY(sel.setTrimPoints(
        {{SurfaceId{1}, TrimLoopId{11}, 2, 2}, {SurfaceId{3}, TrimLoopId{12}, 0, 1}}));
    QVERIFY(!sel.setTrimPoints({{SurfaceId{1}, TrimLoopId{11}, 2, 3}}));
    QCOMPARE(changed.count(), 2);

    changed.clear();
    QVERIFY(f.doc.removeSurface(SurfaceId{2}));
    QCOMPARE(sel.controlPoints().size(), size_t(1));
    QCOMPARE(changed.count(), 1);
    QVERIFY(f.doc.removeTrimLoop(SurfaceId{1}, TrimLoopId{11}));
    QCOMPARE(sel.trimPoints().size(), size_t(1));
    QCOMPARE(sel.trimPoints().front().loop, TrimLoopId{12});
    // A re-sized net renumbers points: that surface's point picks are dropped.
    QVERIFY(f.doc.setGeometry(SurfaceId{1}, patch(5, 4)));
    QVERIFY(sel.controlPoints().empty());
    changed.clear();
    sel.itemSelection()->setCurrentIndex(f.model.index(0, 0, f.model.index(1, 0)),
                                         QItemSelectionModel::ClearAndSelect);
    QCOMPARE(sel.currentSurface(), SurfaceId{3});
    sel.itemSelection()->select(f.model.index(0, 0), QItemSelectionModel::Select);
    QCOMPARE(sel.selectedSurfaces(), std::vector<SurfaceId>({SurfaceId{1}, SurfaceId{3}}));
    QVERIFY(changed.count() > 0);

    QVERIFY(f.doc.resetScene(threeSurfaceScene()));
    QVERIFY(sel.trimPoints().empty());
    QCOMPARE(sel.currentSurface(), SurfaceId{}); // a model reset clears the row selection
}

// A picked point is unpicked when its surface is hidden, or when another surface's row is
// picked; with no row selected, points of several surfaces stay (Select All).
void TestSceneModel::pointsGoWithTheirSurfaceOutOfSight() {
    Fixture f;
    Selection sel(f.model);
    QVERIFY(sel.setControlPoints({{SurfaceId{1}, 0, 0}, {SurfaceId{2}, 1, 1}}));
    QVERIFY(sel.setTrimPoints({{SurfaceId{1}, TrimLoopId{11}, 2, 2}}));
    QSignalSpy changed(&sel, &Selection::changed);
    QVERIFY(f.doc.setHidden(SurfaceId{2}, true));
    QCOMPARE(sel.controlPoints(), std::vector<ControlPointRef>({{SurfaceId{1}, 0, 0}}));
    QCOMPARE(changed.count(), 1);
    QVERIFY(f.doc.setHidden(SurfaceId{2}, false)); // shown again: nothing comes back
    QCOMPARE(sel.controlPoints().size(), size_t(1));

    QVERIFY(sel.setControlPoints({{SurfaceId{1}, 0, 0}, {SurfaceId{2}, 1, 1}}));
    changed.clear();
    const QModelIndex row2 = f.model.index(1, 0);
    QCOMPARE(row2.data(SceneModel::SurfaceIdRole).value<SurfaceId>(), SurfaceId{2});
    sel.itemSelection()->setCurrentIndex(row2, QItemSelectionModel::ClearAndSelect |
                                                   QItemSelectionModel::Rows);
    QCOMPARE(sel.controlPoints(), std::vector<ControlPointRef>({{SurfaceId{2}, 1, 1}}));
    QVERIFY(sel.trimPoints().empty());
    QVERIFY(changed.count() > 0);
    // Adding surface 1's row to the selection keeps surface 2's point.
    sel.itemSelection()->select(f.model.index(0, 0),
                                QItemSelectionModel::Select | QItemSelectionModel::Rows);
    QCOMPARE(sel.controlPoints().size(), size_t(1));
}

QTEST_GUILESS_MAIN(TestSceneModel)
#include "tst_scenemodel.moc"
