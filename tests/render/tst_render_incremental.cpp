// GL test: the renderer syncs what changed (the drag-step target). After one moved
// control point in a scene of 300 surfaces the GPU scene compares one record, not 300
// (FrameReport::recordsSynced), and every frame drawn that way equals the frame a fresh
// renderer draws of the same document: moved points, trim edits, hidden and removed surfaces,
// another view, adaptive partitions.
#include "expected_test_util.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"
#include "trim_test_util.h"

#include <cmath>

using namespace kw;

namespace {

/// `n` wavy patches of two variants, every other one trimmed by a disc (render_test_util.h).
Scene grid(int n) {
    return kwtest::variantGrid(n, true);
}

} // namespace

class TestRenderIncremental : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_kept;  ///< follows one document across edits
    std::unique_ptr<OffscreenRenderer> m_fresh; ///< draws a new copy of it each time

    /// Draws `doc` with the kept renderer and a copy of it with the other (a new document:
    /// every record rebuilt) and checks that the two frames agree; returns the kept report.
    FrameReport frameAgainstFresh(const Document& doc, const Camera& camera,
                                  const RenderOptions& options) {
        QString error;
        FrameReport kept;
        [&] {
            KW_VERIFY_OK(m_kept->render(doc, camera, options));
            kept = m_kept->lastReport();
            const QImage a = m_kept->colorImage();
            Document copy;
            KW_VERIFY_OK(copy.resetScene(doc.scene()));
            KW_VERIFY_OK(m_fresh->render(copy, camera, options));
            const FrameReport& fresh = m_fresh->lastReport();
            QCOMPARE(fresh.recordsSynced, fresh.surfaces); // all new: every record compared
            QCOMPARE(kept.surfaces, fresh.surfaces);
            QCOMPARE(kept.culled, fresh.culled);
            QCOMPARE(kept.partitions.cells, fresh.partitions.cells);
            QCOMPARE(kept.partitions.worstBoundPixels, fresh.partitions.worstBoundPixels);
            QCOMPARE(kept.partitions.unmet, fresh.partitions.unmet);
            QCOMPARE(kept.warnings, fresh.warnings);
            QVERIFY2(a == m_fresh->colorImage(), "the kept renderer's frame differs");
        }();
        return kept;
    }

private Q_SLOTS:
    void initTestCase() {
        auto kept = kwtest::offscreenRenderer(QSize(320, 240), false);
        QVERIFY2(kept, qPrintable(kept.message()));
        m_kept = std::move(kept).value();
        auto fresh = kwtest::offscreenRenderer(QSize(320, 240), false);
        QVERIFY2(fresh, qPrintable(fresh.message()));
        m_fresh = std::move(fresh).value();
    }

    void oneMovedPointSyncsOneRecord() {
        QString error;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(grid(300)));
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        const RenderOptions options;
        FrameReport r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 300);
        QCOMPARE(r.surfaces, 300);
        // Nothing changed: nothing compared, nothing uploaded, no mask drawn.
        QVERIFY(m_kept->render(doc, camera, options));
        r = m_kept->lastReport();
        QCOMPARE(r.recordsSynced, 0);
        QCOMPARE(r.uploads, UploadStats{});
        QCOMPARE(r.masks.redraws, 0);

        // A moved point, on an untrimmed surface and on a trimmed one: one record, one
        // sub-image upload, the fresh renderer's image.
        for (const int k : {40, 41}) {
            const Surface& s = doc.scene().surfaces[size_t(k)];
            QCOMPARE(s.trims.empty(), k % 2 == 0);
            const int index = s.geometry.index(1, 1);
            QVERIFY(doc.setControlPoints(
                s.id, {index}, {s.geometry.points[size_t(index)] + glm::dvec3(0.2, -0.1, 0.6)}));
            r = frameAgainstFresh(doc, camera, options);
            QCOMPARE(r.recordsSynced, 1);
            QCOMPARE(r.uploads.subImageUploads, std::int64_t(1));
            QCOMPARE(r.uploads.fullUploads, std::int64_t(0));
        }

        // A trim edit: one record compared, its mask drawn again.
        const Surface& trimmed = doc.scene().surfaces[7];
        const TrimPointRef ref{trimmed.id, trimmed.trims[0].id, 0, 3};
        QVERIFY(
            doc.setTrimPoint(ref, trimmed.trims[0].curves[0].points[3] + glm::dvec2(0.05, 0.02)));
        r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 1);
        QCOMPARE(r.masks.redraws, 1);

        // Several changes between two frames: each changed record once.
        for (const int k : {3, 150, 299}) {
            const Surface& s = doc.scene().surfaces[size_t(k)];
            const std::vector<int> indices{0, 1};
            QVERIFY(doc.setControlPoints(s.id, indices,
                                         {s.geometry.points[0] + glm::dvec3(0, 0, 0.3),
                                          s.geometry.points[1] + glm::dvec3(0, 0, 0.3)}));
            QVERIFY(doc.setControlPoints(s.id, {0}, {s.geometry.points[0] + glm::dvec3(0.1)}));
        }
        r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 3);

        // Hiding, removing and another view change the draw list or every record's view:
        // all visible records are compared again, and still draw as a fresh renderer does.
        QVERIFY(doc.setHidden(doc.scene().surfaces[10].id, true));
        r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 299);
        QCOMPARE(r.surfaces, 299);
        QVERIFY(doc.removeSurface(doc.scene().surfaces[20].id));
        r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 298);
        QVERIFY(doc.setHidden(doc.scene().surfaces[10].id, false));
        r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 299);
        Camera closer = camera;
        closer.eye = camera.target + 0.4 * (camera.eye - camera.target);
        r = frameAgainstFresh(doc, closer, options);
        QCOMPARE(r.recordsSynced, 299);
        QVERIFY(r.culled > 0);
        // In the close-up, a moved point of a visible surface is again one record.
        const Surface& s = doc.scene().surfaces[0];
        QVERIFY(doc.setControlPoints(s.id, {5}, {s.geometry.points[5] + glm::dvec3(0, 0, 0.5)}));
        r = frameAgainstFresh(doc, closer, options);
        QCOMPARE(r.recordsSynced, 1);
    }

    void adaptivePartitionsFollowTheMovedPoint() {
        QString error;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(grid(60)));
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        RenderOptions options;
        options.partitioning = RenderOptions::Partitioning::Adaptive;
        FrameReport r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 60);
        // A large move inside the scene's bounds (a move that grows them changes the camera's
        // near and far planes, so every record would be compared): the surface's partitions
        // are chosen again.
        QVERIFY(m_kept->render(doc, camera, options));
        QCOMPARE(m_kept->lastReport().recordsSynced, 0);
        const Surface& s = doc.scene().surfaces[25];
        const int index = s.geometry.index(2, 2);
        QVERIFY(doc.setControlPoints(
            s.id, {index}, {s.geometry.points[size_t(index)] + glm::dvec3(1.0, 0.5, 0.0)}));
        r = frameAgainstFresh(doc, camera, options);
        QCOMPARE(r.recordsSynced, 1);
        QCOMPARE(r.partitions.choicesEvaluated, 1);
    }
};

QTEST_MAIN(TestRenderIncremental)
#include "tst_render_incremental.moc"
