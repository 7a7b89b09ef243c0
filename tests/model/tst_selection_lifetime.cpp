// Selection lifetime: the SceneModel and the Selection may be destroyed in either order (the
// selection's QItemSelectionModel is its own child, never the model's).
#include "model/document/document.h"
#include "model/document/scenemodel.h"
#include "model/document/selection.h"
#include "model_fixtures.h"

#include <QPointer>
#include <QSignalSpy>
#include <QTest>
#include <memory>

using namespace kw;

class TestSelectionLifetime : public QObject {
    Q_OBJECT

    /// A document with three surfaces and a selection holding a row and a control point.
    static void pickSomething(SceneModel& model, Selection& sel) {
        sel.itemSelection()->setCurrentIndex(model.index(1, 0),
                                             QItemSelectionModel::ClearAndSelect);
        QVERIFY(sel.setControlPoints({{SurfaceId{2}, 1, 1}}));
        QCOMPARE(sel.currentSurface(), SurfaceId{2});
    }

private Q_SLOTS:
    void itemSelectionIsOwnedBySelection() {
        Document doc;
        QVERIFY(doc.resetScene(test::threeSurfaceScene()));
        SceneModel model(doc);
        auto sel = std::make_unique<Selection>(model);
        QItemSelectionModel* items = sel->itemSelection();
        QCOMPARE(items->model(), &model);
        QCOMPARE(items->parent(), sel.get());
        QVERIFY(!model.children().contains(items));
        QPointer<QItemSelectionModel> watch(items);
        sel.reset();
        QVERIFY(watch.isNull()); // deleted with its Selection, not left behind
    }

    void modelDestroyedBeforeSelection() {
        Document doc;
        QVERIFY(doc.resetScene(test::threeSurfaceScene()));
        auto model = std::make_unique<SceneModel>(doc);
        Selection sel(*model);
        pickSomething(*model, sel);
        QPointer<QItemSelectionModel> items(sel.itemSelection());
        model.reset(); // used to free the selection's member through the model's children
        QVERIFY(!items.isNull());
        QCOMPARE(items->model(), nullptr);
        QVERIFY(!sel.currentSurface().isValid());
        QVERIFY(sel.selectedSurfaces().empty());
        sel.clear();
        QVERIFY(sel.controlPoints().empty());
    }

    void selectionDestroyedBeforeModel() {
        Document doc;
        QVERIFY(doc.resetScene(test::threeSurfaceScene()));
        SceneModel model(doc);
        {
            Selection sel(model);
            pickSomething(model, sel);
        }
        // The model keeps working and has no stale child left by the selection.
        QVERIFY(model.findChildren<QItemSelectionModel*>().isEmpty());
        QCOMPARE(model.rowCount(), 3);
        QVERIFY(doc.removeSurface(SurfaceId{2}));
        QCOMPARE(model.rowCount(), 2);
    }

    void sharedParentDestroysInCreationOrder() {
        // As in MainWindow: document, model and selection are children of one object, deleted
        // in creation order, so the model goes before the selection.
        auto owner = std::make_unique<QObject>();
        auto* doc = new Document(owner.get());
        QVERIFY(doc->resetScene(test::threeSurfaceScene()));
        auto* model = new SceneModel(*doc, owner.get());
        auto* sel = new Selection(*model, owner.get());
        pickSomething(*model, *sel);
        QSignalSpy destroyed(sel, &QObject::destroyed);
        owner.reset();
        QCOMPARE(destroyed.count(), 1);
    }
};

QTEST_GUILESS_MAIN(TestSelectionLifetime)
#include "tst_selection_lifetime.moc"
