// Document::changesSince, the change list the renderer pulls at frame time instead of listening
// to signals: what a reader that last looked at a revision must look at again.
#include "model/document/document.h"
#include "model_fixtures.h"

#include <QTest>
#include <memory>

using namespace kw;
using namespace kw::test;

namespace {

std::vector<std::uint32_t> ids(const Document::Changes& c) {
    std::vector<std::uint32_t> out;
    for (const SurfaceChange& s : c.surfaces)
        out.push_back(s.id.value);
    return out;
}

} // namespace

class TestDocumentChanges : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void firstLookWalksEverything() {
        Document doc;
        // A document nothing has changed yet: a reader's first look is structural, the next
        // one (from `through`) sees nothing.
        Document::Changes c = doc.changesSince(0);
        QVERIFY(c.structural);
        c = doc.changesSince(c.through);
        QVERIFY(!c.structural);
        QVERIFY(c.surfaces.empty());
        QVERIFY(doc.resetScene(threeSurfaceScene()));
        c = doc.changesSince(c.through);
        QVERIFY(c.structural); // a reset
        QVERIFY(!doc.changesSince(c.through).structural);
    }

    void drawnChangesInOrder() {
        Document doc;
        QVERIFY(doc.resetScene(threeSurfaceScene()));
        const std::uint64_t since = doc.changesSince(0).through;
        QVERIFY(doc.setControlPoints(SurfaceId{2}, {0}, {{9, 9, 9}}));
        QVERIFY(doc.setName(SurfaceId{1}, QStringLiteral("renamed"))); // draws nothing new
        QVERIFY(doc.setPartitions(SurfaceId{3}, 7, 7));
        QVERIFY(doc.setControlPoints(SurfaceId{2}, {1}, {{8, 8, 8}}));
        const Document::Changes c = doc.changesSince(since);
        QVERIFY(!c.structural);
        QCOMPARE(ids(c), (std::vector<std::uint32_t>{2, 3, 2}));
        QCOMPARE(c.through, doc.revision());
        // Read from the middle: only what came after.
        const Document::Changes later = doc.changesSince(c.surfaces[1].revision);
        QCOMPARE(ids(later), (std::vector<std::uint32_t>{2}));
        QVERIFY(doc.changesSince(c.through).surfaces.empty());
    }

    void insertAndRemoveAreStructural() {
        Document doc;
        QVERIFY(doc.resetScene(threeSurfaceScene()));
        std::uint64_t since = doc.changesSince(0).through;
        QVERIFY(doc.removeSurface(SurfaceId{3}));
        Document::Changes c = doc.changesSince(since);
        QVERIFY(c.structural);
        since = c.through;
        QVERIFY(doc.insertSurface(0, makeSurface(9, QStringLiteral("New"), patch())));
        QVERIFY(doc.changesSince(since).structural);
        // A reader that caught up after the insert sees the later edits alone.
        since = doc.changesSince(since).through;
        QVERIFY(doc.setControlPoints(SurfaceId{9}, {0}, {{1, 2, 3}}));
        c = doc.changesSince(since);
        QVERIFY(!c.structural);
        QCOMPARE(ids(c), (std::vector<std::uint32_t>{9}));
    }

    void anotherDocumentIsStructural() {
        // A reader that followed one document and is handed a newer one (at the same address,
        // say) has a revision older than that document: it walks everything.
        auto first = std::make_unique<Document>();
        QVERIFY(first->resetScene(threeSurfaceScene()));
        const std::uint64_t since = first->changesSince(0).through;
        first.reset();
        Document second;
        QVERIFY(second.changesSince(since).structural);
    }

    void aReaderFarBehindWalksEverything() {
        Document doc;
        QVERIFY(doc.resetScene(threeSurfaceScene()));
        const std::uint64_t old = doc.changesSince(0).through;
        // More changes than the document keeps between two looks: the log is cut, and a
        // reader from before the cut walks everything, while a recent one does not.
        std::uint64_t recent = old;
        for (int k = 0; k < 70'000; ++k) {
            QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {{0.0, 0.0, double(k + 1)}}));
            if (k == 69'990)
                recent = doc.revision();
        }
        QVERIFY(doc.changesSince(old).structural);
        const Document::Changes c = doc.changesSince(recent);
        QVERIFY(!c.structural);
        QCOMPARE(int(c.surfaces.size()), 9);
    }
};

QTEST_GUILESS_MAIN(TestDocumentChanges)
#include "tst_document_changes.moc"
